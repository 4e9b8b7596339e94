# Inputs typed beyond "a texture" (issue 54): a pass's shadow input takes a
# shadow_map pass's depth and nothing else, said when the graph is checked
# (before, any texture there rendered unshadowed, exit 0, no word).
source "$(dirname "$0")/lib.sh"
cat >"$WORK/shadows.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 2, 3}, target = {0, 0, 0} } }
local sun = scene:add(c.light.directional { direction = {0.3, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -1, 0}, material = c.material.diffuse {} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, material = c.material.glass {} })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun })
g:add("first", c.pass.shade {})
local second = c.param("second", "first.color")
local pass = c.param("pass", "shade")
if pass == "shade" then
  g:add("out", c.pass.shade { shadow = { "shadow.depth", second } })
elseif pass == "refraction" then
  g:add("out", c.pass.refraction { color = "first.color", shadow = second })
else
  g:add("out", c.pass.volume_light { color = "first.color", shadow = second })
end
g:output("out.color")
return { scene = scene, graph = g, size = {32, 32} }
LUA
for pass in shade refraction volume_light; do
  slot=$([ $pass = shade ] && echo "shadow\\[2\\]" || echo "shadow\\[1\\]")
  expect_error "$pass { shadow = a colour image }: refused when the graph is checked" 1 \
    "pass 'out' ($pass) reads" "$WORK/a_$pass.png" -- "$CAUSTICA" render "$WORK/shadows.lua" --set pass=$pass \
    -o "$WORK/a_$pass.png" --trusted
  grep -qE "reads $slot = 'first.color', a texture that is not a shadow_map's" "$WORK/stderr" \
    && pass "$pass: the message names the item and what is expected" || fail "$pass message" "$(cat "$WORK/stderr")"
  "$CAUSTICA" render "$WORK/shadows.lua" --set pass=$pass --set second=shadow.depth -o "$WORK/b_$pass.png" \
    --trusted >"$WORK/b.txt" 2>&1 && pass "$pass: a shadow map's depth is taken" || fail "$pass with a shadow map" "$(cat "$WORK/b.txt")"
done
finish
