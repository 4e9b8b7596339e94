#!/usr/bin/env python3
"""Writes tangent_quad.gltf and tangent_quad_none.gltf (run from tests/data;
standard library only): one quad facing +y, u along +x, whose normal map
is one texel (218, 128, 218): a normal tilted 45 degrees towards the
tangent. tangent_quad.gltf gives a TANGENT of +z (w 1); the other none,
so its tangent is made from the texture coordinates: +x. A sun from +z
lights the first quad's normal about three times as much (issue 50: the
file's TANGENT was ignored)."""
import base64, json, struct

from gltf_bits import data_uri, png, textured_quad

image = png(1, 1, [[218, 128, 218]], False)
material = {"name": "Tilted", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 1},
            "normalTexture": {"index": 0}}
for name, tangent in (("tangent_quad.gltf", True), ("tangent_quad_none.gltf", False)):
    gltf = textured_quad("tests/data/make_tangent_quad.py", material, image)
    if tangent:
        raw = base64.b64decode(gltf["buffers"][0]["uri"].split(",", 1)[1])
        extra = struct.pack("<16f", *([0, 0, 1, 1] * 4))
        buf = raw + extra
        gltf["buffers"][0] = {"byteLength": len(buf), "uri": data_uri("application/octet-stream", buf)}
        gltf["bufferViews"].append({"buffer": 0, "byteOffset": len(raw), "byteLength": 64})
        gltf["accessors"].append({"bufferView": len(gltf["bufferViews"]) - 1, "componentType": 5126, "count": 4,
                                  "type": "VEC4"})
        gltf["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = len(gltf["accessors"]) - 1
    open(name, "w").write(json.dumps(gltf, indent=1) + "\n")
