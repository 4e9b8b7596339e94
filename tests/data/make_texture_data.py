#!/usr/bin/env python3
"""Writes the texture test files (run from tests/data; standard library only):
normal_ridges.png  a 64x64 tangent-space normal map of ridges along u,
                   n ~ (-0.6 sin(2 pi 4 u), 0, 1) normalized
normal_flat.png    a 4x4 flat normal map: every texel (128, 128, 255), the
                   nearest 8 bits come to (0.5, 0.5, 1), a tilt of 0.0055 rad
quadrants.png      2x2 texels: top-left red, top-right green, bottom-left
                   blue, bottom-right white (row 0 is the top row)
transform_quad.gltf a unit quad (x, y in 0..1, facing +z, uv (0,0) at its
                   top-left) whose baseColorTexture is quadrants.png, sampled
                   nearest, with KHR_texture_transform's README example
                   (offset [0, 1], rotation pi/2, scale [0.5, 0.5]): the
                   lower left quadrant only, so the quad is all blue."""
import base64, json, math, struct, zlib

def png(path, w, h, rows):
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) \
        + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    open(path, "wb").write(data)

rows = []
for y in range(64):
    r = []
    for x in range(64):
        u = (x + 0.5) / 64
        n = (-0.6 * math.sin(2 * math.pi * 4 * u), 0.0, 1.0)
        l = math.sqrt(sum(c * c for c in n))
        r += [round((c / l * 0.5 + 0.5) * 255) for c in n]
    rows.append(r)
png("normal_ridges.png", 64, 64, rows)
png("normal_flat.png", 4, 4, [[128, 128, 255] * 4] * 4)
png("quadrants.png", 2, 2, [[255, 0, 0, 0, 255, 0], [0, 0, 255, 255, 255, 255]])

pos = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
nrm = [0, 0, 1] * 4
uv = [0, 1, 1, 1, 1, 0, 0, 0]
idx = [0, 1, 2, 0, 2, 3]
blob = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<8f", *uv) + struct.pack("<6H", *idx)
gltf = {
    "asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_texture_transform"],
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
    "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {
        "offset": [0, 1], "rotation": 1.57079632679, "scale": [0.5, 0.5]}}}}}],
    "textures": [{"source": 0, "sampler": 0}],
    "samplers": [{"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497}],
    "images": [{"uri": "quadrants.png"}],
    "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
}
json.dump(gltf, open("transform_quad.gltf", "w"), indent=1)
