# Recording: an error in update() at frame 37 keeps frames 0-36 intact and
# leaves no partial file; frame N is the same whichever verb renders it.
source "$(dirname "$0")/lib.sh"

cat >"$WORK/fails_at_37.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0, 0} } }
local lamp = scene:add(c.light.point { position = {0, 3, 0}, intensity = {5, 5, 5} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.5 } })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:output("shade.color")
return { scene = scene, graph = g, size = {32, 32}, frames = 50, fps = 30,
  update = function(t, dt)
    lamp.position = {math.cos(t), 3, math.sin(t)}
    if math.floor(t * 30 + 0.5) == 37 then error("the script fails here") end
  end }
LUA
expect_error "update error at frame 37" 1 "fails_at_37.lua:11: the script fails here (in update, frame 37)" - -- \
  "$CAUSTICA" record "$WORK/fails_at_37.lua" -o "$WORK/frames"
count=$(ls "$WORK/frames" | grep -c '^frame_00[0-3][0-9]\.png$')
others=$(ls "$WORK/frames" | grep -vc '^frame_00[0-3][0-9]\.png$')
[ "$count" = 37 ] && [ "$others" = 0 ] && pass "frames 0-36 on disk, nothing else" \
  || fail "frames 0-36 on disk" "$count frames, $others other files: $(ls "$WORK/frames" | tail -3)"
bad=0
for f in "$WORK"/frames/frame_*.png; do
  "$CAUSTICA" compare "$f" "$f" >/dev/null 2>&1 || bad=$((bad + 1))
done
[ "$bad" = 0 ] && pass "every recorded frame is a complete PNG" || fail "complete PNGs" "$bad unreadable"

# Frame 10 rendered alone equals frame 10 of a recording from 0.
"$CAUSTICA" record scenes/demo.lua -o "$WORK/demo" --frames 0:10 --size 64x64 >/dev/null \
  && "$CAUSTICA" render scenes/demo.lua --frame 10 --size 64x64 -o "$WORK/alone.png" \
  && line=$("$CAUSTICA" compare "$WORK/alone.png" "$WORK/demo/frame_0010.png") \
  && grep -q "rmse=0 " <<<"$line" && pass "frame 10 alone == frame 10 recorded" \
  || fail "frame 10 alone == frame 10 recorded" "${line:-render failed}"
# ... and the light moved and the dinosaur morphed between frames 0 and 10.
line=$("$CAUSTICA" compare "$WORK/demo/frame_0000.png" "$WORK/demo/frame_0010.png")
rmse=$(metric rmse "$line")
awk "BEGIN { exit !($rmse > 0.01) }" && pass "the animation moves (rmse $rmse)" || fail "animation moves" "$line"

# Going back in time reloads the script: frame 3 after frame 10 is frame 3.
"$CAUSTICA" render scenes/demo.lua --frame 3 --size 64x64 -o "$WORK/three.png" \
  && line=$("$CAUSTICA" compare "$WORK/three.png" "$WORK/demo/frame_0003.png") \
  && grep -q "rmse=0 " <<<"$line" && pass "frame 3 == recorded frame 3" || fail "frame 3" "${line:-failed}"

# PFM output is linear float; PNG of the same frame is its tone-mapped copy.
"$CAUSTICA" render scenes/demo.lua --size 64x64 -o "$WORK/d.pfm" && "$CAUSTICA" render scenes/demo.lua --size 64x64 -o "$WORK/d.png" \
  && line=$("$CAUSTICA" compare "$WORK/d.pfm" "$WORK/d.png") \
  && rmse=$(metric rmse "$line") && awk "BEGIN { exit !($rmse < 0.005) }" \
  && pass "PFM and PNG agree (rmse $rmse)" || fail "PFM and PNG agree" "${line:-failed}"
finish
