#!/usr/bin/env bash
# The farm recipe on a real single-node Slurm: this test starts munged,
# slurmctld and slurmd on 127.0.0.1 (its own key, ports, state and spool in
# a temporary directory; stopped by PID at the end), submits
# data/farm/dirt-render-array.sbatch as a 3-task array over a sequence,
# kills one task's dirt-render mid-frame (SIGKILL: its claim and temp file
# stay behind), resubmits the array, and checks that every frame exists
# once, complete, equal to a one-process render, with no claim or temp file
# left (frames compared pixel for pixel: their headers differ by the command
# line that made them). Needs root (the daemons run as root); skips (77)
# elsewhere.
# usage: test_slurm.sh DIRT_RENDER SOURCE_ROOT EXR_COMPARE
set -u
render=$(realpath "$1") root=$(realpath "$2") exr=$(realpath "$3")
passes=0 fails=0
ok() { passes=$((passes + 1)); }
fail() { fails=$((fails + 1)); echo "FAIL: $*" >&2; }
finish() { echo "$passes passed, $fails failed"; [ $fails -eq 0 ]; exit $?; }
skip() {
  if [ "${CI:-}" = true ]; then fail "$1 (CI=true: the Slurm test must run)"; finish; fi
  echo "$1: skipping"; exit 77
}

[ "$(id -u)" -eq 0 ] || { echo "not root: skipping"; exit 77; }
for p in munged mungekey slurmctld slurmd sbatch squeue sinfo; do
  command -v $p >/dev/null || skip "no $p (apt-get install slurm-wlm munge)"
done
scene=${DIRT_SHARED_DIR:-../shared}/scenes/gltf/BoxAnimated/BoxAnimated.gltf
[ -r "$scene" ] || skip "no $scene"
scene=$(realpath "$scene")

T=$(mktemp -d)
pids=()
cleanup() {
  for f in "$T"/slurmd.pid "$T"/slurmctld.pid "$T"/munged.pid; do
    [ -s "$f" ] && kill "$(cat "$f")" 2>/dev/null
  done
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  sleep 1
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null; done
  rm -rf "$T"
}
trap cleanup EXIT
mkdir -p "$T/state" "$T/spool" "$T/out"
mungekey -c -k "$T/munge.key" -b 1024 || skip "mungekey failed"
chmod 600 "$T/munge.key"
munged --key-file="$T/munge.key" --socket="$T/munge.sock" --pid-file="$T/munged.pid" \
  --log-file="$T/munged.log" --seed-file="$T/munge.seed" --force || skip "munged did not start"
host=$(hostname -s)
port=$((20000 + RANDOM % 20000))
cat >"$T/slurm.conf" <<EOF
ClusterName=dirttest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$T/munge.sock
CredType=cred/munge
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/slurmctld.log
SlurmdLogFile=$T/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
KillWait=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=dirt Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$T/slurm.conf
slurmctld -D -f "$SLURM_CONF" >"$T/ctld.out" 2>&1 & pids+=($!)
sleep 1
slurmd -D -f "$SLURM_CONF" -N "$host" >"$T/d.out" 2>&1 & pids+=($!)
for _ in $(seq 1 60); do
  sinfo -h -o %t 2>/dev/null | grep -q idle && break
  sleep 0.5
done
sinfo -h -o %t 2>/dev/null | grep -q idle && ok || { fail "the node never became idle"; cat "$T"/*.log "$T"/*.out >&2; finish; }

# wait_jobs: until the queue is empty (at most 5 minutes).
wait_jobs() {
  for _ in $(seq 1 600); do
    [ -z "$(squeue -h 2>/dev/null)" ] && return 0
    sleep 0.5
  done
  return 1
}
frames=0:8
args="-W 24 -H 18 --spp 160 -q --claim-timeout 3" # frames of a second or more: a kill lands mid-frame
export DIRT_RENDER=$render DIRT_SCENE=$scene DIRT_OUTPUT=$T/out/f_####.exr DIRT_FRAMES=$frames \
  DIRT_LOG_DIR=$T/out DIRT_ARGS=$args
cd "$T" || exit 1
job=$(sbatch --parsable --array=0-2 "$root/data/farm/dirt-render-array.sbatch") && ok || fail "sbatch"
# Kill the first task that is mid-frame: its claim exists, its frame does not.
victim=
for _ in $(seq 1 600); do
  for c in "$T"/out/*.claim.*; do
    [ -e "$c" ] || continue
    f=${c%.claim.*}
    [ -e "$f" ] && continue
    # The claim names its holder ("HOST PID"): kill that worker, not any
    # task (another may be between frames or already exiting).
    victim=$(awk '{print $2}' "$c" 2>/dev/null)
    [ -n "$victim" ] && [ ! -e "$f" ] && kill -0 "$victim" 2>/dev/null && break 2
    victim=
  done
  sleep 0.1
done
[ -n "$victim" ] && kill -KILL "$victim" && ok || fail "no task to kill mid-frame"
wait_jobs && ok || fail "first array did not finish"
left=$(ls "$T/out" | grep -c '\.claim\.')
[ "$left" -ge 1 ] && ok || fail "the killed task left no claim (was it mid-frame?)"
missing=0
for i in $(seq 0 8); do [ -e "$T/out/f_$(printf %04d "$i").exr" ] || missing=$((missing + 1)); done
[ $missing -ge 1 ] && ok || fail "nothing was missing after the kill"
sleep 4 # the killed worker's claim goes stale (--claim-timeout 3)
job2=$(sbatch --parsable --array=0-2 "$root/data/farm/dirt-render-array.sbatch") && ok || fail "resubmit"
wait_jobs && ok || fail "second array did not finish"
for f in "$T"/dirt-render_"$job2"_*.out; do
  [ -s "$f" ] && { echo "task output $f:" >&2; cat "$f" >&2; }
done

# Every frame once, complete, equal to one process; nothing left behind.
"$render" "$scene" -o "$T/one/f_####.exr" --frames $frames ${args% --claim-timeout 3} \
  || fail "one-process render"
for i in $(seq 0 8); do
  n=$(printf %04d "$i")
  "$exr" --exact "$T/out/f_$n.exr" "$T/one/f_$n.exr" >/dev/null && ok || fail "frame $n missing or differs"
done
[ "$(ls "$T/out" | grep -c '\.exr$')" -eq 9 ] && ok || fail "frames: $(ls "$T/out")"
[ "$(ls "$T/out" | grep -c -e '\.claim\.' -e '\.tmp\.')" -eq 0 ] && ok \
  || fail "claims or temp files left: $(ls "$T/out")"
rendered=$(cat "$T"/out/task_"$job2"_*.jsonl | grep -c '"frame"')
[ "$rendered" -eq "$missing" ] && ok || fail "resubmission rendered $rendered, $missing were missing"
finish
