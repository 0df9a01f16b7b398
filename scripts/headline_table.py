#!/usr/bin/env python3
"""Prints the headline table of docs/measured/ao.md from a run's records.csv.

Usage: scripts/headline_table.py results/runs/<run>/records.csv

One row per record, in the file's order: fragments and depth complexity from the census,
build and AO medians, the build over both raster baselines, memory and accuracy. Reads the
CSV alone, so the table regenerates from a committed run.
"""
import sys
import ldmrecords
from ldmrecords import number


def fmt(value, spec):
    return "–" if value is None else format(value, spec)


def main(path):
    rows = ldmrecords.read(path)
    print("| scene | structure | status | fragments (max depth) | build ms | × raster touch "
          "| AO ms | allocated MiB | used MiB | MSE | MSSIM |")
    print("| --- | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    mib = 1 << 20
    for r in rows:
        fragments = number(r, "fragments")
        depth = number(r, "max_depth_complexity")
        allocated, used = number(r, "bytes_allocated"), number(r, "bytes_used")
        print(f"| {r['scene']} | {r['structure']} | {r['status']} "
              f"| {fmt(fragments, ',.0f')} ({fmt(depth, '.0f')}) "
              f"| {fmt(number(r, 'build_ms_median'), '.1f')} "
              f"| {fmt(number(r, 'build_vs_raster_touch'), '.1f')} "
              f"| {fmt(number(r, 'ao_ms_median'), '.1f')} "
              f"| {fmt(allocated and allocated / mib, '.2f')} | {fmt(used and used / mib, '.2f')} "
              f"| {fmt(number(r, 'mse'), '.2e')} | {fmt(number(r, 'mssim'), '.4f')} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
