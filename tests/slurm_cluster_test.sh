#!/usr/bin/env bash
# CTest slurm_cluster: a real single-node Slurm cluster on localhost runs sharded rayint jobs
# through scripts/slurm/ and the merged reports equal single runs.
#   slurm_cluster_test.sh RAYINT SOURCE_DIR
# Starts munged, slurmctld and slurmd (Debian's munge and slurm-wlm; scripts/install-deps.sh)
# with a minimal slurm.conf in a temporary directory (proctrack/linuxproc, task/none,
# select/cons_tres, its own ports and munge socket, so it does not touch a system Slurm), submits
# a 4-shard stress run and a 4-shard slab Monte Carlo run with scripts/slurm/submit.sh (an array
# job plus a merge job with --dependency=afterok), waits for them and compares the merged
# reports with single runs (tests/compare_reports.py). Stops the daemons it started (by pid).
# If Slurm cannot start, it says why and FAILS: it never skips.
set -uo pipefail
rayint=$(readlink -f "$1") src=$(readlink -f "$2")
start_time=$(date +%s)
fail() { echo "slurm_cluster: FAIL: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || fail "must run as root to start munged, slurmctld and slurmd (CI runs as root)"
for tool in munged slurmctld slurmd sbatch sinfo squeue scontrol; do
  command -v "$tool" >/dev/null || fail "$tool not found: install munge and slurm-wlm (scripts/install-deps.sh)"
done
T=$(mktemp -d /tmp/rayint-slurm.XXXXXX)
chmod 755 "$T"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  for _ in $(seq 100); do
    alive=0
    for p in "${pids[@]}"; do kill -0 "$p" 2>/dev/null && alive=1; done
    [ "$alive" = 0 ] && break
    sleep 0.1
  done
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null; done
  wait 2>/dev/null
  if [ "${KEEP_SLURM_DIR:-0}" = 1 ]; then echo "kept $T"; else rm -rf "$T"; fi
}
trap cleanup EXIT
mkdir -p "$T"/{key,munge,state,spool,log,run,out}
chmod 700 "$T/key"
host=$(hostname -s)
cpus=$(nproc)
# munge: its own key, socket and files
dd if=/dev/urandom of="$T/key/munge.key" bs=1024 count=1 status=none
chmod 400 "$T/key/munge.key"
munged --foreground --force --key-file="$T/key/munge.key" --socket="$T/munge/munge.sock" \
  --pid-file="$T/munge/munged.pid" --log-file="$T/log/munged.log" --seed-file="$T/key/seed" \
  >"$T/log/munged.stdout" 2>&1 &
pids+=($!)
for _ in $(seq 50); do [ -S "$T/munge/munge.sock" ] && break; sleep 0.1; done
[ -S "$T/munge/munge.sock" ] || fail "munged did not start: $(tail -3 "$T/log/munged.log" 2>/dev/null)"
port=$((17000 + RANDOM % 2000))
cat >"$T/slurm.conf" <<CONF
ClusterName=rayintci
SlurmctldHost=$host
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$T/munge/munge.sock
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/run/slurmctld.pid
SlurmdPidFile=$T/run/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SchedulerType=sched/builtin
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
MinJobAge=300
KillWait=5
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=ci Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$T/slurm.conf
slurmctld -D -i -f "$T/slurm.conf" >"$T/log/slurmctld.stdout" 2>&1 &
pids+=($!)
slurmd -D -f "$T/slurm.conf" >"$T/log/slurmd.stdout" 2>&1 &
pids+=($!)
state=""
for _ in $(seq 120); do
  state=$(sinfo -h -N -o %T 2>/dev/null | head -1)
  [ "$state" = idle ] && break
  sleep 0.5
done
if [ "$state" != idle ]; then
  echo "--- slurmctld log"; tail -15 "$T/log/slurmctld.log" "$T/log/slurmctld.stdout" 2>/dev/null
  echo "--- slurmd log"; tail -15 "$T/log/slurmd.log" "$T/log/slurmd.stdout" 2>/dev/null
  fail "the node did not become idle in 60 s (state '${state:-none}'): Slurm could not start (logs above)"
fi
echo "slurm up after $(( $(date +%s) - start_time )) s (slurm $(slurmctld -V | awk '{print $2}'), node $host, $cpus CPUs)"

cd "$T/out"
export RAYINT=$rayint
stress_args=(stress --count 400 --seed 11 --methods exact,riemann:n=8 --json --no-worst)
slab_args=(slab --tau 1 --albedo 0.9 --phase hg:0.7 --mu-up 0.1,1 --mu-down 0.1,0.5 --method monte_carlo
           --photons 400000 --seed 4)
"$src/scripts/slurm/submit.sh" -n 4 -d "$T/out/stress" -r "$T/out/stress_merged.json" -- "${stress_args[@]}" || fail "submitting the stress run"
"$src/scripts/slurm/submit.sh" -n 4 -d "$T/out/slab" -r "$T/out/slab_merged.json" -w -- "${slab_args[@]}" || {
  tail -n 5 "$T"/out/slab/slurm-*.out; fail "the slab run or its merge failed"; }
# wait for the stress jobs too
for _ in $(seq 600); do
  [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break
  sleep 1
done
[ -z "$(squeue -h -o %i)" ] || fail "jobs still queued after 10 minutes: $(squeue)"
[ -s "$T/out/stress_merged.json" ] || { tail -n 5 "$T"/out/stress/slurm-*.out; fail "the stress merge wrote no report"; }
slurm_done=$(date +%s)
# The single runs, here, with the shards' thread count (the slab report records it)
"$rayint" "${stress_args[@]}" --threads 1 -o "$T/out/stress_one.json" -q
"$rayint" "${slab_args[@]}" --threads 1 -o "$T/out/slab_one.json" --quiet
cmp "$T/out/stress_one.json" "$T/out/stress_merged.json" || fail "stress: merged report differs from the single run"
/usr/bin/python3 "$src/tests/compare_reports.py" "$T/out/slab_one.json" "$T/out/slab_merged.json" ||
  fail "slab: merged report differs from the single run"
echo "slurm_cluster: PASS: 4-shard stress (byte-identical) and slab Monte Carlo (identical but wall time) through sbatch --array + afterok merge"
echo "slurm_cluster: wall time $(( $(date +%s) - start_time )) s (cluster start to jobs done: $(( slurm_done - start_time )) s)"
