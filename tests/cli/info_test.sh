# `caustica info` lists every pass as kept or left out, with the reason.
source "$(dirname "$0")/lib.sh"
"$CAUSTICA" info tests/scenes/passes.lua --set mode=prune >"$WORK/prune.txt" 2>&1
grep -q "unused           environment      left out: contributes nothing to the output 'shade.color'" "$WORK/prune.txt" \
  && pass "unused pass left out with reason" || fail "unused pass" "$(cat "$WORK/prune.txt")"
grep -q "shade            shade            kept" "$WORK/prune.txt" && pass "output pass kept" || fail "output pass kept" "$(cat "$WORK/prune.txt")"
# The demo's light moves: its shadow map runs every frame.
"$CAUSTICA" info scenes/demo.lua --size 64x64 >"$WORK/demo.txt" 2>&1
grep -q "shadow .*runs every frame" "$WORK/demo.txt" && pass "moving light: shadow map redrawn" \
  || fail "moving light" "$(cat "$WORK/demo.txt")"
grep -q "in  shadow0      <- shadow.depth" "$WORK/demo.txt" && pass "inputs listed" || fail "inputs listed" "$(cat "$WORK/demo.txt")"
# A caustics pass the scene does not ask for (its sun below the horizon) is left out, with the reason.
"$CAUSTICA" info tests/scenes/flat_water.lua --set elevation=-10 >"$WORK/water.txt" 2>&1
grep -q "cv .*kept, but does nothing on frame 0: the light is below the horizon" "$WORK/water.txt" && pass "caustics left out when not needed" \
  || fail "caustics left out" "$(cat "$WORK/water.txt")"
"$CAUSTICA" render scenes/demo.lua --size 64x64 --timings -o "$WORK/t.png" >"$WORK/timings.txt" 2>&1
grep -qE "^shade +shade +[0-9.]+ +[0-9]+ +[0-9]+$" "$WORK/timings.txt" && grep -qE "^total" "$WORK/timings.txt" \
  && pass "--timings prints per-pass milliseconds, draws and triangles" || fail "--timings" "$(cat "$WORK/timings.txt")"
# the layered passes name their stages, and draw the refractor three times per view (the light's
# view in the depth_layers block the graph adds for layered_caustics, its receivers in another,
# the camera's in the one it adds for layered_refraction, the floor's impostor in the impostors
# block it adds for it (issue 54), and layered_refraction itself none: it traces them full-screen)
"$CAUSTICA" render scenes/chaudhari_fig45.lua --size 64x64 --timings -o "$WORK/t.png" >"$WORK/timings.txt" 2>&1
grep -qE "^glass +layered_refraction +[0-9.]+ +0 +" "$WORK/timings.txt" && grep -qE "^impostors +impostors +[0-9.]+ +1 +" "$WORK/timings.txt" && grep -qE "^depth_layers_2 +depth_layers +[0-9.]+ +3 +" "$WORK/timings.txt" && grep -qE "^  trace +[0-9.]+$" "$WORK/timings.txt" \
  && grep -qE "^  voxelize +[0-9.]+$" "$WORK/timings.txt" && grep -qE "^caustics +layered_caustics +[0-9.]+ +0 +" "$WORK/timings.txt" \
  && grep -qE "^depth_layers +depth_layers +[0-9.]+ +3 +" "$WORK/timings.txt" \
  && grep -qE "^receivers +receivers +[0-9.]+ +1 +" "$WORK/timings.txt" \
  && pass "--timings: the layered passes' draws and stages" || fail "--timings (layered)" "$(cat "$WORK/timings.txt")"
# illumination textures: reused on a camera orbit, made again when the light turns
"$CAUSTICA" info scenes/iwasaki_fig1.lua --size 64x48 >"$WORK/info.txt" 2>&1
grep -q "caustics .*illumination textures are reused (light, glass and targets unchanged" "$WORK/info.txt" \
  && grep -q "transport tables: 1, 1225 vertices x 256 directions" "$WORK/info.txt" \
  && pass "info: illumination textures reused when only the camera moves, with the table's size" \
  || fail "info (illumination textures, camera)" "$(cat "$WORK/info.txt")"
"$CAUSTICA" info scenes/iwasaki_fig1.lua --size 64x48 --set moving=light >"$WORK/info.txt" 2>&1
grep -q "illumination textures are made again" "$WORK/info.txt" \
  && pass "info: illumination textures made again when the light moves" \
  || fail "info (illumination textures, light)" "$(cat "$WORK/info.txt")"
# the transport tables' disk cache: traced once, read back, traced again when damaged
export CAUSTICA_CACHE="$WORK/cache"
"$CAUSTICA" info scenes/iwasaki_fig1.lua --size 64x48 >"$WORK/info1.txt" 2>&1
"$CAUSTICA" info scenes/iwasaki_fig1.lua --size 64x48 >"$WORK/info2.txt" 2>&1
for f in "$WORK"/cache/transport/*.table; do printf 'garbage' | dd of="$f" bs=1 seek=100 conv=notrunc 2>/dev/null; done
"$CAUSTICA" info scenes/iwasaki_fig1.lua --size 64x48 >"$WORK/info3.txt" 2>&1
grep -q "10.8 MB, traced in" "$WORK/info1.txt" && grep -q "10.8 MB, read from the cache in" "$WORK/info2.txt" \
  && grep -q "10.8 MB, traced in" "$WORK/info3.txt" \
  && pass "transport tables: traced, then read from the disk cache, traced again when the file is damaged" \
  || fail "transport table cache" "$(cat "$WORK/info1.txt" "$WORK/info2.txt" "$WORK/info3.txt" | grep transport)"
unset CAUSTICA_CACHE
# A still says what its one frame does, not what a next frame would reuse.
"$CAUSTICA" info tests/scenes/fog.lua --size 16x16 >"$WORK/still.txt" 2>&1
grep -q "shade            shade            kept; runs once (a still)" "$WORK/still.txt" && ! grep -q "since the last frame" "$WORK/still.txt" \
  && pass "a still: runs once" || fail "a still" "$(cat "$WORK/still.txt")"
# Photons of a static scene are traced once and reused; without glass the pass does nothing (one clear line).
cat >"$WORK/static_photons.lua" <<'LUA'
local c = require "caustica"
local glass = c.param("glass", true)
local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0, 0} } }
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -1, 0} })
if glass then scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, material = c.material.glass { ior = 1.5 } }) end
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 64 })
g:add("photons", c.pass.photon_caustics { light = sun, buffer = 32, texture = 32 })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "photons.irradiance" })
g:output("shade.color")
local update = c.param("orbit", false) and function(t) scene.camera.eye = {3 * math.sin(t), 1, 3 * math.cos(t)} end or nil
return { scene = scene, graph = g, size = {16, 16}, frames = 4, update = update }
LUA
"$CAUSTICA" info "$WORK/static_photons.lua" >"$WORK/photons.txt" 2>&1
grep -A1 "photons          photon_caustics  kept; runs every frame" "$WORK/photons.txt" \
  | grep -q "on frame 1: the photon buffer and caustic textures reused" \
  && pass "static photons: reused, said so" || fail "static photons" "$(cat "$WORK/photons.txt")"
# Only the camera moves: the photons are kept, the caustic textures made
# again over the box the camera now sees (window.glsl).
"$CAUSTICA" info "$WORK/static_photons.lua" --set orbit=true >"$WORK/orbit.txt" 2>&1
grep -A1 "photons          photon_caustics  kept; runs every frame" "$WORK/orbit.txt" \
  | grep -q "on frame 1: the photon buffer and caustic textures reused.*; the caustic textures rebuilt for the camera's view" \
  && pass "photons under an orbiting camera: traced once, textures rebuilt, said so" \
  || fail "photons under an orbiting camera" "$(cat "$WORK/orbit.txt")"
# A static light and static casters over several frames: the shadow map is reused on frame 1.
grep -q "shadow .*on frame 1 reused: the light and the casters did not change" "$WORK/photons.txt" \
  && pass "static shadow map reused" || fail "static shadow reuse" "$(cat "$WORK/photons.txt")"
"$CAUSTICA" info "$WORK/static_photons.lua" --set glass=false >"$WORK/noglass.txt" 2>&1
grep -q "photons          photon_caustics  kept, but does nothing on frame 1: no refractive or reflective object" "$WORK/noglass.txt" \
  && pass "no glass: the photon pass does nothing, one line" || fail "no glass" "$(cat "$WORK/noglass.txt")"
# Glass behind the camera: the refraction passes pass the image through, and say why.
cat >"$WORK/behind.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0.5, 2}, target = {0, 0.3, 5} }, background = {0.2, 0.3, 0.4} }
local sun = scene:add(c.light.directional { direction = {0, -1, 0.3}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 40 }, position = {0, -1, 0} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shade", c.pass.shade { specular = false })
g:add("glass", c.pass.refraction { color = "shade.color" })
g:add("layered", c.pass.layered_refraction { color = "glass.color", depth = "shade.depth" })
g:output(c.param("out", "layered.color"))
return { scene = scene, graph = g, size = {32, 32} }
LUA
"$CAUSTICA" info "$WORK/behind.lua" >"$WORK/behind.txt" 2>&1
grep -q "glass            refraction       kept; runs once (a still): passes the image through: no refractive object in the camera's view" "$WORK/behind.txt" \
  && grep -q "layered          layered_refraction kept; runs once (a still): passes the image through: no glass or water in the camera's view" "$WORK/behind.txt" \
  && pass "glass behind the camera: the refraction passes say they pass the image through" || fail "glass behind" "$(cat "$WORK/behind.txt")"
"$CAUSTICA" render "$WORK/behind.lua" -o "$WORK/behind.pfm" >/dev/null 2>&1 \
  && "$CAUSTICA" render "$WORK/behind.lua" --set out=shade.color -o "$WORK/shade.pfm" >/dev/null 2>&1 \
  && line=$("$CAUSTICA" compare "$WORK/behind.pfm" "$WORK/shade.pfm") && grep -q "rmse=0 " <<<"$line" \
  && pass "... and the image is the shaded one, unchanged" || fail "pass-through image" "${line:-render failed}"
# Mistakes that render without an error: glass no pass draws, caustics for an unshadowed light.
cat >"$WORK/undrawn.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0, 0} } }
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -1, 0} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("photons", c.pass.photon_caustics { light = sun, buffer = 32, texture = 32 })
g:add("shade", c.pass.shade { caustics = "photons.irradiance", specular = false })
g:output("shade.color")
return { scene = scene, graph = g, size = {16, 16} }
LUA
"$CAUSTICA" info "$WORK/undrawn.lua" >"$WORK/undrawn.txt" 2>&1
grep -q "^warning: object 2 (glass) is drawn by no pass" "$WORK/undrawn.txt" \
  && grep -q "^warning: pass 'shade' adds the caustics of 'photons' for a light it does not shadow" "$WORK/undrawn.txt" \
  && pass "info warns of undrawn glass and of caustics for an unshadowed light" || fail "lint in info" "$(cat "$WORK/undrawn.txt")"
"$CAUSTICA" render "$WORK/undrawn.lua" -o "$WORK/undrawn.png" >/dev/null 2>"$WORK/undrawn.err"
[ "$(grep -c "drawn by no pass" "$WORK/undrawn.err")" = 1 ] && pass "render warns once" || fail "render warning" "$(cat "$WORK/undrawn.err")"
# Why the caustics passes stay on with the glass out of view: its caustics land in view.
cat >"$WORK/offscreen.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0.3, 0}, target = {0, -1, 0}, up = {0, 0, -1}, fov = 60 } }
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 8 }, position = {0, -1, 0} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, position = {0, 1.2, 0}, material = c.material.glass { ior = 1.5 } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun, size = 256 })
g:add("caustics", c.pass.photon_caustics { light = sun, buffer = 64, texture = 128 })
g:add("shade", c.pass.shade { shadow = "shadow.depth", caustics = "caustics.irradiance" })
g:output(c.param("out", "shade.color"))
return { scene = scene, graph = g, size = {32, 32} }
LUA
"$CAUSTICA" render "$WORK/offscreen.lua" --set out=caustics.irradiance -o "$WORK/offscreen.pfm" >/dev/null 2>&1
python3 - "$WORK/offscreen.pfm" <<'PY' && pass "glass above the view still casts caustics into it" || fail "off-screen caustics" "none in view"
import struct, sys
data = open(sys.argv[1], "rb").read()
body = data.split(b"\n", 3)[3]
values = struct.unpack("<%df" % (len(body) // 4), body)
sys.exit(0 if max(values) > 0.05 else 1)
PY
# a depth range the depth buffer cannot resolve at the scene is said once; an
# orthographic camera's tiny near plane is harmless and says nothing
"$CAUSTICA" info tests/scenes/ortho.lua --set ortho=false --set near=1e-5 --no-render >"$WORK/near.txt" 2>&1
[ "$(grep -c "the camera's near and far planes (1e-05, 100) resolve depth only to" "$WORK/near.txt")" = 1 ] \
  && pass "a perspective near plane of 1e-5: one warning" || fail "near 1e-5" "$(cat "$WORK/near.txt")"
"$CAUSTICA" info tests/scenes/ortho.lua --set far=1e6 --no-render >"$WORK/far.txt" 2>&1
grep -q "near and far planes (0.05, 1e+06)" "$WORK/far.txt" && pass "an orthographic far plane of 1e6: a warning" \
  || fail "far 1e6" "$(cat "$WORK/far.txt")"
"$CAUSTICA" info tests/scenes/ortho.lua --set near=1e-5 --no-render >"$WORK/ortho.txt" 2>&1
! grep -q "near and far planes" "$WORK/ortho.txt" && pass "an orthographic near plane of 1e-5: no warning" \
  || fail "ortho near" "$(cat "$WORK/ortho.txt")"
finish
