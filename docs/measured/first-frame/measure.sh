#!/usr/bin/env bash
# Issue 21, first frames: the build before the change (OLD) and after it (NEW), run in turn
# (OLD NEW OLD NEW ...) so that both see the same machine. Each run measures every frame
# (--warmup 0), so frame 0 is the first frame under previous_frame (overflow + rebuild) and
# frames 1.. are steady; summarise.py reads the per-frame samples and the wall times.
# Usage: measure.sh OLD_BINARY NEW_BINARY OUT_DIR PAIRS [ldmbench run arguments...]
set -euo pipefail
old=$1 new=$2 out=$3 pairs=$4
shift 4
mkdir -p "$out"
for i in $(seq 1 "$pairs"); do
  for side in old new; do
    bin=$old; [ "$side" = new ] && bin=$new
    dir="$out/$side-$i"
    rm -rf "$dir"
    start=$(date +%s.%N)
    "$bin" run "$@" --out "$dir" > "$dir.log" 2>&1
    end=$(date +%s.%N)
    echo "$side $i $(echo "$end - $start" | bc)" >> "$out/wall.txt"
  done
done
