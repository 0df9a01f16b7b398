#!/usr/bin/env python3
"""At equal time, which AO method errs least? (issue 36; docs/measured/ao-methods.md, README)

  scripts/equal_time_table.py RECORDS.csv [--reference-config SUBSTRING] [--factors 1,2,4]

From one run of sweeps/ao-methods.json (every method measured side by side, one reference
per scene), per scene: GTAO's frame time at its defaults (8 slices x 16 steps; or the
configuration whose id contains --reference-config) is the unit; for each method, the least
MSE any of its configurations reaches with a frame time within 1x, 2x and 4x that unit,
and which configuration. Frame times are as each method would run on a dynamic scene: the
LDM structures build every frame (their frame is build + pass); GPU RTAO's frame excludes
its BVH, built once on the CPU for a static scene, and the column "GPU RTAO + BVH" counts
the BVH build in every frame (a dynamic scene rebuilds it). MSE is over the whole image,
with the reference's own noise (ref_noise_mse) beside it; a method with no configuration
within a budget shows "-". Prints Markdown.
"""
import argparse
import math
import sys
from collections import defaultdict
import ldmrecords
from ldmrecords import value

METHODS = [  # (label, pass, frame time of a record)
    ("LDM AO (best structure)", "ao", lambda r: value(r, "frame_ms_median")),
    ("HBAO", "hbao", lambda r: value(r, "frame_ms_median")),
    ("GTAO", "gtao", lambda r: value(r, "frame_ms_median")),
    ("GPU RTAO", "rtao_gpu", lambda r: value(r, "frame_ms_median")),
    ("GPU RTAO + BVH build", "rtao_gpu", lambda r: value(r, "frame_ms_median") + value(r, "rtao_gpu_bvh_ms")),
]
GTAO_DEFAULT = {"gtao_slices": 8, "gtao_steps": 16}  # harness/passes/gtao.h's defaults


def unit_time(rows, reference_config):
    """GTAO's frame time at its defaults (ids name only what differs from the defaults)."""
    gtao = [r for r in rows if r["pass"] == "gtao"]
    if reference_config:
        chosen = [r for r in gtao if reference_config in r["config_id"]]
    else:
        # The defaults, read from the records' own parameter columns.
        chosen = [r for r in gtao if value(r, "gtao_slices") == GTAO_DEFAULT["gtao_slices"]
                  and value(r, "gtao_steps") == GTAO_DEFAULT["gtao_steps"]]
    if not chosen:
        return None, None
    return value(chosen[0], "frame_ms_median"), chosen[0]["config_id"]


def short(config_id, scene):
    return config_id[len(scene) + 1:] if config_id.startswith(scene + "-") else config_id


def table(rows, factors, reference_config):
    by_scene = defaultdict(list)
    for r in rows:
        if r.get("status") == "ok" and math.isfinite(value(r, "mse")):
            by_scene[r["scene_name"] or r["scene"]].append(r)
    out = []
    for scene, srows in by_scene.items():
        unit, unit_id = unit_time(srows, reference_config)
        if unit is None or not math.isfinite(unit):
            out.append(f"{scene}: no GTAO record at its defaults to set the unit of time; skipped\n")
            continue
        noise = min((value(r, "ref_noise_mse") for r in srows if math.isfinite(value(r, "ref_noise_mse"))),
                    default=math.nan)
        out.append(f"**{scene}**: unit = GTAO at its defaults ({short(unit_id, scene)}), {unit:.3g} ms a frame; "
                   f"the reference's noise {noise:.2g} in MSE.\n")
        out.append("| method | " + " | ".join(f"within {f:g}x ({f * unit:.3g} ms)" for f in factors) + " |")
        out.append("| --- |" + " --- |" * len(factors))
        for label, pass_name, frame in METHODS:
            cells = []
            for f in factors:
                within = [r for r in srows if r["pass"] == pass_name and frame(r) <= f * unit]
                if not within:
                    cells.append("-")
                    continue
                best = min(within, key=lambda r: value(r, "mse"))
                cells.append(f"{value(best, 'mse'):.3g} ({short(best['config_id'], scene)}, {frame(best):.3g} ms)")
            out.append(f"| {label} | " + " | ".join(cells) + " |")
        out.append("")
    return "\n".join(out)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("records")
    p.add_argument("--reference-config", default="")
    p.add_argument("--factors", default="1,2,4")
    a = p.parse_args()
    rows = ldmrecords.read(a.records)
    factors = [float(x) for x in a.factors.split(",")]
    text = table(rows, factors, a.reference_config)
    if not text.strip():
        sys.exit(f"{a.records}: no scored records")
    print(text)


if __name__ == "__main__":
    main()
