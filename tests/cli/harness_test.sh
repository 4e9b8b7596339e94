# The test harness on a user's own test folder outside caustica's tree:
# golden images beside the test (refs/), written by --update-refs; a failed
# comparison writes the rendered image, the golden and their difference to
# out/ beside the test and names them, the golden's path, the measured
# values and the thresholds, at the user's line; --report writes one HTML
# page with them side by side.
source "$(dirname "$0")/lib.sh"
mkdir -p "$WORK/mine"
cat >"$WORK/mine/look_test.lua" <<LUA
local t = require "caustica.test"
local frame = tonumber(FRAME_TO_USE or 0)
t.case("the demo against its golden", function()
  local img = t.render("$ROOT/scenes/demo.lua", { size = {24, 24}, frame = frame })
  t.expect_golden(img, "demo.png")
end)
LUA
"$CAUSTICA" test "$WORK/mine" --update-refs >"$WORK/update.txt" 2>&1
[ -f "$WORK/mine/refs/demo.png" ] && grep -q "updated $WORK/mine/refs/demo.png" "$WORK/update.txt" \
  && pass "--update-refs writes refs/ beside the test" || fail "--update-refs" "$(cat "$WORK/update.txt")"
"$CAUSTICA" test "$WORK/mine" >"$WORK/same.txt" 2>&1 && pass "the golden matches" || fail "golden" "$(cat "$WORK/same.txt")"
sed -i 's/FRAME_TO_USE or 0/10/' "$WORK/mine/look_test.lua"
cat >"$WORK/mine/other_test.lua" <<'LUA'
local t = require "caustica.test"
t.case("a & b < c, passing", function() t.expect(1 + 1 == 2, "arithmetic") end)
t.case("an image that passes", function()
  local img = t.render("ROOT/scenes/demo.lua", { size = {16, 16} })
  t.expect_close(img, img)
end)
LUA
sed -i "s#ROOT/#$ROOT/#" "$WORK/mine/other_test.lua"
"$CAUSTICA" test "$WORK/mine" --report "$WORK/report.html" --junit "$WORK/junit.xml" >"$WORK/fail.txt" 2>&1
rc=$?
line=$(grep "^FAIL" "$WORK/fail.txt")
[ "$rc" = 1 ] && grep -q "look_test.lua:5: differs from the golden $WORK/mine/refs/demo.png: rmse [0-9.]* (at most 0.0078" <<<"$line" \
  && pass "the failure names the user's line, the golden, the values and the threshold" || fail "failure message" "rc $rc: $line"
ok=1
for kind in new ref diff; do
  f="$WORK/mine/out/look_test.the_demo_against_its_golden.$kind.png"
  grep -qF "$f" <<<"$line" && "$CAUSTICA" compare "$f" "$f" >/dev/null 2>&1 || ok=0
done
[ "$ok" = 1 ] && pass "new, ref and diff images written and named" || fail "failure images" "$line $(ls "$WORK/mine/out" 2>&1)"
[ "$(grep -c '<img src="data:image/png;base64,' "$WORK/report.html")" = 3 ] && grep -q 'class="flip"' "$WORK/report.html" &&
  ! grep -q "file://" "$WORK/report.html" && grep -q "2 passed, 1 failed" "$WORK/report.html" &&
  [ "$(grep -o '<img class="thumb" src="data:image/png;base64,' "$WORK/report.html" | wc -l)" = 2 ] \
  && pass "--report: one self-contained page, the three images side by side, a flip view, thumbnails of passing image cases" \
  || fail "--report" "$(head -c 600 "$WORK/report.html")"
if command -v xmllint >/dev/null; then
  xmllint --noout --schema tests/data/junit.xsd "$WORK/junit.xml" >"$WORK/xsd.txt" 2>&1 &&
    grep -q '<testsuites name="caustica" tests="3" failures="1"' "$WORK/junit.xml" &&
    grep -q '<testcase classname="[^"]*look_test.lua" name="the demo against its golden" time="[0-9.]*">' "$WORK/junit.xml" &&
    grep -q '<failure message="[^"]*look_test.lua:5: differs from the golden' "$WORK/junit.xml" &&
    grep -q 'name="a &amp; b &lt; c, passing"' "$WORK/junit.xml" \
    && pass "--junit: valid JUnit XML (tests/data/junit.xsd), a suite per file, the failure's message" \
    || fail "--junit" "$(cat "$WORK/xsd.txt" "$WORK/junit.xml")"
fi
expect_error "a filter that matches nothing" 1 "no case matches --filter 'nothing like this'" - -- \
  "$CAUSTICA" test "$WORK/mine" --filter "nothing like this"
finish
