#!/usr/bin/env python3
"""Prints the GTAO / GPU RTAO tables of docs/measured/gtao-rtao-gpu.md from a run's records.csv.

Usage: scripts/gtao_rtao_gpu_tables.py headline|bvh|fit RECORDS.csv

  headline  per scene and method (GTAO and HBAO at their defaults, the GPU RTAO and the CPU
            RTAO at each k): frame and pass time, median with its 95 % interval, MSE, MSSIM
  bvh       per scene: the GPU RTAO's BVH (nodes, leaves, depth, bytes, build and upload time)
            and its traversal work per ray (nodes visited, triangles tested: mean and max)
  fit       per scene: the GPU RTAO's error beyond the reference's noise, e_k = MSE - noise,
            and the least-squares slope of log e_k over log k with its standard error (the
            1/k law is slope -1)

Reads the CSV alone (docs/measured/gtao-rtao-gpu/headline-llvmpipe.csv).
"""
import csv
import math
import sys


def number(row, key):
    try:
        return float(row.get(key, ""))
    except ValueError:
        return None


def scene(row):
    return row["scene"]


def k_of(row):
    for key in ("rtao_gpu_spp", "rtao_spp"):
        if row.get(key):
            return int(float(row[key]))
    return None


def label(row):
    p = row["pass"]
    if p == "gtao":
        return f"gtao {row['gtao_slices']}x{row['gtao_steps']}"
    if p == "hbao":
        return f"hbao {row['hbao_directions']}x{row['hbao_steps']}"
    if p == "rtao_gpu":
        return f"rtao_gpu {k_of(row)} spp"
    if p == "rtao":
        return f"rtao (CPU) {k_of(row)} spp"
    return p


def interval(row, name):
    m, lo, hi = (number(row, f"{name}_ms_{s}") for s in ("median", "ci_low", "ci_high"))
    if m is None:
        return "–"
    if lo is None or hi is None:
        return f"{m:.1f}"
    return f"{m:.1f} [{lo:.1f}, {hi:.1f}]"


ORDER = {"gtao": 0, "hbao": 1, "rtao_gpu": 2, "rtao": 3}


def sorted_rows(rows):
    scenes = []
    for r in rows:
        if scene(r) not in scenes:
            scenes.append(scene(r))
    return sorted(rows, key=lambda r: (scenes.index(scene(r)), ORDER.get(r["pass"], 9), k_of(r) or 0))


def headline(rows):
    print("| scene | method | timer | frame ms [95 % CI] | pass ms [95 % CI] | MSE | MSSIM |")
    print("| --- | --- | --- | ---: | ---: | ---: | ---: |")
    for r in sorted_rows(rows):
        own = {"gtao": "gtao", "hbao": "hbao", "rtao_gpu": "rtao_gpu", "rtao": "rtao"}[r["pass"]]
        print(f"| {scene(r)} | {label(r)} | {r['timer']} | {interval(r, 'frame')} | {interval(r, own)} "
              f"| {number(r, 'mse'):.2e} | {number(r, 'mssim'):.3f} |")


def bvh(rows):
    print("| scene | triangles | nodes | leaves | depth | BVH MiB | build ms | upload ms | nodes/ray mean | max | triangles/ray mean | max | loop iterations max (k) |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    seen = set()
    for r in sorted_rows(rows):
        if r["pass"] != "rtao_gpu" or scene(r) in seen:
            continue
        seen.add(scene(r))
        mine = [x for x in rows if x["pass"] == "rtao_gpu" and scene(x) == scene(r)]
        biggest = max(mine, key=k_of)
        print(f"| {scene(r)} | {int(number(r, 'triangles'))} | {int(number(r, 'rtao_gpu_bvh_nodes'))} "
              f"| {int(number(r, 'rtao_gpu_bvh_leaves'))} | {int(number(r, 'rtao_gpu_bvh_depth'))} "
              f"| {number(r, 'rtao_gpu_bvh_bytes') / 2**20:.2f} | {number(r, 'rtao_gpu_bvh_ms'):.1f} "
              f"| {number(r, 'rtao_gpu_bvh_upload_ms'):.2f} | {number(r, 'work_rtao_gpu_nodes_mean'):.1f} "
              f"| {int(number(r, 'work_rtao_gpu_nodes_max'))} | {number(r, 'work_rtao_gpu_triangles_mean'):.1f} "
              f"| {int(number(r, 'work_rtao_gpu_triangles_max'))} "
              f"| {int(number(biggest, 'rtao_gpu_steps_max'))} ({k_of(biggest)}) |")


def slope(points):
    """Least-squares slope of y over x and its standard error."""
    n = len(points)
    mx = sum(x for x, _ in points) / n
    my = sum(y for _, y in points) / n
    sxx = sum((x - mx) ** 2 for x, _ in points)
    b = sum((x - mx) * (y - my) for x, y in points) / sxx
    a = my - b * mx
    residual = sum((y - a - b * x) ** 2 for x, y in points)
    se = math.sqrt(residual / (n - 2) / sxx) if n > 2 else float("nan")
    return b, se


def fit(rows):
    gpu = [r for r in sorted_rows(rows) if r["pass"] == "rtao_gpu"]
    ks = sorted({k_of(r) for r in gpu})
    print("| scene | noise MSE | " + " | ".join(f"e_{k}" for k in ks) + " | slope ± SE | e_1 / e_k at the largest k |")
    print("| --- | ---: | " + " | ".join("---:" for _ in ks) + " | ---: | ---: |")
    scenes = []
    for r in gpu:
        if scene(r) not in scenes:
            scenes.append(scene(r))
    slopes = []
    for s in scenes:
        mine = {k_of(r): r for r in gpu if scene(r) == s}
        noise = number(mine[ks[0]], "ref_noise_mse")
        e = {k: number(mine[k], "mse") - noise for k in ks}
        b, se = slope([(math.log(k), math.log(e[k])) for k in ks])
        slopes.append(b)
        print(f"| {s} | {noise:.1e} | " + " | ".join(f"{e[k]:.2e}" for k in ks) +
              f" | {b:.3f} ± {se:.3f} | {e[ks[0]] / e[ks[-1]]:.1f} (1/k: {ks[-1] / ks[0]:.0f}) |")
    print(f"\nmean slope over {len(slopes)} scenes: {sum(slopes) / len(slopes):.3f} "
          f"(range {min(slopes):.3f} .. {max(slopes):.3f})")


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("headline", "bvh", "fit"):
        sys.exit(__doc__)
    with open(sys.argv[2], newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["status"] == "ok"]
    {"headline": headline, "bvh": bvh, "fit": fit}[sys.argv[1]](rows)


if __name__ == "__main__":
    main()
