#!/bin/bash
# The distributed reference measured on this machine (docs/REFERENCE.md,
# "One frame, many nodes"): every shard runs alone on the whole machine, one
# after another, as each would on its own node.
#
#   examples/reference_shards/measure.sh [SCENE] [SIZE] [PHOTONS]
#
# Strong scaling: the same 16 passes split over 1, 2 and 4 shards; the
# slowest shard's time is the array's wall time. Equal wall time: n shards of
# 4 passes each (what n nodes render in the time one renders 4), merged,
# against a converged truth of 64 passes with another seed.
set -euo pipefail
scene=${1:-scenes/compare/ball.lua}
size=${2:-512x512}
photons=${3:-200000}
caustica=${CAUSTICA:-build/caustica}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() { # OUT SHARD SPP [SEED]: prints the seconds the shard took
  local start end
  start=$(date +%s.%N)
  "$caustica" reference "$scene" -o "$1" --size "$size" --photons "$photons" --spp "$3" --shard "$2" \
    --seed "${4:-1}" -q >/dev/null
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }'
}
echo "scene $scene at $size, $photons photons a pass, $(nproc) CPUs"
truth_s=$(run "$work/truth.exr" 0/1 64 7)
echo "truth: 64 passes, seed 7, ${truth_s} s"
echo
echo "| shards | passes each | slowest shard | speed-up |"
echo "|---|---|---|---|"
base=""
for n in 1 2 4; do
  slowest=0
  for ((i = 0; i < n; i++)); do
    t=$(run "$work/s${n}_$i.exr" "$i/$n" 16)
    slowest=$(awk -v a="$slowest" -v b="$t" 'BEGIN { print (b > a ? b : a) }')
  done
  [ -z "$base" ] && base=$slowest
  echo "| $n | $((16 / n)) | ${slowest} s | $(awk -v a="$base" -v b="$slowest" 'BEGIN { printf "%.2f", a / b }') |"
done
echo
echo "| nodes | passes merged | rel_rmse against the truth | x sqrt(nodes) |"
echo "|---|---|---|---|"
for n in 1 2 4; do
  for ((i = 0; i < n; i++)); do
    run "$work/e${n}_$i.exr" "$i/$n" $((4 * n)) >/dev/null
  done
  "$caustica" merge "$work"/e${n}_*.exr -o "$work/e$n.exr" -q >/dev/null 2>&1
  rel=$("$caustica" compare "$work/e$n.exr" "$work/truth.exr" | tr ' ' '\n' | sed -n 's/^rel_rmse=//p')
  echo "| $n | $((4 * n)) | $rel | $(awk -v r="$rel" -v n="$n" 'BEGIN { printf "%.4f", r * sqrt(n) }') |"
done
