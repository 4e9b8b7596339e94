# A pass that cannot handle an object of the scene says so, once, naming
# the pass, the object and what is left out (issue 27); one that can says nothing.
source "$(dirname "$0")/lib.sh"
leaves_out() { grep -c "leaves out object" "$1"; }
"$CAUSTICA" render tests/scenes/matrix/water.lua --set technique=illumination_textures --size 16x16 -o "$WORK/a.png" \
  >"$WORK/a.txt" 2>&1
[ "$(grep -c "pass 'caustics' (illumination_textures) leaves out object 2 (water): .*no caustics through it" "$WORK/a.txt")" = 1 ] \
  && pass "illumination_textures over water: one warning" || fail "illumination_textures over water" "$(cat "$WORK/a.txt")"
# caustic volumes over a pool with a glass ball in it: the ball is left out
cat >"$WORK/pool.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 2, 3}, target = {0, -1, 0} } }
local sun = scene:add(c.light.directional { direction = {0.3, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -1, 0}, material = c.material.diffuse {} })
local water = scene:add(c.water { size = 4, resolution = 17, depth = 1 })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.3 }, position = {0, -0.5, 0}, material = c.material.glass {} })
local g = c.graph()
g:add("caustics", c.pass.caustic_volumes { light = sun, water = water })
g:add("shade", c.pass.shade { caustics = "caustics.irradiance" })
g:output("shade.color")
return { scene = scene, graph = g, size = {32, 32} }
LUA
"$CAUSTICA" info "$WORK/pool.lua" --no-render --trusted >"$WORK/b.txt" 2>&1
grep -q "pass 'caustics' (caustic_volumes) leaves out object 3 (glass): caustic volumes are built from the water surface" "$WORK/b.txt" \
  && [ "$(leaves_out "$WORK/b.txt")" = 1 ] && pass "caustic_volumes with glass in the pool: one warning, not for its water" \
  || fail "caustic_volumes with glass in the pool" "$(cat "$WORK/b.txt")"
"$CAUSTICA" info tests/scenes/matrix/ball.lua --set technique=layered_caustics --no-render >"$WORK/c.txt" 2>&1
[ "$(leaves_out "$WORK/c.txt")" = 0 ] && pass "layered_caustics through glass: no warning" \
  || fail "layered_caustics through glass" "$(cat "$WORK/c.txt")"
# a mirror beside the glass: the layered passes leave it out, photon_caustics does not
cat >"$WORK/mirror.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 2, 3}, target = {0, 0, 0} } }
local sun = scene:add(c.light.directional { direction = {0, -1, 0}, intensity = {1, 1, 1} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -1, 0}, material = c.material.diffuse {} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.4 }, material = c.material.glass { ior = 1.5 } })
scene:add(c.object { mesh = c.mesh.box { size = {0.3, 0.3, 0.3} }, position = {1, 0, 0}, material = c.material.mirror {} })
local g = c.graph()
g:add("caustics", c.pass[c.param("technique", "layered_caustics")] { light = sun })
g:add("shade", c.pass.shade { caustics = "caustics.irradiance" })
g:output("shade.color")
return { scene = scene, graph = g, size = {32, 32} }
LUA
for t in layered_caustics beam_caustics; do
  "$CAUSTICA" info "$WORK/mirror.lua" --set technique=$t --no-render --trusted >"$WORK/m.txt" 2>&1
  grep -q "pass 'caustics' ($t) leaves out object 3 (mirror): the light's depth layers hold glass and water only" "$WORK/m.txt" \
    && [ "$(leaves_out "$WORK/m.txt")" = 1 ] && pass "$t beside a mirror: one warning" || fail "$t beside a mirror" "$(cat "$WORK/m.txt")"
done
"$CAUSTICA" info "$WORK/mirror.lua" --set technique=photon_caustics --no-render --trusted >"$WORK/p.txt" 2>&1
[ "$(leaves_out "$WORK/p.txt")" = 0 ] && pass "photon_caustics beside a mirror: no warning" \
  || fail "photon_caustics beside a mirror" "$(cat "$WORK/p.txt")"
# the camera inside a glass ball: sliced_refraction says it does not refract it; refraction and
# layered_refraction trace paths that start inside, and say nothing
for t in sliced_refraction refraction layered_refraction; do
  "$CAUSTICA" info tests/scenes/matrix/identity.lua --set technique=$t --set inside=true --set ior=1.5 --no-render \
    >"$WORK/i.txt" 2>&1
  want=0
  [ $t = sliced_refraction ] && want=1
  [ "$(grep -c "leaves out object 4 (glass): the camera is inside it" "$WORK/i.txt")" = $want ] \
    && pass "$t with the camera inside the glass: $want warning(s)" || fail "$t, camera inside" "$(cat "$WORK/i.txt")"
done
# beams through a tilted glass cube: the light of cells whose corners' paths part (different faces,
# total internal reflection) makes no beam, and one line says how much of the light that lands in
# view (measured against the exact trace: 0.88 of its light reaches the floor at IOR 2.42, the line
# says 14%); a ball's paths never part: no line; nor rippled water's, whose floor gets all its light
# (the line said 16% while it counted light that lands past the view)
"$CAUSTICA" render tests/scenes/matrix/cube.lua --set technique=beam_caustics --size 32x32 -o "$WORK/cube.png" \
  >"$WORK/cube.txt" 2>&1
n=$(grep -c "beam_caustics: [0-9]*% of the light through the glass that lands in view falls in cells whose corners' light leaves" "$WORK/cube.txt")
share=$(sed -n "s/.*beam_caustics: \([0-9]*\)% of the light.*/\1/p" "$WORK/cube.txt" | head -1)
[ "$n" = 1 ] && [ "${share:-0}" -ge 10 ] && [ "${share:-0}" -le 18 ] \
  && pass "beam_caustics through a tilted cube: one line, ${share}% dropped where paths part" \
  || fail "beam_caustics through a tilted cube" "$(cat "$WORK/cube.txt")"
"$CAUSTICA" render tests/scenes/matrix/ball.lua --set technique=beam_caustics --set floor=2.5 --size 32x32 \
  -o "$WORK/ball.png" >"$WORK/ball.txt" 2>&1
[ "$(grep -c "of the light through the glass that lands in view" "$WORK/ball.txt")" = 0 ] \
  && pass "beam_caustics through a ball: no line" || fail "beam_caustics through a ball" "$(cat "$WORK/ball.txt")"
"$CAUSTICA" render tests/scenes/matrix/water.lua --set technique=beam_caustics --set amplitude=0.025 \
  -o "$WORK/ripples.png" >"$WORK/ripples.txt" 2>&1
! grep -q "makes no beam" "$WORK/ripples.txt" && pass "beam_caustics through rippled water: no line" \
  || fail "beam_caustics through rippled water" "$(cat "$WORK/ripples.txt")"
# a red box inside a glass block (issue 50): the view techniques find what lies behind the glass's
# surfaces, not within them, and say so, once each; a box in a hollow glass cup (a lathe with a
# wall) is behind its inner surface and is found: nothing said
cat >"$WORK/embedded.lua" <<'LUA'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1.2, 3}, target = {0, 0.3, 0} } }
local sun = scene:add(c.light.directional { direction = {-0.3, -1, -0.5}, intensity = {2, 2, 2} })
scene:add(c.object { mesh = c.mesh.plane { size = 6 }, material = c.material.diffuse {} })
if c.param("cup", false) then
  scene:add(c.object { mesh = c.mesh.lathe { profile = {{0, 0}, {0.5, 0}, {0.5, 1}, {0.45, 1}, {0.45, 0.05},
                                                        {0, 0.05}} }, material = c.material.glass { ior = 1.5 } })
else
  scene:add(c.object { mesh = c.mesh.box { size = {1, 1, 1} }, position = {0, 0.5, 0},
                       material = c.material.glass { ior = 1.5 } })
end
scene:add(c.object { mesh = c.mesh.box { size = {0.3, 0.3, 0.3} }, position = {0, 0.5, 0},
                     material = c.material.diffuse { color = {0.9, 0.1, 0.1} } })
local g = c.graph()
g:add("shade", c.pass.shade { specular = false })
g:add("glass", c.pass[c.param("technique", "refraction")] { color = "shade.color" })
g:output("glass.color")
return { scene = scene, graph = g, size = {32, 32} }
LUA
for t in refraction layered_refraction sliced_refraction; do
  "$CAUSTICA" info "$WORK/embedded.lua" --set technique=$t --no-render --trusted >"$WORK/e.txt" 2>&1
  "$CAUSTICA" info "$WORK/embedded.lua" --set technique=$t --set cup=true --no-render --trusted >"$WORK/h.txt" 2>&1
  [ "$(grep -c "pass 'glass' ($t) leaves out object 2 (glass): object 3 inside its glass: the pass finds what lies behind" "$WORK/e.txt")" = 1 ] \
    && [ "$(grep -c "inside its glass" "$WORK/h.txt")" = 0 ] \
    && pass "$t: a box inside a glass block said once; one inside a hollow cup not" \
    || fail "$t, a box inside glass" "$(cat "$WORK/e.txt" "$WORK/h.txt")"
done
# fog with a glass ball: caustics on surfaces only draw no shaft, and say so once (issue 52); beams make it
"$CAUSTICA" info tests/scenes/fog.lua --set ball=true --set technique=photons --no-render >"$WORK/fog.txt" 2>&1
[ "$(grep -c "pass 'photons' (photon_caustics) makes caustics on surfaces only: none of the light that object 1 (glass) bends is drawn where the scene's medium scatters it" "$WORK/fog.txt")" = 1 ] \
  && pass "photon_caustics in fog: one warning, no volume caustic" || fail "photon_caustics in fog" "$(cat "$WORK/fog.txt")"
"$CAUSTICA" info tests/scenes/fog.lua --set ball=true --set technique=beams --no-render >"$WORK/fogb.txt" 2>&1
! grep -q "surfaces only" "$WORK/fogb.txt" && pass "beam_caustics in fog: no warning" \
  || fail "beam_caustics in fog" "$(cat "$WORK/fogb.txt")"
! grep -q "surfaces only" "$WORK/c.txt" && pass "layered_caustics with no medium: no volume warning" \
  || fail "layered_caustics with no medium" "$(cat "$WORK/c.txt")"
# the camera inside a glass ball that the input shows (shade draws it): refraction's view through it
# carries no caustics, said once; with the floor left in the input, or the camera outside, nothing
"$CAUSTICA" info tests/scenes/inside_ball.lua --no-render >"$WORK/ib.txt" 2>&1
"$CAUSTICA" info tests/scenes/inside_ball.lua --set specular=false --no-render >"$WORK/ib2.txt" 2>&1
"$CAUSTICA" info tests/scenes/inside_ball.lua --set outside=true --no-render >"$WORK/ib3.txt" 2>&1
[ "$(grep -c "pass 'glass' (refraction): the camera is inside object 2 (glass), which its input shows, so what it sees through it is its own lookups' view, lit without caustics" "$WORK/ib.txt")" = 1 ] \
  && ! grep -q "lit without caustics" "$WORK/ib2.txt" "$WORK/ib3.txt" \
  && pass "the camera inside a ball the input shows: one line, none with the floor in the input or outside" \
  || fail "the camera inside a ball" "$(cat "$WORK/ib.txt" "$WORK/ib2.txt" "$WORK/ib3.txt")"
# a ball lens resting 0.01 radii above its floor: each caustics pass leaves most of its shadow black
# (the rim's light spread thin, samples far apart) and says so once, counting; at the paraxial focus
# (1.5 radii) the shadow is lit and nothing is said; nor for the IOR-2.42 cube tilted in the sun, whose
# shadow the exact trace itself leaves a quarter dark (issue 52, case 11)
for t in photon_caustics layered_caustics beam_caustics illumination_textures; do
  "$CAUSTICA" render tests/scenes/matrix/ball.lua --set technique=$t --set floor=1.01 --set near=0.0005 \
    --size 64x64 -o "$WORK/touch.png" >"$WORK/touch.txt" 2>&1
  "$CAUSTICA" render tests/scenes/matrix/ball.lua --set technique=$t --set floor=1.5 --size 64x64 \
    -o "$WORK/focus.png" >"$WORK/focus.txt" 2>&1
  "$CAUSTICA" render tests/scenes/matrix/cube.lua --set technique=$t --set ior=2.42 --size 64x64 \
    -o "$WORK/cube.png" >"$WORK/cube.txt" 2>&1
  [ "$(grep -cE "$t 'caustics': [0-9]+ of the [0-9]+ pixels in the shadow of object 2 \(glass\) \([0-9]+%\) got none of the light through it" "$WORK/touch.txt")" = 1 ] \
    && ! grep -q "got none of the light" "$WORK/focus.txt" "$WORK/cube.txt" \
    && pass "$t: a ball resting on its floor, the black in its shadow said once; at its focus and under the cube nothing" \
    || fail "$t, the black in a ball's shadow" "$(cat "$WORK/touch.txt" "$WORK/focus.txt" "$WORK/cube.txt")"
done
# A pane between the glass and the floor (tests/scenes/pane_caustic.lua --set below=true): every caustics
# pass says, once, that the caustic through it is not dimmed; with the pane above the glass (its light on
# the way to the glass, which the pane filter dims) none says anything of it (issue 50)
for t in photon_caustics layered_caustics beam_caustics illumination_textures caustic_volumes; do
  "$CAUSTICA" info tests/scenes/pane_caustic.lua --set technique=$t --set below=true --no-render >"$WORK/below.txt" 2>&1
  "$CAUSTICA" info tests/scenes/pane_caustic.lua --set technique=$t --no-render >"$WORK/above.txt" 2>&1
  [ "$(grep -c "($t) leaves out object 3 (thin glass): it lies beyond object 2 (\(glass\|water\))" "$WORK/below.txt")" = 1 ] \
    && [ "$(leaves_out "$WORK/above.txt")" = 0 ] \
    && pass "$t: a pane between the glass and the floor said once; one above the glass not" \
    || fail "$t, a pane below the glass" "$(cat "$WORK/below.txt" "$WORK/above.txt")"
done

# glossy_reflection adds its reflections over shade's panes: it says so of each pane in a scene with
# glTF BRDF surfaces (the pane of tests/data/pane.gltf before brdf_quads.gltf's quads), not without them
cat >"$WORK/glossy_pane.lua" <<LUA
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1, 3}, target = {0, 0, 0} } }
scene:add(c.light.directional { direction = {0, -1, -1}, intensity = {1, 1, 1} })
if c.param("brdf", true) then scene:add(c.object { mesh = c.mesh.load("$ROOT/tests/data/brdf_quads.gltf") }) end
scene:add(c.object { mesh = c.mesh.load("$ROOT/tests/data/pane.gltf"), position = {0, 0, 1},
                     rotation = c.quat.axis_angle({1, 0, 0}, math.pi / 2) })
local g = c.graph()
g:add("shade", c.pass.shade {})
g:add("glossy", c.pass.glossy_reflection { color = "shade.color" })
g:output("glossy.color")
return { scene = scene, graph = g, size = {32, 32} }
LUA
"$CAUSTICA" info "$WORK/glossy_pane.lua" --no-render --trusted >"$WORK/gp.txt" 2>&1
"$CAUSTICA" info "$WORK/glossy_pane.lua" --set brdf=false --no-render --trusted >"$WORK/gp0.txt" 2>&1
[ "$(grep -c "(glossy_reflection) leaves out object [0-9]* (thin glass): where this pane lies in front of a glossy surface" "$WORK/gp.txt")" = 1 ] \
  && [ "$(leaves_out "$WORK/gp0.txt")" = 0 ] \
  && pass "glossy_reflection: a pane before glTF BRDF surfaces said once; without them nothing" \
  || fail "glossy_reflection and a pane" "$(cat "$WORK/gp.txt" "$WORK/gp0.txt")"

# alphaMode holes on a mirror and on solid glass: refraction draws them and says nothing; a caustics pass
# and the other view techniques draw the surface whole and say so (tests/scenes/cut_specular.lua)
"$CAUSTICA" info tests/scenes/cut_specular.lua --set material=1 --no-render >"$WORK/cut1.txt" 2>&1
[ "$(leaves_out "$WORK/cut1.txt")" = 0 ] && ! grep -q "drawn by pass" "$WORK/cut1.txt" \
  && pass "refraction draws a mirror's alphaMode holes: nothing said" || fail "refraction and holes" "$(cat "$WORK/cut1.txt")"
# ... but shade { specular = true } under it would show the ball in its holes: said once
"$CAUSTICA" info tests/scenes/cut_specular.lua --set material=1 --set shade_specular=true --no-render >"$WORK/cut1s.txt" 2>&1
[ "$(grep -c "object 3 (mirror, alphaMode MASK) is drawn by pass 'shade' (shade) into 'shade.color', over which pass 'view' (refraction) draws it: each of its holes shows it again" "$WORK/cut1s.txt")" = 1 ] \
  && pass "shade { specular = true } under refraction fills a mirror's holes: said once" \
  || fail "shade under holes" "$(cat "$WORK/cut1s.txt")"
"$CAUSTICA" info tests/scenes/cut_specular.lua --set material=3 --set view=layered_refraction --set caustics=true \
  --no-render >"$WORK/cut3.txt" 2>&1
grep -q "(photon_caustics) leaves out object 3 (glass): .*its alphaMode MASK's holes: all the light that meets it is refracted as by .*whole glass" "$WORK/cut3.txt" \
  && grep -q "(layered_refraction) leaves out object 3 (glass): .*its alphaMode MASK's holes: the view through it is drawn as through .*whole glass" "$WORK/cut3.txt" \
  && pass "photon_caustics and layered_refraction say they draw glass with holes whole" \
  || fail "glass with holes in other passes" "$(cat "$WORK/cut3.txt")"
finish
