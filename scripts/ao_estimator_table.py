#!/usr/bin/env python3
"""Prints the AO estimator table of docs/measured/trace-variants.md from a run of
docs/measured/ao-estimator/sweep.json: per scene and estimator, the MSE against the
reference at every N, and the ratio normalized / eq13 (below 1: normalized is better)."""
import sys
from collections import defaultdict
import ldmrecords


def main(path):
    rows = ldmrecords.read(path)
    mse = defaultdict(dict)
    noise = {}
    views = sorted({int(r["n_views"]) for r in rows})
    for r in rows:
        if r["status"] != "ok":
            continue
        mse[(r["scene_name"], r["ao_estimator"])][int(r["n_views"])] = float(r["mse"])
        noise[r["scene_name"]] = float(r["ref_noise_mse"])
    scenes = sorted({s for s, _ in mse})
    print("| scene | estimator | " + " | ".join(f"N={n} MSE" for n in views) + " |")
    print("| --- | --- | " + " | ".join("---:" for _ in views) + " |")
    for s in scenes:
        for e in ("eq13", "normalized"):
            print(f"| {s} | `{e}` | " + " | ".join(f"{mse[(s, e)].get(n, float('nan')):.3g}" for n in views) + " |")
        ratio = [mse[(s, "normalized")].get(n, float("nan")) / mse[(s, "eq13")].get(n, float("nan")) for n in views]
        print(f"| {s} | normalized / eq13 | " + " | ".join(f"**{q:.2f}**" if q > 1 else f"{q:.2f}" for q in ratio) + " |")
    print()
    for s in scenes:
        print(f"{s}: reference noise MSE {noise[s]:.3g}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/measured/ao-estimator/records.csv")
