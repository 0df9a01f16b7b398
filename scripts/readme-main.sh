#!/usr/bin/env bash
# The run behind the README's main table: the default sweep's AO base point (the Cornell box
# and the atrium, N = 32, R_LDM = 128, a 128x128 image, every structure and the peers HBAO,
# GTAO, GPU RTAO at 1, 4 and 16 rays per pixel and the CPU RTAO), 3 repetitions each (fresh GL
# contexts, round robin), so that every time carries a 95 % interval over the repetitions.
# Then prints the table (scripts/readme_table.py) and the equal-time table
# (scripts/equal_time_table.py) of the same records.
#   scripts/readme-main.sh [OUT]        (default OUT: docs/measured/readme-main)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-docs/measured/readme-main}"
source scripts/run-lib.sh
require_ldmbench readme-main.sh
keep_failed "$ldmbench" run --scene cornell,atrium --pass ao,hbao,gtao,rtao_gpu,rtao --structure all -N 32 -R 128 \
  --param rtao_gpu:spp=1,4,16 --image-size 128x128 --repetitions 3 --no-images --out "$out"
"${PYTHON:-python3}" scripts/readme_table.py "$out/records.csv"  # needs numpy (scripts/setup.sh)
echo
"${PYTHON:-python3}" scripts/equal_time_table.py "$out/records.csv"
exit $status
