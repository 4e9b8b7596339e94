# A glTF file is a scene without a script (issue 51): render, record, info
# and reference take FILE.gltf or FILE.glb and run lua/caustica/gltf_scene.lua
# for it: its camera (or one framing it), its lights (or a sun), a floor,
# a default graph, its animations on the scene clock.
source "$(dirname "$0")/lib.sh"
K=scenes/assets/khronos

# every glTF file the project carries renders without a script
for f in $(find $K -name "*.glb" -o -name "*.gltf" | sort); do
  n=$(basename "$f")
  if "$CAUSTICA" render "$f" --size 32x32 -o "$WORK/$n.png" -q >"$WORK/log" 2>&1 && [ -s "$WORK/$n.png" ]; then
    pass "render $n with no script"
  else
    fail "render $n with no script" "$(grep -v warning "$WORK/log" | head -1)"
  fi
done

# info says what was chosen: the graph, the animation's frames
"$CAUSTICA" info $K/BoxAnimated/BoxAnimated.glb >"$WORK/info" 2>&1
grep -q "89 frames at 24 fps" "$WORK/info" && grep -q "shadow_map" "$WORK/info" && grep -q " shade " "$WORK/info" \
  && pass "info BoxAnimated.glb: 89 frames at 24 fps (3.708 s), shadow map and shade" \
  || fail "info BoxAnimated.glb" "$(head -3 "$WORK/info")"
"$CAUSTICA" info $K/GlassHurricaneCandleHolder/GlassHurricaneCandleHolder.glb >"$WORK/info" 2>&1
grep -q "photon_caustics" "$WORK/info" && grep -q "refraction" "$WORK/info" \
  && pass "info of a file with glass: photon caustics and refraction chosen" \
  || fail "info of a file with glass" "$(head -3 "$WORK/info")"

"$CAUSTICA" info $K/BoxAnimated/BoxAnimated.glb --fps 10 >"$WORK/info" 2>&1
grep -q "37 frames at 10 fps" "$WORK/info" && pass "info --fps 10: the animation's 3.708 s in 37 frames" \
  || fail "info --fps 10" "$(head -1 "$WORK/info")"

# info --script writes the script the file is rendered with: saved and
# rendered as any script, the same image
"$CAUSTICA" info $K/BoxAnimated/BoxAnimated.glb --script >"$WORK/box.lua" 2>"$WORK/err"
"$CAUSTICA" render "$WORK/box.lua" --size 48x48 --frame 30 -o "$WORK/s30.pfm" -q 2>>"$WORK/err"
"$CAUSTICA" render $K/BoxAnimated/BoxAnimated.glb --size 48x48 --frame 30 -o "$WORK/g30.pfm" -q 2>>"$WORK/err"
line=$("$CAUSTICA" compare "$WORK/s30.pfm" "$WORK/g30.pfm" 2>&1 | tail -1)
[ "$(metric rmse "$line")" = 0 ] && pass "info --script: the written script renders the same image" \
  || fail "info --script" "$line $(head -2 "$WORK/err")"
expect_error "info --script of a script" 2 "info --script writes the script of a glTF file" - -- \
  "$CAUSTICA" info tests/scenes/passes.lua --script

# the animation plays: frame 0 and frame 30 (1.25 s, the inner box risen) differ
"$CAUSTICA" render $K/BoxAnimated/BoxAnimated.glb --size 48x48 --frame 0 -o "$WORK/f0.pfm" -q
"$CAUSTICA" render $K/BoxAnimated/BoxAnimated.glb --size 48x48 --frame 30 -o "$WORK/f30.pfm" -q
line=$("$CAUSTICA" compare "$WORK/f30.pfm" "$WORK/f0.pfm" 2>&1 | tail -1)
rel=$(metric rel_rmse "$line")
awk -v r="$rel" 'BEGIN { exit !(r > 0.02) }' && pass "frame 30 differs from frame 0 (rel_rmse $rel)" \
  || fail "the animation moves nothing" "$line"
"$CAUSTICA" record $K/BoxAnimated/BoxAnimated.glb --size 32x32 --frame-count 3 -o "$WORK/rec" -q >/dev/null 2>&1
[ "$(ls "$WORK/rec" | wc -l)" = 3 ] && pass "record writes the file's frames" || fail "record" "$(ls "$WORK/rec")"

# the camera by number; a camera the file lacks is an error naming what it has
"$CAUSTICA" render $K/Cameras/Cameras.gltf --size 48x48 -o "$WORK/c1.pfm" -q
"$CAUSTICA" render $K/Cameras/Cameras.gltf --size 48x48 --set camera=2 -o "$WORK/c2.pfm" -q
line=$("$CAUSTICA" compare "$WORK/c2.pfm" "$WORK/c1.pfm" 2>&1 | tail -1)
rel=$(metric rel_rmse "$line")
awk -v r="$rel" 'BEGIN { exit !(r > 0.02) }' && pass "--set camera=2: the orthographic camera's view (rel_rmse $rel)" \
  || fail "--set camera=2 changes nothing" "$line"
expect_error "a camera the file lacks" 1 "Cameras.gltf: --set camera=9: the file has no such camera (it has 2" \
  "$WORK/c9.png" -- "$CAUSTICA" render $K/Cameras/Cameras.gltf --set camera=9 -o "$WORK/c9.png"

# the reference renders the same scene
"$CAUSTICA" reference $K/Cameras/Cameras.gltf --size 32x32 --time-budget 0.5 -o "$WORK/ref.pfm" -q >/dev/null 2>&1 \
  && [ -s "$WORK/ref.pfm" ] && pass "reference Cameras.gltf" || fail "reference Cameras.gltf" "no image"
finish
