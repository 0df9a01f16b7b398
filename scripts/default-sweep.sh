#!/usr/bin/env bash
# The default sweep in one command: the AO experiments with the peers (sweeps/default.json)
# and the indirect-lighting experiments (sweeps/indirect.json), then one report over both.
# Resumable like every sweep: run it again into the same folder to finish what is missing.
#   scripts/default-sweep.sh [OUT]        (default OUT: results/runs/default)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-results/runs/default}"
source scripts/run-lib.sh
require_ldmbench default-sweep.sh
keep_failed "$ldmbench" sweep sweeps/default.json --out "$out/ao"
keep_failed "$ldmbench" sweep sweeps/indirect.json --out "$out/indirect"
"$ldmbench" report "$out/ao" "$out/indirect" --out "$out/report"
exit $status
