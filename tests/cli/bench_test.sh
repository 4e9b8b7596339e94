# `caustica bench`: CSV, Markdown table and plot; the ground truth cached;
# the reference's own error falls as it runs longer.
source "$(dirname "$0")/lib.sh"
B="$WORK/bench"
"$CAUSTICA" bench tests/scenes/ball_lens.lua --sweep floor=0.75,1.0 --sweep shade.caustics=0 --size 32x32 --frames 2 \
  -o "$B" --ref-photons 20000 --ref-spp 8 >"$WORK/out.txt" 2>"$WORK/err.txt"
# (shade has no number parameter: that sweep must be refused)
grep -q "not a number parameter\|has no parameter" "$WORK/err.txt" && pass "a non-number pass parameter is refused" \
  || fail "non-number pass parameter" "$(cat "$WORK/err.txt")"

"$CAUSTICA" bench tests/scenes/ball_lens.lua --sweep floor=0.75,1.0 --size 32x32 --frames 2 \
  -o "$B" --ref-photons 20000 --ref-spp 8 >"$WORK/out.txt" 2>"$WORK/err.txt" || fail "bench" "$(cat "$WORK/err.txt")"
# The first variant timed in the process runs its timing frames once untimed first (the process's
# own first use: a first variant measured 1,257 ms against 277 for the next), said once with -v.
"$CAUSTICA" bench tests/scenes/ball_lens.lua --sweep floor=0.75,1.0 --size 32x32 --frames 2 \
  -o "$B" --ref-photons 20000 --ref-spp 8 -v >/dev/null 2>"$WORK/warm.txt"
[ "$(grep -c "bench: warm-up: 2 untimed frames of 'floor=0.75' before the first timed variant" "$WORK/warm.txt")" = 1 ] \
  && pass "bench warms the process up once, over the first variant's timing frames" \
  || fail "bench warm-up" "$(grep -i warm "$WORK/warm.txt")"
for f in results.csv results.md plot.svg; do
  [ -s "$B/$f" ] && pass "wrote $f" || fail "wrote $f" "missing"
done
rows=$(grep -c '^gpu,' "$B/results.csv"); refs=$(grep -c '^reference,' "$B/results.csv")
[ "$rows" = 2 ] && [ "$refs" = 8 ] && pass "2 variants and 4 reference levels for each of the 2 scenes" \
  || fail "rows" "$rows gpu, $refs reference"
[ "$(grep -c '^reference,0.75,' "$B/results.csv")" = 4 ] && [ "$(grep -c '^reference,1.0,' "$B/results.csv")" = 4 ] \
  && pass "every reference row carries its scene's parameters" || fail "reference rows" "$(cat "$B/results.csv")"
grep -q "<svg" "$B/plot.svg" && grep -q "reference: floor=0.75" "$B/plot.svg" && grep -q "reference: floor=1.0" "$B/plot.svg" \
  && [ "$(grep -c '<polyline' "$B/plot.svg")" = 2 ] && pass "the plot has one labelled reference curve per scene" \
  || fail "plot" "$(head -c 300 "$B/plot.svg")"
grep -q ">1  floor=0.75 (" "$B/plot.svg" && grep -q ">10  reference 8 it floor=1.0 (" "$B/plot.svg" \
  && pass "the points are numbered, with a side table" || fail "numbered points" "$(grep -o '>[0-9]*  [^<]*' "$B/plot.svg" | head)"
# the reference's error against its truth falls from 1 to 8 iterations: over the image (rel_rmse);
# the caustic region at 32 x 32 is the few pixels about a singular focus, whose error is where a
# handful of photons fall (2026-12-07, the ball traced as a sphere: 0.2545 -> 0.3703 -> 0.2947 ->
# 0.2635 at 1, 2, 4, 8 iterations; as triangles 0.2660 -> 0.3638 -> 0.2984 -> 0.2511; the image's
# 0.1555 -> 0.0880 and 0.1571 -> 0.0849)
ecol=$(head -1 "$B/results.csv" | tr ',' '\n' | grep -nx rel_rmse | cut -d: -f1)
first=$(grep '^reference,' "$B/results.csv" | head -1 | cut -d, -f"$ecol")
last=$(grep '^reference,' "$B/results.csv" | sed -n 4p | cut -d, -f"$ecol")
awk "BEGIN { exit !($last < 0.75 * $first) }" && pass "reference error falls by a quarter or more ($first -> $last)" || fail "reference error falls" "$first -> $last"
ls "$B"/cache/truth_*.pfm >/dev/null 2>&1 && pass "ground truth cached" || fail "cache" "no files"
grep -q "rendering the ground truth" "$WORK/err.txt" && pass "first run renders the truth" || fail "first run" "$(cat "$WORK/err.txt")"
"$CAUSTICA" bench tests/scenes/ball_lens.lua --sweep floor=0.75,1.0 --size 32x32 --frames 2 \
  -o "$B" --ref-photons 20000 --ref-spp 8 >"$WORK/out2.txt" 2>"$WORK/err2.txt"
grep -q "rendering the ground truth" "$WORK/err2.txt" && fail "second run" "rendered the truth again" || pass "second run reuses the cache"

# A truth from elsewhere (issue 28): a reference rendered in two shards and merged is bench's ground
# truth (no truth rendered), its .part checked against the frame and size bench measures.
for i in 0 1; do
  "$CAUSTICA" reference scenes/demo.lua -o "$WORK/tp$i.exr" --size 64x64 --photons 1000 --spp 8 --shard $i/2 -q >/dev/null
done
"$CAUSTICA" merge "$WORK/tp0.exr" "$WORK/tp1.exr" -o "$WORK/truth.exr" -q
"$CAUSTICA" bench scenes/demo.lua --sweep shadow.size=256,1024 --size 64x64 --frames 2 -o "$WORK/bt" \
  --ref-photons 1000 --ref-spp 8 --truth "$WORK/truth.exr" >"$WORK/bt.txt" 2>&1
! grep -q "rendering the ground truth" "$WORK/bt.txt" && [ "$(grep -c '^| shadow.size=' "$WORK/bt/results.md")" = 2 ] \
  && pass "bench --truth: a merged reference is the ground truth, none rendered" || fail "bench --truth" "$(cat "$WORK/bt.txt")"
"$CAUSTICA" bench scenes/demo.lua --sweep shadow.size=256,1024 --size 32x32 --frames 1 -o "$WORK/bt2" \
  --ref-photons 1000 --ref-spp 8 --truth "$WORK/truth.exr" >/dev/null 2>"$WORK/bt2.txt"
rc=$?
[ $rc = 1 ] && grep -q "a reference of frame 0 at 64x64; bench measures frame 0 at 32x32" "$WORK/bt2.txt" \
  && pass "bench --truth of another size is refused" || fail "bench --truth size" "exit $rc: $(cat "$WORK/bt2.txt")"

# The demo with a sweep of a pass parameter.
"$CAUSTICA" bench scenes/demo.lua --sweep shadow.size=256,1024 --size 64x64 --frames 2 -o "$WORK/demo" \
  --ref-photons 1000 --ref-spp 8 >"$WORK/demo.txt" 2>&1 && [ -s "$WORK/demo/results.md" ] \
  && pass "bench on the demo" || fail "bench on the demo" "$(cat "$WORK/demo.txt")"
expect_error "bad sweep" 2 "--sweep needs key=v1,v2" - -- "$CAUSTICA" bench scenes/demo.lua --sweep nothing
finish
