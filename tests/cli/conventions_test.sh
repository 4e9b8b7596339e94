# Command-line conventions (issue 29): --opt=value and --, one-line usage
# errors with a hint, VERB --help with every option's meaning and default,
# "did you mean" for verbs, options, passes, meshes, materials and fields,
# strings refused where numbers belong, the new primitives, and info's
# warning about glass drawn twice.
source "$(dirname "$0")/lib.sh"
O="$WORK/out.png"

"$CAUSTICA" render tests/scenes/glass.lua --size=24x16 --output="$O" >/dev/null 2>"$WORK/err" \
  && [ "$(file -b "$O" | grep -o '24 x 16')" = "24 x 16" ] && pass "--opt=value" || fail "--opt=value" "$(cat "$WORK/err")"
rm -f "$O"
printf 'local c = require "caustica"\nlocal g = c.graph()\ng:add("shade", c.pass.shade {})\ng:output("shade.color")\nreturn { scene = c.scene {}, graph = g, size = {8, 8} }\n' >"$WORK/-dash.lua"
(cd "$WORK" && "$CAUSTICA" render --size 16x16 -o out.png -- -dash.lua >/dev/null 2>"$WORK/err") && [ -s "$WORK/out.png" ] \
  && pass "-- ends the options (a script named -dash.lua)" || fail "--" "$(cat "$WORK/err")"
rm -f "$WORK/out.png"

usage_error() { # usage_error NAME TEXT command...: exit 2, TEXT on the first line, the hint on the second, no more
  local name=$1 text=$2
  shift 2
  "$@" >"$WORK/out" 2>"$WORK/err"
  local rc=$?
  if [ $rc = 2 ] && grep -qF -- "$text" <<<"$(head -1 "$WORK/err")" && [ "$(wc -l <"$WORK/err")" = 2 ] &&
     grep -q '^see `caustica' "$WORK/err"; then
    pass "$name"
  else
    fail "$name" "exit $rc: $(cat "$WORK/err")"
  fi
}
usage_error "a misspelt option: did you mean" "unknown option '--siz' (did you mean --size?)" \
  "$CAUSTICA" render scenes/demo.lua --siz 32x32
usage_error "an abbreviation is refused with the full name" "unknown option '--tim' (did you mean --timings?)" \
  "$CAUSTICA" render scenes/demo.lua --tim
usage_error "an option the verb does not take" "render does not take --sweep" \
  "$CAUSTICA" render scenes/demo.lua --sweep a=1,2
usage_error "a switch given a value" "--timings takes no value" "$CAUSTICA" render scenes/demo.lua --timings=yes
usage_error "a bad value, one line" "--size needs WxH (1..16384), got '12'" "$CAUSTICA" render scenes/demo.lua --size=12
usage_error "a misspelt verb: did you mean" "unknown command 'rendr' (did you mean 'render'?)" "$CAUSTICA" rendr x.lua
usage_error "--ref-spp's limit" "--ref-spp needs a count >= 8" "$CAUSTICA" bench scenes/demo.lua --ref-spp 4

for verb in render record run test info reference compare convert bench choose; do
  "$CAUSTICA" $verb --help >"$WORK/help" 2>&1 && grep -q "^  caustica $verb " "$WORK/help" && grep -q "^options:" "$WORK/help" \
    && grep -q "^  --backend osmesa|egl " "$WORK/help" || fail "$verb --help" "$(head -5 "$WORK/help")"
done
"$CAUSTICA" bench --help >"$WORK/help"
grep -q -- "--ref-spp N .*default 8; >= 8" <<<"$(tr -s ' \n' ' ' <"$WORK/help")" && grep -q -- "--sweep KEY=V1,V2" "$WORK/help" \
  && pass "VERB --help gives each option's meaning, default and limits" || fail "bench --help" "$(cat "$WORK/help")"
"$CAUSTICA" convert --help | grep -q "reads .png, .pfm, .hdr, .exr (IN.exr:layer for one layer); writes .png, .pfm, .hdr, .exr" \
  && pass "convert --help names every format it reads and writes" || fail "convert --help" "$("$CAUSTICA" convert --help | head -4)"
"$CAUSTICA" record --help | tr -s ' \n' ' ' | grep -q "out/f_####.png (.png, .pfm, .hdr, .exr)" \
  && pass "record --help names every frame format" || fail "record --help" "$("$CAUSTICA" record --help | head -8)"
"$CAUSTICA" help --help >"$WORK/help" 2>&1 && grep -q "caustica help PASS" "$WORK/help" && pass "help --help" \
  || fail "help --help" "$(cat "$WORK/help")"
"$CAUSTICA" help record | grep -q "^  caustica record " && pass "help VERB is VERB --help" || fail "help record" "no usage"
expect_error "help: a misspelt pass" 1 "no pass named 'photon_caustic' (did you mean 'photon_caustics'?)" - -- \
  "$CAUSTICA" help photon_caustic

# Scripts: names the API does not have, numbers given as strings.
script_error() { # script_error NAME TEXT LUA-LINE
  printf 'local c = require "caustica"\n%s\nreturn { scene = c.scene {}, graph = c.graph(), size = {8, 8} }\n' "$3" >"$WORK/s.lua"
  expect_error "$1" 1 "$2" "$O" -- "$CAUSTICA" render "$WORK/s.lua" -o "$O"
}
script_error "an unknown material lists the known ones" "s.lua:2: unknown material 'crystal' (known: diffuse, emissive, glass, mirror, water)" \
  'local m = c.material.crystal {}'
script_error "a misspelt mesh: did you mean" "s.lua:2: unknown mesh 'cylindr' (did you mean 'cylinder'?)" \
  'local m = c.mesh.cylindr {}'
script_error "an unknown light lists the known ones" "s.lua:2: unknown light 'area' (known: directional, linear, point, spot)" \
  'local l = c.light.area {}'
script_error "a misspelt pass: did you mean" "s.lua:2: unknown pass 'layered_caustic' (did you mean 'layered_caustics'?)" \
  'local p = c.pass.layered_caustic {}'
script_error "a misspelt field: did you mean" "s.lua:2: unknown field 'radus' in 'sphere' (did you mean 'radius'?)" \
  'local m = c.mesh.sphere { radus = 1 }'
script_error "a number given as a string is refused with the field's name" \
  "s.lua:2: bad argument 'angle' to 'spot' (number expected, got string)" 'local l = c.light.spot { angle = "30" }'
script_error "a vector of strings is refused" "s.lua:2: bad argument 'position' to 'point'" \
  'local l = c.light.point { position = {"1", 0, 0} }'
script_error "a lathe profile point that is not {r, y}" "s.lua:2: bad argument 'profile' to 'lathe' (point 2: {radius, height} expected)" \
  'local m = c.mesh.lathe { profile = { {0, 0}, {1} } }'
script_error "a cylinder of height 0" "s.lua:2: cylinder: radius and height must be finite and > 0" \
  'local m = c.mesh.cylinder { height = 0 }'

# The primitives in both renderers: a glass cylinder, a cone and a lathe on a floor render finite,
# and the reference sees the same shapes (the coverage of the objects agrees).
cat >"$WORK/shapes.lua" <<'EOF'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 1.2, 2.6}, target = {0, 0, 0}, fov = 40 }, background = {0.2, 0.3, 0.5} }
local sun = scene:add(c.light.directional { direction = {0.2, -1, -0.3}, intensity = {2, 2, 2} })
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -0.5, 0} })
scene:add(c.object { mesh = c.mesh.cylinder { radius = 0.25, height = 0.8 }, position = {-0.7, -0.1, 0},
                     material = c.material.diffuse { color = {0.8, 0.2, 0.2} } })
scene:add(c.object { mesh = c.mesh.cone { radius = 0.3, height = 0.7 }, position = {0, -0.15, 0},
                     material = c.material.diffuse { color = {0.2, 0.8, 0.2} } })
scene:add(c.object { mesh = c.mesh.lathe { profile = { {0, -0.4}, {0.3, -0.4}, {0.15, 0}, {0.3, 0.4}, {0, 0.4} } },
                     position = {0.7, -0.1, 0}, material = c.material.diffuse { color = {0.2, 0.2, 0.8} } })
local g = c.graph()
g:add("shadow", c.pass.shadow_map { light = sun })
g:add("shade", c.pass.shade { shadow = "shadow.depth" })
g:output("shade.color")
return { scene = scene, graph = g, size = {96, 64} }
EOF
"$CAUSTICA" render "$WORK/shapes.lua" -o "$WORK/gpu.pfm" >/dev/null 2>"$WORK/err" &&
  "$CAUSTICA" reference "$WORK/shapes.lua" -o "$WORK/ref.pfm" --spp 2 --photons 20000 >/dev/null 2>>"$WORK/err" &&
  line=$("$CAUSTICA" compare "$WORK/gpu.pfm" "$WORK/ref.pfm") || fail "primitives render" "$(cat "$WORK/err")"
rel=$(metric rel_rmse "${line:-}")
nan=$(metric nan "${line:-}")
awk -v r="${rel:-9}" 'BEGIN { exit !(r < 0.15) }' && [ "${nan:-1}" = 0 ] \
  && pass "cylinder, cone and lathe: the passes and the reference agree (rel_rmse $rel)" \
  || fail "primitives in both renderers" "$line"

# info: glass drawn by shade and again by a refraction pass over shade's image.
cat >"$WORK/twice.lua" <<'EOF'
local c = require "caustica"
local scene = c.scene { camera = c.camera { eye = {0, 0, 3}, target = {0, 0, 0} } }
scene:add(c.object { mesh = c.mesh.plane { size = 4 }, position = {0, -1, 0} })
scene:add(c.object { mesh = c.mesh.sphere { radius = 0.5 }, material = c.material.glass {} })
local g = c.graph()
g:add("shade", c.pass.shade { specular = c.param("specular", true) })
g:add("glass", c.pass.layered_refraction { color = "shade.color" })
g:output("glass.color")
return { scene = scene, graph = g, size = {16, 16} }
EOF
"$CAUSTICA" info "$WORK/twice.lua" --no-render 2>&1 | grep -q "pass 'glass' (layered_refraction) draws the glass over 'shade.color', in which pass 'shade' (shade) already drew it" \
  && pass "info warns when a refraction pass draws over glass shade already drew" \
  || fail "info: glass drawn twice" "$("$CAUSTICA" info "$WORK/twice.lua" --no-render 2>&1 | tail -5)"
! "$CAUSTICA" info "$WORK/twice.lua" --no-render --set specular=false 2>&1 | grep -q "already drew" \
  && pass "and not once shade leaves the glass to it" || fail "info: specular = false" "still warns"
finish
