#!/usr/bin/env python3
"""Writes cut_specular.gltf (run from tests/data; standard library only):
glTF's alphaMode on a mirror and on solid glass, four materials on four
primitives of one 1 x 1 quad (tests/scenes/cut_specular.lua puts each on a
sphere of its own):
  1 "Mirror with holes": metallic 1, roughness 0 (a mirror), alphaMode MASK
    (cutoff 0.5) by an 8 x 8 RGBA base colour texture, sampled nearest, of
    white bands whose every other one has alpha 0;
  2 "Half mirror": the same mirror, alphaMode BLEND, baseColorFactor alpha 0.5;
  3 "Glass with holes": KHR_materials_transmission 1, KHR_materials_volume
    (thickness 1: solid glass), KHR_materials_ior 1.5, MASK by the same texture;
  4 "Half glass": that glass, BLEND at alpha 0.5."""
import json

from gltf_bits import png, textured_quad


rows = [[255, 255, 255, 255 if (y // 2) % 2 == 0 else 0] * 8 for y in range(8)]
image = png(8, 8, rows, True)
glass = {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.5},
         "KHR_materials_volume": {"thicknessFactor": 1}}
materials = [
    {"name": "Mirror with holes", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
     "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 1, "roughnessFactor": 0}},
    {"name": "Half mirror", "alphaMode": "BLEND", "doubleSided": True,
     "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5], "metallicFactor": 1, "roughnessFactor": 0}},
    {"name": "Glass with holes", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
     "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 0},
     "extensions": glass},
    {"name": "Half glass", "alphaMode": "BLEND", "doubleSided": True,
     "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5], "metallicFactor": 0, "roughnessFactor": 0},
     "extensions": glass},
]
gltf = textured_quad("tests/data/make_cut_specular.py", materials[0], image)
gltf["materials"] = materials
primitive = gltf["meshes"][0]["primitives"][0]
gltf["meshes"][0]["primitives"] = [dict(primitive, material=k) for k in range(4)]
gltf["extensionsUsed"] = ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"]
open("cut_specular.gltf", "w").write(json.dumps(gltf, indent=1) + "\n")
