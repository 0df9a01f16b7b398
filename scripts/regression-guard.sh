#!/usr/bin/env bash
# CI's regression guard: runs the sweep of a committed baseline (BASELINE/sweep.args) and
# compares it with BASELINE/records.json by `ldmbench compare`, failing (exit 1) on accuracy,
# memory, status or work regressions. Time is not guarded: CI has no GPU and its timings are
# noise; performance is guarded by work instead (docs/reference/work-counters.md): a
# deterministic work counter that grows at all, or an arrival-dependent one beyond
# --work-tolerance, fails the guard.
#
#   scripts/regression-guard.sh [BASELINE]            check (default results/baselines/ci-small)
#   scripts/regression-guard.sh --update [BASELINE]   re-measure and replace the baseline
#
# LDMBENCH names the binary (default build/ldmbench). LDM_GUARD_RUN_ARGS and
# LDM_GUARD_COMPARE_ARGS add arguments to the run and to the comparison; the tests use them
# to degrade a configuration on purpose and check that the guard fails.
set -euo pipefail
cd "$(dirname "$0")/.."
update=0
if [ "${1:-}" = "--update" ]; then update=1; shift; fi
baseline="${1:-results/baselines/ci-small}"
ldmbench="${LDMBENCH:-build/ldmbench}"
[ -f "$baseline/sweep.args" ] || { echo "regression-guard: no $baseline/sweep.args" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
args=()
while IFS= read -r line; do
  case "$line" in ''|'#'*) ;; *) args+=("$line") ;; esac
done < "$baseline/sweep.args"
# shellcheck disable=SC2206  # word splitting of the extra arguments is intended
extra_run=(${LDM_GUARD_RUN_ARGS:-})
# shellcheck disable=SC2206
extra_compare=(${LDM_GUARD_COMPARE_ARGS:-})

# Exit 3 (some configurations failed or invalid) is a result to compare, not an error.
status=0
"$ldmbench" run "${args[@]}" "${extra_run[@]}" --cache-dir "$work/cache" --out "$work/run" \
  > "$work/run.log" 2>&1 || status=$?
if [ "$status" -ne 0 ] && [ "$status" -ne 3 ]; then
  cat "$work/run.log" >&2
  echo "regression-guard: ldmbench run exited $status" >&2
  exit 2
fi

if [ "$update" -eq 1 ]; then
  cp "$work/run/records.json" "$work/run/records.csv" "$baseline/"
  rm -rf "$baseline/samples"
  [ ! -d "$work/run/samples" ] || cp -r "$work/run/samples" "$baseline/samples"  # named by the records
  echo "regression-guard: baseline $baseline updated"
  exit 0
fi
# --no-time: nothing time-based, not even a printed verdict (CI's times are noise).
"$ldmbench" compare "$baseline" "$work/run" --no-time --fail-on accuracy,memory,status,work "${extra_compare[@]}"
