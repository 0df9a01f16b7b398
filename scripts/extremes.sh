#!/usr/bin/env bash
# The extremes sweep (issue 12): runs ldmbench at the edges of its input space and prints
# one line per record with what came out, then checks that no NaN or infinity reached an
# `ok` record. Small sizes (llvmpipe-friendly, a few minutes); findings are in
# docs/measured/extremes.md. Usage: scripts/extremes.sh [OUT_DIR]   (default results/extremes)
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${LDMBENCH:-build/ldmbench}"
out="${1:-results/extremes}"
rm -rf "$out"
mkdir -p "$out/scenes"
common=(--width 64 --height 64 --frames 1 --warmup 0 --cache-dir "$out/cache")

# Meshes: two parallel unit-spaced squares; a stack of L squares; slivers and a degenerate.
python3 - "$out/scenes" <<'PY'
import json, sys, os
d = sys.argv[1]
def quad(f, y, s=4.0, base=0):
    f.write(f"v {-s} {y} {-s}\nv {s} {y} {-s}\nv {s} {y} {s}\nv {-s} {y} {s}\n")
    b = base + 1
    f.write(f"f {b} {b+1} {b+2} {b+3}\n")
with open(f"{d}/planes.obj", "w") as f:
    quad(f, 0.0); quad(f, 1.0, base=4)
for layers in (1, 16, 201, 1024):
    with open(f"{d}/stack{layers}.obj", "w") as f:
        for i in range(layers):
            quad(f, i / layers, base=4 * i)
with open(f"{d}/slivers.obj", "w") as f:
    quad(f, 0.0)
    # a sliver 1e-6 wide standing on the floor, a zero-area triangle (skipped by the loader)
    f.write("v -1 0 0\nv 1 0 0\nv 1 1 1e-6\nf 5 6 7\nv 0 0 0\nv 1 1 1\nv 2 2 2\nf 8 9 10\n")
camera = {"eye": [0.5, 0.75, 2.0], "target": [0.0, 0.25, 0.0]}
def scene(name, mesh, scale=1.0, translate=(0, 0, 0), d_max=2.0, cam=camera):
    t = list(translate)
    c = {k: [v * scale + t[i] for i, v in enumerate(cam[k])] for k in ("eye", "target")}
    json.dump({"name": name, "meshes": [{"file": mesh, "scale": scale, "translate": t}],
               "camera": c, "ao": {"d_max": d_max * scale, "normal_offset": 1.0}},
              open(f"{d}/{name}.json", "w"))
for e in (0, 3, 4, 5, 6):
    scene(f"far1e{e}", "planes.obj", translate=(10.0**e if e else 0,) * 3)
for e in (-6, -3, 0, 3, 5):
    scene(f"scale1e{e}", "planes.obj", scale=10.0**e)
for layers in (1, 16, 201, 1024):
    scene(f"stack{layers}", f"stack{layers}.obj", d_max=0.5)
scene("slivers", "slivers.obj")
# grazing: the camera a hair above the floor plane, looking along it
scene("grazing", "planes.obj", cam={"eye": [0.0, 0.001, 6.0], "target": [0.0, 0.0, 0.0]})
PY

run() {  # run NAME ARGS...: one sweep into $out/NAME (exit 3 = some records failed/invalid)
  local name=$1; shift
  echo "== $name: ldmbench run $*"
  local status=0
  "$bin" run "$@" "${common[@]}" --out "$out/$name" > "$out/$name.log" 2>&1 || status=$?
  if [ $status -ne 0 ] && [ $status -ne 3 ]; then tail -n 5 "$out/$name.log"; fi
  echo "   exit $status"
}
s="$out/scenes"
run far --scene "$s/far1e0.json,$s/far1e3.json,$s/far1e4.json,$s/far1e5.json,$s/far1e6.json" \
    -N 16 -R 64 --reference-spp 256
run scale --scene "$s/scale1e-6.json,$s/scale1e-3.json,$s/scale1e0.json,$s/scale1e3.json,$s/scale1e5.json" \
    -N 16 -R 64 --reference-spp 256
run dmax --scene cornell -N 16 -R 64 --d-max 1e-6,1e-3,0.1,1,1e3,1e29 --reference-spp 256
run depth --scene "$s/stack1.json,$s/stack16.json,$s/stack201.json,$s/stack1024.json" \
    --structure all -N 2 -R 32 --no-reference
run views --scene cornell -N 1,4096 -R 1,16 --no-reference
run degenerate --scene "$s/slivers.json,$s/grazing.json" -N 16 -R 64 --reference-spp 256

echo "== layer separation (two squares h apart, N = 1, R = 16)"
LDM_EXTREMES_SCAN=1 build/tests/test_extremes --gtest_filter='ExtremesSeparation.*' 2>&1 |
  grep '^separation' | tee "$out/separation.txt"

python3 - "$out" <<'PY'
import csv, glob, math, os, sys
out = sys.argv[1]
unflagged = 0
for path in sorted(glob.glob(f"{out}/*/records.csv")):
    print(f"\n# {os.path.basename(os.path.dirname(path))}")
    for r in csv.DictReader(open(path)):
        cols = ["scene_name", "structure", "n_views", "r_ldm", "d_max", "status", "fragments",
                "max_depth_complexity", "fragments_lost", "mse", "ref_noise_mse", "ref_ray_offset",
                "ref_ray_offset_ok"]
        print("  " + "  ".join(f"{c}={r.get(c, '')}" for c in cols if r.get(c, "") != ""),
              ("| " + r["status_detail"][:120]) if r.get("status_detail") else "")
        # psnr is +inf exactly when mse is 0 (identical images): a value, not a fault.
        bad = [k for k, v in r.items() if v in ("nan", "inf", "-inf")
               and not (k == "psnr" and r.get("mse") == "0")]
        if bad and r["status"] == "ok":
            unflagged += 1
            print(f"  UNFLAGGED non-finite values in an ok record: {bad}")
print(f"\nok records with NaN/Inf: {unflagged}")
sys.exit(1 if unflagged else 0)
PY
