# One scene through OSMesa, EGL and a GLFW window (under xvfb-run): the
# same pixels, RMSE at most 1/255.
source "$(dirname "$0")/lib.sh"
max=$(awk 'BEGIN { print 1 / 255 }')
"$CAUSTICA" render scenes/demo.lua --frame 20 --size 128x128 -o "$WORK/osmesa.png" || fail "osmesa render" "failed"
"$CAUSTICA" render scenes/demo.lua --frame 20 --size 128x128 --backend egl -o "$WORK/egl.png" || fail "egl render" "failed"
line=$("$CAUSTICA" compare "$WORK/osmesa.png" "$WORK/egl.png")
rmse=$(metric rmse "$line")
awk "BEGIN { exit !($rmse <= $max) }" && pass "EGL == OSMesa ($line)" || fail "EGL == OSMesa" "$line"
if command -v xvfb-run >/dev/null; then
  xvfb-run -a "$CAUSTICA" run scenes/demo.lua --frames 21 --size 128x128 --screenshot "$WORK/window.png" 2>"$WORK/err" \
    || fail "window run" "$(cat "$WORK/err")"
  line=$("$CAUSTICA" compare "$WORK/osmesa.png" "$WORK/window.png")
  rmse=$(metric rmse "$line")
  awk "BEGIN { exit !($rmse <= $max) }" && pass "window == OSMesa ($line)" || fail "window == OSMesa" "$line"
  # The keyboard, as scripted input: two steps forward (which pause) and a
  # screenshot of frame 2 (the same image as frame 2 rendered offscreen) into the folder run was
  # started from, not next to the script (a shipped scene's folder is the install prefix).
  mkdir -p "$WORK/scripts" "$WORK/shots"
  cp tests/scenes/deform.lua "$WORK/scripts/keys.lua"
  (cd "$WORK/shots" && xvfb-run -a "$CAUSTICA" run "$WORK/scripts/keys.lua" --frames 3 --size 48x48 --keys right,right,s) \
    2>"$WORK/keys.err" || fail "window keys" "$(cat "$WORK/keys.err")"
  "$CAUSTICA" render "$WORK/scripts/keys.lua" --frame 2 --size 48x48 -o "$WORK/frame2.png" >/dev/null 2>&1
  line=$("$CAUSTICA" compare "$WORK/shots/keys_frame_0002.png" "$WORK/frame2.png" 2>&1)
  grep -q "wrote keys_frame_0002.png" "$WORK/keys.err" && rmse=$(metric rmse "$line") && [ "$(ls "$WORK/scripts")" = keys.lua ] \
    && awk "BEGIN { exit !($rmse <= $max) }" && pass "right, right, s: frame 2 saved in the current folder, not the script's" \
    || fail "window keys" "$(cat "$WORK/keys.err") $line"
  expect_error "an unknown key" 2 "--keys: unknown key 'q'" - -- "$CAUSTICA" run "$WORK/keys.lua" --keys right,q
  # --frames N on a still loops over its one frame (it said "frame 1 is past the last frame" before)
  xvfb-run -a "$CAUSTICA" run tests/scenes/cutout.lua --frames 3 --screenshot "$WORK/still.png" 2>"$WORK/still.err" &&
    "$CAUSTICA" render tests/scenes/cutout.lua -o "$WORK/still_offscreen.png" -q 2>/dev/null &&
    rmse=$(metric rmse "$("$CAUSTICA" compare "$WORK/still.png" "$WORK/still_offscreen.png")") &&
    awk "BEGIN { exit !($rmse <= $max) }" && pass "run --frames 3 on a still shows its frame" \
    || fail "run a still" "$(cat "$WORK/still.err")"
else
  fail "window" "xvfb-run is not installed (make deps installs it)"
fi
# Without a display the window verb fails cleanly.
expect_error "no display" 1 "cannot open a window" - -- env -u DISPLAY -u WAYLAND_DISPLAY "$CAUSTICA" run scenes/demo.lua --frames 1
finish
