#!/usr/bin/env python3
"""Compare two `ldmbench run` output folders: records and images must be the same.

Usage: scripts/compare_runs.py BEFORE_DIR AFTER_DIR [LDMBENCH]

Used to check that a refactoring leaves what `ldmbench run` measures unchanged: every record
column except those that vary from run to run (times, wall clock, the build's version and
commit, whether the reference came from the cache) must hold the same value in the same
column order, and every image must be the same: PNGs byte for byte, EXRs pixel for pixel
(OpenImageIO stamps a date into the EXR header), through `LDMBENCH compare-images`
(default build/ldmbench). Exits 0 when they agree, 1 with
a list of the differences otherwise.
"""
import csv
import filecmp
import os
import re
import subprocess
import sys
import ldmrecords

# Columns that differ between two builds by design: which build measured.
BUILD_IDENTITY = {"git_commit", "ldmbench_version"}


def volatile(column, ldmbench):
    """Differs between two runs of one configuration (the schema's varies_between_runs) or
    between two builds by design."""
    return column in BUILD_IDENTITY or bool(ldmrecords.varies_between_runs(ldmbench).match(column))


def read_records(folder):
    with open(ldmrecords.records_path(folder), newline="") as f:
        header = next(csv.reader(f))
    return header, ldmrecords.read(folder)


def same_image(a, b, ldmbench):
    if filecmp.cmp(a, b, shallow=False):
        return True
    if not a.endswith(".exr"):
        return False
    out = subprocess.run([ldmbench, "compare-images", a, b], capture_output=True, text=True)
    return out.returncode == 0 and re.search(r"^mse: 0$", out.stdout, re.M) is not None


def main(before, after, ldmbench):
    problems = []
    columns_a, records_a = read_records(before)
    columns_b, records_b = read_records(after)
    stable_a = [c for c in columns_a if not volatile(c, ldmbench)]
    stable_b = [c for c in columns_b if not volatile(c, ldmbench)]
    if stable_a != stable_b:
        problems.append("columns differ:\n  only before: %s\n  only after: %s\n  order same: %s" % (
            sorted(set(stable_a) - set(stable_b)), sorted(set(stable_b) - set(stable_a)),
            [c for c in stable_a if c in stable_b] == [c for c in stable_b if c in stable_a]))
    if len(records_a) != len(records_b):
        problems.append("%d records before, %d after" % (len(records_a), len(records_b)))
    compared = 0
    for ra, rb in zip(records_a, records_b):
        rid = ra.get("config_id")
        for column in stable_a:
            if column in rb and ra.get(column) != rb.get(column):
                problems.append("%s: %s: %r -> %r" % (rid, column, ra.get(column), rb.get(column)))
            compared += 1
    images_a = sorted(os.listdir(os.path.join(before, "images")))
    images_b = sorted(os.listdir(os.path.join(after, "images")))
    if images_a != images_b:
        problems.append("image files differ: only before %s, only after %s" % (
            sorted(set(images_a) - set(images_b)), sorted(set(images_b) - set(images_a))))
    same_images = 0
    for name in sorted(set(images_a) & set(images_b)):
        if same_image(os.path.join(before, "images", name), os.path.join(after, "images", name),
                      ldmbench):
            same_images += 1
        else:
            problems.append("image %s differs" % name)
    print("%d records, %d values compared (%d stable columns); %d of %d images identical" % (
        len(records_a), compared, len(stable_a), same_images, len(images_a)))
    for p in problems:
        print("DIFF", p)
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2], sys.argv[3] if len(sys.argv) == 4 else "build/ldmbench"))
