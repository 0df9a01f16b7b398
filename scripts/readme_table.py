#!/usr/bin/env python3
"""Prints the README's main table (its "Main results") from a run's records.csv.

Usage: scripts/readme_table.py docs/measured/readme-main/records.csv

The run is `scripts/readme-main.sh`: the default sweep's AO base point (the Cornell box and
the atrium, N = 32, R_LDM = 128, 128x128, every structure and the peers) with
--repetitions 3. Every time is the median with its 95 % interval, printed to the digits the
interval supports, as the report prints it ("32.1 ±2.4%": the interval's relative
half-width); memory is exact; MSE and MSSIM are against the Embree reference, whose own
noise floor (ref_noise_mse) is the last column. Reads the CSV alone, so the table
regenerates from the committed run.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "report"))
from ldmreport.pages import fmt, fmt_time  # noqa: E402  (the report's own formatting)
import ldmrecords
from ldmrecords import number

MIB = float(1 << 20)


def timed(row, subpass):
    """The sub-pass's median with its interval, as the report prints it."""
    return fmt_time(number(row, f"{subpass}_ms_median"), number(row, f"{subpass}_ms_ci_low"),
                    number(row, f"{subpass}_ms_ci_high"))


def method(row):
    if row["pass"] == "ao":
        return row["structure"]
    if row["pass"] == "rtao":
        return f"rtao (peer, {row.get('rtao_spp') or '1'} spp, CPU)"
    if row["pass"] == "rtao_gpu":
        return f"rtao_gpu (peer, {row.get('rtao_gpu_spp') or '1'} spp)"
    return f"{row['pass']} (peer)"


def build(row):
    """An LDM structure's build per frame; GPU RTAO's BVH build (CPU wall time, once per
    static scene, so not in its frame) in parentheses; '–' for a peer that builds nothing."""
    if row["pass"] == "ao":
        return timed(row, "build")
    bvh = number(row, "rtao_gpu_bvh_ms")
    return f"({bvh:.2g} ms BVH, once)" if row["pass"] == "rtao_gpu" and bvh is not None else "–"


def measured_with(rows):
    """The GL driver(s) the GPU rows ran on, from their records (rtao's device is the CPU)."""
    drivers = sorted({f"{r['device']}, OpenGL {r['gl_version']}" for r in rows if r["pass"] != "rtao"})
    return "Measured with " + "; ".join(drivers) + "."


def main(path):
    rows = ldmrecords.read(path)
    print(measured_with(rows))
    print()
    print("| scene | method | status | build ms | pass ms | frame ms | MiB allocated | MiB used "
          "| MSE | MSSIM | reference noise MSE |")
    print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in rows:
        ldm = r["pass"] == "ao"
        # The query is the AO pass's own time (frame minus build) for an LDM structure; a
        # peer has no build, and its whole frame is its query.
        query = timed(r, "pass") if ldm else timed(r, "frame")
        allocated, used = number(r, "bytes_allocated"), number(r, "bytes_used")
        print(f"| {r['scene']} | {method(r)} | {r['status']} | {build(r)} | {query} "
              f"| {timed(r, 'frame')} | {fmt(None if allocated is None else allocated / MIB)} "
              f"| {fmt(None if used is None else used / MIB)} | {fmt(number(r, 'mse'))} "
              f"| {fmt(number(r, 'mssim'))} | {fmt(number(r, 'ref_noise_mse'), 2)} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip().split("\n\n")[1])
    main(sys.argv[1])
