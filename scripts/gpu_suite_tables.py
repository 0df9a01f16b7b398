#!/usr/bin/env python3
"""Prints the tables of docs/measured/gpu-suite.md from the GPU suite's records of one
device (scripts/gpu-suite.sh): the AO of every structure at the base point and against N,
the peers, the clock state of each round of repetitions, how often the first run's
intervals held the second run's medians, and the indirect repetitions that ran.

    scripts/gpu_suite_tables.py DEVICE_FOLDER      (holds run-1/ and, if measured, run-2/)

Times are the device's (its records name it); counts, memory and errors are the same on any."""
import json
import math
import statistics
import sys
from collections import defaultdict
from pathlib import Path

import ldmrecords

STRUCTURES = ("psppsll", "ppsll", "dfbuffer", "habuffer", "ppfla", "psppfla")


def num(row, column):
    value = ldmrecords.number(row, column)
    return math.nan if value is None else value


def ms(x):
    return "–" if math.isnan(x) else (f"{x:.3g}" if x < 100 else f"{x:.0f}")


def repetitions(journal):
    """The per-repetition rows of a run's journal (records.jsonl), in the order measured."""
    rows = []
    for line in Path(journal).read_text().splitlines():
        entry = json.loads(line)
        if "repetition" in entry:
            rows.append(entry["repetition"])
    return rows


def base_point(rows):
    print("| scene | structure | build ms | AO pass ms | frame ms [95 % interval] | MSE | MiB allocated |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
    for scene in ("cornell", "atrium"):
        for s in STRUCTURES:
            r = next(r for r in rows if r["scene"] == scene and r["structure"] == s and r["pass"] == "ao"
                     and r["n_views"] == "32" and r["r_ldm"] == "256")
            print(f"| {scene} | {s} | {ms(num(r, 'build_ms_median'))} | {ms(num(r, 'pass_ms_median'))} | "
                  f"{ms(num(r, 'frame_ms_median'))} [{ms(num(r, 'frame_ms_ci_low'))}, {ms(num(r, 'frame_ms_ci_high'))}] | "
                  f"{num(r, 'mse'):.3g} | {num(r, 'bytes_allocated') / 2**20:.1f} |")


def against_n(rows):
    print("| scene | structure | " + " | ".join(f"N {n}: build / frame ms" for n in (16, 32, 64, 128)) + " |")
    print("| --- | --- |" + " ---: |" * 4)
    for scene in ("cornell", "atrium"):
        for s in STRUCTURES:
            cells = []
            for n in ("16", "32", "64", "128"):
                r = next((r for r in rows if r["scene"] == scene and r["structure"] == s and r["pass"] == "ao"
                          and r["n_views"] == n and r["r_ldm"] == "256"), None)
                cells.append("–" if r is None else f"{ms(num(r, 'build_ms_median'))} / {ms(num(r, 'frame_ms_median'))}")
            print(f"| {scene} | {s} | " + " | ".join(cells) + " |")


def peers(rows):
    print("| scene | method | pass ms | MSE |")
    print("| --- | --- | ---: | ---: |")
    for scene in ("cornell", "atrium"):
        for r in rows:
            if r["scene"] != scene or r["structure"] != "none":
                continue
            name = r["pass"] + (f" {r['config_id'].rsplit('spp=', 1)[1]} spp" if "spp=" in r["config_id"] else "")
            print(f"| {scene} | {name} | {ms(num(r, 'pass_ms_median'))} | {num(r, 'mse'):.3g} |")


def clock_rounds(reps):
    """Each round of repetitions: how much slower than the configuration's fastest round,
    and the SM clock at its start."""
    fastest = defaultdict(lambda: math.inf)
    for r in reps:
        fastest[r["config_id"]] = min(fastest[r["config_id"]], float(r["frame_ms_median"]))
    print("| round | repetitions | slower than the fastest round by > 20 % | median slowdown | "
          "median SM clock at the start, MHz | warned in status_detail |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: |")
    by_round = defaultdict(list)
    for r in reps:
        by_round[int(r.get("repetition", 0))].append(r)
    for k in sorted(by_round):
        rs = by_round[k]
        slow = [float(r["frame_ms_median"]) / fastest[r["config_id"]] for r in rs]
        clocks = [float(r["gpu_sm_clock_mhz_start"]) for r in rs if r.get("gpu_sm_clock_mhz_start") not in (None, "")]
        warned = sum("GPU SM clock" in (r.get("status_detail") or "") for r in rs)
        print(f"| {k} | {len(rs)} | {sum(x > 1.2 for x in slow)} | ×{statistics.median(slow):.2f} | "
              f"{statistics.median(clocks):.0f} | {warned} |")


def coverage(run1_rows, run2_reps):
    """Does run 1's frame interval hold the median of run 2's repetitions of the same
    configuration? Run 2 may be partial: whatever repetitions it measured."""
    first = {r["config_id"]: r for r in run1_rows}
    by_config = defaultdict(list)
    for r in run2_reps:
        by_config[r["config_id"]].append(float(r["frame_ms_median"]))
    held, missed = 0, []
    for config, medians in by_config.items():
        r = first.get(config)
        if r is None:
            continue
        m2 = statistics.median(medians)
        if num(r, "frame_ms_ci_low") <= m2 <= num(r, "frame_ms_ci_high"):
            held += 1
        else:
            missed.append((config, num(r, "frame_ms_median"), m2))
    total = held + len(missed)
    print(f"Run 1's frame interval held run 2's median in {held} of {total} configurations "
          f"({100 * held / total:.0f} %). Missed:")
    print()
    print("| configuration | run 1 median ms | run 2 median ms | ratio |")
    print("| --- | ---: | ---: | ---: |")
    for config, a, b in missed:
        print(f"| {config} | {ms(a)} | {ms(b)} | ×{b / a:.2f} |")


def model_fits(run):
    """`ldmbench model RUN`'s fit quality per sub-pass (5-fold cross-validation by
    configuration): the fit is deterministic, so its figures are the records'."""
    import re
    import subprocess
    out = subprocess.run([ldmrecords.default_ldmbench(), "model", str(run)], check=True,
                         capture_output=True, text=True).stdout
    pattern = re.compile(r"· (\w+) \(.*\): (\d+) records, \d+ configurations; R² ([-0-9.]+), "
                         r"held-out median error ([0-9.]+ %) \(p90 ([0-9.]+ %)")
    print("| sub-pass | records | R² | held-out median error | p90 |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for line in out.splitlines():
        m = pattern.search(line)
        if m:
            print("| " + " | ".join(m.groups()) + " |")


def indirect(reps):
    print("One repetition each (round 1 of 3, the rest stopped by the time guard): no interval.\n")
    print("| configuration | splatting ms | frame ms | photons stored | splat fragments | fragments per µs |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for r in reps:
        fragments = num(r, "work_splatting_fragments")
        splat = num(r, "splatting_ms_median")
        print(f"| {r['config_id']} | {ms(splat)} | {ms(num(r, 'frame_ms_median'))} | {num(r, 'photons_stored'):.0f} | "
              f"{fragments:.0f} | {fragments / splat / 1000:.0f} |")


def utilisation(smi_csv):
    """How often nvidia-smi, sampling every 0.5 s through the suite, saw the GPU idle."""
    lines = Path(smi_csv).read_text().splitlines()[1:]
    busy = [int(line.split(",")[5].strip().rstrip("%").strip()) for line in lines if line.count(",") >= 6]
    idle = sum(b == 0 for b in busy)
    print(f"nvidia-smi read 0 % utilisation in {idle} of its {len(busy)} samples "
          f"({100 * idle / len(busy):.0f} %); the median sample {statistics.median(busy):.0f} %.")


def deterministic_work_columns():
    """The work_* columns the schema declares deterministic (`ldmbench columns --json`),
    the driver's own pipeline statistics (work_*_gl_*) left out."""
    import subprocess
    out = subprocess.run([ldmrecords.default_ldmbench(), "columns", "--json"], check=True,
                         capture_output=True, text=True).stdout
    return {c["name"] for c in json.loads(out)["columns"]
            if c["name"].startswith("work_") and c.get("deterministic") and "_gl_" not in c["name"]}


def across_devices(other_csv, device_rows):
    """The deterministic counters of the same configurations counted on another device
    (llvmpipe): per sub-pass, how many values are equal and the largest relative difference."""
    deterministic = deterministic_work_columns()
    here = {r["config_id"]: r for r in device_rows}
    equal, differ, largest = defaultdict(int), defaultdict(int), defaultdict(float)
    configs = 0
    for other in ldmrecords.read(other_csv):
        mine = here.get(other["config_id"])
        if mine is None or other["status"] != "ok" and not other["status"].startswith("ok"):
            continue
        configs += 1
        for column in deterministic:
            a, b = other.get(column, ""), mine.get(column, "")
            if a in ("", None) and b in ("", None):
                continue
            subpass = next((p for p in ("prefix_sum", "construct", "gbuffer", "count", "sort", "ao")
                            if column.startswith(f"work_{p}_")), "other")
            x, y = float(a), float(b)
            if x == y:
                equal[subpass] += 1
            else:
                differ[subpass] += 1
                largest[subpass] = max(largest[subpass], abs(x - y) / max(abs(x), abs(y)))
    print(f"{configs} configurations counted on both devices.\n")
    print("| sub-pass | deterministic values equal | differing | largest relative difference |")
    print("| --- | ---: | ---: | ---: |")
    for subpass in ("count", "prefix_sum", "construct", "sort", "gbuffer", "ao", "other"):
        if equal[subpass] or differ[subpass]:
            gap = f"{largest[subpass]:.1e}" if differ[subpass] else "0"
            print(f"| {subpass} | {equal[subpass]} | {differ[subpass]} | {gap} |")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    device = Path(sys.argv[1])
    run1 = device / "run-1"
    rows = ldmrecords.read(run1 / "ao")
    reps1 = repetitions(run1 / "ao" / "records.jsonl")
    print("### AO at the base point (N 32, R_LDM 256, 1280×720)\n")
    base_point(rows)
    print("\n### AO against N (R_LDM 256)\n")
    against_n(rows)
    print("\n### The peers\n")
    peers(rows)
    print("\n### The GPU's clock, round by round (run 1)\n")
    clock_rounds(reps1)
    if (run1 / "smi.csv").exists():
        print("\n### How busy the GPU was (run 1)\n")
        utilisation(run1 / "smi.csv")
    if (device / "run-2" / "ao" / "records.jsonl").exists():
        print("\n### Run 1's intervals against run 2's medians\n")
        coverage(rows, repetitions(device / "run-2" / "ao" / "records.jsonl"))
    other = device.parent / "llvmpipe-same-configurations" / "records.csv"
    if other.exists():
        print("\n### The same configurations counted on llvmpipe\n")
        across_devices(other, rows)
    print("\n### The cost model fitted on run 1's AO\n")
    model_fits(run1 / "ao")
    if (run1 / "indirect" / "records.jsonl").exists():
        print("\n### Indirect light: the repetitions that ran\n")
        indirect(repetitions(run1 / "indirect" / "records.jsonl"))


if __name__ == "__main__":
    main()
