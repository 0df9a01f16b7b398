#!/usr/bin/env bash
# A sweep spread over a Slurm cluster (Debian: slurm-wlm) as a job array: array task i runs
# shard i of n (`ldmbench sweep FILE --shard i/n`, configurations k with k mod n = i) into
# OUT/shard-i, and a job that starts after the whole array joins them (`ldmbench merge`).
#
#   scripts/slurm-sweep.sh SWEEP_FILE [SHARDS=8] [OUT=results/runs/<sweep name>]
#
# On the login node this submits both jobs (sbatch); Slurm then runs this same script with
# SLURM_ARRAY_TASK_ID set (one shard) and with LDM_SLURM_MERGE=1 (the merge). A task that
# is requeued or resubmitted resumes its shard: finished configurations are skipped. Run it
# from the repository root on a shared file system; LDMBENCH names the binary (default
# build/ldmbench), SBATCH_ARGS adds options to both sbatch calls (partition, account, ...).
#SBATCH --job-name=ldmbench-sweep
#SBATCH --cpus-per-task=2
#SBATCH --time=04:00:00
#SBATCH --output=slurm-ldmbench-%A_%a.out
set -euo pipefail
sweep="${1:?usage: scripts/slurm-sweep.sh SWEEP_FILE [SHARDS] [OUT]}"
shards="${2:-8}"
out="${3:-results/runs/$(basename "$sweep" .json)}"
ldmbench="${LDMBENCH:-build/ldmbench}"

if [ -n "${SLURM_ARRAY_TASK_ID:-}" ]; then
  # One array task: its shard. Exit 3 (some configurations failed, recorded) is a result.
  status=0
  "$ldmbench" sweep "$sweep" --shard "$SLURM_ARRAY_TASK_ID/$shards" --out "$out/shard-$SLURM_ARRAY_TASK_ID" || status=$?
  [ "$status" -eq 0 ] || [ "$status" -eq 3 ] || exit "$status"
  exit 0
fi
if [ "${LDM_SLURM_MERGE:-0}" = 1 ]; then
  shard_dirs=()
  for ((i = 0; i < shards; i++)); do shard_dirs+=("$out/shard-$i"); done
  exec "$ldmbench" merge --overwrite "$out/merged" "${shard_dirs[@]}"
fi

# The login node: the array, then the merge once every task has ended.
# shellcheck disable=SC2086  # SBATCH_ARGS is split on purpose
array=$(sbatch --parsable ${SBATCH_ARGS:-} --array=0-$((shards - 1)) "$0" "$sweep" "$shards" "$out")
# shellcheck disable=SC2086
sbatch ${SBATCH_ARGS:-} --dependency=afterany:"$array" --export=ALL,LDM_SLURM_MERGE=1 \
  --job-name=ldmbench-merge "$0" "$sweep" "$shards" "$out"
echo "slurm-sweep: array job $array ($shards shards of $sweep into $out/shard-*), merge into $out/merged after it"
