#!/bin/sh
# advise against an exhaustive sweep of the same space (issue 24's proof), one command:
#   scripts/advise-vs-exhaustive.sh [OUT]        (default results/runs/advise-vs-exhaustive)
# On the Cornell box, the atrium and the teapots (a real scene, scenes/teapots.json): the whole space of docs/measured/advise/space.json at a
# normal run's precision, measured twice (the second run shows how often the exhaustive method
# agrees with itself), then `ldmbench advise` for two budgets each; the comparison
# (recommendation on the exhaustive front, same answer, wall-time ratio) in
# OUT/comparison.md. Resumable: a rerun keeps what finished. The small files (records,
# results, reports; no images) are copied to docs/measured/advise/.
set -eu
cd "$(dirname "$0")/.."
OUT=${1:-results/runs/advise-vs-exhaustive}
BIN=${LDMBENCH:-build/ldmbench}
status=0
/usr/bin/python3 scripts/advise_vs_exhaustive.py --ldmbench "$BIN" --space docs/measured/advise/space.json \
  --out "$OUT" --scene cornell --scene atrium --scene scenes/teapots.json --image-size 128x128 --reference-max-spp 256 || status=$?
DOCS=docs/measured/advise
for f in comparison.md comparison.json; do cp "$OUT/$f" "$DOCS/$f"; done
for scene in cornell atrium teapots; do
  [ -d "$OUT/$scene" ] || continue
  for run in exhaustive exhaustive-again; do
    [ -f "$OUT/$scene/$run/run/records.csv" ] || continue
    mkdir -p "$DOCS/$scene/$run"
    cp "$OUT/$scene/$run/sweep.json" "$OUT/$scene/$run/wall_s.txt" "$OUT/$scene/$run/run/records.csv" \
       "$DOCS/$scene/$run/"
  done
  for advice in "$OUT/$scene"/advise-*; do
    [ -f "$advice/advice/result.json" ] || continue
    dest="$DOCS/$scene/$(basename "$advice")"
    mkdir -p "$dest/report"
    cp "$advice/wall_s.txt" "$advice/advice/result.json" "$advice/advice/advise.json" "$advice/advice/advise.jsonl" "$dest/"
    cp "$advice/advice/report/summary.md" "$advice/advice/report/front.png" "$dest/report/"
    rm -rf "$dest/stages"
    for stage in "$advice/advice/stages"/*; do
      mkdir -p "$dest/stages/$(basename "$stage")"
      cp "$stage/sweep.json" "$dest/stages/$(basename "$stage")/"
      # the census's memory plan, or the stage's records (sharded: the merged ones)
      for f in "$stage/plan/memory-plan.csv" "$stage/run/records.csv" "$stage"/shards-*/merged/records.csv; do
        if [ -f "$f" ]; then cp "$f" "$dest/stages/$(basename "$stage")/"; fi
      done
    done
  done
done
exit $status
