#!/usr/bin/env python3
"""Regenerates the tables of docs/measured/real-scenes.md from the committed records
(docs/measured/scenes/): scripts/scenes_tables.py profiles|memory|fit [CSV]

  profiles  the depth-complexity profile of every scene (profiles-llvmpipe.csv)
  memory    memory M against R_LDM per scene and structure, with the growth per doubling
            (memory-vs-r_ldm-llvmpipe.csv: sweeps/memory-vs-r_ldm.json)
  fit       the thesis's Table 5 M_Lists figures fitted by M = a + b R^2 (no CSV: the
            thesis's own numbers, quoted)"""
import sys
import ldmrecords

MIB = float(1 << 20)
DOCS = "docs/measured/scenes/"


def rows(path):
    return ldmrecords.read(path)


def profiles(path):
    print("| scene | triangles | scene radius | fragments | p50 | p90 | p99 | max | mean | d_max (source) | trace steps (max / bound) |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: |")
    for r in rows(path):
        source = r["d_max_source"].split(" (")[0]
        print(f"| {r['scene_name']} | {int(r['triangles']):,} | {float(r['scene_radius']):.4g} | "
              f"{int(r['fragments']):,} | {r['depth_p50']} | {r['depth_p90']} | {r['depth_p99']} | "
              f"{r['max_depth_complexity']} | {float(r['mean_depth_complexity']):.2f} | "
              f"{float(r['d_max']):.4g} ({source}) | {r['trace_steps_max']} / {r['trace_steps_bound']} |")


def memory(path):
    records = rows(path)
    # A failed record (refused before the measurement) has no scene_name: its --scene spec's.
    name_of = {r["scene"]: r["scene_name"] for r in records if r["scene_name"]}
    by = {}
    for r in records:
        by.setdefault((name_of.get(r["scene"], r["scene"]), r["structure"]), []).append(r)
    print("| scene | structure | R_LDM 32 | 64 | 128 | 256 | growth per doubling (used) | fragments x per doubling |")
    print("| --- | --- | ---: | ---: | ---: | ---: | --- | --- |")
    for (scene, structure), rs in by.items():
        rs.sort(key=lambda r: int(r["r_ldm"]))
        cells, used, frags = [], [], []
        for r in rs:
            if r["status"] == "failed":
                cells.append("failed")
                used.append(None)
                frags.append(None)
                continue
            cells.append(f"{float(r['bytes_used']) / MIB:.2f} ({float(r['bytes_allocated']) / MIB:.2f})")
            used.append(float(r["bytes_used"]))
            frags.append(float(r["fragments"]))
        growth = lambda v: ", ".join(f"{b / a:.2f}" if a and b else "–" for a, b in zip(v, v[1:]))
        print(f"| {scene} | {structure} | " + " | ".join(cells) + f" | {growth(used)} | {growth(frags)} |")


def fit():
    # Thesis Table 5, M_Lists in MB at R_LDM 50, 100, 150, 200 (N = 512).
    thesis = {"sponza": [204.1, 324.2, 525.1, 805.5], "hairball": [295.5, 690.2, 1348, 2269]}
    r = [50, 100, 150, 200]
    print("| scene | M_Lists (thesis, MB) | a (MB) | b (MB per R_LDM^2) | a + b R^2 | growth 50 -> 100 | 100 -> 200 |")
    print("| --- | --- | ---: | ---: | --- | ---: | ---: |")
    for scene, m in thesis.items():
        n = len(r)
        x = [v * v for v in r]
        mx, my = sum(x) / n, sum(m) / n
        b = sum((xi - mx) * (yi - my) for xi, yi in zip(x, m)) / sum((xi - mx) ** 2 for xi in x)
        a = my - b * mx
        model = ", ".join(f"{a + b * xi:.1f}" for xi in x)
        print(f"| {scene} | {', '.join(str(v) for v in m)} | {a:.1f} | {b:.4f} | {model} | "
              f"{m[1] / m[0]:.2f} | {m[3] / m[1]:.2f} |")


if __name__ == "__main__":
    mode = sys.argv[1] if len(sys.argv) > 1 else "profiles"
    if mode == "profiles":
        profiles(sys.argv[2] if len(sys.argv) > 2 else DOCS + "profiles-llvmpipe.csv")
    elif mode == "memory":
        memory(sys.argv[2] if len(sys.argv) > 2 else DOCS + "memory-vs-r_ldm-llvmpipe.csv")
    elif mode == "fit":
        fit()
    else:
        sys.exit(__doc__)
