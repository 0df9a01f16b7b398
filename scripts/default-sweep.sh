#!/usr/bin/env bash
# The default sweep in one command: the AO experiments with the peers (sweeps/default.json)
# and the indirect-lighting experiments (sweeps/indirect.json), then one report over both.
# Resumable like every sweep: run it again into the same folder to finish what is missing.
#   scripts/default-sweep.sh [OUT]        (default OUT: results/runs/default)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-results/runs/default}"
ldmbench="${LDMBENCH:-build/ldmbench}"
[[ -x "$ldmbench" ]] || { echo "default-sweep.sh: $ldmbench not built (cmake --build build)" >&2; exit 2; }
status=0
# exit status 3: some configuration failed (recorded as failed); the sweep went on
"$ldmbench" sweep sweeps/default.json --out "$out/ao" || { s=$?; [[ $s -eq 3 ]] || exit $s; status=3; }
"$ldmbench" sweep sweeps/indirect.json --out "$out/indirect" || { s=$?; [[ $s -eq 3 ]] || exit $s; status=3; }
"$ldmbench" report "$out/ao" "$out/indirect" --out "$out/report"
exit $status
