#!/usr/bin/env bash
# Writes the seed corpus of the scene-script fuzzer into DIR: the project's
# own scene scripts, with asset paths rewritten to "scenes/assets/..." (the
# harness links scenes/ beside the script it runs).
set -eu
out=${1:?usage: script_corpus.sh DIR}
root=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"
for f in "$root"/tests/scenes/*.lua; do
  sed -e 's#\.\./\.\./scenes/assets#scenes/assets#g' "$f" >"$out/tests_$(basename "$f")"
done
for f in "$root"/scenes/demo.lua "$root"/scenes/glass_sphere.lua "$root"/scenes/sandberg_pool.lua \
         "$root"/scenes/huqin_sphere.lua "$root"/examples/*.lua; do
  [ -f "$f" ] || continue
  sed -e 's#"assets/#"scenes/assets/#g' -e 's#\.\./scenes/assets#scenes/assets#g' "$f" \
    >"$out/$(basename "$(dirname "$f")")_$(basename "$f")"
done
