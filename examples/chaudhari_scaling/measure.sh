#!/usr/bin/env bash
# Chaudhari 2008, Table 4.1 as ratios: layered_refraction's frame time
# against the model's triangle count at 16 and 32 layers, split into the
# stages that scale with triangles (bounds + voxelize + attributes: one
# draw of the mesh each) and those that scale with pixels and depth
# complexity (peel + ranges + trace). Median of --repeat runs of
# `caustica render --timings` (each a fresh second run of the frame).
#   examples/chaudhari_scaling/measure.sh [CAUSTICA] [SIZE] [REPEAT]
set -u
CAUSTICA=${1:-build/caustica}
SIZE=${2:-512x512}
REPEAT=${3:-3}
cd "$(dirname "$0")/../.."
median() { sort -n | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }
echo "| model | triangles | layers | pass ms | triangle-bound ms | pixel-bound ms |"
echo "|---|---:|---:|---:|---:|---:|"
for model in bunny15k bunny69k armadillo86k dragon40k dragon200k dragon800k; do
  for layers in 16 32; do
    tri=""; : >/tmp/caustica_scaling.$$
    for r in $(seq "$REPEAT"); do
      "$CAUSTICA" render scenes/chaudhari_table41.lua --set model=$model --set layers=$layers --size "$SIZE" \
        --timings -o /tmp/caustica_scaling_$$.png >/tmp/caustica_scaling_out.$$ 2>&1 || { cat /tmp/caustica_scaling_out.$$; exit 1; }
      awk '/^glass /{pass=$3; tri=$5} /^  (bounds|voxelize|attributes) /{g+=$2} /^  (peel|ranges|trace) /{p+=$2}
           END {print pass, g, p, tri}' /tmp/caustica_scaling_out.$$ >>/tmp/caustica_scaling.$$
    done
    pass=$(awk '{print $1}' /tmp/caustica_scaling.$$ | median)
    geo=$(awk '{print $2}' /tmp/caustica_scaling.$$ | median)
    pix=$(awk '{print $3}' /tmp/caustica_scaling.$$ | median)
    tri=$(awk 'NR==1{print $4 / 3}' /tmp/caustica_scaling.$$)
    printf "| %s | %d | %d | %.1f | %.1f | %.1f |\n" "$model" "$tri" "$layers" "$pass" "$geo" "$pix"
  done
done
rm -f /tmp/caustica_scaling.$$ /tmp/caustica_scaling_out.$$ /tmp/caustica_scaling_$$.png
