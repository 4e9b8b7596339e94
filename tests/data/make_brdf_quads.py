#!/usr/bin/env python3
"""Writes brdf_quads.gltf (run from tests/data; standard library only): six
1 x 1 quads in the xz plane (y = 0, facing +y), centred at x = 0, 1.5, 3,
4.5, 6 and 7.5, z = 0, one primitive and one material each, for glTF's
metallic-roughness BRDF (issue 50; tests/lua/brdf_test.lua):
  0: metallic 1, roughness 0.4, base colour (0.9, 0.6, 0.3)
  1: metallic 1, roughness 0.7, the same colour
  2: metallic 0, roughness 0.3, base colour (0.2, 0.5, 0.8)
  3: metallic 0, roughness 0.8, the same colour
  4: factors metallic 1, roughness 1, base colour (0.9, 0.6, 0.3), and a
     2 x 1 metallicRoughnessTexture sampled nearest: the half at x < 6 has
     G = 77 (roughness 0.302) and B = 255 (metal), the half at x > 6 G = 204
     (0.8) and B = 0 (a dielectric); and a 2 x 1 occlusionTexture (R = 255 on
     the left, 64 on the right) of strength 0.5
  5: metallic 0, roughness 0.4, base colour (0.2, 0.5, 0.8), KHR_materials_ior
     1.7 and KHR_materials_specular: specularFactor 0.5, specularColorFactor
     (2, 0.5, 1)."""
import base64, json, struct, zlib

def png_rgb(w, h, rows):
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) \
        + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")

mr_png = png_rgb(2, 1, [[0, 77, 255, 0, 204, 0]])
occ_png = png_rgb(2, 1, [[255, 255, 255, 64, 64, 64]])
centres = [0.0, 1.5, 3.0, 4.5, 6.0, 7.5]
pos, nrm, uv, idx = [], [], [], []
for k, cx in enumerate(centres):
    for (x, z, u, v) in [(-0.5, -0.5, 0, 0), (0.5, -0.5, 1, 0), (0.5, 0.5, 1, 1), (-0.5, 0.5, 0, 1)]:
        pos += [cx + x, 0.0, z]
        nrm += [0.0, 1.0, 0.0]
        uv += [u, v]
    b = 4 * k
    idx += [b, b + 2, b + 1, b, b + 3, b + 2]
n = len(centres) * 4
geometry = struct.pack("<%df" % len(pos), *pos) + struct.pack("<%df" % len(nrm), *nrm) \
    + struct.pack("<%df" % len(uv), *uv) + struct.pack("<%dH" % len(idx), *idx)
while len(geometry) % 4:
    geometry += b"\x00"
images = mr_png + b"\x00" * ((4 - len(mr_png) % 4) % 4)
mr_offset = len(geometry)
occ_offset = mr_offset + len(images)
buf = geometry + images + occ_png
views = [
    {"buffer": 0, "byteOffset": 0, "byteLength": 12 * n},
    {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n},
    {"buffer": 0, "byteOffset": 24 * n, "byteLength": 8 * n},
]
accessors = [
    {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
     "min": [min(pos[0::3]), 0, -0.5], "max": [max(pos[0::3]), 0, 0.5]},
    {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"},
]
primitives = []
for k in range(len(centres)):
    views.append({"buffer": 0, "byteOffset": 32 * n + 12 * k, "byteLength": 12})
    accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": 6, "type": "SCALAR"})
    primitives.append({"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": len(accessors) - 1,
                       "material": k})
views.append({"buffer": 0, "byteOffset": mr_offset, "byteLength": len(mr_png)})
views.append({"buffer": 0, "byteOffset": occ_offset, "byteLength": len(occ_png)})
orange, blue = [0.9, 0.6, 0.3, 1.0], [0.2, 0.5, 0.8, 1.0]
def material(name, color, metallic, roughness, extra=None):
    m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": color, "metallicFactor": metallic,
                                                "roughnessFactor": roughness}}
    if extra:
        m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {"index": 0}
        m["occlusionTexture"] = {"index": 1, "strength": 0.5}
    return m
gltf = {
    "asset": {"version": "2.0", "generator": "tests/data/make_brdf_quads.py"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": primitives}],
    "materials": [material("metal 0.4", orange, 1.0, 0.4), material("metal 0.7", orange, 1.0, 0.7),
                  material("dielectric 0.3", blue, 0.0, 0.3), material("dielectric 0.8", blue, 0.0, 0.8),
                  material("textured", orange, 1.0, 1.0, True),
                  dict(material("specular", blue, 0.0, 0.4),
                       extensions={"KHR_materials_ior": {"ior": 1.7},
                                   "KHR_materials_specular": {"specularFactor": 0.5,
                                                              "specularColorFactor": [2.0, 0.5, 1.0]}})],
    "extensionsUsed": ["KHR_materials_ior", "KHR_materials_specular"],
    "samplers": [{"magFilter": 9728, "minFilter": 9728}],
    "images": [{"bufferView": len(views) - 2, "mimeType": "image/png"},
               {"bufferView": len(views) - 1, "mimeType": "image/png"}],
    "textures": [{"sampler": 0, "source": 0}, {"sampler": 0, "source": 1}],
    "bufferViews": views,
    "accessors": accessors,
    "buffers": [{"byteLength": len(buf),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
}
with open("brdf_quads.gltf", "w") as f:
    json.dump(gltf, f, indent=1)
