# Hardening, round three (issue 55): each reproducer of the probe, as it was
# reported, ends cleanly now. Every check here failed before the fix it
# names. No check reads a clock: a command that could hang runs under
# `timeout`, whose exit (124) fails the check, with a margin of minutes.
source "$(dirname "$0")/lib.sh"

# scene NAME BODY: a script in $WORK that runs BODY, then returns a tiny
# environment-only frame.
scene() {
  cat >"$WORK/$1.lua" <<EOF
local c = require "caustica"
local dir = c.param("dir", "")
$2
local g = c.graph()
g:add("env", c.pass.environment {})
g:output("env.color")
return { scene = c.scene {}, graph = g, size = {8, 8}, frames = tonumber(c.param("frames", "1")),
         fps = tonumber(c.param("fps", "30")) }
EOF
}
scene tiny ''

# ---- 1. caustica test holds --script-timeout and --script-memory, per case --
# (each limit alone, the other lifted: how busy the machine is changes neither verdict)
mkdir -p "$WORK/limits" "$WORK/memory"
cat >"$WORK/limits/limits_test.lua" <<'EOF'
local t = require "caustica.test"
t.case("loops", function() while true do end end)
t.case("still runs", function() t.expect(1 + 1 == 2) end)
EOF
cat >"$WORK/memory/memory_test.lua" <<'EOF'
local t = require "caustica.test"
t.case("grows", function() local heap = {} while true do heap[#heap + 1] = ("x"):rep(1000) .. #heap end end)
t.case("still runs", function() t.expect(1 + 1 == 2) end)
EOF
# limited_case NAME FOLDER FAIL-LINE-PATTERN LIMIT-OPTIONS...: the folder's one failing case fails by
# the limit with that line, and its "still runs" case passes after it
limited_case() {
  local name=$1 folder=$2 pattern=$3
  shift 3
  timeout 120 "$CAUSTICA" test "$folder" "$@" >"$WORK/out" 2>&1
  local rc=$?
  [ $rc = 1 ] && grep -q "$pattern" "$WORK/out" && grep -q "^ok   .*still runs" "$WORK/out" &&
    [ "$(tail -1 "$WORK/out")" = "1 passed, 1 failed" ] && pass "$name" || fail "$name" "exit $rc: $(tail -3 "$WORK/out")"
}
limited_case "caustica test --script-timeout: a looping case fails at its line, the next case runs" "$WORK/limits" \
  "FAIL .*limits_test.lua: loops: .*limits_test.lua:2: script ran longer than 1 s" --script-timeout 1 --script-memory 0
limited_case "caustica test --script-memory: a growing case fails by the limit, the next case runs" "$WORK/memory" \
  "FAIL .*memory_test.lua: grows: .*used more than 64 MB" --script-timeout 0 --script-memory 64

# ---- 2. a nested render leaves the watchdog armed --------------------------
cat >"$WORK/limits/nested_test.lua" <<EOF
local t = require "caustica.test"
t.case("render, then a handler that loops", function()
  t.render("$WORK/tiny.lua", { size = {4, 4} })
  xpcall(error, function() while true do end end)
end)
EOF
timeout 120 "$CAUSTICA" test "$WORK/limits/nested_test.lua" --script-timeout 2 >"$WORK/out" 2>&1
rc=$?
[ $rc = 1 ] && grep -q "ran past --script-timeout inside a C function, a message handler" "$WORK/out" \
  && pass "after t.render, a looping message handler is still ended by the watchdog" \
  || fail "nested render disarms the watchdog" "exit $rc: $(tail -3 "$WORK/out")"
# the render's own time is not the case's: a case of renders longer than the limit passes
cat >"$WORK/limits/renders_test.lua" <<EOF
local t = require "caustica.test"
t.case("renders", function()
  for _ = 1, 4 do t.render("$WORK/tiny.lua", { size = {64, 64} }) end
end)
EOF
timeout 120 "$CAUSTICA" test "$WORK/limits/renders_test.lua" --script-timeout 30 >"$WORK/out" 2>&1 \
  && pass "renders in a case run under the case's limit" || fail "renders under the limit" "$(tail -3 "$WORK/out")"

# ---- 3. pattern work that used to cost no steps ---------------------------
scene bigset 'local set = "[" .. ("a"):rep(1 << 20) .. "]"
local s = ("b"):rep(100000)
s:find(set)'
timeout 120 "$CAUSTICA" render "$WORK/bigset.lua" -o "$WORK/o.png" --script-timeout 1 >/dev/null 2>"$WORK/err"
rc=$?
[ $rc = 1 ] && grep -q "bigset.lua:5: script ran longer than 1 s (in a string pattern" "$WORK/err" \
  && pass "a 1 MB character set ends with the script's error at its line, not the watchdog" \
  || fail "1 MB set" "exit $rc: $(cat "$WORK/err")"

# ---- 4. load, loadfile and dofile in the sandbox keep the environment -------
printf 'shared = (shared or 0) + 1\nreturn math.floor(2.5) + shared\n' >"$WORK/chunk.lua"
scene loads 'assert(load("x = 1; return math.pi")() == math.pi and x == 1, "load")
assert(load("return y", "c", "t", { y = 2 })() == 2, "load with an environment")
assert(loadfile(dir .. "/chunk.lua")() == 3, "loadfile")
assert(dofile(dir .. "/chunk.lua") == 4, "dofile")
assert(not pcall(load("return math.pi", "c", "t", nil)), "an explicit nil environment is nil")'
"$CAUSTICA" render "$WORK/loads.lua" -o "$WORK/o.png" --set dir="$WORK" >/dev/null 2>"$WORK/err" \
  && pass "sandboxed load, loadfile and dofile give the chunk the script's globals" \
  || fail "sandboxed load" "$(cat "$WORK/err")"

# ---- 5 and 10. the reports: a result without a file, any bytes -------------
cat >"$WORK/limits/report_test.lua" <<'EOF'
local t = require "caustica.test"
t.case("bad\1name \255\254 and \27[31m", function() error("message with \0 a NUL, \8 a backspace, \192\128 overlong") end)
t.case("adds a result of its own", function() t._results[#t._results + 1] = { ok = false } end)
t.case("plain é ✓", function() end)
EOF
timeout 120 "$CAUSTICA" test "$WORK/limits/report_test.lua" --junit "$WORK/junit.xml" --report "$WORK/report.html" \
  >"$WORK/out" 2>&1
rc=$?
if [ $rc = 1 ] && ! grep -qiE "segmentation|core dumped" "$WORK/out" && [ -s "$WORK/junit.xml" ]; then
  pass "--junit with a result that has no file name: no crash"
else
  fail "--junit crash" "exit $rc: $(tail -3 "$WORK/out")"
fi
if xmllint --noout --schema tests/data/junit.xsd "$WORK/junit.xml" 2>"$WORK/xerr"; then
  pass "the JUnit XML is valid with control characters and invalid UTF-8 in names and messages"
else
  fail "JUnit XML" "$(head -3 "$WORK/xerr")"
fi
grep -q 'bad\\x01name \\xFF\\xFE and \\x1B\[31m' "$WORK/junit.xml" && grep -q "plain é ✓" "$WORK/junit.xml" \
  && pass "bytes that XML cannot hold are written as \\xNN, UTF-8 as it is" || fail "escapes" "$(grep -a name= "$WORK/junit.xml")"
if iconv -f UTF-8 -t UTF-8 "$WORK/report.html" >/dev/null 2>&1 && ! LC_ALL=C grep -q $'[\x01-\x08\x0b\x0c\x0e-\x1f]' "$WORK/report.html"; then
  pass "the HTML report is valid UTF-8 with no control characters"
else
  fail "HTML report bytes" "not clean UTF-8"
fi

# ---- 6, 7 and 12. record --video ------------------------------------------
if command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null; then
  frames_in() { ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$1"; }
  for fps in 24 60; do
    for n in 1 5; do
      "$CAUSTICA" record "$WORK/tiny.lua" --set frames=$n --set fps=$fps -o "$WORK/v$fps.$n/frame_####.png" \
        --video "$WORK/v$fps.$n.mp4" >"$WORK/out" 2>&1
      got=$(frames_in "$WORK/v$fps.$n.mp4" 2>/dev/null)
      [ "$got" = "$n" ] && grep -q "($n frame" "$WORK/out" && pass "record --video at $fps fps: $n frame(s) in, $n out" \
        || fail "video of $n frames at $fps fps" "decoded '$got': $(cat "$WORK/out")"
    done
  done
  "$CAUSTICA" record "$WORK/tiny.lua" --set frames=3 -o "$WORK/v3/frame_####.png" --video "$WORK/v3.gif" >/dev/null 2>&1
  [ "$(frames_in "$WORK/v3.gif" 2>/dev/null)" = 3 ] && pass "record --video .gif: 3 frames in, 3 out" \
    || fail "gif frames" "$(frames_in "$WORK/v3.gif" 2>&1)"
  # a newline in the frames' path was a line of ffmpeg's concat list: here it would name another file
  "$CAUSTICA" record "$WORK/tiny.lua" --set frames=2 -o "$WORK/planted/frame_####.png" >/dev/null 2>&1
  odd="$WORK/odd
file '$WORK/planted/frame_0000.png'
x"
  mkdir -p "$odd"
  "$CAUSTICA" record "$WORK/tiny.lua" --set frames=4 -o "$odd/frame_####.png" --video "$WORK/odd.mp4" >"$WORK/out" 2>&1
  rc=$?
  [ $rc = 0 ] && [ "$(frames_in "$WORK/odd.mp4")" = 4 ] \
    && pass "a newline in the frames' path: the video holds exactly its 4 frames, no other file" \
    || fail "newline in the frames' path" "exit $rc, $(frames_in "$WORK/odd.mp4" 2>&1): $(cat "$WORK/out")"
  # an encode killed with -9 left its private folder: the next --video to that name removes it
  sh -c 'exit 0' & dead=$!
  wait $dead
  mkdir -p "$WORK/videos/.clip.mp4.caustica-tmp.$dead.AbCdEf"
  echo x >"$WORK/videos/.clip.mp4.caustica-tmp.$dead.AbCdEf/frames.txt"
  ln -s /etc/hostname "$WORK/videos/.clip.mp4.caustica-tmp.$dead.AbCdEf/00000000.png"
  "$CAUSTICA" record "$WORK/tiny.lua" --set frames=2 -o "$WORK/v2/frame_####.png" --video "$WORK/videos/clip.mp4" \
    >/dev/null 2>&1
  left=$(find "$WORK/videos" -mindepth 1 -name '.*' | wc -l)
  [ -s "$WORK/videos/clip.mp4" ] && [ "$left" = 0 ] && [ -s /etc/hostname ] \
    && pass "a dead encoder's private folder beside the video is removed (its link unlinked, not followed)" \
    || fail "stale video folder" "$(ls -a "$WORK/videos")"
else
  echo "skip: ffmpeg/ffprobe not installed (record --video checks)"
fi

# ---- 8. .part fields are range-checked --------------------------------------
"$CAUSTICA" reference tests/scenes/ball_lens.lua -o "$WORK/p.pfm" --size 8x8 --photons 100 --spp 2 --shard 0/1 -q \
  >/dev/null 2>&1
part_case() { # NAME SED-EXPRESSION EXPECTED-TEXT
  cp "$WORK/p.pfm" "$WORK/edit.pfm"
  sed "$2" "$WORK/p.pfm.part" >"$WORK/edit.pfm.part"
  expect_error "merge refuses a part with $1" 1 "$3" "$WORK/merged_edit.pfm" -- \
    timeout 60 "$CAUSTICA" merge "$WORK/edit.pfm" -o "$WORK/merged_edit.pfm"
}
part_case "passes 4294967298 (read as 2 before)" 's/^passes 2$/passes 4294967298/' "malformed reference part"
part_case "frame 2^32 (read as 0)" 's/^frame 0$/frame 4294967296/' "malformed reference part"
part_case "frame -1" 's/^frame 0$/frame -1/' "malformed reference part"
part_case "seed -1" 's/^seed .*/seed -1/' "malformed reference part"
part_case "photons -5" 's/^photons .*/photons -5/' "malformed reference part"
part_case "2^31 passes" 's/^passes 2$/passes 2147483648/;s/^passes_total 2$/passes_total 2147483648/' \
  "malformed reference part"
# two halves of 2^31 - 1 passes that claim 2^30 each: the sum (2^31) is past int, and said
"$CAUSTICA" reference tests/scenes/ball_lens.lua -o "$WORK/h0.pfm" --size 8x8 --photons 100 --spp 2 --shard 0/2 -q \
  >/dev/null 2>&1
"$CAUSTICA" reference tests/scenes/ball_lens.lua -o "$WORK/h1.pfm" --size 8x8 --photons 100 --spp 2 --shard 1/2 -q \
  >/dev/null 2>&1
for h in h0 h1; do
  sed -i 's/^passes_total .*/passes_total 2147483647/;s/^passes .*/passes 1073741824/' "$WORK/$h.pfm.part"
done
expect_error "merge adds 2^30 + 2^30 passes without overflow" 1 \
  "the parts hold 2147483648 passes, their shards 2147483647" "$WORK/big.pfm" -- \
  timeout 60 "$CAUSTICA" merge "$WORK/h0.pfm" "$WORK/h1.pfm" -o "$WORK/big.pfm"

# ---- 9. KHR_materials_volume thicknessFactor --------------------------------
for value in 1e308 -1; do
  sed "s/\"thicknessFactor\": 0.1/\"thicknessFactor\": $value/" tests/data/glass_material.gltf >"$WORK/thick.gltf"
  scene thick 'c.mesh.load(dir .. "/thick.gltf")'
  expect_error "thicknessFactor $value is refused" 1 "thicknessFactor must be a finite distance" "$WORK/o2.png" -- \
    "$CAUSTICA" render "$WORK/thick.lua" -o "$WORK/o2.png" --set dir="$WORK"
done

# ---- 11. caustica test DIR with links to itself -----------------------------
mkdir -p "$WORK/loop"
printf 'local t = require "caustica.test"\nt.case("one", function() end)\n' >"$WORK/loop/one_test.lua"
ln -s . "$WORK/loop/again"
ln -s "$WORK/loop" "$WORK/loop/and_again"
timeout 60 "$CAUSTICA" test "$WORK/loop" >"$WORK/out" 2>&1
rc=$?
[ $rc = 0 ] && [ "$(tail -1 "$WORK/out")" = "1 passed, 0 failed" ] \
  && pass "caustica test DIR holding two links to itself: each file once" || fail "test walk" "exit $rc: $(tail -2 "$WORK/out")"

# ---- 13. sizes that follow from parameters, checked before allocation --------
scene lathe 'local pts = {}
for i = 1, 4096 do pts[i] = {0.1 + i / 4096, i / 4096} end
c.mesh.lathe { profile = pts, segments = 4096 }'
scene torus 'c.mesh.torus { segments = 4096, sides = 4096 }'
# 700 MB of address space, where a render fits in it (the old code's allocation of the mesh ran out of
# it); a machine whose GL driver alone needs more checks the message only
space=700000
(ulimit -v $space; exec "$CAUSTICA" render "$WORK/tiny.lua" -o "$WORK/o3.png") >/dev/null 2>&1 || space=unlimited
for shape in lathe torus; do
  (ulimit -v $space; exec "$CAUSTICA" render "$WORK/$shape.lua" -o "$WORK/o3.png" --script-memory 64) \
    >/dev/null 2>"$WORK/err"
  rc=$?
  [ $rc = 1 ] && grep -q "$shape.lua:.*mesh '$shape' (.* vertices) needs .* MB, which would take the script past --script-memory 64 MB" "$WORK/err" \
    && pass "c.mesh.$shape of 4096 x 4096 is refused by --script-memory before it is made" \
    || fail "$shape before allocation" "exit $rc: $(cat "$WORK/err")"
done

finish
