# A technique added as docs/ARCHITECTURE.md's "Adding a pass" says (one
# descriptor, one registry line) joins the comparisons by itself (issue 54):
# the test build caustica_new_technique (CMakeLists.txt) registers
# tests/new_technique/example_caustics.c, a caustics technique, and nothing
# else is edited. It shows in `help` (under its family) and in the Lua API's
# c.techniques, in the optics matrix as "not measured" (it has no bounds
# there), and in `bench --sweep technique=all` on the comparison scene of
# surface caustics (scenes/compare/ball.lua) at its defaults. The plain build
# has none of it.
source "$(dirname "$0")/lib.sh"
EXTRA=$(dirname "$CAUSTICA")/caustica_new_technique
if [ ! -x "$EXTRA" ]; then
  fail "test build" "$EXTRA is missing (make build makes it beside caustica)"
  finish
fi

"$EXTRA" help passes >"$WORK/help.txt" 2>&1
"$CAUSTICA" help passes >"$WORK/help0.txt" 2>&1
grep -q "^example_caustics: no caustics at all" "$WORK/help.txt" &&
  grep -A3 "^example_caustics:" "$WORK/help.txt" | grep -q "technique: caustics" &&
  ! grep -q "example_caustics" "$WORK/help0.txt" &&
  pass "help lists the registered technique with its family; the plain build does not" ||
  fail "help" "$(grep -A4 example_caustics "$WORK/help.txt")"

cat >"$WORK/list.lua" <<'LUA'
local c = require "caustica"
print("caustics: " .. table.concat(c.techniques("caustics"), " "))
print("view: " .. table.concat(c.techniques("view"), " "))
local ok, err = pcall(c.techniques, "shadows")
print("bad family: " .. tostring(err))
return { scene = c.scene {}, graph = c.graph() }
LUA
"$EXTRA" info "$WORK/list.lua" --no-render --trusted >"$WORK/list.txt" 2>&1
grep -q "^caustics: photon_caustics layered_caustics illumination_textures beam_caustics example_caustics$" "$WORK/list.txt" &&
  grep -q "^view: refraction layered_refraction sliced_refraction$" "$WORK/list.txt" &&
  grep -q "bad family: .*a technique family expected: caustics, water_caustics, view or water_view" "$WORK/list.txt" &&
  pass "c.techniques lists each family in the registry's order, the new technique last" ||
  fail "c.techniques" "$(cat "$WORK/list.txt")"

# the optics matrix: its one case that lists what it does not measure
"$EXTRA" test tests/lua/optics_matrix_test.lua --filter "every registered technique" >"$WORK/matrix.txt" 2>&1
"$CAUSTICA" test tests/lua/optics_matrix_test.lua --filter "every registered technique" >"$WORK/matrix0.txt" 2>&1
grep -q "^matrix| every case | example_caustics | .* | not measured: " "$WORK/matrix.txt" &&
  ! grep -q "example_caustics" "$WORK/matrix0.txt" && grep -q "^ok " "$WORK/matrix.txt" &&
  pass "the optics matrix lists the new technique as not measured" ||
  fail "optics matrix" "$(cat "$WORK/matrix.txt")"

# bench: the comparison scene of surface caustics tries it beside the others, at its defaults
"$EXTRA" bench scenes/compare/ball.lua --sweep technique=all --size 16x16 --frames 1 --error-frames 1 \
  --ref-photons 2000 --ref-spp 8 --truth-spp 8 -o "$WORK/bench" >"$WORK/bench.txt" 2>&1
rc=$?
[ $rc = 0 ] && grep -q "^gpu,example_caustics,defaults," "$WORK/bench/results.csv" &&
  grep -q "^| example_caustics | " "$WORK/bench/results.md" &&
  grep -q "^gpu,photons," "$WORK/bench/results.csv" &&
  pass "bench --sweep technique=all measures the new technique beside the scene's own" ||
  fail "bench" "exit $rc: $(tail -5 "$WORK/bench.txt"; head -3 "$WORK/bench/results.csv" 2>/dev/null)"
finish
