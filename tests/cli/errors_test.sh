# Bad input gets a clear error naming the file (and line), exit 1, and no
# partial output; bad command lines exit 2 with usage.
source "$(dirname "$0")/lib.sh"
O="$WORK/out.png"

printf 'local c = require "caustica"\nlocal x = = 1\n' >"$WORK/syntax.lua"
expect_error "Lua syntax error" 1 "syntax.lua:2:" "$O" -- "$CAUSTICA" render "$WORK/syntax.lua" -o "$O"

expect_error "missing .glb" 1 "nope.glb" "$O" -- \
  "$CAUSTICA" render tests/scenes/mesh_file.lua --set path=nope.glb -o "$O"
head -c 3000 scenes/assets/teapot.glb >"$WORK/truncated.glb"
expect_error "truncated .glb" 1 "truncated.glb" "$O" -- \
  "$CAUSTICA" render tests/scenes/mesh_file.lua --set path="$WORK/truncated.glb" -o "$O"
expect_error "out-of-range indices" 1 "bad_indices.gltf: mesh '': index 5 is out of range" "$O" -- \
  "$CAUSTICA" render tests/scenes/mesh_file.lua --set path=../data/bad_indices.gltf -o "$O"
expect_error "FLOAT indices (NaN among them) are refused before any cast" 1 \
  "float_indices.gltf: mesh '': indices must be unsigned integers (glTF 2.0 3.7.2.1), got component type 5126" "$O" -- \
  "$CAUSTICA" render tests/scenes/mesh_file.lua --set path=../data/float_indices.gltf -o "$O"
expect_error "NaN positions" 1 "nan_positions.gltf" "$O" -- \
  "$CAUSTICA" render tests/scenes/mesh_file.lua --set path=../data/nan_positions.gltf -o "$O"
expect_error "error names the script line" 1 "mesh_file.lua:7:" "$O" -- \
  "$CAUSTICA" render tests/scenes/mesh_file.lua --set path=../data/nan_positions.gltf -o "$O"

printf 'local c = require "caustica"\nlocal p = c.pass.nosuch {}\n' >"$WORK/unknown_pass.lua"
expect_error "unknown pass" 1 "unknown_pass.lua:2: unknown pass 'nosuch' (known passes: shadow_map" "$O" -- \
  "$CAUSTICA" render "$WORK/unknown_pass.lua" -o "$O"
printf 'local c = require "caustica"\nlocal l = c.light.point {}\nlocal p = c.pass.shadow_map { light = l, size = "big" }\n' >"$WORK/param.lua"
expect_error "wrong parameter type" 1 \
  "param.lua:3: bad argument 'size' to 'shadow_map' (number expected, got string)" "$O" -- \
  "$CAUSTICA" render "$WORK/param.lua" -o "$O"
printf 'local c = require "caustica"\nlocal p = c.pass.shade { shadows = "x.depth" }\n' >"$WORK/field.lua"
expect_error "unknown parameter" 1 "field.lua:2: unknown field 'shadows' in 'shade'" "$O" -- \
  "$CAUSTICA" render "$WORK/field.lua" -o "$O"

expect_error "shader that fails to compile" 1 "broken.frag:7: error" "$O" -- \
  "$CAUSTICA" render tests/scenes/passes.lua --set mode=broken_shader -o "$O"
expect_error "deformer GLSL that fails to compile" 1 "deform.lua:18 (deformer):3: error" "$O" -- \
  "$CAUSTICA" render tests/scenes/deform.lua --set mode=broken -o "$O"
expect_error "input made only by a later pass" 1 "move 'shade' before 'invert'" "$O" -- \
  "$CAUSTICA" render tests/scenes/passes.lua --set mode=late_input -o "$O"

expect_error "unwritable output folder" 1 "is not writable" - -- \
  "$CAUSTICA" render scenes/demo.lua -o /proc/self/out.png
expect_error "missing output folder" 1 "does not exist" - -- \
  "$CAUSTICA" render scenes/demo.lua -o "$WORK/no/such/dir/out.png"
expect_error "record into an unwritable folder" 1 "/proc/self/frames" - -- \
  "$CAUSTICA" record scenes/demo.lua -o /proc/self/frames --frames 0:1
expect_error "missing script" 1 "nosuch.lua: no such file" "$O" -- "$CAUSTICA" render "$WORK/nosuch.lua" -o "$O"
# Mistakes that rendered without a word (issue 56): the camera inside an opaque solid, a typo in
# g:output, frames = 0 (each now names its line, or says what is wrong).
"$CAUSTICA" render tests/scenes/camera_inside.lua --set inside=box -o "$O" 2>"$WORK/err" >/dev/null
grep -q "the camera (eye at 0, 0, 0.2) is inside object 1 (receiver, 'box'), a closed opaque surface" "$WORK/err" \
  && pass "the camera inside an opaque box is warned of" || fail "camera inside" "$(cat "$WORK/err")"
for beside in plane none; do
  "$CAUSTICA" render tests/scenes/camera_inside.lua --set inside=$beside -o "$O" 2>"$WORK/err" >/dev/null
  ! grep -q "inside object" "$WORK/err" && pass "no such warning with the camera beside an open plane or nothing ($beside)" \
    || fail "camera not inside ($beside)" "$(cat "$WORK/err")"
done
rm -f "$O"
printf 'local c = require "caustica"\nlocal g = c.graph()\ng:add("env", c.pass.environment {})\ng:output("env.colr")\nreturn { scene = c.scene {}, graph = g, size = {8, 8} }\n' >"$WORK/typo.lua"
expect_error "a typo in g:output: its line and the nearest output" 1 \
  "typo.lua:4: graph output 'env.colr' is made by no pass (did you mean 'env.color'?)" "$O" -- \
  "$CAUSTICA" render "$WORK/typo.lua" -o "$O"
printf 'local c = require "caustica"\nlocal g = c.graph()\ng:add("env", c.pass.environment {})\ng:output("env.color")\n\nreturn { scene = c.scene {}, graph = g, frames = 0 }\n' >"$WORK/frames0.lua"
expect_error "frames = 0: the line of the returned table" 1 \
  "frames0.lua:6: the returned table's frames = 0: a count of frames from 1 to 10^7" "$O" -- \
  "$CAUSTICA" render "$WORK/frames0.lua" -o "$O"
printf 'return 42\n' >"$WORK/returns_number.lua"
expect_error "script returning the wrong thing" 1 "must return a table" "$O" -- \
  "$CAUSTICA" render "$WORK/returns_number.lua" -o "$O"

for try in execute popen write loadlib; do
  expect_error "sandbox denies $try" 1 "sandbox.lua:" "$O" -- \
    "$CAUSTICA" render tests/scenes/sandbox.lua --set try=$try -o "$O"
done
test ! -e /tmp/caustica-sandbox-escape.txt && pass "sandboxed write left no file" || fail "sandboxed write" "file exists"
"$CAUSTICA" render tests/scenes/sandbox.lua --set try=execute --trusted -o "$O" 2>"$WORK/err" \
  && pass "--trusted lifts the sandbox" || fail "--trusted lifts the sandbox" "$(cat "$WORK/err")"
rm -f "$O"

# Bad command lines: exit 2 with usage.
expect_error "no verb" 2 "usage" - -- "$CAUSTICA"
expect_error "unknown verb" 2 "unknown command 'frob'" - -- "$CAUSTICA" frob
expect_error "unknown option" 2 "unknown option '--frobnicate'" - -- "$CAUSTICA" render scenes/demo.lua --frobnicate
expect_error "bad --size" 2 "--size needs WxH" - -- "$CAUSTICA" render scenes/demo.lua --size 12
expect_error "bad --set" 2 "--set needs name=value" - -- "$CAUSTICA" render scenes/demo.lua --set x
expect_error "bad --backend" 2 "--backend must be osmesa or egl" - -- "$CAUSTICA" render scenes/demo.lua --backend vulkan
expect_error "bad output extension" 2 "must end in .png, .jpg, .tif, .pfm, .hdr or .exr" - -- "$CAUSTICA" render scenes/demo.lua -o x.bmp
expect_error "record without -o" 2 "record needs" - -- "$CAUSTICA" record scenes/demo.lua

# --version, VERB --help, and a test filter that selects nothing.
for spelling in --version -V version; do
  "$CAUSTICA" $spelling | grep -qE "^caustica [0-9]+\.[0-9]+\.[0-9]+$" && pass "$spelling" || fail "$spelling" "$("$CAUSTICA" $spelling 2>&1)"
done
for verb in render record run test info reference compare bench convert; do
  out=$("$CAUSTICA" $verb --help 2>&1)
  rc=$?
  [ $rc = 0 ] && grep -q "^  caustica $verb " <<<"$out" && ! grep -q "^  caustica [a-z]" <<<"$(grep -v "^  caustica $verb " <<<"$out")" \
    && pass "$verb --help shows its own usage" || fail "$verb --help" "exit $rc: $out"
done
printf 'local c = require "caustica"\nlocal g = c.graph()\ng:add("shade", c.pass.shade {})\ng:add("glass", c.pass.refraction { color = "shade.colour" })\ng:output("glass.color")\nreturn { scene = c.scene{}, graph = g, size = {8,8} }\n' >"$WORK/colour.lua"
expect_error "an input no pass makes names the line and what the pass makes" 1 \
  "colour.lua:4: pass 'glass' (refraction, pass 2) reads color = 'shade.colour', which no earlier pass makes; pass 'shade' makes 'shade.color', 'shade.depth'" \
  "$O" -- "$CAUSTICA" render "$WORK/colour.lua" -o "$O"
printf 'local c = require "caustica"\nerror("deliberate")\n' >"$WORK/raise.lua"
"$CAUSTICA" render "$WORK/raise.lua" -o "$O" 2>"$WORK/quiet"; "$CAUSTICA" render "$WORK/raise.lua" -o "$O" --verbose 2>"$WORK/loud"
! grep -q "stack traceback" "$WORK/quiet" && grep -q "stack traceback" "$WORK/loud" && grep -q "raise.lua:2: deliberate" "$WORK/loud" \
  && pass "--verbose prints the Lua traceback" || fail "--verbose traceback" "$(cat "$WORK/loud")"
(cd "$WORK" && "$CAUSTICA" render "$ROOT/tests/scenes/glass.lua" >"$WORK/said" 2>&1) && grep -qx "wrote out.png" "$WORK/said" \
  && test -f "$WORK/out.png" && pass "render without -o says where it wrote" || fail "render without -o" "$(cat "$WORK/said")"
rm -f "$WORK/out.png"
printf 'local t = require "caustica.test"\nt.case("fails", function()\n  t.render("tests/scenes/nosuch.lua")\nend)\n' >"$WORK/user_test.lua"
"$CAUSTICA" test "$WORK/user_test.lua" >"$WORK/said" 2>&1
grep -q "user_test.lua:3: " "$WORK/said" && ! grep -q "lua/caustica/test.lua" "$WORK/said" \
  && pass "a harness helper's error points at the user's test line" || fail "harness error line" "$(cat "$WORK/said")"
expect_error "a --filter that matches no case" 1 "no case matches --filter 'no such case'" - -- \
  "$CAUSTICA" test tests/lua/values_test.lua --filter "no such case"
finish
