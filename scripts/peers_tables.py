#!/usr/bin/env python3
"""Prints the peer tables of docs/measured/peers.md from a run's records.csv.

Usage: scripts/peers_tables.py headline|dmax|samples RECORDS.csv

  headline  one row per record: the LDM AO through its structures, HBAO and RTAO side by side
  dmax      Table 3 in miniature: per scene and d_max, frame time and MSE of every method
  samples   Table 4 in miniature: per method and sample count (N views for the LDM AO,
            N_HBAO directions for HBAO, spp for RTAO), frame time and MSE per scene

Reads the CSV alone, so the tables regenerate from the committed records
(docs/measured/peers-*-llvmpipe.csv).
"""
import sys
import ldmrecords
from ldmrecords import number


def fmt(value, spec):
    return "–" if value is None else format(value, spec)


def method(row):
    """A short label: ao (structure), hbao (jitter, blur), rtao (spp)."""
    if row["pass"] == "ao":
        return f"ao {row['structure']}"
    if row["pass"] == "hbao":
        extras = []
        if row.get("hbao_jitter") == "on":
            extras.append("jitter")
        if row.get("hbao_blur") not in (None, "", "0"):
            extras.append(f"blur {row['hbao_blur']}")
        return "hbao" + (" " + ", ".join(extras) if extras else "")
    if row["pass"] == "rtao":
        return f"rtao {row['rtao_spp']} spp"
    return row["pass"]


def samples(row):
    """The method's own sample count: N, N_HBAO or spp."""
    key = {"ao": "n_views", "hbao": "hbao_directions", "rtao": "rtao_spp"}[row["pass"]]
    return int(float(row[key]))


def pass_ms(row):
    """The method's own sub-passes (not the G-buffer): ao, hbao + blur, rtao."""
    keys = {"ao": ["ao"], "hbao": ["hbao", "blur"], "rtao": ["rtao"]}[row["pass"]]
    values = [number(row, k + "_ms_median") for k in keys]
    values = [v for v in values if v is not None]
    return sum(values) if values else None


def headline(rows):
    print("| scene | method | device (timer) | frame ms | build ms | pass ms | allocated MiB "
          "| MSE | MSSIM |")
    print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in rows:
        device = "CPU" if r["timer"] == "cpu_wall" else r["device"].split(" (")[0]
        allocated = number(r, "bytes_allocated")
        print(f"| {r['scene']} | {method(r)} | {device} ({r['timer']}) "
              f"| {fmt(number(r, 'frame_ms_median'), '.1f')} "
              f"| {fmt(number(r, 'build_ms_median'), '.1f')} | {fmt(pass_ms(r), '.1f')} "
              f"| {fmt(allocated and allocated / (1 << 20), '.2f')} "
              f"| {fmt(number(r, 'mse'), '.2e')} | {fmt(number(r, 'mssim'), '.3f')} |")


def dmax(rows):
    methods = list(dict.fromkeys(method(r) for r in rows))
    header = "| scene | d_max | " + " | ".join(f"{m} ms | {m} MSE" for m in methods) + " |"
    print(header)
    print("| --- | ---: |" + " ---: | ---: |" * len(methods))
    cells = {}
    for r in rows:
        cells[(r["scene"], float(r["d_max"]), method(r))] = r
    for scene in dict.fromkeys(r["scene"] for r in rows):
        for d in sorted({float(r["d_max"]) for r in rows if r["scene"] == scene}):
            line = f"| {scene} | {d:g} |"
            for m in methods:
                r = cells.get((scene, d, m))
                line += time_and_mse_cells(r)
            print(line)


def time_and_mse_cells(r):
    """A record's frame time and MSE cells, or dashes where there is no record."""
    return f" {fmt(number(r, 'frame_ms_median'), '.1f')} | {fmt(number(r, 'mse'), '.2e')} |" if r else " – | – |"


def sample_counts(rows):
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    print("| method | samples | " + " | ".join(f"{s} frame ms | {s} MSE" for s in scenes) + " |")
    print("| --- | ---: |" + " ---: | ---: |" * len(scenes))
    cells = {(r["pass"], samples(r), r["scene"]): r for r in rows}
    labels = {"ao": "ao psppsll (N views)", "hbao": "hbao (N_HBAO directions)", "rtao": "rtao (spp)"}
    for p in dict.fromkeys(r["pass"] for r in rows):
        for n in sorted({samples(r) for r in rows if r["pass"] == p}):
            line = f"| {labels.get(p, p)} | {n} |"
            for s in scenes:
                r = cells.get((p, n, s))
                line += time_and_mse_cells(r)
            print(line)


def main(kind, path):
    rows = ldmrecords.with_status(ldmrecords.read(path), "ok")
    {"headline": headline, "dmax": dmax, "samples": sample_counts}[kind](rows)


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("headline", "dmax", "samples"):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
