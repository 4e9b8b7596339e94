#!/usr/bin/env python3
"""A procedural sky as an equirectangular Radiance RGBE (.hdr) file, made for
caustica (CC0): a blue gradient sky, a warm horizon, a dark ground and a
small bright sun, 256x128. Usage: make_sky.py OUT.hdr"""
import math, struct, sys

W, H = 256, 128
SUN = (0.45, 0.55, -0.70)  # direction to the sun (normalised below)
n = math.sqrt(sum(c * c for c in SUN))
SUN = tuple(c / n for c in SUN)

def radiance(d):
    x, y, z = d
    if y < 0:  # ground: dark brown, darker towards the nadir
        g = 0.08 + 0.06 * (1 + y)
        return (g * 1.0, g * 0.8, g * 0.6)
    horizon = math.exp(-8 * y)
    sky = (0.25 + 0.5 * horizon, 0.45 + 0.4 * horizon, 0.95 + 0.1 * horizon)
    c = sum(a * b for a, b in zip(d, SUN))
    sun = 400.0 if c > math.cos(math.radians(2.5)) else 0.0
    glow = 2.0 * max(c, 0) ** 64
    return tuple(s * 0.8 + sun + glow * w for s, w in zip(sky, (1.0, 0.9, 0.7)))

def rgbe(r, g, b):
    m = max(r, g, b)
    if m < 1e-32:
        return b"\0\0\0\0"
    mant, e = math.frexp(m)
    f = mant * 256.0 / m
    return bytes((int(r * f), int(g * f), int(b * f), e + 128))

out = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (H, W))
for j in range(H):
    theta = (j + 0.5) / H * math.pi  # v = acos(y) / pi
    for i in range(W):
        phi = ((i + 0.5) / W - 0.5) * 2 * math.pi  # u = 0.5 + atan2(x, -z) / 2 pi
        d = (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))
        out += rgbe(*radiance(d))
open(sys.argv[1], "wb").write(out)
