#!/bin/bash
# A Slurm array job recording a caustica scene in shards: each array task
# renders every n-th frame of the set (interleaved), into one shared folder
# (frames are written to a temporary and renamed, so tasks never see each
# other's partial files; a resubmitted task skips frames already there).
#
#   sbatch --array=0-3 examples/slurm/record_array.sh scenes/demo.lua out/demo 0-119
#
# The array size is the shard count (SLURM_ARRAY_TASK_COUNT); any farm
# that sets an index and a count (OpenCue, Deadline, Flamenco `exec` jobs)
# can run the same `caustica record ... --shard i/n` line.
#SBATCH --job-name=caustica-record
#SBATCH --output=caustica-record-%A_%a.log
#SBATCH --cpus-per-task=2
set -euo pipefail
scene=${1:?usage: record_array.sh SCENE.lua OUT_DIR_OR_PATTERN [FRAMES]}
out=${2:?usage: record_array.sh SCENE.lua OUT_DIR_OR_PATTERN [FRAMES]}
frames=${3:-}
index=${SLURM_ARRAY_TASK_ID:?not inside a Slurm array job (sbatch --array=0-N)}
count=${SLURM_ARRAY_TASK_COUNT:?not inside a Slurm array job (sbatch --array=0-N)}
caustica=${CAUSTICA:-caustica}
args=(record "$scene" -o "$out" --shard "$index/$count")
[ -n "$frames" ] && args+=(--frames "$frames")
[ -n "${CAUSTICA_SIZE:-}" ] && args+=(--size "$CAUSTICA_SIZE")
exec "$caustica" "${args[@]}"
