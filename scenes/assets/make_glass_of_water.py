#!/usr/bin/env python3
"""Writes glass_of_water.gltf (run from scenes/assets; standard library only):
one glTF mesh of three primitives, each with its own material:

- "Glass": a tumbler 0.8 high, 0.3 in outer radius, walls 0.02 and a base 0.05
  thick (a closed shell), KHR_materials_transmission 1, KHR_materials_ior 1.5;
- "Water": the water in it, up to 0.55, 0.275 in radius (0.005 short of the
  glass wall: an air gap, so that every interface is air to glass or air to
  water, which both renderers trace; a glass-water interface would need
  nested media), IOR 1.33, KHR_materials_volume absorbing red a little
  (attenuationColor (0.75, 0.93, 1.0) at 1.0);
- "Label": a paper band around the glass from 0.25 to 0.45, alphaMode MASK
  (cutoff 0.5) with a 256 x 64 RGBA texture: white with a blue stripe and
  six round windows (alpha 0) through which the glass shows.

The base sits at y = 0. Everything is a surface of revolution about +y,
48 segments around."""
import base64, json, math, struct, zlib

SEGMENTS = 48


def lathe(profile, u_range=None, v_of=None):
    """A surface of revolution of the profile [(r, y), ...], each profile
    segment its own band (a crease at every profile point), normals
    perpendicular to the segment, the winding made counter-clockwise seen
    from the normal's side. Returns positions, normals, texcoords, indices."""
    pos, nrm, uv, idx = [], [], [], []
    for (r0, y0), (r1, y1) in zip(profile, profile[1:]):
        dr, dy = r1 - r0, y1 - y0
        length = math.hypot(dr, dy)
        nr, ny = dy / length, -dr / length
        base = len(pos) // 3
        for k in range(SEGMENTS + 1):
            a = 2 * math.pi * k / SEGMENTS
            c, s = math.cos(a), math.sin(a)
            for r, y in ((r0, y0), (r1, y1)):
                pos += [r * c, y, r * s]
                nrm += [nr * c, ny, nr * s]
                v = v_of(y) if v_of else 0.0
                uv += [k / SEGMENTS, v]
        for k in range(SEGMENTS):
            a0, a1 = base + 2 * k, base + 2 * k + 1      # ring k at p0, p1
            b0, b1 = base + 2 * k + 2, base + 2 * k + 3  # ring k + 1
            for tri in ((a0, b0, a1), (a1, b0, b1)):
                p = [pos[i * 3:i * 3 + 3] for i in tri]
                e1 = [p[1][j] - p[0][j] for j in range(3)]
                e2 = [p[2][j] - p[0][j] for j in range(3)]
                cr = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
                if math.sqrt(sum(x * x for x in cr)) < 1e-12:
                    continue  # a triangle on the axis (the profile ends there): no area
                n = nrm[tri[0] * 3:tri[0] * 3 + 3]
                if sum(cr[j] * n[j] for j in range(3)) < 0:
                    tri = (tri[0], tri[2], tri[1])
                idx += list(tri)
    return pos, nrm, uv, idx


def png_rgba(w, h, rows):
    raw = b"".join(b"\x00" + bytes(r) for r in rows)

    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) \
        + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def label_texture():
    w, h = 256, 64
    rows = []
    for y in range(h):
        row = []
        for x in range(w):
            rgba = [240, 236, 226, 255]                     # paper
            if 40 <= y < 52:
                rgba = [40, 80, 170, 255]                   # a blue stripe
            cx = (x // (w // 6)) * (w // 6) + w // 12       # six windows along u
            if (x - cx) ** 2 + (y - 22) ** 2 < 13 ** 2:
                rgba = [0, 0, 0, 0]                         # cut out
            row += rgba
        rows.append(row)
    return png_rgba(w, h, rows)


glass = lathe([(0.0, 0.0), (0.3, 0.0), (0.3, 0.8), (0.28, 0.8), (0.28, 0.05), (0.0, 0.05)])
water = lathe([(0.0, 0.055), (0.275, 0.055), (0.275, 0.55), (0.0, 0.55)])
label = lathe([(0.305, 0.25), (0.305, 0.45)], v_of=lambda y: (0.45 - y) / 0.2)

buf = bytearray()
views, accessors, primitives = [], [], []


def add_view(data, target):
    while len(buf) % 4:
        buf.append(0)
    views.append({"buffer": 0, "byteOffset": len(buf), "byteLength": len(data), "target": target})
    buf.extend(data)
    return len(views) - 1


for material, (pos, nrm, uv, idx) in enumerate((glass, water, label)):
    n = len(pos) // 3
    attrs = {}
    for name, data, kind in (("POSITION", pos, "VEC3"), ("NORMAL", nrm, "VEC3"), ("TEXCOORD_0", uv, "VEC2")):
        view = add_view(struct.pack("<%df" % len(data), *data), 34962)
        acc = {"bufferView": view, "componentType": 5126, "count": n, "type": kind}
        if name == "POSITION":
            acc["min"] = [min(pos[i::3]) for i in range(3)]
            acc["max"] = [max(pos[i::3]) for i in range(3)]
        accessors.append(acc)
        attrs[name] = len(accessors) - 1
    view = add_view(struct.pack("<%dH" % len(idx), *idx), 34963)
    accessors.append({"bufferView": view, "componentType": 5123, "count": len(idx), "type": "SCALAR"})
    primitives.append({"attributes": attrs, "indices": len(accessors) - 1, "material": material})

gltf = {
    "asset": {"version": "2.0", "generator": "scenes/assets/make_glass_of_water.py"},
    "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"],
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"name": "glass of water", "mesh": 0}],
    "meshes": [{"name": "glass of water", "primitives": primitives}],
    "materials": [
        {"name": "Glass", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.5},
                        "KHR_materials_volume": {"thicknessFactor": 0.02}}},
        {"name": "Water", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.33},
                        "KHR_materials_volume": {"thicknessFactor": 0.55, "attenuationDistance": 1.0,
                                                 "attenuationColor": [0.75, 0.93, 1.0]}}},
        {"name": "Label", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
         "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 0.9}},
    ],
    "textures": [{"source": 0, "sampler": 0}],
    "samplers": [{"magFilter": 9729, "minFilter": 9987}],
    "images": [{"name": "label", "uri": "data:image/png;base64," + base64.b64encode(label_texture()).decode()}],
    "buffers": [{"byteLength": len(buf),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}],
    "bufferViews": views,
    "accessors": accessors,
}
open("glass_of_water.gltf", "w").write(json.dumps(gltf) + "\n")
