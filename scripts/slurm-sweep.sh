#!/usr/bin/env bash
# A sweep spread over a Slurm cluster (Debian: slurm-wlm) as a job array: array task i runs
# shard i of n (`ldmbench sweep FILE --shard i/n`, an interleaved slice: docs/guide/sweeps.md)
# into OUT/shard-i, and a job that starts after the whole array joins them (`ldmbench merge`)
# into OUT/merged. The jobs' logs go to OUT/slurm-logs/, named after shard and job:
# ldmbench-shard-<i>-of-<n>-job-<array>_<i>.out and ldmbench-merge-job-<id>.out.
#
#   scripts/slurm-sweep.sh SWEEP_FILE [SHARDS=8] [OUT=results/runs/<sweep name>]
#
# On the login node this submits both jobs (sbatch); Slurm then runs this same script with
# SLURM_ARRAY_TASK_ID set (one shard) and with LDM_SLURM_MERGE=1 (the merge). A task that
# is requeued or resubmitted resumes its shard: finished configurations are skipped. Run it
# from the repository root on a shared file system. Environment:
#   LDMBENCH          the binary (default build/ldmbench)
#   LDM_SLURM_GPUS    1 (default): every task gets a GPU of its own, LDM_SLURM_GPU_ARGS
#                     (default "--gres=gpu:1"; several tasks share a node, one per GPU, and
#                     each renders on the GPU Slurm gave it: CUDA ordinal 0 of the ones
#                     CUDA_VISIBLE_DEVICES leaves it, docs/guide/gpu-nodes.md#choosing-the-gpu);
#                     0: no GPU options (a node without GPUs, such as the CI's)
#   LDM_SLURM_TASKS   which array tasks to submit (sbatch --array syntax, e.g. "3" or "1,5");
#                     default all: resubmit the failed ones after a failure (the merge reruns)
#   LDM_SWEEP_ARGS    more `ldmbench sweep` options for every task (--cache-dir, ...)
#   SBATCH_ARGS       more sbatch options for both jobs (partition, account, time, ...)
#   LDM_SLURM_JOBS_FILE  where to write the submitted job ids as JSON, {"array": ID,
#                     "merge": ID} (what `ldmbench advise --launcher slurm` waits for)
#   LDM_SLURM_PLAN    1: instead of the array, one job, waited for (sbatch --wait), runs
#                     `ldmbench sweep FILE --memory-plan --out OUT` on a GPU node with the
#                     same GPU options (advise's census: the storage block that refuses a
#                     buffer is the GPU's); exits with its status, 3 (refused rows) as 0
#SBATCH --job-name=ldmbench-sweep
#SBATCH --cpus-per-task=2
#SBATCH --time=04:00:00
#SBATCH --output=slurm-ldmbench-shard-%a-job-%A_%a.out
set -euo pipefail
sweep="${1:?usage: scripts/slurm-sweep.sh SWEEP_FILE [SHARDS] [OUT]}"
shards="${2:-8}"
out="${3:-results/runs/$(basename "$sweep" .json)}"
ldmbench="${LDMBENCH:-build/ldmbench}"

if [ "${LDM_SLURM_MERGE:-0}" = 1 ]; then
  shard_dirs=()
  for ((i = 0; i < shards; i++)); do shard_dirs+=("$out/shard-$i"); done
  exec "$ldmbench" merge --overwrite "$out/merged" "${shard_dirs[@]}"
fi
if [ "${LDM_SLURM_PLAN_JOB:-0}" = 1 ]; then
  status=0
  "$ldmbench" sweep "$sweep" --memory-plan --out "$out" || status=$?
  [ "$status" -eq 0 ] || [ "$status" -eq 3 ] || exit "$status"
  exit 0
fi
if [ -n "${SLURM_ARRAY_TASK_ID:-}" ]; then
  # One array task: its shard. Exit 3 (some configurations failed, recorded) is a result.
  # The records name the node, job, array task and GPUs (ldmbench reads SLURM_* itself).
  echo "slurm-sweep: shard $SLURM_ARRAY_TASK_ID/$shards of $sweep on ${SLURMD_NODENAME:-$(hostname)}," \
    "job ${SLURM_ARRAY_JOB_ID:-?}_$SLURM_ARRAY_TASK_ID, GPUs: ${SLURM_JOB_GPUS:-${CUDA_VISIBLE_DEVICES:-none allocated}}"
  # The task's GPU is ordinal 0 of those Slurm left visible: an LDM_GPU of the submitting
  # shell (a GPU of the login node's numbering) must not pick another (--gpu in
  # LDM_SWEEP_ARGS still wins). SLURM_JOB_GPUS, the physical ids, is only recorded.
  if [ -n "${CUDA_VISIBLE_DEVICES:-}" ]; then export LDM_GPU=0; fi
  status=0
  # shellcheck disable=SC2086  # LDM_SWEEP_ARGS is split on purpose
  "$ldmbench" sweep "$sweep" --shard "$SLURM_ARRAY_TASK_ID/$shards" --out "$out/shard-$SLURM_ARRAY_TASK_ID" \
    ${LDM_SWEEP_ARGS:-} || status=$?
  [ "$status" -eq 0 ] || [ "$status" -eq 3 ] || exit "$status"
  exit 0
fi

# The login node: the array, then the merge once every task has ended (afterany: a failed
# shard leaves a partial merge, with a warning naming it; resubmit it, and the merge reruns).
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || { echo "slurm-sweep: SHARDS '$shards' is not a positive count" >&2; exit 2; }
[ -f "$sweep" ] || { echo "slurm-sweep: sweep file '$sweep' not found" >&2; exit 2; }
# ldmbench checks the sweep (and the shard count) here, before anything is queued.
"$ldmbench" sweep "$sweep" --dry-run --shard "0/$shards" >/dev/null
# ldmbench renders on the EGL device whose CUDA ordinal is 0 among the GPUs
# CUDA_VISIBLE_DEVICES leaves (Slurm sets it for --gres=gpu:1), so the shards of one node
# each time on their own GPU, whether or not the site's cgroups hide the others: no
# --exclusive, no idle GPUs. Add --exclusive to LDM_SLURM_GPU_ARGS to keep a node to one
# shard (when shards on one node would disturb each other's timing through the CPU or bus).
gpu_args=""
case "${LDM_SLURM_GPUS:-1}" in
  1) gpu_args="${LDM_SLURM_GPU_ARGS:---gres=gpu:1}" ;;
  0) ;;
  *) echo "slurm-sweep: LDM_SLURM_GPUS must be 1 or 0, not '${LDM_SLURM_GPUS}'" >&2; exit 2 ;;
esac
logs="$out/slurm-logs"
mkdir -p "$logs"  # Slurm opens the logs but makes no folder
if [ "${LDM_SLURM_PLAN:-0}" = 1 ]; then
  # shellcheck disable=SC2086
  exec sbatch --wait --parsable $gpu_args ${SBATCH_ARGS:-} --job-name=ldmbench-plan \
    --export=ALL,LDM_SLURM_PLAN_JOB=1 --output="$logs/ldmbench-plan-job-%j.out" "$0" "$sweep" 1 "$out"
fi
# shellcheck disable=SC2086  # SBATCH_ARGS and gpu_args are split on purpose
array=$(sbatch --parsable $gpu_args ${SBATCH_ARGS:-} --array="${LDM_SLURM_TASKS:-0-$((shards - 1))}" \
  --output="$logs/ldmbench-shard-%a-of-$shards-job-%A_%a.out" "$0" "$sweep" "$shards" "$out")
array=${array%%;*}  # --parsable: "id" or "id;cluster"
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_ARGS:-} --dependency=afterany:"$array" --export=ALL,LDM_SLURM_MERGE=1 \
  --job-name=ldmbench-merge --output="$logs/ldmbench-merge-job-%j.out" "$0" "$sweep" "$shards" "$out")
merge=${merge%%;*}
if [ -n "${LDM_SLURM_JOBS_FILE:-}" ]; then
  printf '{"array": "%s", "merge": "%s"}\n' "$array" "$merge" >"$LDM_SLURM_JOBS_FILE"
fi
echo "slurm-sweep: array job $array (tasks ${LDM_SLURM_TASKS:-0-$((shards - 1))} of $shards shards of $sweep" \
  "into $out/shard-*), merge job $merge into $out/merged after it; logs in $logs"
