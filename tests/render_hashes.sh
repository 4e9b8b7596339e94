#!/usr/bin/env bash
# Byte-identity check for refactors (issue 10): renders every scene in
# scenes/ and tests/scenes/ at 128x128, frames 0 and 10 (10 where the script
# has that many), as PNG and PFM, plus the reference renderer at a fixed seed
# on two scenes, and prints one "sha256  name" line per image.
#
#   tests/render_hashes.sh build/caustica > before.txt
#   (refactor, rebuild)
#   tests/render_hashes.sh build/caustica | diff before.txt -
#
# `--check FILE` compares against a stored list and exits 1 on any difference.
set -u
CAUSTICA=${1:?usage: render_hashes.sh CAUSTICA [--check FILE]}
CHECK=""
[ "${2:-}" = "--check" ] && CHECK=${3:?--check needs a file}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
WORK=$(mktemp -d /tmp/caustica-hashes.XXXXXX)
trap 'rm -rf "$WORK"' EXIT
out="$WORK/hashes.txt"
: >"$out"
for script in scenes/*.lua tests/scenes/*.lua; do
  case "$script" in tests/scenes/sandbox.lua) continue ;; esac
  for frame in 0 10; do
    for ext in png pfm; do
      name="$(basename "$(dirname "$script")")_$(basename "$script" .lua)_f${frame}.$ext"
      if "$CAUSTICA" render "$script" --frame $frame --size 128x128 -o "$WORK/$name" >/dev/null 2>"$WORK/err"; then
        (cd "$WORK" && sha256sum "$name") >>"$out"
      elif ! grep -q "past the script's last frame" "$WORK/err"; then
        echo "error  $name: $(head -1 "$WORK/err")" >>"$out"
      fi
    done
  done
done
for script in tests/scenes/ball_lens.lua scenes/glass_sphere.lua; do
  name="reference_$(basename "$script" .lua).pfm"
  "$CAUSTICA" reference "$script" --size 32x32 --photons 20000 --spp 2 --seed 7 -o "$WORK/$name" >/dev/null 2>&1 \
    && (cd "$WORK" && sha256sum "$name") >>"$out" || echo "error  $name" >>"$out"
done
if [ -n "$CHECK" ]; then
  if diff "$CHECK" "$out" >"$WORK/diff"; then
    echo "render_hashes: $(wc -l <"$out") images identical to $CHECK"
  else
    cat "$WORK/diff"
    echo "render_hashes: images differ from $CHECK"
    exit 1
  fi
else
  cat "$out"
fi
