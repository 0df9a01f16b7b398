#!/usr/bin/env bash
# CI: scripts/slurm-sweep.sh on a real Slurm, a single node on this machine (Debian's
# slurm-wlm and munge; no systemd: munged, slurmctld and slurmd are started here, as root,
# from a minimal slurm.conf in a scratch folder, and stopped on exit, whatever happens).
#
#   scripts/slurm-ci.sh            (as root, from anywhere; needs build/ldmbench)
#
# 1. sweeps/slurm-ci.json (8 configurations) measured in one run, and as a job array of 2
#    shards plus the merge job: the merged run must equal the single run in every column
#    that does not measure time or name the node (scripts/same_records.py says which).
# 2. A fresh array of the same sweep, one task's ldmbench killed (SIGKILL) after its first
#    record: the merge after it must be partial (the check must see the difference), then
#    resubmitting that task the documented way (LDM_SLURM_TASKS=1 scripts/slurm-sweep.sh ...)
#    resumes it, and the new merge must equal the single run again.
# 3. `ldmbench advise --launcher slurm --shards 2`: the memory plan a Slurm job, every
#    measured stage a job array plus merge. Jobs are submitted held; with the first stage's
#    array still held, the advise is killed (its whole process group, SIGKILL) and rerun:
#    the rerun must wait for the queued jobs (journal event "reattached") instead of
#    submitting the stage again; released, the advise must answer. Its memory plan must
#    equal an unsharded local advise's, and every stage's merged records must name their
#    array task.
# Exit nonzero, with the daemons' and jobs' logs, on any mismatch, failed job or timeout.
# LDM_SLURM_CI_DIR: scratch folder (default: a new one under /tmp, removed on success).
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
ldmbench="$repo/build/ldmbench"
sweep=sweeps/slurm-ci.json
shards=2
timeout_s=600   # for each wait on the queue
started=$SECONDS

say() { echo "slurm-ci: $*"; }
fail() {
  echo "slurm-ci: FAILED: $*" >&2
  show_logs >&2
  exit 1
}

[ "$(id -u)" = 0 ] || { echo "slurm-ci: needs root (it starts munged, slurmctld and slurmd)" >&2; exit 2; }
[ -x "$ldmbench" ] || { echo "slurm-ci: $ldmbench is missing; build first (scripts/test.sh)" >&2; exit 2; }

# CI machines start bare: Slurm and munge come from Debian, installed here (not by
# scripts/setup.sh: only this step needs them).
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  say "installing slurm-wlm and munge"
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y --no-install-recommends slurm-wlm munge >/dev/null ||
    { apt-get update >/dev/null && apt-get install -y --no-install-recommends slurm-wlm munge >/dev/null; }
fi

work="${LDM_SLURM_CI_DIR:-$(mktemp -d /tmp/ldm-slurm-ci.XXXXXX)}"
mkdir -p "$work"/{state,spool,log}
export SLURM_CONF="$work/slurm.conf"
pids=()
munged_pid=/run/munge/ldm-ci-munged.pid
started_munged=0

show_logs() {
  for f in "$work"/log/*.log "$work"/runs/*/slurm-logs/*.out "$work"/advise/*/stages/*/shards-*/slurm-logs/*.out \
    "$work"/advise/*/stages/*/plan/slurm-logs/*.out; do
    [ -f "$f" ] || continue
    echo "---- $f (last 40 lines)"
    tail -n 40 "$f"
  done
}

# Every job of ours cancelled, then the daemons this script started, by their ids.
cleanup() {
  local status=$?
  scancel --quiet --user=root 2>/dev/null || true
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  if [ "$started_munged" = 1 ] && [ -s "$munged_pid" ]; then kill "$(cat "$munged_pid")" 2>/dev/null || true; fi
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
  if [ "$status" = 0 ] && [ -z "${LDM_SLURM_CI_DIR:-}" ]; then rm -rf "$work"; fi
  exit "$status"
}
trap cleanup EXIT

start_munge() {
  # The key: Debian's munge package makes one on install; make it if that did not happen.
  if [ ! -s /etc/munge/munge.key ]; then
    mungekey --create --keyfile=/etc/munge/munge.key
    chown munge:munge /etc/munge/munge.key
    chmod 400 /etc/munge/munge.key
  fi
  mkdir -p /run/munge /var/log/munge /var/lib/munge
  chown munge:munge /run/munge /var/log/munge /var/lib/munge
  # munged forks into the background itself; its pid file (where the munge user may write)
  # is how it is stopped. A munged already answering is left alone, running.
  if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    rm -f "$munged_pid"
    runuser -u munge -- /usr/sbin/munged --force --pid-file="$munged_pid" --log-file=/var/log/munge/ldm-ci-munged.log
    started_munged=1
  fi
  munge -n | unmunge >/dev/null || fail "munge does not authenticate"
}

write_slurm_conf() {
  # The node as slurmd sees it (CPUs, sockets, memory), so that it is never drained for
  # having less than slurm.conf claims; addressed by 127.0.0.1 (the CI's hostname may not
  # resolve). No cgroups, no accounting database: proctrack/linuxproc, task/none.
  local node
  node=$(slurmd -C | head -n 1)
  local name=${node%% *}
  name=${name#NodeName=}
  cat >"$SLURM_CONF" <<EOF
ClusterName=ldmci
SlurmctldHost=$name(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
KillWait=5
MinJobAge=3600
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=ci Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
}

start_slurm() {
  slurmctld -D -i >"$work/log/slurmctld.out" 2>&1 &
  pids+=($!)
  slurmd -D >"$work/log/slurmd.out" 2>&1 &
  pids+=($!)
  local deadline=$((SECONDS + 60))
  until sinfo -h -o %t 2>/dev/null | grep -qx idle; do
    [ $SECONDS -lt $deadline ] || fail "the node did not come up idle within 60 s ($(sinfo -h -o '%t %E' 2>&1))"
    sleep 1
  done
}

# Waits until the queue is empty (this cluster runs only our jobs).
wait_for_queue() {
  local deadline=$((SECONDS + timeout_s))
  while [ -n "$(squeue -h -o %i)" ]; do
    [ $SECONDS -lt $deadline ] || fail "jobs still queued after ${timeout_s} s: $(squeue -h)"
    sleep 1
  done
}

# "STATE EXITCODE" of a job (or array task, JOBID_TASK), as slurmctld keeps it (MinJobAge).
job_state() {
  scontrol -o show job "$1" | sed -E 's/.*JobState=([^ ]*).* ExitCode=([^ ]*).*/\1 \2/'
}

expect_state() {
  local state
  state=$(job_state "$1")
  [ "$state" = "$2" ] || fail "job $1 is '$state', expected '$2'"
}

# Submits the sweep's array and merge into OUT; prints "ARRAY MERGE".
submit() {
  local out=$1 line
  line=$(scripts/slurm-sweep.sh "$sweep" "$shards" "$out" | tail -n 1)
  echo "$line" >&2
  sed -E 's/.*array job ([0-9]+).* merge job ([0-9]+).*/\1 \2/' <<<"$line"
}

# The array tasks get one CPU each (the #SBATCH line asks for 2), so both shards run at once
# on a 2-core CI machine and share the reference cache as shards on a cluster do; no GPU.
export LDMBENCH="$ldmbench" LDM_SLURM_GPUS=0 SBATCH_ARGS="--cpus-per-task=1"
export LDM_SWEEP_ARGS="--cache-dir $work/cache"

say "starting munged, slurmctld and slurmd in $work"
start_munge
write_slurm_conf
start_slurm
say "cluster up after $((SECONDS - started)) s: $(sinfo -h -o '%P %D %c CPUs %t')"

# 1. The whole sweep in one run, then as an array plus merge.
whole="$work/runs/whole"
"$ldmbench" sweep "$sweep" --out "$whole" --cache-dir "$work/cache" >"$work/log/whole.log" 2>&1 ||
  fail "the unsharded sweep failed ($(tail -n 3 "$work/log/whole.log"))"
ids=$(submit "$work/runs/array")
read -r array merge <<<"$ids"
wait_for_queue
for ((i = 0; i < shards; i++)); do expect_state "${array}_$i" "COMPLETED 0:0"; done
expect_state "$merge" "COMPLETED 0:0"
for ((i = 0; i < shards; i++)); do
  [ -f "$work/runs/array/slurm-logs/ldmbench-shard-$i-of-$shards-job-${array}_$i.out" ] ||
    fail "no log named after shard $i and job ${array}_$i in $work/runs/array/slurm-logs"
done
[ -f "$work/runs/array/slurm-logs/ldmbench-merge-job-$merge.out" ] || fail "no merge log named after job $merge"
scripts/same_records.py "$whole" "$work/runs/array/merged" || fail "the merged array differs from the single run"
grep -q '"slurm_array_task_id"' "$work/runs/array/merged/records.json" ||
  fail "the merged records do not name their Slurm array task"

# 2. A fresh array; task 1's ldmbench killed after its first record, while it still has
# configurations to measure: stopped (SIGSTOP) to look at its journal, killed when it holds
# at least one record and fewer than the shard's, let go on (SIGCONT) otherwise.
killed="$work/runs/killed"
ids=$(submit "$killed")
read -r array merge <<<"$ids"
journal="$killed/shard-1/records.jsonl"
per_shard=$("$ldmbench" sweep "$sweep" --dry-run --shard 1/$shards | grep -c $'\t')
deadline=$((SECONDS + timeout_s))
victim=""
while [ -z "$victim" ]; do
  [ $SECONDS -lt $deadline ] || fail "task ${array}_1 never got to its first record"
  pid=$(pgrep -f -- "--out $killed/shard-1( |$)" | head -n 1 || true)
  if [ -n "$pid" ]; then
    kill -STOP "$pid" 2>/dev/null || continue
    done_count=$(grep -c '"record"' "$journal" 2>/dev/null || true)
    if [ "${done_count:-0}" -ge 1 ] && [ "$done_count" -lt "$per_shard" ]; then
      kill -KILL "$pid"
      victim=$pid
      say "killed task ${array}_1 (pid $pid) after $done_count of its $per_shard configurations"
    else
      kill -CONT "$pid" 2>/dev/null || true
    fi
  elif [ "$(job_state "${array}_1" | cut -d' ' -f1)" = COMPLETED ]; then
    fail "task ${array}_1 finished before it could be killed mid-run"
  fi
  sleep 0.05
done
wait_for_queue
expect_state "${array}_1" "FAILED 137:0"
expect_state "$merge" "COMPLETED 0:0"
if scripts/same_records.py "$whole" "$killed/merged" >"$work/log/partial.txt"; then
  fail "the merge after the killed task equals the single run: the kill or the check did nothing"
fi
say "the merge after the kill is partial, as it must be: $(sed -n 1p "$work/log/partial.txt")"

# The documented way back (docs/guide/sweeps.md): the same command for the failed task only.
ids=$(LDM_SLURM_TASKS=1 submit "$killed")
read -r array merge <<<"$ids"
wait_for_queue
expect_state "${array}_1" "COMPLETED 0:0"
expect_state "$merge" "COMPLETED 0:0"
grep -q "resuming: [1-9]" "$killed/slurm-logs/ldmbench-shard-1-of-$shards-job-${array}_1.out" ||
  fail "the resubmitted task did not resume its shard"
scripts/same_records.py "$whole" "$killed/merged" || fail "the merge after resubmitting differs from the single run"

# 3. advise through Slurm, killed while its first measured stage is queued, rerun, reattached.
# Every job is submitted held (sbatch --hold) and released from here: the memory plan's job
# at once, the first stage's array only after the advise has been killed and its rerun has
# reattached to it, so that the kill always lands while that stage is queued.
advise_dir="$work/advise"
mkdir -p "$advise_dir"
cat >"$advise_dir/space.json" <<'EOF2'
{"axes": {"structures": ["psppsll", "habuffer", "ppfla"], "views": [2, 4], "r_ldm": [16, 32], "ppfla:k": [2, 8]}}
EOF2
advise_args=(advise --scene cornell --space "$advise_dir/space.json" --image-size 32x32 --reference-max-spp 16
  --cache-dir "$work/cache" --budget-ms 1000 --budget-mib 0.25)
"$ldmbench" "${advise_args[@]}" --out "$advise_dir/local" >"$work/log/advise-local.log" 2>&1 ||
  fail "the local advise failed ($(tail -n 3 "$work/log/advise-local.log"))"
sharded="$advise_dir/slurm"
export LDM_ADVISE_POLL_S=0.5 SBATCH_ARGS="--cpus-per-task=1 --hold"
unset LDM_SWEEP_ARGS   # advise adds its own --cache-dir to the jobs' sweeps
release_held() {       # the held jobs (named NAME, or all), released
  local id
  for id in $(squeue -h -t PD ${1:+-n "$1"} -o '%F %r' | awk '$2 == "JobHeldUser" {print $1}' | sort -u); do
    scontrol release "$id" 2>/dev/null || true
  done
}
setsid "$ldmbench" "${advise_args[@]}" --launcher slurm --shards 2 --out "$sharded" >"$work/log/advise-killed.log" 2>&1 &
advise_pid=$!
deadline=$((SECONDS + 120))
until grep -q '"event": "submitted"' "$sharded/advise.jsonl" 2>/dev/null; do
  [ $SECONDS -lt $deadline ] || fail "advise submitted no stage within 120 s ($(tail -n 3 "$work/log/advise-killed.log"))"
  kill -0 "$advise_pid" 2>/dev/null || fail "advise ended before submitting ($(tail -n 3 "$work/log/advise-killed.log"))"
  release_held ldmbench-plan
  sleep 0.2
done
kill -KILL -- "-$advise_pid"
wait "$advise_pid" 2>/dev/null || true
[ -n "$(squeue -h -n ldmbench-sweep -o %i)" ] || fail "the killed advise's stage is not queued"
say "advise killed with its first stage queued ($(squeue -h -o '%i %j %T' | tr '\n' ' '))"
"$ldmbench" "${advise_args[@]}" --launcher slurm --shards 2 --out "$sharded" >"$work/log/advise-slurm.log" 2>&1 &
advise_pid=$!
deadline=$((SECONDS + 60))
until grep -q '"event": "reattached"' "$sharded/advise.jsonl"; do
  [ $SECONDS -lt $deadline ] || fail "the rerun advise did not reattach to the queued jobs within 60 s"
  kill -0 "$advise_pid" 2>/dev/null || fail "the rerun advise ended without reattaching ($(tail -n 3 "$work/log/advise-slurm.log"))"
  sleep 0.2
done
deadline=$((SECONDS + timeout_s))
while kill -0 "$advise_pid" 2>/dev/null; do
  [ $SECONDS -lt $deadline ] || fail "the rerun advise did not finish within ${timeout_s} s"
  release_held
  sleep 0.2
done
advise_status=0
wait "$advise_pid" || advise_status=$?
[ "$advise_status" = 0 ] || fail "the rerun advise exited $advise_status ($(tail -n 5 "$work/log/advise-slurm.log"))"
grep -q "Recommended: " "$work/log/advise-slurm.log" || fail "the advise through Slurm recommended nothing"
first_stage=$(grep -m1 '"event": "submitted"' "$sharded/advise.jsonl" | sed -E 's/.*"stage": "([^"]*)".*/\1/')
submissions=$(grep '"event": "submitted"' "$sharded/advise.jsonl" | grep -c "\"stage\": \"$first_stage\"" || true)
[ "$submissions" = 1 ] || fail "stage $first_stage was submitted $submissions times (1 expected)"
ls "$sharded"/stages/01-census/plan/slurm-logs/ldmbench-plan-job-*.out >/dev/null 2>&1 ||
  fail "the memory plan did not run as a Slurm job"
cmp -s "$advise_dir/local/stages/01-census/plan/memory-plan.csv" "$sharded/stages/01-census/plan/memory-plan.csv" ||
  fail "the memory plan through Slurm differs from the local one"
for merged in "$sharded"/stages/*/shards-*/merged; do
  grep -q '"slurm_array_task_id"' "$merged/records.json" || fail "$merged: its records do not name their array task"
done
say "advise through Slurm: killed, reattached, answered ($(grep -c '"event": "submitted"' "$sharded/advise.jsonl") stages submitted)"

say "passed in $((SECONDS - started)) s"
