#!/usr/bin/env python3
"""Prints the ranking table of docs/measured/work-ranking.md from an AO run of every
structure: per structure the measured build and AO times beside the work counters that
explain them — storage bytes and atomics per fragment built, bytes and loop steps per LDM
entry the AO trace read, and the structure's own per-query counter (list nodes, hash
probes, array slots).

    scripts/work_ranking_table.py RUN_FOLDER_OR_RECORDS

Times are this run's medians (the device it ran on); the counters are the same on any."""
import math
import sys
import ldmrecords

PASS_SUBPASSES = ("gbuffer", "ao")


def number(r, column):
    value = r.get(column, "")
    try:
        return float(value)
    except (TypeError, ValueError):
        return float("nan")


def work_sum(r, subpasses, kind):
    """The sum of the totals work_<subpass>_<kind>* over `subpasses` (None: every build
    sub-pass, i.e. every one but the pass's)."""
    total = 0.0
    for key, value in r.items():
        if not key.startswith("work_") or "_gl_" in key or value in ("", None):
            continue
        # A distribution's statistics beside its _total (not a counter named ..._max).
        suffix = next((x for x in ("_mean", "_p50", "_p99", "_max") if key.endswith(x)), None)
        if suffix and key[: -len(suffix)] + "_total" in r:
            continue
        rest = key[len("work_"):]
        subpass = next((s for s in PASS_SUBPASSES if rest.startswith(s + "_")), None)
        in_scope = (subpass is None) if subpasses is None else (subpass in subpasses)
        if not in_scope:
            continue
        counter = rest[len(subpass) + 1:] if subpass else rest.split("_", 1)[1] if "_" in rest else rest
        if kind == "bytes" and counter.startswith("bytes_"):
            total += float(value)
        elif kind == "atomics" and counter.startswith("atomic_") and not counter.endswith(("_failed", "_on_loss")):
            total += float(value)
        elif kind == "fragments" and counter == "fragments":
            total += float(value)
    return total


def query_counter(r):
    for name in ("nodes_visited", "hash_probes", "slots_scanned"):
        if f"work_ao_{name}_total" in r and r[f"work_ao_{name}_total"] not in ("", None):
            return name, number(r, f"work_ao_{name}_total")
    return "-", float("nan")


def main(path):
    rows = [r for r in ldmrecords.read(path) if r.get("pass") == "ao" and r.get("status") in ("ok", "lossy")]
    rows.sort(key=lambda r: number(r, "build_ms_median"))
    print("| structure | build ms | fragments shaded / stored | bytes / fragment | atomics / fragment | AO trace ms | "
          "bytes / entry read | loop steps / entry read | per-query counter / entry read |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---|")
    for r in rows:
        fragments = number(r, "fragments_stored") or number(r, "work_construct_fragments")
        entries = number(r, "work_ao_entries_read_total")
        name, count = query_counter(r)
        per_query = f"{count / entries:.2f} {name.replace('_', ' ')}" if entries and not math.isnan(count) else "-"
        print(f"| {r['structure']} | {number(r, 'build_ms_median'):.1f} | {work_sum(r, None, 'fragments') / fragments:.2f} | "
              f"{work_sum(r, None, 'bytes') / fragments:.1f} | "
              f"{work_sum(r, None, 'atomics') / fragments:.2f} | {number(r, 'ao_ms_median'):.1f} | "
              f"{work_sum(r, ('ao',), 'bytes') / entries:.1f} | "
              f"{number(r, 'work_ao_trace_steps_total') / entries:.2f} | {per_query} |")


if __name__ == "__main__":
    main(sys.argv[1])
