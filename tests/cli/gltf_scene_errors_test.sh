# A glTF file read as a scene (c.gltf.load, issue 51) that is wrong in one
# way (tests/data/make_bad_scenes.py) is an error naming the file, the
# script's line and what is wrong: exit 1, no image, no crash.
source "$(dirname "$0")/lib.sh"
O="$WORK/out.png"
D="$ROOT/tests/data"

bad() { # NAME TEXT: bad_scene_NAME.gltf fails with TEXT on the first line
  expect_error "$1" 1 "$2" "$O" -- "$CAUSTICA" render tests/scenes/gltf_file.lua --set path="$D/bad_scene_$1.gltf" -o "$O"
}
bad cycle "gltf_file.lua:8: $D/bad_scene_cycle.gltf: node 1 is its own ancestor (a cycle in the node tree)"
bad two_parents "bad_scene_two_parents.gltf: node 2 is a child of both node 0 and node 1 (glTF allows one parent)"
bad deep "bad_scene_deep.gltf: node 257 lies more than 256 levels deep in the node tree (at most 256)"
bad nan_time "bad_scene_nan_time.gltf: animation 0 ('move') channel 0: keyframe time 1 is not finite"
bad unsorted_times "bad_scene_unsorted_times.gltf: animation 0 ('move') channel 0: keyframe times are not in order (key 1 at 0.500000 s comes before key 0 at 1.000000 s)"
bad short_output "bad_scene_short_output.gltf: animation 0 ('move') channel 0: output holds 2 values, 3 keyframes need 3"
bad weights_no_targets "bad_scene_weights_no_targets.gltf: animation 0 ('move') channel 0: animates the weights of node 0, whose mesh has no morph targets"
bad huge_keys "bad_scene_huge_keys.gltf: animation 0 ('move') channel 0: input: accessor count 3000000 is larger than the file can describe"
bad bad_camera "bad_scene_bad_camera.gltf: camera 0 ('camera 0'): yfov 0.000000 is not in (0, pi) radians"
bad skin_joint_missing "bad_scene_skin_joint_missing.gltf: skin 0 ('skin 0'): joint 1 is node 7, out of range (the file has 2 nodes)"
bad skin_joint_unused "bad_scene_skin_joint_unused.gltf: node 0 ('node 0'): its mesh's JOINTS_0 names joint 3, its skin 0 has 1 joints"
bad skin_short_ibm "bad_scene_skin_short_ibm.gltf: skin 0 ('skin 0'): inverseBindMatrices holds 1 matrices for 2 joints"

# the same file given for a script (no script: lua/caustica/gltf_scene.lua)
expect_error "a bad file with no script" 1 "$D/bad_scene_two_parents.gltf: node 2 is a child of both node 0 and node 1" \
  "$O" -- "$CAUSTICA" render "$D/bad_scene_two_parents.gltf" -o "$O"

# the scene asked for by a name the file does not have
cat >"$WORK/scene_name.lua" <<LUA
local c = require "caustica"
local f = c.gltf.load("$ROOT/scenes/assets/khronos/MultipleScenes/MultipleScenes.gltf", { scene = "Kitchen" })
LUA
expect_error "unknown scene name" 1 "scene_name.lua:2: $ROOT/scenes/assets/khronos/MultipleScenes/MultipleScenes.gltf: no scene named 'Kitchen'" "$O" -- \
  "$CAUSTICA" render "$WORK/scene_name.lua" -o "$O"
finish
