# A real Slurm cluster on this machine: where Debian's slurm-wlm and munge
# are installed and the test runs as root, start munged, slurmctld and
# slurmd with a generated slurm.conf (their sockets, spool and state in a
# temporary folder, unusual ports), submit examples/slurm/record_array.sh
# as an array job of 4 tasks over 8 frames, wait for it, check the frames
# equal a local `record` byte for byte, and stop the cluster. Skipped (exit
# 77, ctest's "skipped") with the reason otherwise. `make test-farm`
# installs the packages and runs it.
source "$(dirname "$0")/lib.sh"
skip() { echo "skip slurm: $1"; exit 77; }
for tool in munged slurmctld slurmd sbatch sinfo; do
  command -v "$tool" >/dev/null || skip "$tool is not installed (apt-get install slurm-wlm munge, or make test-farm)"
done
[ "$(id -u)" = 0 ] || skip "the daemons are started as root (run as root, or make test-farm)"
[ -r /etc/munge/munge.key ] || skip "no /etc/munge/munge.key (the munge package makes one)"
C="$WORK/cluster"
mkdir -p "$C/spool" "$C/state" "$C/log"
host=$(hostname -s)
port=$((17000 + RANDOM % 2000))
cat >"$C/slurm.conf" <<CONF
ClusterName=caustica-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CryptoType=crypto/munge
AuthInfo=socket=$C/munge.socket
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$C/state
SlurmdSpoolDir=$C/spool
SlurmctldPidFile=$C/slurmctld.pid
SlurmdPidFile=$C/slurmd.pid
SlurmctldLogFile=$C/log/slurmctld.log
SlurmdLogFile=$C/log/slurmd.log
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=caustica Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$C/slurm.conf"
stop_cluster() {
  scontrol shutdown >/dev/null 2>&1 # the controller and the node daemon
  for i in 1 2 3 4 5; do
    pgrep -f "$C/slurm" >/dev/null 2>&1 || [ ! -f "$C/slurmctld.pid" ] || break
    sleep 1
  done
  for pidfile in "$C/slurmd.pid" "$C/slurmctld.pid" "$C/munged.pid"; do
    [ -f "$pidfile" ] && kill "$(cat "$pidfile")" 2>/dev/null
  done
  pkill -f -- "--socket=$C/munge.socket" 2>/dev/null
  sleep 1
  rm -rf "$WORK"
}
trap stop_cluster EXIT
munged --force --socket="$C/munge.socket" --key-file=/etc/munge/munge.key --log-file="$C/log/munge.log" \
  --pid-file="$C/munged.pid" --seed-file="$C/munge.seed" 2>"$C/log/munged.err" \
  || skip "munged would not start here: $(tail -1 "$C/log/munged.err")"
slurmctld 2>"$C/log/ctld.err" || skip "slurmctld would not start here: $(tail -1 "$C/log/ctld.err")"
slurmd 2>"$C/log/d.err" || skip "slurmd would not start here: $(tail -1 "$C/log/d.err")"
for i in $(seq 1 30); do
  sinfo -h -o %t 2>/dev/null | grep -q idle && break
  sleep 1
done
sinfo -h -o %t 2>/dev/null | grep -q idle \
  || skip "the one-node cluster did not come up in 30 s: $(tail -2 "$C/log/slurmctld.log" "$C/log/slurmd.log" 2>&1 | tr '\n' ' ')"
pass "a one-node Slurm cluster on $host (port $port)"
OUT="$WORK/farm"
CAUSTICA="$CAUSTICA" CAUSTICA_SIZE=24x24 timeout 300 sbatch --wait --array=0-3 --chdir="$ROOT" \
  --output="$C/log/task-%a.log" examples/slurm/record_array.sh tests/scenes/deform.lua "$OUT" 0-7 >"$WORK/sbatch.txt" 2>&1 \
  && pass "sbatch --array=0-3 --wait: the array job finished" \
  || fail "the array job" "$(cat "$WORK/sbatch.txt" "$C"/log/task-*.log 2>&1 | tail -5)"
"$CAUSTICA" record tests/scenes/deform.lua -o "$WORK/local" --frames 0-7 --size 24x24 >/dev/null
same=0
for f in "$WORK"/local/*.png; do cmp -s "$f" "$OUT/$(basename "$f")" && same=$((same + 1)); done
[ "$same" = 8 ] && [ "$(ls "$OUT" | wc -l)" = 8 ] && pass "8 frames from 4 shards == a local record, byte for byte" \
  || fail "frames" "$same of 8 equal: $(ls "$OUT" 2>&1 | tr '\n' ' ')"
grep -q "frame_0001.png .. .*frame_0005.png" "$C/log/task-1.log" && pass "task 1 rendered frames 1 and 5" \
  || fail "task 1" "$(cat "$C/log/task-1.log" 2>&1)"
# One reference frame over the array: 4 tasks, 8 independent passes, merged; equal to one run of the same
# 8 passes but for floating-point rounding.
CAUSTICA="$CAUSTICA" CAUSTICA_SIZE=32x32 CAUSTICA_PHOTONS=5000 timeout 300 sbatch --wait --array=0-3 --chdir="$ROOT" \
  --output="$C/log/ref-%a.log" examples/slurm/reference_array.sh tests/scenes/ball_lens.lua "$WORK/ref" 8 \
  >"$WORK/sbatch_ref.txt" 2>&1 \
  && "$CAUSTICA" merge "$WORK"/ref.part_*.exr -o "$WORK/ref.exr" >/dev/null 2>"$WORK/merge.err" \
  && pass "sbatch --array=0-3 reference_array.sh, then caustica merge" \
  || fail "the reference array job" "$(cat "$WORK/sbatch_ref.txt" "$WORK/merge.err" "$C"/log/ref-*.log 2>&1 | tail -5)"
"$CAUSTICA" reference tests/scenes/ball_lens.lua -o "$WORK/ref_local.exr" --size 32x32 --photons 5000 --spp 8 \
  --shard 0/1 >/dev/null 2>&1
rel=$(metric rel_rmse "$("$CAUSTICA" compare "$WORK/ref.exr" "$WORK/ref_local.exr" 2>&1)")
[ -n "$rel" ] && awk "BEGIN { exit !($rel < 1e-6) }" && pass "the merged reference == one local run of the 8 passes (rel $rel)" \
  || fail "merged reference" "rel_rmse '$rel'"
finish
