#!/usr/bin/env python3
"""Writes pane.gltf (run from tests/data; standard library only): a 1 x 1
quad in the xz plane (y = 0, facing +y, x and z in -0.5..0.5) of thin-walled
glass as glTF defines it: KHR_materials_transmission 1 and KHR_materials_ior
1.5 without KHR_materials_volume. Its base colour is an 8 x 8 RGBA texture,
sampled nearest: a pale blue tint (sRGB 170 200 255) with a crack along the
diagonal (texels x == y, alpha 0), cut out by alphaMode MASK (cutoff 0.5):
a broken window pane in one quad."""
import json, struct

from gltf_bits import data_uri, png


rows = [sum(([170, 200, 255, 0] if x == y else [170, 200, 255, 255] for x in range(8)), []) for y in range(8)]
image = png(8, 8, rows, True)
pos = [-0.5, 0, -0.5, 0.5, 0, -0.5, 0.5, 0, 0.5, -0.5, 0, 0.5]
nrm = [0, 1, 0] * 4
uv = [0, 0, 1, 0, 1, 1, 0, 1]
idx = [0, 2, 1, 0, 3, 2]
buf = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<8f", *uv) + struct.pack("<6H", *idx)
gltf = {
    "asset": {"version": "2.0", "generator": "tests/data/make_pane.py"},
    "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior"],
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                "material": 0}]}],
    "materials": [{"name": "Cracked pane", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
                   "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0,
                                            "roughnessFactor": 0},
                   "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                                  "KHR_materials_ior": {"ior": 1.5}}}],
    "textures": [{"source": 0, "sampler": 0}],
    "samplers": [{"magFilter": 9728, "minFilter": 9728}],
    "images": [{"uri": data_uri("image/png", image)}],
    "buffers": [{"byteLength": len(buf), "uri": data_uri("application/octet-stream", buf)}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-0.5, 0, -0.5], "max": [0.5, 0, 0.5]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
}
open("pane.gltf", "w").write(json.dumps(gltf, indent=1) + "\n")
