#!/usr/bin/env python3
"""Prints the GTAO / GPU RTAO tables of docs/measured/gtao-rtao-gpu.md from a run's records.csv.

Usage: scripts/gtao_rtao_gpu_tables.py headline|beside|floor|bvh|fit RECORDS.csv

  headline  per scene and method (GTAO and HBAO at their defaults, the GPU RTAO and the CPU
            RTAO at each k): frame and pass time, median with its 95 % interval, MSE, MSSIM
  beside    per scene: GTAO and HBAO at their defaults, the GPU and the CPU RTAO at 16 spp
  floor     per scene: the rasterised G-buffer's MSE floor, the GPU RTAO's e_64 with
            primary=raster less that with primary=trace, beside GTAO's MSE
  bvh       per scene: the GPU RTAO's BVH (nodes, leaves, depth, bytes, build and upload time)
            and its traversal work per ray (nodes visited, triangles tested: mean and max)
  fit       per scene: the GPU RTAO's error beyond the reference's noise, e_k = MSE - noise,
            and the least-squares slope of log e_k over log k with its standard error (the
            1/k law is slope -1)

Reads the CSV alone (docs/measured/gtao-rtao-gpu/headline-llvmpipe.csv).
"""
import math
import os
import sys
import ldmrecords
from ldmrecords import number


def scene(row):
    """The scene's name (a scene file's path without folder and extension)."""
    return os.path.splitext(os.path.basename(row["scene"]))[0]


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
        return f"rtao_gpu {k_of(row)} spp" + (", raster" if row.get("rtao_gpu_primary") == "raster" else "")
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
    return sorted(rows, key=lambda r: (scenes.index(scene(r)), ORDER.get(r["pass"], 9),
                                       r.get("rtao_gpu_primary") == "raster", k_of(r) or 0))


def headline(rows):
    print("| scene | method | frame ms [95 % CI] | method's own ms [95 % CI] | MSE | MSSIM |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    for r in sorted_rows(rows):
        own = {"gtao": "gtao", "hbao": "hbao", "rtao_gpu": "rtao_gpu", "rtao": "rtao"}[r["pass"]]
        print(f"| {scene(r)} | {label(r)} | {interval(r, 'frame')} | {interval(r, own)} "
              f"| {number(r, 'mse'):.2e} | {number(r, 'mssim'):.3f} |")


def bvh(rows):
    print("| scene | triangles | nodes | leaves | depth | BVH MiB | build ms | upload ms | nodes/ray mean | max | triangles/ray mean | max | loop iterations max (k) |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    seen = set()
    traced = [r for r in rows if r["pass"] == "rtao_gpu" and r.get("rtao_gpu_primary") != "raster"]
    for r in sorted_rows(traced):
        if scene(r) in seen:
            continue
        seen.add(scene(r))
        mine = [x for x in traced if scene(x) == scene(r)]
        biggest = max(mine, key=k_of)
        print(f"| {scene(r)} | {int(number(r, 'triangles'))} | {int(number(r, 'rtao_gpu_bvh_nodes'))} "
              f"| {int(number(r, 'rtao_gpu_bvh_leaves'))} | {int(number(r, 'rtao_gpu_bvh_depth'))} "
              f"| {number(r, 'rtao_gpu_bvh_bytes') / 2**20:.2f} | {number(r, 'rtao_gpu_bvh_ms'):.1f} "
              f"| {number(r, 'rtao_gpu_bvh_upload_ms'):.2f} | {number(r, 'work_rtao_gpu_nodes_mean'):.1f} "
              f"| {int(number(r, 'work_rtao_gpu_nodes_max'))} | {number(r, 'work_rtao_gpu_triangles_mean'):.1f} "
              f"| {int(number(r, 'work_rtao_gpu_triangles_max'))} "
              f"| {int(number(biggest, 'rtao_gpu_steps_max'))} ({k_of(biggest)}) |")


def find(rows, s, p, **values):
    for r in rows:
        if scene(r) == s and r["pass"] == p and all(r.get(k) == v for k, v in values.items()):
            return r
    return None


def scene_names(rows):
    names = []
    for r in rows:
        if scene(r) not in names:
            names.append(scene(r))
    return names


def beside(rows):
    print("| scene | GTAO MSE | frame ms [95 % CI] | HBAO MSE | frame ms [95 % CI] "
          "| GPU RTAO 16 spp MSE | frame ms [95 % CI] | CPU RTAO 16 spp MSE | ms [95 % CI] |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for s in scene_names(rows):
        g, h = find(rows, s, "gtao"), find(rows, s, "hbao")
        t = find(rows, s, "rtao_gpu", rtao_gpu_spp="16", rtao_gpu_primary="trace")
        c = find(rows, s, "rtao", rtao_spp="16")
        print(f"| {s} | " + " | ".join(f"{number(r, 'mse'):.2e} | {interval(r, 'frame')}" for r in (g, h, t, c)) + " |")


def floor(rows):
    print("| scene | GPU RTAO e_64, traced | rasterised | difference: the G-buffer's floor | GTAO's MSE | floor / GTAO's |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for s in scene_names(rows):
        t = find(rows, s, "rtao_gpu", rtao_gpu_spp="64", rtao_gpu_primary="trace")
        r = find(rows, s, "rtao_gpu", rtao_gpu_spp="64", rtao_gpu_primary="raster")
        g = find(rows, s, "gtao")
        noise = number(t, "ref_noise_mse")
        et, er = number(t, "mse") - noise, number(r, "mse") - noise
        print(f"| {s} | {et:.2e} | {er:.2e} | {er - et:.1e} | {number(g, 'mse'):.2e} "
              f"| {100 * (er - et) / number(g, 'mse'):.1f} % |")


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
    for method in ("rtao_gpu", "rtao_gpu raster", "rtao"):
        print(f"\n{method}\n")
        fit_method([r for r in rows if label(r).startswith(method.split()[0] + " ") and
                    (r.get("rtao_gpu_primary") == "raster") == method.endswith("raster")])


def fit_method(rows):
    gpu = sorted_rows(rows)
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
    commands = {"headline": headline, "beside": beside, "floor": floor, "bvh": bvh, "fit": fit}
    if len(sys.argv) != 3 or sys.argv[1] not in commands:
        sys.exit(__doc__)
    rows = ldmrecords.with_status(ldmrecords.read(sys.argv[2]), "ok")
    commands[sys.argv[1]](rows)


if __name__ == "__main__":
    main()
