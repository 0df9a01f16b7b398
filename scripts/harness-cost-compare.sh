#!/usr/bin/env bash
# Issue 21's overhead measurement, side by side: two builds of ldmbench run the same
# 12-configuration sweep in turn (A B A B ...), references cached first, each run's wall
# time taken by /usr/bin/time; scripts/harness_cost.py then gives per run the measured
# frames' time, the build checks' share and wall / measured, and for each pair whether the
# second build's frame and build medians lie in the first's 95% intervals.
#
#   scripts/harness-cost-compare.sh OLD_LDMBENCH NEW_LDMBENCH [OUT=results/runs/harness-cost] [PAIRS=3]
set -euo pipefail
old="${1:?usage: scripts/harness-cost-compare.sh OLD_LDMBENCH NEW_LDMBENCH [OUT] [PAIRS]}"
new="${2:?usage: scripts/harness-cost-compare.sh OLD_LDMBENCH NEW_LDMBENCH [OUT] [PAIRS]}"
out="${3:-results/runs/harness-cost}"
pairs="${4:-3}"
sweep=(--scene cornell --structure all -N 16,32 -R 128 --frames 5 --warmup 2 --width 128 --height 128)
mkdir -p "$out"
run() {  # LABEL BINARY: one timed run into OUT/LABEL, its wall seconds in OUT/LABEL.wall
  /usr/bin/time -f %e -o "$out/$1.wall" "$2" run "${sweep[@]}" --cache-dir "$out/cache-$3" \
    --out "$out/$1" --overwrite > "$out/$1.log" 2>&1 || true
}
run warm-old "$old" old
run warm-new "$new" new
args=()
for ((i = 1; i <= pairs; ++i)); do
  run "old-$i" "$old" old
  run "new-$i" "$new" new
  args+=("old-$i=$out/old-$i:$(cat "$out/old-$i.wall")" "new-$i=$out/new-$i:$(cat "$out/new-$i.wall")")
done
/usr/bin/python3 "$(dirname "$0")/harness_cost.py" "${args[@]}" | tee "$out/harness-cost.txt"
