# Issue 32: photon_caustics { accumulate = 16 } on the comparison ball (the
# still light at 128 x 128, the turning one at 96; docs/TEMPORAL.md). Still: the
# 32 x 32 grid (a point a photon) accumulated over 16 frames comes within
# 20% of a one-frame 128 x 128 grid (16 times the photons) and well below
# its own one frame. The turning light: its flicker at most half and its
# error not worse. (The layered and beam accumulation and the accumulated
# frames' NaN and still-history checks are tests/cli/temporal_test.sh: the
# two files were one, the suite's longest, and now run side by side.)
source "$(dirname "$0")/lib.sh"
col() { # col CSV BUFFER ACCUMULATE COLUMN: the GPU row with that grid and accumulation
  awk -F, -v b="$2" -v a="$3" -v name="$4" 'NR == 1 { for (i = 1; i <= NF; i++) h[$i] = i; next }
    $1 == "gpu" && $h["caustics.buffer"] == b && $h["caustics.accumulate"] == a { print $h[name]; exit }' "$1"
}
ref="--ref-photons 20000 --ref-spp 16"
"$CAUSTICA" bench scenes/compare/ball.lua --set technique=photons --set turn=0 --size 128x128 --frames 1 --frame 16 \
  --error-frames 1 --sweep caustics.buffer=32,128 --sweep caustics.footprint=0 --sweep caustics.accumulate=1,16 \
  $ref -o "$WORK/still" >"$WORK/still.txt" 2>&1
one32=$(col "$WORK/still/results.csv" 32 1 error)
acc32=$(col "$WORK/still/results.csv" 32 16 error)
one128=$(col "$WORK/still/results.csv" 128 1 error)
if [ -n "$acc32" ] && [ -n "$one128" ] && [ -n "$one32" ] &&
   awk -v a="$acc32" -v b="$one128" -v o="$one32" 'BEGIN { exit !(a <= 1.2 * b && a < 0.6 * o) }'; then
  pass "still light: 32x32 grid over 16 frames $acc32, one 128x128 frame $one128, one 32x32 frame $one32"
else
  fail "still light" "16 frames '$acc32', 128 one frame '$one128', 32 one frame '$one32': $(tail -3 "$WORK/still.txt")"
fi
# Six error frames: the first of them is frame 0, where no history can be
# (the same image either way); with three it was a third of the mean and
# decided the ratio (0.155 -> 0.081, 52%; over six 0.161 -> 0.058, 36%).
"$CAUSTICA" bench scenes/compare/ball.lua --set technique=photons --set turn=0.3 --size 96x96 --frames 1 \
  --error-frames 6 --sweep caustics.buffer=32 --sweep caustics.footprint=0 --sweep caustics.accumulate=1,16 \
  $ref -o "$WORK/turn" >"$WORK/turn.txt" 2>&1
e1=$(col "$WORK/turn/results.csv" 32 1 error)
e16=$(col "$WORK/turn/results.csv" 32 16 error)
f1=$(col "$WORK/turn/results.csv" 32 1 flicker)
f16=$(col "$WORK/turn/results.csv" 32 16 flicker)
if [ -n "$e16" ] && [ -n "$f16" ] && awk -v e1="$e1" -v e16="$e16" -v f1="$f1" -v f16="$f16" \
   'BEGIN { exit !(f16 <= 0.5 * f1 && e16 <= e1) }'; then
  pass "turning light: flicker $f1 -> $f16, error $e1 -> $e16"
else
  fail "turning light" "flicker '$f1' -> '$f16', error '$e1' -> '$e16': $(tail -3 "$WORK/turn.txt")"
fi
finish
