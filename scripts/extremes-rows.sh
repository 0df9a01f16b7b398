#!/usr/bin/env bash
# The extremes of issue 35's table (docs/measured/extremes.md), each measured into its own
# folder under OUT: N = 1 and 2; d_max from one LDM pixel to 10x the scene; 16x16 images;
# degenerate and sliver triangles and coincident surfaces (scenes/extremes/); the hairball at
# the largest R_LDM whose census fits the storage block at N = 32 (and the next size, refused
# naming the limit); photons too fine for the float grid where they land (a laser-narrow spot).
# 64x64 images, one frame, 256 reference samples a half; llvmpipe: about 5 minutes.
# Usage: scripts/extremes-rows.sh [OUT_DIR] (default results/extremes-rows); with
# KEEP=docs/measured/extremes the records are copied there as <row>.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${LDMBENCH:-build/ldmbench}"
out="${1:-results/extremes-rows}"
keep="${KEEP:-}"
rm -rf "$out"
mkdir -p "$out/scenes"
common=(--frames 1 --warmup 0 --cache-dir "$out/cache" --reference-spp 256)

run() {  # run NAME ARGS...: one sweep into $out/NAME (exit 3 = some records failed/invalid)
  local name=$1; shift
  echo "== $name: ldmbench run $*"
  local status=0
  local size=(--image-size 64x64)
  if [[ " $* " == *" --image-size "* ]]; then size=(); fi
  "$bin" run "${common[@]}" "${size[@]}" "$@" --out "$out/$name" > "$out/$name.log" 2>&1 || status=$?
  if [ $status -ne 0 ] && [ $status -ne 3 ]; then tail -n 5 "$out/$name.log"; exit 1; fi
  echo "   exit $status"
  if [ -n "$keep" ]; then cp "$out/$name/records.csv" "$keep/$name.csv"; fi
}

# A laser-narrow spot in the Cornell box: 0.01 degrees (footprints ~200 float steps wide
# where the photons land) and 0.0001 degrees (~2 steps: photons_unresolved).
for angle in 0.01 0.0001; do
  cat > "$out/scenes/laser$angle.json" <<EOF
{"name": "laser$angle", "generator": {"type": "cornell"}, "light": {"type": "spot",
 "position": [2.78, 5.4, 2.8], "direction": [0.1, -1, 0.05], "intensity": [8, 8, 8],
 "inner_angle_deg": 0, "outer_angle_deg": $angle}}
EOF
done

# The Cornell box's LDM pixel at R_LDM 64 is 2 x 4.8037 / 64 = 0.15012 (scene_radius 4.8037);
# the scene's size (its bounding sphere's diameter) 9.6074.
run n1-n2-cornell --scene cornell -N 1,2 -R 64 --structure all
run n1-n2-cornell-normalized --scene cornell -N 1,2 -R 64 --ao-estimator normalized
run n1-n2-cornell-indirect --scene cornell -N 1,2 -R 64 --pass indirect
run dmax-pixel-to-10x-cornell --scene cornell -N 16 -R 64 --d-max 0.15012,0.60047,2.4019,9.6074,96.074
run image16-cornell --scene cornell -N 8 -R 64 --image-size 16x16 --pass ao,hbao,gtao,rtao,rtao_gpu,indirect
run slivers --scene scenes/extremes/slivers.json -N 8 -R 64 --structure all
run coincident --scene scenes/extremes/coincident.json,scenes/extremes/coincident_control.json \
    -N 8 -R 64 --structure all
run coincident-indirect --scene scenes/extremes/coincident.json,scenes/extremes/coincident_control.json \
    -N 8 -R 64 --pass indirect
run hairball-largest --scene hairball -N 32 -R 212,214,216
run photon-laser --scene "$out/scenes/laser0.01.json,$out/scenes/laser0.0001.json" -N 8 -R 64 \
    --pass indirect --no-reference
