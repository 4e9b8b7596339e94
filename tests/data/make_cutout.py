#!/usr/bin/env python3
"""Writes cutout_quad.gltf (run from tests/data; standard library only): a
1 x 1 quad in the xz plane (y = 0, facing +y, x and z in -0.5..0.5) whose
material is alphaMode MASK (cutoff 0.5) with a 4 x 4 RGBA base colour
texture, sampled nearest: an orange checker whose dark squares have alpha 0,
so half the quad is cut out, in squares of 0.25. And blend_quad.gltf: the
same quad, alphaMode BLEND, orange of alpha 0.5 (baseColorFactor, no
texture)."""
import json

from gltf_bits import png, textured_quad


rows = [sum(([230, 120, 40, 255] if (x + y) % 2 == 0 else [20, 20, 20, 0] for x in range(4)), []) for y in range(4)]
image = png(4, 4, rows, True)
gltf = textured_quad("tests/data/make_cutout.py", {
    "name": "Checker cut-out", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
    "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}, image)
open("cutout_quad.gltf", "w").write(json.dumps(gltf, indent=1) + "\n")

blend = json.loads(json.dumps(gltf))
blend["asset"]["generator"] = "tests/data/make_cutout.py (blend)"
blend["materials"] = [{"name": "Half see-through", "alphaMode": "BLEND", "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.19, 0.02, 0.5], "metallicFactor": 0}}]
del blend["textures"], blend["samplers"], blend["images"]
open("blend_quad.gltf", "w").write(json.dumps(blend, indent=1) + "\n")
