#!/usr/bin/env bash
# How close to its --time-budget `caustica reference` ends, on an idle machine and beside two CPU
# hogs: a measurement, not a test (the suite judges the budget by what the reference reports of its
# own work; tests/cli/reference_test.sh). Prints one row a run: the scene, the load, the budget, the
# reference's own clock and the whole process's wall time. docs/TESTING.md keeps the last figures.
#   tests/bench/reference_budget.sh [CAUSTICA] [RUNS]
set -u
cd "$(dirname "$0")/../.."
CAUSTICA=${1:-build/caustica}
RUNS=${2:-3}
WORK=$(mktemp -d /tmp/caustica-budget.XXXXXX)
hogs=""
trap 'kill $hogs 2>/dev/null; rm -rf "$WORK"' EXIT
printf '| scene | beside | budget | its clock (s) | wall (s) |\n|---|---|---|---|---|\n'
for load in idle "two hogs"; do
  if [ "$load" = "two hogs" ]; then
    for _ in 1 2; do (exec timeout 900 sh -c 'while :; do :; done') & hogs="$hogs $!"; done
  fi
  for scene in "tests/scenes/ball_lens.lua" "tests/scenes/fog.lua --set ball=true"; do
    for _ in $(seq "$RUNS"); do
      start=$(date +%s.%N)
      # shellcheck disable=SC2086
      "$CAUSTICA" reference $scene -o "$WORK/b.pfm" --size 256x256 --photons 50000000 --time-budget 2 \
        >"$WORK/out.txt" 2>/dev/null
      wall=$(awk "BEGIN { printf \"%.2f\", $(date +%s.%N) - $start }")
      clock=$(sed -n 's/.*photons (.* caustic), \([0-9.]*\) s on.*/\1/p' "$WORK/out.txt")
      printf '| %s | %s | 2 s | %s | %s |\n' "$scene" "$load" "${clock:-?}" "$wall"
    done
  done
done
