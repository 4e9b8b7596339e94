#!/usr/bin/env python3
"""Writes pane.gltf (run from tests/data; standard library only): a 1 x 1
quad in the xz plane (y = 0, facing +y, x and z in -0.5..0.5) of thin-walled
glass as glTF defines it: KHR_materials_transmission 1 and KHR_materials_ior
1.5 without KHR_materials_volume. Its base colour is an 8 x 8 RGBA texture,
sampled nearest: a pale blue tint (sRGB 170 200 255) with a crack along the
diagonal (texels x == y, alpha 0), cut out by alphaMode MASK (cutoff 0.5):
a broken window pane in one quad."""
import json

from gltf_bits import png, textured_quad


rows = [sum(([170, 200, 255, 0] if x == y else [170, 200, 255, 255] for x in range(8)), []) for y in range(8)]
image = png(8, 8, rows, True)
gltf = textured_quad("tests/data/make_pane.py", {
    "name": "Cracked pane", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
    "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 0},
    "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.5}}},
    image)
gltf["extensionsUsed"] = ["KHR_materials_transmission", "KHR_materials_ior"]
open("pane.gltf", "w").write(json.dumps(gltf, indent=1) + "\n")
