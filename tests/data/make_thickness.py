#!/usr/bin/env python3
"""Writes thickness.gltf (run from tests/data; standard library only): one
quad of glass with a volume (KHR_materials_transmission 1,
KHR_materials_volume thicknessFactor 1, attenuationColor (0.2, 0.5, 0.9) at
attenuationDistance 1) whose thicknessTexture is 2 x 1 texels sampled
nearest: green 0 on the left half (no thickness: nothing absorbed), 255 on
the right (the whole factor). shade's one interface absorbs over the
thickness, so the right half is the left times the attenuation colour
(issue 50: the texture was listed as ignored)."""
import json

from gltf_bits import png, textured_quad

image = png(2, 1, [[0, 0, 0, 0, 255, 0]], False)
material = {"name": "Thick glass", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                           "KHR_materials_volume": {"thicknessFactor": 1, "thicknessTexture": {"index": 0},
                                                    "attenuationColor": [0.2, 0.5, 0.9],
                                                    "attenuationDistance": 1}}}
gltf = textured_quad("tests/data/make_thickness.py", material, image)
gltf["extensionsUsed"] = ["KHR_materials_transmission", "KHR_materials_volume"]
open("thickness.gltf", "w").write(json.dumps(gltf, indent=1) + "\n")
