#!/usr/bin/env python3
"""Writes every_extension.gltf (run from tests/data; standard library only):
one triangle whose material asks for every glTF material extension
caustica does not draw (clearcoat, drawn on the BRDF's surfaces but not on
this glass, sheen, iridescence, anisotropy,
dispersion, diffuse transmission, unlit), and for a TANGENT attribute,
the specular extension's textures and the volume's thickness texture,
which are read: `caustica info` must list each of the others, on one line that
is not cut (issue 50). And 30
vendor extensions of 50 characters each, more than a line of names holds:
each named, or counted in "and N more"."""
import json, struct

from gltf_bits import data_uri, png


image = png(1, 1, [[200, 200, 200]], False)
pos = [0, 0, 0, 1, 0, 0, 0, 1, 0]
nrm = [0, 0, 1] * 3
tan = [1, 0, 0, 1] * 3
uv = [0, 0, 1, 0, 0, 1]
buf = struct.pack("<9f", *pos) + struct.pack("<9f", *nrm) + struct.pack("<12f", *tan) + struct.pack("<6f", *uv)
tex = {"index": 0}
extensions = {
    "KHR_materials_clearcoat": {"clearcoatFactor": 1},
    "KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1]},
    "KHR_materials_iridescence": {"iridescenceFactor": 1},
    "KHR_materials_anisotropy": {"anisotropyStrength": 0.5},
    "KHR_materials_dispersion": {"dispersion": 0.1},
    "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.5},
    "KHR_materials_unlit": {},
    "KHR_materials_specular": {"specularFactor": 0.5, "specularTexture": tex, "specularColorTexture": tex},
    "KHR_materials_volume": {"thicknessFactor": 1, "thicknessTexture": tex},
    "KHR_materials_transmission": {"transmissionFactor": 1},
}
for k in range(30):
    extensions["XYZ_materials_vendor_specific_extension_number_%02d" % k] = {}
gltf = {
    "asset": {"version": "2.0", "generator": "tests/data/make_every_extension.py"},
    "extensionsUsed": sorted(extensions),
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TANGENT": 2, "TEXCOORD_0": 3},
                                "material": 0}]}],
    "materials": [{"name": "Every extension", "pbrMetallicRoughness": {"metallicFactor": 0},
                   "extensions": extensions}],
    "textures": [{"source": 0}],
    "images": [{"uri": data_uri("image/png", image)}],
    "buffers": [{"byteLength": len(buf), "uri": data_uri("application/octet-stream", buf)}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 72, "byteLength": 48}, {"buffer": 0, "byteOffset": 120, "byteLength": 24}],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"},
        {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC2"}],
}
open("every_extension.gltf", "w").write(json.dumps(gltf, indent=1) + "\n")
