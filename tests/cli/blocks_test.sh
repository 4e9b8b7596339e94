# The graph's building blocks (issue 26): three caustics passes for one
# light draw the receiver G-buffer once, the two layered techniques build
# the light's depth layers once (counted from --timings' draws), the same
# blocks named in the script give the same image, blocks of different
# sizes stay apart, and a layer set is refused where an image is read.
source "$(dirname "$0")/lib.sh"
S=tests/scenes/shared_blocks.lua
"$CAUSTICA" render $S --timings --size 64x64 -o "$WORK/a.pfm" >"$WORK/t.txt" 2>&1 || fail "render" "$(cat "$WORK/t.txt")"
rows() { grep -cE "^$1 +$2 " "$WORK/t.txt"; }
draws() { awk -v n="$1" '$1 == n { print $4 }' "$WORK/t.txt"; }
[ "$(rows receivers receivers)" = 1 ] && [ "$(grep -cE '^[a-z_0-9]+ +receivers ' "$WORK/t.txt")" = 1 ] \
  && [ "$(draws receivers)" = 2 ] \
  && pass "three caustics passes: one receiver G-buffer, 2 draws (the floor and the box)" \
  || fail "one receiver G-buffer" "$(cat "$WORK/t.txt")"
# the refractors (the ball and the water) drawn three times (bounds, voxels, attributes) by one layer set
[ "$(grep -cE '^[a-z_0-9]+ +depth_layers ' "$WORK/t.txt")" = 2 ] && [ "$(draws depth_layers)" = 6 ] \
  && [ "$(draws depth_layers_2)" = 6 ] \
  && [ "$(draws beams)" != "" ] && ! grep -qE "^(beams|layered) .* (bounds|voxelize)" "$WORK/t.txt" \
  && pass "beam_caustics and layered_caustics for one light: its layers built once (6 refractor draws); the camera's for layered_refraction" \
  || fail "one layer set" "$(cat "$WORK/t.txt")"
"$CAUSTICA" info $S --no-render >"$WORK/i.txt" 2>&1
grep -q "added by the graph for 'volumes': a building block" "$WORK/i.txt" \
  && grep -q "receivers.position (rgba32f)" "$WORK/i.txt" && grep -q "depth_layers.layers (layer_set)" "$WORK/i.txt" \
  && pass "info shows the blocks, what they make and for whom" || fail "info" "$(cat "$WORK/i.txt")"
"$CAUSTICA" render $S --set explicit=true --timings --size 64x64 -o "$WORK/b.pfm" >"$WORK/e.txt" 2>&1
out=$("$CAUSTICA" compare "$WORK/a.pfm" "$WORK/b.pfm")
rel=$(sed -n 's/.*rel_rmse=\([^ ]*\).*/\1/p' <<<"$out")
[ "$(grep -cE '^[a-z_0-9]+ +(receivers|depth_layers) ' "$WORK/e.txt")" = 3 ] && grep -qE "^recv +receivers " "$WORK/e.txt" \
  && awk -v r="$rel" 'BEGIN { exit !(r < 1e-5) }' \
  && pass "the blocks named in the script: no others added, the same image (rel $rel)" \
  || fail "explicit blocks" "$out $(cat "$WORK/e.txt")"
"$CAUSTICA" render $S --set buffer=128 --timings --size 64x64 -o "$WORK/c.pfm" >"$WORK/c.txt" 2>&1
[ "$(grep -cE '^depth_layers(_[23])? +depth_layers ' "$WORK/c.txt")" = 3 ] \
  && pass "the light's layers at two sizes: two sets, and the camera's" || fail "two sizes" "$(cat "$WORK/c.txt")"
cat >"$WORK/bad.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1, 2}, target = {0, 0, 0} } }
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.3 }, material = c.material.glass {} })
local g = c.graph()
g:add("L", c.pass.depth_layers { light = sun })
local read = c.param("read", "L.layers")
if c.param("beams", false) then
  g:add("shade", c.pass.shade {})
  g:add("beams", c.pass.beam_caustics { light = sun, light_layers = "shade.color" })
  g:output("beams.irradiance")
  return { scene = scene, graph = g, size = {16, 16} }
end
g:add("shade", c.pass.shade { caustics = read ~= "none" and read or nil })
g:output(c.param("out", "shade.color"))
return { scene = scene, graph = g, size = {16, 16} }
LUA
expect_error "a layer set read as an image" 1 "reads caustics0 = 'L.layers', which is a layer_set, where a texture is expected" \
  "$WORK/x.png" -- "$CAUSTICA" render "$WORK/bad.lua" --trusted -o "$WORK/x.png"
expect_error "a layer set as the graph's output" 1 "graph output 'L.layers' is a layer_set, not an image" \
  "$WORK/y.png" -- "$CAUSTICA" render "$WORK/bad.lua" --trusted --set read=none --set out=L.layers -o "$WORK/y.png"
expect_error "an image where a layer set is read" 1 "reads light_layers = 'shade.color', which is a texture, where a layer_set is expected" \
  "$WORK/z.png" -- "$CAUSTICA" render "$WORK/bad.lua" --trusted --set beams=true -o "$WORK/z.png"
# (after the scene's own warning: caustic_volumes leaves the glass ball out)
"$CAUSTICA" render $S --size 32x32 --aov depth_layers.layers -o "$WORK/w.exr" >"$WORK/w.txt" 2>&1
rc=$?
[ $rc = 1 ] && grep -q "^caustica: --aov depth_layers.layers: a layer_set, not an image" "$WORK/w.txt" && [ ! -e "$WORK/w.exr" ] \
  && pass "--aov of a layer set refused" || fail "--aov of a layer set" "rc $rc: $(cat "$WORK/w.txt")"
# Reuse by version: with the light turning, the receivers (camera and
# geometry still) are reused and the light's layers made again; the
# recorded frame 3 equals a fresh render of frame 3 bit for bit.
M="scenes/compare_caustics.lua --set technique=layered --set moving=true"
"$CAUSTICA" info $M --size 48x48 >"$WORK/m.txt" 2>&1
grep -qE "^ 2  receivers +receivers +kept; on frame 1 reuses its outputs" "$WORK/m.txt" \
  && grep -qE "^ 3  depth_layers +depth_layers +kept; runs every frame" "$WORK/m.txt" \
  && pass "a turning light: the receivers reused, the light's layers made again" || fail "reuse" "$(cat "$WORK/m.txt")"
"$CAUSTICA" record $M --size 48x48 --frames 0-3 -o "$WORK/rec_####.pfm" >/dev/null 2>&1
"$CAUSTICA" render $M --size 48x48 --frame 3 -o "$WORK/fresh.pfm" >/dev/null 2>&1
out=$("$CAUSTICA" compare "$WORK/rec_0003.pfm" "$WORK/fresh.pfm" 2>&1)
grep -q "rmse=0 " <<<"$out" && pass "reused blocks: frame 3 recorded = frame 3 rendered alone" || fail "reused blocks" "$out"
# A light the scene does not hold: every pass alike makes nothing and says so
# once (three used to refuse it and three to render zero without a word).
cat >"$WORK/nolight.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1, 2}, target = {0, 0, 0} } }
local sun = scene:add(c.light.directional { direction = {0, -1, 0.2}, intensity = {1, 1, 1} })
local lamp = c.light.point { position = {0, 2, 0}, intensity = {3, 3, 3} } -- never added
scene:add(c.object { mesh = c.mesh.plane { size = 3 }, position = {0, -0.5, 0}, material = c.material.diffuse {} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.3 }, material = c.material.glass {} })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun })
g:add("lamp_shadow", c.pass.shadow_map { light = lamp })
g:add(c.param("kind", "photon_caustics"), c.pass[c.param("kind", "photon_caustics")] { light = lamp })
g:add("shade", c.pass.shade { shadow = { "shadow.depth", "lamp_shadow.depth" },
                              caustics = c.param("kind", "photon_caustics") .. ".irradiance", specular = false })
g:add("glass", c.pass.refraction { color = "shade.color" })
g:output("glass.color")
return { scene = scene, graph = g, size = {32, 32} }
LUA
for k in photon_caustics layered_caustics beam_caustics; do
  "$CAUSTICA" render "$WORK/nolight.lua" --trusted --set kind=$k -o "$WORK/nl_$k.png" >"$WORK/nl.txt" 2>&1
  rc=$?
  [ $rc = 0 ] && [ -s "$WORK/nl_$k.png" ] \
    && [ "$(grep -c "pass '$k' ($k): its light is not among the scene's lights, so it makes nothing" "$WORK/nl.txt")" = 1 ] \
    && [ "$(grep -c "pass 'lamp_shadow' (shadow_map): its light is not among the scene's lights" "$WORK/nl.txt")" = 1 ] \
    && pass "$k and a shadow map of a light not in the scene: rendered, one warning each" \
    || fail "$k of a light not in the scene" "rc $rc: $(cat "$WORK/nl.txt")"
done
# a block the script names is shared with a reader that names none (issue 54): the script's
# depth_layers for the sun serves layered_caustics too, and the graph adds no second one
"$CAUSTICA" info tests/scenes/graph_checks.lua --set case=twice --no-render >"$WORK/tw.txt" 2>&1
"$CAUSTICA" info tests/scenes/graph_checks.lua --set case=twice --set buffer=128 --no-render >"$WORK/tw2.txt" 2>&1
[ "$(grep -cE "^ +[0-9]+ +[a-z_0-9]+ +depth_layers " "$WORK/tw.txt")" = 1 ] \
  && grep -qE "in  light_layers <- mylayers.layers" <(sed -n '/ caustics /,/out caustics/p' "$WORK/tw.txt") \
  && [ "$(grep -cE "^ +[0-9]+ +[a-z_0-9]+ +depth_layers " "$WORK/tw2.txt")" = 2 ] \
  && pass "the script's depth_layers serves a reader with the same light and size; at another size the graph adds its own" \
  || fail "a script's block shared" "$(cat "$WORK/tw.txt" "$WORK/tw2.txt")"
finish
