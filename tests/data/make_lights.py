#!/usr/bin/env python3
"""Writes lights.gltf and lights_blender.gltf (run from tests/data; standard
library only): one triangle and three KHR_lights_punctual lights on nodes
turned and moved (a directional light of 3 lux, a point light of 683 cd, a
spot of 1366 cd with cones 0.2 and 0.4 rad), written as a tool would
(asset.generator "tests/data/make_lights.py") and as Blender's exporter
says it writes (its sun's lux are W/m^2): tests/lua/gltf_scene_test.lua."""
import json, math, struct

from gltf_bits import data_uri


def doc(generator):
    tri = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    half = math.sqrt(0.5)
    return {
        "asset": {"version": "2.0", "generator": generator},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "Sun", "type": "directional", "intensity": 3.0, "color": [1, 0.5, 0.25]},
            {"name": "Bulb", "type": "point", "intensity": 683.0},
            {"name": "Spot", "type": "spot", "intensity": 1366.0,
             "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.4}}]}},
        "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [{"mesh": 0},
                  # -z turned 90 degrees about x: pointing down -y
                  {"name": "SunNode", "rotation": [-half, 0, 0, half], "extensions": {"KHR_lights_punctual": {"light": 0}}},
                  {"name": "BulbNode", "translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 1}}},
                  # -z turned 90 degrees about y: pointing down -x
                  {"name": "SpotNode", "translation": [0, 4, 0], "rotation": [0, half, 0, half],
                   "extensions": {"KHR_lights_punctual": {"light": 2}}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"byteLength": len(tri), "uri": data_uri("application/octet-stream", tri)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
    }


with open("lights.gltf", "w") as f:
    json.dump(doc("tests/data/make_lights.py"), f, indent=1)
with open("lights_blender.gltf", "w") as f:
    json.dump(doc("Khronos glTF Blender I/O v3.4.50"), f, indent=1)
