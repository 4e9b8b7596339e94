#!/usr/bin/env python3
"""Writes bad_scene_*.gltf (run from tests/data; standard library only):
glTF files whose node tree, cameras or animations are wrong in one way
each, for tests/cli/gltf_scene_errors_test.sh (issue 51). Each holds one
triangle, so only the fault named in its file name is wrong."""
import json, struct

from gltf_bits import data_uri

NAN = struct.unpack("<f", b"\x00\x00\xc0\x7f")[0]


def scene(nodes, animations=None, cameras=None, times=(0.0, 1.0), outputs=(0, 0, 0, 1, 0, 0), extra=None):
    tri = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    t = struct.pack("<%df" % len(times), *times)
    o = struct.pack("<%df" % len(outputs), *outputs)
    buf = tri + t + o
    doc = {
        "asset": {"version": "2.0", "generator": "tests/data/make_bad_scenes.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"byteLength": len(buf), "uri": data_uri("application/octet-stream", buf)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": len(t)},
                        {"buffer": 0, "byteOffset": 36 + len(t), "byteLength": len(o)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": len(times), "type": "SCALAR"},
                      {"bufferView": 2, "componentType": 5126, "count": len(outputs) // 3, "type": "VEC3"}],
    }
    if animations is not None:
        doc["animations"] = animations
    if cameras is not None:
        doc["cameras"] = cameras
    if extra:
        extra(doc)
    return doc


def move(output=2, path="translation"):
    return [{"name": "move", "channels": [{"sampler": 0, "target": {"node": 0, "path": path}}],
             "samplers": [{"input": 1, "output": output, "interpolation": "LINEAR"}]}]


def huge(doc):
    # an output with no buffer view is all zeros, legal glTF; 3 million of
    # them are more than a file of a few hundred bytes can describe
    doc["accessors"].append({"componentType": 5126, "count": 3000000, "type": "SCALAR"})
    doc["accessors"][1]["count"] = 2
    doc["animations"][0]["samplers"][0]["input"] = 3


def skinned(joint_nodes, joints_used, ibm_count):
    """One triangle skinned to joints_used (each vertex to one), a skin of
    joint_nodes with ibm_count inverse bind matrices (identity)."""
    def extra(doc):
        j = struct.pack("<12B", *([joints_used, 0, 0, 0] * 3))
        w = struct.pack("<12f", *([1.0, 0, 0, 0] * 3))
        ibm = struct.pack("<%df" % (16 * ibm_count), *([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] * ibm_count))
        extra_buf = j + w + ibm
        doc["buffers"].append({"byteLength": len(extra_buf), "uri": data_uri("application/octet-stream", extra_buf)})
        views = [(0, 12), (12, 48), (60, len(ibm))]
        for off, ln in views:
            doc["bufferViews"].append({"buffer": 1, "byteOffset": off, "byteLength": ln})
        base = len(doc["bufferViews"]) - 3
        doc["accessors"] += [{"bufferView": base, "componentType": 5121, "count": 3, "type": "VEC4"},
                             {"bufferView": base + 1, "componentType": 5126, "count": 3, "type": "VEC4"},
                             {"bufferView": base + 2, "componentType": 5126, "count": ibm_count, "type": "MAT4"}]
        a = len(doc["accessors"]) - 3
        doc["meshes"][0]["primitives"][0]["attributes"].update({"JOINTS_0": a, "WEIGHTS_0": a + 1})
        doc["skins"] = [{"joints": joint_nodes, "inverseBindMatrices": a + 2}]
        doc["nodes"][0]["skin"] = 0
    return scene([{"mesh": 0}, {}], extra=extra)


files = {
    "skin_joint_missing": skinned([1, 7], 0, 2),
    "skin_joint_unused": skinned([1], 3, 1),
    "skin_short_ibm": skinned([1, 1], 0, 1),
    "cycle": scene([{"mesh": 0}, {"children": [2]}, {"children": [1]}]),
    "two_parents": scene([{"mesh": 0, "children": [2]}, {"children": [2]}, {}],
                         extra=lambda d: d["scenes"][0]["nodes"].append(1)),
    "deep": scene([{"mesh": 0, "children": [1]}] + [{"children": [i + 2]} for i in range(299)] + [{}]),
    "nan_time": scene([{"mesh": 0}], move(), times=(0.0, NAN)),
    "unsorted_times": scene([{"mesh": 0}], move(), times=(1.0, 0.5)),
    "short_output": scene([{"mesh": 0}], move(), times=(0.0, 1.0, 2.0)),
    "weights_no_targets": scene([{"mesh": 0}], move(path="weights")),
    "huge_keys": scene([{"mesh": 0}], move(), extra=huge),
    "bad_camera": scene([{"mesh": 0}, {"camera": 0}], cameras=[{"type": "perspective",
                                                               "perspective": {"yfov": 0, "znear": 0.1}}],
                        extra=lambda d: d["scenes"][0]["nodes"].append(1)),
}
for name, doc in files.items():
    with open("bad_scene_%s.gltf" % name, "w") as f:
        json.dump(doc, f, indent=1)
