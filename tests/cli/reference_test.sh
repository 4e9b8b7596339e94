# `caustica reference` from the command line: time budgets hold at any
# photon count, the noise report, HDR output.
source "$(dirname "$0")/lib.sh"

# A budget of 2 s with far more photons than 2 s can trace (minutes of them): judged by what the
# reference reports of its own work, not by a clock the machine's load can move (how close to the
# budget it ends, on an idle machine and beside two CPU hogs, is measured by
# tests/bench/reference_budget.sh, docs/TESTING.md). It stops by the budget: it reports fewer
# photons than one iteration asks, its one warning says what the budget cut, its own clock reached
# the budget (it did not give up early), and it ends (timeout 300 is a hang guard: the 5e8 photons
# alone take many minutes here). The fog scene also reserves time for its volume gather.
for scene in "tests/scenes/ball_lens.lua" "tests/scenes/fog.lua --set ball=true"; do
  # shellcheck disable=SC2086
  timeout 300 "$CAUSTICA" reference $scene -o "$WORK/budget.pfm" --size 128x128 --photons 500000000 --time-budget 2 \
    >"$WORK/out.txt" 2>"$WORK/err.txt"
  rc=$?
  photons=$(sed -n 's/.*iterations\?, \([0-9]*\) photons (.* caustic), [0-9.]* s on.*/\1/p' "$WORK/out.txt")
  seconds=$(sed -n 's/.*photons (.* caustic), \([0-9.]*\) s on.*/\1/p' "$WORK/out.txt")
  if [ $rc = 0 ] && [ -n "$photons" ] && [ "$photons" -lt 500000000 ] && awk "BEGIN { exit !($seconds >= 1.8) }" &&
     [ "$(grep -c "bought less than one full iteration" "$WORK/err.txt")" = 1 ]; then
    pass "--time-budget 2 with 5e8 photons: stopped by the budget at $photons photons, $seconds s by its clock ($scene)"
  else
    fail "budget on $scene" "exit $rc, $photons photons, $seconds s: $(cat "$WORK/out.txt" "$WORK/err.txt")"
  fi
done
"$CAUSTICA" reference tests/scenes/ball_lens.lua -o "$WORK/many.pfm" --size 32x32 --photons 20000 --time-budget 1 \
  >"$WORK/out.txt" 2>"$WORK/err.txt"
! grep -q "bought less" "$WORK/err.txt" && grep -q "iterations" "$WORK/out.txt" \
  && pass "a budget that buys many iterations warns of nothing" || fail "no warning" "$(cat "$WORK/out.txt" "$WORK/err.txt")"
grep -q ", by SPPM (radii shrunk per pixel) -> " "$WORK/out.txt" && pass "a plain reference names its estimator (SPPM)" \
  || fail "estimator named" "$(cat "$WORK/out.txt")"
"$CAUSTICA" reference tests/scenes/ball_lens.lua -o "$WORK/shard.pfm" --size 16x16 --photons 500 --spp 2 --shard 1/2 \
  >"$WORK/out.txt" 2>/dev/null
grep -q ", by independent passes (shard 1/2, radii fixed per pass) -> " "$WORK/out.txt" \
  && pass "a shard names its estimator (independent passes)" || fail "shard's estimator" "$(cat "$WORK/out.txt")"
"$CAUSTICA" merge --help | tr '\n' ' ' | grep -q "that of .reference --shard 0/1. .*not of a plain .reference." \
  && pass "merge --help says up front which run a merge equals" || fail "merge --help" "$("$CAUSTICA" merge --help)"
"$CAUSTICA" compare "$WORK/budget.pfm" "$WORK/budget.pfm" | grep -q "nan=0" && pass "the cut-short image is finite" \
  || fail "finite" "$("$CAUSTICA" compare "$WORK/budget.pfm" "$WORK/budget.pfm")"

# Distributed reference: --shard i/n renders the independent passes p % n == i; caustica merge averages
# the parts into what one run of all the passes gives (floating-point rounding apart), for a surface
# caustic and a volume caustic (with the EXR's caustic layer), at any thread count.
for scene in "tests/scenes/ball_lens.lua" "tests/scenes/fog.lua --set ball=true"; do
  # shellcheck disable=SC2086
  "$CAUSTICA" reference $scene -o "$WORK/one.exr" --size 32x32 --photons 5000 --spp 8 --shard 0/1 --threads 1 -q \
    >/dev/null
  for i in 0 1 2 3; do
    # shellcheck disable=SC2086
    "$CAUSTICA" reference $scene -o "$WORK/part$i.exr" --size 32x32 --photons 5000 --spp 8 --shard $i/4 -q \
      >/dev/null
  done
  [ "$scene" = tests/scenes/ball_lens.lua ] && cp "$WORK/part1.exr" "$WORK/ball1.exr" && cp "$WORK/part1.exr.part" "$WORK/ball1.exr.part"
  "$CAUSTICA" merge "$WORK"/part[0-3].exr -o "$WORK/merged.exr" >"$WORK/out.txt" 2>&1
  rel=$(metric rel_rmse "$("$CAUSTICA" compare "$WORK/merged.exr" "$WORK/one.exr" 2>&1)")
  relc=$(metric rel_rmse "$("$CAUSTICA" compare "$WORK/merged.exr:caustic" "$WORK/one.exr:caustic" 2>&1)")
  grep -q "merged 4 parts (8 of 8 passes" "$WORK/out.txt" && [ -n "$rel" ] && [ -n "$relc" ] &&
    awk "BEGIN { exit !($rel < 1e-6 && $relc < 1e-6) }" \
    && pass "4 shards merged == one run of the same 8 passes (rel $rel, caustic layer $relc; $scene)" \
    || fail "merge ($scene)" "rel '$rel' '$relc': $(cat "$WORK/out.txt")"
done
grep -q "^shards 0,1,2,3$" "$WORK/merged.exr.part" && grep -q "^passes 8$" "$WORK/merged.exr.part" \
  && pass "the merged image's .part says what it holds" || fail "merged .part" "$(cat "$WORK/merged.exr.part")"
"$CAUSTICA" merge "$WORK/part0.exr" "$WORK/part2.exr" -o "$WORK/half.pfm" >/dev/null 2>"$WORK/err.txt" &&
  grep -q "warning: merged 2 of 4 shards (4 of 8 passes).*missing: 1, 3" "$WORK/err.txt" \
  && pass "merging some shards says which are missing" || fail "missing shards" "$(cat "$WORK/err.txt")"
expect_error "a shard merged twice is refused" 1 "shard 0/4 is already in an earlier part" "$WORK/twice.pfm" -- \
  "$CAUSTICA" merge "$WORK/part0.exr" "$WORK/part0.exr" -o "$WORK/twice.pfm"
expect_error "parts of another scene are refused" 1 "ball1.exr: a part of tests/scenes/ball_lens.lua, not of tests/scenes/fog.lua" \
  "$WORK/mixed.pfm" -- "$CAUSTICA" merge "$WORK/half.pfm" "$WORK/ball1.exr" -o "$WORK/mixed.pfm"
expect_error "an image without its .part is refused" 1 "not a reference part" "$WORK/none.pfm" -- \
  "$CAUSTICA" merge "$WORK/budget.pfm" -o "$WORK/none.pfm"
expect_error "--shard with --time-budget is refused" 2 "not with --time-budget" - -- \
  "$CAUSTICA" reference tests/scenes/ball_lens.lua -o "$WORK/x.pfm" --shard 0/2 --time-budget 1

# --report: one line per iteration, the noise estimate falling
"$CAUSTICA" reference tests/scenes/ball_lens.lua -o "$WORK/r.hdr" --size 32x32 --photons 20000 --spp 6 --report \
  >"$WORK/out.txt" 2>"$WORK/err.txt"
n=$(grep -c "noise ~" "$WORK/err.txt")
first=$(grep "noise ~" "$WORK/err.txt" | head -1 | sed 's/.*noise ~\([0-9.e+-]*\)%.*/\1/')
last=$(grep "noise ~" "$WORK/err.txt" | tail -1 | sed 's/.*noise ~\([0-9.e+-]*\)%.*/\1/')
[ "$n" = 5 ] && awk "BEGIN { exit !($last < $first) }" && pass "--report: 5 estimates, falling ($first% -> $last%)" \
  || fail "--report" "$(cat "$WORK/err.txt")"
[ "$(grep -c "so far: eye [0-9.]* s, pilot [0-9.]* s, photons [0-9.]* s, photon gather [0-9.]* s, volume gather [0-9.]* s, update" "$WORK/err.txt")" = 6 ] \
  && pass "--report: where the time went, stage by stage, each iteration" || fail "--report stages" "$(cat "$WORK/err.txt")"
[ -s "$WORK/r.hdr" ] && head -c 10 "$WORK/r.hdr" | grep -q "#?RADIANCE" && pass "reference writes .hdr" \
  || fail "hdr" "no Radiance file"
# --photons 0 is a count: no photons at all (the eye paths alone); it was taken for "not given" and
# traced the default 200,000 an iteration (ortho.lua: a sun through a glass ball: 400,000 in 2)
"$CAUSTICA" reference tests/scenes/ortho.lua -o "$WORK/p0.pfm" --size 16x16 --spp 2 --photons 0 >"$WORK/p0.txt" 2>&1
grep -q "2 iterations, 0 photons (0 caustic)" "$WORK/p0.txt" && pass "--photons 0 traces none" \
  || fail "--photons 0" "$(cat "$WORK/p0.txt")"
# Paths cut at the bounce cap say so: a glass rod of 200 guides the light past 1,024 total internal
# reflections (the rod of 6, about 90, shows its end exactly: tests/lua/reference_test.lua)
"$CAUSTICA" reference tests/scenes/light_guide.lua --set length=200 -o "$WORK/guide.pfm" --spp 1 --photons 0 \
  >"$WORK/guide.txt" 2>&1
"$CAUSTICA" reference tests/scenes/light_guide.lua -o "$WORK/guide6.pfm" --spp 1 --photons 0 >"$WORK/guide6.txt" 2>&1
grep -q "warning: reference: [1-9][0-9]* eye paths and 0 glossy rays were cut after 1024 specular bounces" \
  "$WORK/guide.txt" && ! grep -q "were cut" "$WORK/guide6.txt" \
  && pass "eye paths cut at the bounce cap are counted and said, once; none in a rod they cross" \
  || fail "bounce cap" "$(cat "$WORK/guide.txt" "$WORK/guide6.txt")"
finish
