#!/usr/bin/env python3
"""How GTAO's defaults were chosen (docs/measured/gtao-rtao-gpu.md): its MSE against the Embree
AO reference on the shipped scenes, one parameter varied at a time around a base point.

Usage:
  scripts/gtao_tuning.py run OUT [--ldmbench build/ldmbench] [--base KEY=VALUE ...] [--size 128]
      measures every block below into OUT/<block>/records.csv (ldmbench run, 1 frame: the MSE
      is what is compared; the images are deterministic)
  scripts/gtao_tuning.py collect OUT FILE.csv
      the columns the tables need from every block's records, in one CSV (the committed
      docs/measured/gtao-rtao-gpu/gtao-tuning-llvmpipe.csv)
  scripts/gtao_tuning.py table OUT|FILE.csv
      prints, per block and value, the geometric mean of the MSE over the scenes and each
      scene's MSE, the best marked

The geometric mean weighs every scene alike (the scenes' MSEs differ by 100x). The base point
is the pass's own defaults unless --base overrides some of them.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import ldmrecords

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
SCENES = ["cornell", "atrium"] + [os.path.join(ROOT, "scenes", f + ".json") for f in
                                  ("sponza_like", "teapots", "house", "wuson", "knot_in_box",
                                   "engine", "hairball")]
# One parameter at a time (a block may vary two together: the sample counts, jitter x denoise).
BLOCKS = {
    "estimator": {"estimator": ["mean", "normalized"]},
    "radius": {"radius": ["0.5", "0.75", "1", "1.25", "1.5", "2"]},
    "falloff": {"falloff": ["0", "0.2", "0.4", "0.6", "0.8"]},
    "attenuation": {"attenuation": ["reference", "binary"], "falloff": ["0", "0.3", "0.6", "1"]},
    "thickness": {"thickness": ["0", "0.05", "0.1", "0.25", "0.5"]},
    "step_power": {"step_power": ["1", "1.25", "1.5", "1.75", "2", "3"]},
    "noise": {"jitter": ["off", "on"], "denoise": ["0", "2", "4"]},
    "samples": {"slices": ["1", "2", "4", "8", "16"], "steps": ["2", "4", "8", "16", "32"]},
}


def run(out, ldmbench, base, size):
    for block, axes in BLOCKS.items():
        params = dict(base)
        params.update({k: ",".join(v) for k, v in axes.items()})
        command = [ldmbench, "run", "--scene", ",".join(SCENES), "--pass", "gtao",
                   "--image-size", f"{size}x{size}", "--frames", "1", "--warmup", "0",
                   "--time-target", "0", "--no-images", "--out", os.path.join(out, block),
                   "--overwrite"]
        for key, value in params.items():
            command += ["--param", f"gtao:{key}={value}"]
        print(" ".join(command), flush=True)
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)


def scene_label(row):
    """The scene's name (a scene file's path without folder and extension)."""
    return os.path.splitext(os.path.basename(row["scene"]))[0]


KEPT = ["block", "scene", "status", "mse", "mssim", "ref_noise_mse"]


def block_rows(out):
    """{block: [record]} from a folder of runs or from a collected CSV."""
    if out.endswith(".csv"):
        rows = ldmrecords.read(out)
        return {b: [r for r in rows if r["block"] == b] for b in BLOCKS}
    blocks = {}
    for block in BLOCKS:
        path = os.path.join(out, block, "records.csv")
        if os.path.exists(path):
            blocks[block] = [dict(r, block=block) for r in ldmrecords.read(path)]
    return blocks


def collect(out, target):
    blocks = block_rows(out)
    columns = KEPT + sorted({k for rows in blocks.values() for r in rows for k in r if k.startswith("gtao_") and not k.startswith("gtao_ms")})
    with open(target, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore", lineterminator="\n")
        writer.writeheader()
        for rows in blocks.values():
            for r in rows:
                writer.writerow({k: _short(v) for k, v in r.items()})


def _short(value):
    """Floats to 6 significant digits (the tables print 3)."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        return value
    return value if value.isdigit() else f"{number:.6g}"


def table(out):
    blocks = block_rows(out)
    for block, axes in BLOCKS.items():
        rows = [r for r in blocks.get(block, []) if r["status"] == "ok"]
        if not rows:
            continue
        keys = list(axes)
        scenes = sorted({scene_label(r) for r in rows}, key=lambda s: [scene_label(r) for r in rows].index(s))
        by_value = {}
        for r in rows:
            value = tuple(r["gtao_" + k] for k in keys)
            by_value.setdefault(value, {})[scene_label(r)] = float(r["mse"])
        summary = []
        for value, mse in by_value.items():
            if len(mse) != len(scenes):
                continue
            summary.append((math.exp(sum(math.log(m) for m in mse.values()) / len(mse)), value, mse))
        best = min(s[0] for s in summary)
        print(f"\n{block}\n")
        print("| " + " | ".join(keys) + " | geo-mean MSE | " + " | ".join(scenes) + " |")
        # (the values as recorded: 0.2 as the float 0.2, printed by _canonical's spelling)
        print("| " + " | ".join("---" for _ in keys) + " | ---: | " + " | ".join("---:" for _ in scenes) + " |")
        order = {k: [v for v in axes[k]] for k in keys}
        summary.sort(key=lambda s: [order[k].index(_canonical(s[1][i], order[k])) for i, k in enumerate(keys)])
        for geo, value, mse in summary:
            mark = " **best**" if geo == best else ""
            spelled = [_canonical(v, order[k]) for v, k in zip(value, keys)]
            print("| " + " | ".join(spelled) + f" | {geo:.3e}{mark} | " +
                  " | ".join(f"{mse[s]:.2e}" for s in scenes) + " |")


def _canonical(recorded, choices):
    """The block's spelling of a recorded value (1 for 1.0)."""
    for c in choices:
        try:
            if abs(float(c) - float(recorded)) <= 1e-6 * max(1.0, abs(float(c))):
                return c
        except ValueError:
            if c == recorded:
                return c
    return choices[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run")
    r.add_argument("out")
    r.add_argument("--ldmbench", default=os.path.join(ROOT, "build", "ldmbench"))
    r.add_argument("--base", nargs="*", default=[], help="KEY=VALUE overrides of the base point")
    r.add_argument("--size", type=int, default=128)
    c = sub.add_parser("collect")
    c.add_argument("out")
    c.add_argument("file")
    t = sub.add_parser("table")
    t.add_argument("out")
    args = parser.parse_args()
    if args.command == "run":
        run(args.out, args.ldmbench, dict(kv.split("=", 1) for kv in args.base), args.size)
    elif args.command == "collect":
        collect(args.out, args.file)
    else:
        table(args.out)


if __name__ == "__main__":
    sys.exit(main())
