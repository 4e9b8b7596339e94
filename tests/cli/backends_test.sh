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
else
  fail "window" "xvfb-run is not installed (make deps installs it)"
fi
# Without a display the window verb fails cleanly.
expect_error "no display" 1 "cannot open a window" - -- env -u DISPLAY -u WAYLAND_DISPLAY "$CAUSTICA" run scenes/demo.lua --frames 1
finish
