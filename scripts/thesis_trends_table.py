#!/usr/bin/env python3
"""Prints the thesis-trend tables of docs/measured/thesis-trends.md from a run of
sweeps/thesis-trends.json (issue 33, part 5): per varied parameter, the counters and memory
that the thesis explains its results by, and their ratios to the first row beside the
thesis's own.

    scripts/thesis_trends_table.py RUN_FOLDER_OR_RECORDS

Counts and bytes only (device-independent): no time is read."""
import sys
import ldmrecords

# The thesis's own figures: Table 6's M_lists (MB) at N = 8, 32, 128, 512.
THESIS_M_LISTS_MB = {8: 12.84, 32: 50.44, 128: 201.0, 512: 805.5}


def number(r, column):
    value = r.get(column, "")
    return float(value) if value not in ("", None) else float("nan")


def ratio_text(value, first):
    return f"×{value / first:.2f}" if first else "-"


def vary(rows, column, base):
    """The rows that vary `column` (every other axis at the base point), sorted by it."""
    out = []
    for r in rows:
        if r.get("status") not in ("ok", "lossy"):
            continue
        if all(str(r.get(k)) == str(v) for k, v in base.items() if k != column):
            out.append(r)
    # The base point is in every block (once under its explicit value): one row per value.
    by_value = {}
    for r in sorted(out, key=lambda r: number(r, column)):
        by_value.setdefault(number(r, column), r)
    return list(by_value.values())


def table(rows, column, base, *headings):
    """Prints a table's head (every column right-aligned); returns its rows: those that vary
    `column` (vary)."""
    print("| " + " | ".join(headings) + " |")
    print("|" + "---:|" * len(headings))
    return vary(rows, column, base)


def table_n(rows):
    rows = table(rows, "n_views", {"r_ldm": "32", "splat_scale": "4"}, "N", "fragments stored", "ratio",
                 "M_lists (MiB)", "ratio", "thesis M_lists (MB)", "thesis ratio")
    if not rows:
        return
    f0, m0 = number(rows[0], "work_construct_fragments"), number(rows[0], "bytes_allocated")
    t0 = THESIS_M_LISTS_MB.get(int(number(rows[0], "n_views")))
    for r in rows:
        n = int(number(r, "n_views"))
        f, m = number(r, "work_construct_fragments"), number(r, "bytes_allocated")
        t = THESIS_M_LISTS_MB.get(n)
        print(f"| {n} | {f:.0f} | {ratio_text(f, f0)} | {m / 2**20:.2f} | {ratio_text(m, m0)} | "
              f"{t if t else '-'} | {ratio_text(t, t0) if t and t0 else '-'} |")


def table_s(rows):
    rows = table(rows, "splat_scale", {"n_views": "16", "r_ldm": "64"}, "s = a", "photons stored",
                 "splat fragments", "ratio to the s before", "fragments in the kernel", "ratio to the s before")
    previous = None
    for r in rows:
        f, k = number(r, "work_splatting_fragments"), number(r, "work_splatting_fragments_in_kernel")
        rf = ratio_text(f, previous[0]) if previous else "-"
        rk = ratio_text(k, previous[1]) if previous else "-"
        print(f"| {number(r, 'splat_scale'):g} | {number(r, 'photons_stored'):.0f} | {f:.0f} | {rf} | {k:.0f} | {rk} |")
        previous = (f, k)


def table_r(rows):
    rows = table(rows, "r_ldm", {"n_views": "16", "splat_scale": "4"}, "R_LDM", "photons traced", "photons stored",
                 "stored / traced", "ratio (stored)", "LDM entries read per photon, mean")
    if not rows:
        return
    s0 = number(rows[0], "photons_stored")
    for r in rows:
        traced, stored = number(r, "work_photon_tracing_photons_traced"), number(r, "photons_stored")
        print(f"| {number(r, 'r_ldm'):.0f} | {traced:.0f} | {stored:.0f} | {stored / traced:.3f} | "
              f"{ratio_text(stored, s0)} | {number(r, 'work_photon_tracing_entries_read_mean'):.2f} |")


def main(path):
    rows = ldmrecords.read(path)
    print("### M_lists and fragments against N (R_LDM = 32)\n")
    table_n(rows)
    print("\n### Splat fragments against s (N = 16, R_LDM = 64)\n")
    table_s(rows)
    print("\n### Photons stored against R_LDM (N = 16)\n")
    table_r(rows)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/measured/thesis-trends/records.csv")
