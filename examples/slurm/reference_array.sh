#!/bin/bash
# A Slurm array job rendering one ground-truth frame across nodes: each
# array task renders its share of the reference's independent passes
# (`caustica reference --shard i/n`: probabilistic progressive photon
# mapping, so passes share no state), writing OUT_PREFIX.part_<i>.exr and
# its .part file; `caustica merge` then averages the parts into the
# estimate one run of all the passes makes (equal to it but for
# floating-point rounding).
#
#   jid=$(sbatch --parsable --array=0-15 examples/slurm/reference_array.sh scenes/compare/ball.lua out/ball 64)
#   sbatch --dependency=afterok:$jid --wrap "caustica merge out/ball.part_*.exr -o out/ball.exr"
#
# SPP is the passes of the whole estimate (--spp), shared out over the
# array (each task renders about SPP / n of them); CAUSTICA_PHOTONS sets
# the photons per pass, CAUSTICA_SIZE the image size, CAUSTICA_FRAME the
# frame.
#SBATCH --job-name=caustica-reference
#SBATCH --output=caustica-reference-%A_%a.log
#SBATCH --cpus-per-task=2
set -euo pipefail
usage="usage: reference_array.sh SCENE.lua OUT_PREFIX SPP"
scene=${1:?$usage}
prefix=${2:?$usage}
spp=${3:?$usage}
index=${SLURM_ARRAY_TASK_ID:?not inside a Slurm array job (sbatch --array=0-N)}
count=${SLURM_ARRAY_TASK_COUNT:?not inside a Slurm array job (sbatch --array=0-N)}
caustica=${CAUSTICA:-caustica}
args=(reference "$scene" -o "$prefix.part_$index.exr" --spp "$spp" --shard "$index/$count")
[ -n "${CAUSTICA_PHOTONS:-}" ] && args+=(--photons "$CAUSTICA_PHOTONS")
[ -n "${CAUSTICA_SIZE:-}" ] && args+=(--size "$CAUSTICA_SIZE")
[ -n "${CAUSTICA_FRAME:-}" ] && args+=(--frame "$CAUSTICA_FRAME")
exec "$caustica" "${args[@]}"
