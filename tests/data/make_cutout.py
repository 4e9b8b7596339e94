#!/usr/bin/env python3
"""Writes cutout_quad.gltf (run from tests/data; standard library only): a
1 x 1 quad in the xz plane (y = 0, facing +y, x and z in -0.5..0.5) whose
material is alphaMode MASK (cutoff 0.5) with a 4 x 4 RGBA base colour
texture, sampled nearest: an orange checker whose dark squares have alpha 0,
so half the quad is cut out, in squares of 0.25. And blend_quad.gltf: the
same quad, alphaMode BLEND, orange of alpha 0.5 (baseColorFactor, no
texture)."""
import json, struct

from gltf_bits import data_uri, png


rows = [sum(([230, 120, 40, 255] if (x + y) % 2 == 0 else [20, 20, 20, 0] for x in range(4)), []) for y in range(4)]
image = png(4, 4, rows, True)
pos = [-0.5, 0, -0.5, 0.5, 0, -0.5, 0.5, 0, 0.5, -0.5, 0, 0.5]
nrm = [0, 1, 0] * 4
uv = [0, 0, 1, 0, 1, 1, 0, 1]
idx = [0, 2, 1, 0, 3, 2]
buf = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<8f", *uv) + struct.pack("<6H", *idx)
gltf = {
    "asset": {"version": "2.0", "generator": "tests/data/make_cutout.py"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                "material": 0}]}],
    "materials": [{"name": "Checker cut-out", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
                   "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
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
open("cutout_quad.gltf", "w").write(json.dumps(gltf, indent=1) + "\n")

blend = json.loads(json.dumps(gltf))
blend["asset"]["generator"] = "tests/data/make_cutout.py (blend)"
blend["materials"] = [{"name": "Half see-through", "alphaMode": "BLEND", "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.19, 0.02, 0.5], "metallicFactor": 0}}]
del blend["textures"], blend["samplers"], blend["images"]
open("blend_quad.gltf", "w").write(json.dumps(blend, indent=1) + "\n")
