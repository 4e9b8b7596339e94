#!/usr/bin/env bash
# Regenerates docs/OPTICS_MATRIX.md: runs the technique x case matrix
# (tests/lua/optics_matrix_test.lua, the same test `make test` runs) and
# writes its rows as a table. Usage: tests/optics_matrix.sh [build/caustica]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/caustica}
out=docs/OPTICS_MATRIX.md
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if ! "$bin" test tests/lua/optics_matrix_test.lua >"$log" 2>&1; then
  grep -E '^(FAIL|ok) ' "$log" >&2 || cat "$log" >&2
  echo "tests/optics_matrix.sh: the matrix test failed; $out not written" >&2
  exit 1
fi
{
  echo "# The technique x case matrix"
  echo
  echo "Written by \`tests/optics_matrix.sh\` from \`tests/lua/optics_matrix_test.lua\` (run by \`make test\`), on"
  echo "$(date -u +%Y-%m-%d), llvmpipe. Each technique at its defaults on cases built from their own closed forms"
  echo "(\`tests/lua/closed_forms.lua\`; the scenes are \`tests/scenes/matrix/\`):"
  echo
  echo "- **water**: a sun 30 degrees off the zenith over water of IOR 1.33 absorbing {0.2, 0.5, 1.0} per unit length,"
  echo "  the floor 2 below, seen straight down 1 wide (orthographic: its 64 pixel centres on the water grid's"
  echo "  lines). Flat (E cos ti exp(-sigma d / cos tt)), and ridges A sin(2 pi x) traced as rays binned per"
  echo "  pixel column. Error: relative RMS of the column means against the binned truth, over R, G and B."
  echo "- **ball lens**: radius 0.5, the sun straight above, the floor 1.25, 1.5 (the paraxial focus) and 2.5"
  echo "  radii below its centre (and 1.01: almost touching; at 2.5 also of radius 0.01 and 100, the whole case"
  echo "  scaled). Error: relative RMS of the mean irradiance in 16 rings of its shadow against"
  echo "  an exact 2D trace."
  echo "  The same water under a sun 5 and 2 degrees up, 100 wide seen 1 wide (sun 60 and 3 degrees up), the whole"
  echo "  case scaled by 0.01 and 100, and flat water through a 174-degree perspective camera; \"light kept\": the"
  echo "  mean over the view against the truth's (the error column is |kept - 1|)."
  echo "- **IOR 1.0 identity**: an IOR-1.0 sphere before a checkered wall, a box and a floor (also with the near"
  echo "  plane 1e-5 of the far); an IOR-1.0 cube and sphere before the environment alone; the room of coloured"
  echo "  boxes (inside the sphere's silhouette, 256 x 256). Error: relative RMS difference from the same graph"
  echo "  without them."
  echo "- **shadow border**: the ball at IOR 1.0 and 1.0001 lit with a shadow map, the caustics pass and shade;"
  echo "  the relative RMS difference from the floor without the ball."
  echo "- **cube**: a glass cube tilted under the sun (IOR 2.42, 0.8; the sun straight down and 40 degrees off),"
  echo "  its caustic against an exact light trace through it, as 4 x 4-pixel block means. No closed form but"
  echo "  the reference's exact trace: the IOR-2.42 cube with Fresnel seen in the room (128 x 128; relative RMS"
  echo "  over the pixels whose path meets a total internal reflection, and how many are within 0.02), and a"
  echo "  wine glass with walls 0.012 thick under a spot light (the floor around it, 128 x 128, against 16"
  echo "  iterations of 400,000 photons)."
  echo "- A pass that leaves a third or more of a glass object's shadow black says so in one warning, counting"
  echo "  (the ball 0.01 radii above its floor: every technique; tests/cli/leaves_out_test.sh)."
  echo
  echo "\"black\": pixels at 0 where the closed form lights the whole pixel. \"known\": a failure measured and"
  echo "not fixed yet; its bound is the measured value with a margin (a regression still fails the test)."
  echo "\"n/a\": the technique does not handle the case, and why; \"not measured\": a registered technique no case"
  echo "names yet (c.techniques; issue 54). Time: the pass's milliseconds in that render"
  echo "(64 x 64 for water, 128 x 128 for the ball and the identity)."
  echo
  echo "| case | technique | camera | error | bound | black | ms | status |"
  echo "|---|---|---|---|---|---|---|---|"
  grep '^matrix| ' "$log" | sed -e 's/^matrix| /| /' -e 's/$/ |/'
  echo
  echo "The same cases at 256 x 256 where photons or beams land farther apart than the 64- and 128-pixel"
  echo "cells show: black pixels only (the error is the cells' job above)."
  echo
  echo "| case | technique | black | bound | status |"
  echo "|---|---|---|---|---|"
  grep '^black256| ' "$log" | sed -e 's/^black256| /| /'
} >"$out"
echo "wrote $out"
