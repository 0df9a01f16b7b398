#!/usr/bin/env python3
"""Whether two run folders hold the same records in every column that neither measures time
nor names the machine or job that measured: the Slurm CI step's check (scripts/slurm-ci.sh)
that a sweep measured as a job array and merged equals the same sweep measured in one run.

  scripts/same_records.py EXPECTED_RUN ACTUAL_RUN

Records are matched by config_id (a merge orders them by shard, a single run by the sweep:
the order is not compared). Exit 0 when equal; 1 listing each difference (a configuration
missing or extra, a column missing, a value differing); 2 when a folder cannot be read.

Columns left out: those the column schema declares as varying between runs
(`ldmbench columns --json`, flag varies_between_runs; the binary is $LDMBENCH, else
build/ldmbench). Today, and why (everything else, present in either record, must be equal):
- measured time (`ldmbench columns`, group time): the <subpass>_ms_* statistics,
  build_vs_raster*, fragments_per_second, time_half_width, time_target_met, wall_seconds,
  ref_render_seconds, rtao_bvh_ms, rtao_gpu_bvh_ms, rtao_gpu_bvh_upload_ms, the run-to-run
  spread and machine state (load, clocks), and the harness's own costs frames_timed_ms, verify_ms,
  verify_warmup_ms, verify_share. Two runs never time alike. frames_measured and the
  interval's coverage stay compared: with settings.timing.target 0 (the CI sweep) they are
  the fixed frame count, not a measurement.
- where and by which job it ran: host and the slurm_* columns (which node, job, array task
  and GPUs; a shard and the single run are different jobs, possibly on different nodes).
- ref_from_cache: whether an earlier run had already rendered the reference (runs sharing a
  cache: whichever came first rendered it); the reference's own columns (ref_spp,
  ref_noise_mse, ref_cache_key, ...) are compared.
Columns compared within a tolerance: those the schema declares summed in arrival order
(flag summed_in_arrival_order: the accuracy columns, the indirect pass's flux audits) agree
within the record's image_order_tolerance, relative, where the record has one (the indirect
pass: its splats blend in the order photons were appended); exactly everywhere else.
The image and sample files the records name must exist in both folders (their paths are
compared as columns; the sample files hold frame times and are not compared).
"""
import math
import re
import sys
from pathlib import Path
import ldmrecords

FILE_COLUMNS = re.compile(r"^(.+_(exr|png)|frame_samples_csv)$")


def excluded(column):
    """Varies between two runs of one configuration, by the schema (ldmbench columns --json)."""
    return bool(ldmrecords.varies_between_runs().match(column))


class Unreadable(Exception):
    pass


def load_records(run):
    path = Path(run) / "records.json"
    try:
        _run, records = ldmrecords.read_run(path)
    except (OSError, ValueError, KeyError, TypeError) as error:
        raise Unreadable(f"{path}: cannot read its records ({error})") from None
    by_id = {}
    for record in records:
        if record.get("config_id") in by_id:
            raise Unreadable(f"{path}: config_id {record.get('config_id')} twice")
        by_id[record.get("config_id")] = record
    return by_id


def same_value(a, b, tolerance=0.0):
    # NaN (a metric with no value) equals NaN; numbers agree within `tolerance` (relative);
    # everything else compares exactly.
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    numbers = all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in (a, b))
    if tolerance > 0 and numbers:
        return abs(a - b) <= tolerance * max(abs(a), abs(b))
    return a == b


def order_tolerance(column, a, b):
    """The relative tolerance two records' `column` agree within: the records' own
    image_order_tolerance for a column summed in arrival order, else 0 (exact)."""
    if not ldmrecords.summed_in_arrival_order().match(column):
        return 0.0
    tolerances = [r.get("image_order_tolerance") for r in (a, b)]
    if not all(isinstance(t, (int, float)) and not isinstance(t, bool) for t in tolerances):
        return 0.0
    return max(tolerances)


def differences(expected_run, actual_run):
    expected, actual = load_records(expected_run), load_records(actual_run)
    out = []
    for config in sorted(expected.keys() - actual.keys()):
        out.append(f"{config}: missing from {actual_run}")
    for config in sorted(actual.keys() - expected.keys()):
        out.append(f"{config}: not in {expected_run}")
    for config in sorted(expected.keys() & actual.keys()):
        a, b = expected[config], actual[config]
        for column in sorted(a.keys() | b.keys()):
            if excluded(column):
                continue
            if column not in a or column not in b:
                out.append(f"{config}: column {column} only in {expected_run if column in a else actual_run}")
            elif not same_value(a[column], b[column], order_tolerance(column, a, b)):
                out.append(f"{config}: {column}: {a[column]!r} != {b[column]!r}")
            elif FILE_COLUMNS.match(column) and isinstance(a[column], str) and a[column]:
                for run in (expected_run, actual_run):
                    if not (Path(run) / a[column]).is_file():
                        out.append(f"{config}: {column}: {Path(run) / a[column]} does not exist")
    return out, len(expected)


def main(argv):
    if len(argv) != 3:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    try:
        found, count = differences(argv[1], argv[2])
    except Unreadable as error:
        print(f"same_records: {error}", file=sys.stderr)
        return 2
    if found:
        print(f"same_records: {argv[1]} and {argv[2]} differ ({len(found)} differences):")
        for line in found:
            print("  " + line)
        return 1
    print(f"same_records: {argv[1]} and {argv[2]}: the same {count} records in every non-time column")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
