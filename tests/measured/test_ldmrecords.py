#!/usr/bin/env python3
"""scripts/ldmrecords: one reader of records for every script (issue 32, item 5)."""
import ast
import csv
import json
import math
import os
import sys
import tempfile
import unittest

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts")
sys.path.insert(0, SCRIPTS)
import ldmrecords  # noqa: E402


def write_run(folder, rows, run=None):
    with open(os.path.join(folder, "records.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(folder, "records.json"), "w") as f:
        json.dump({"run": run or {}, "records": rows}, f)


class Reading(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp()
        write_run(self.folder, [{"config_id": "a", "status": "ok", "mse": "0.5", "bvh_ms": ""},
                                {"config_id": "b", "status": "lossy", "mse": "n/a", "bvh_ms": "3"}],
                  run={"command": "ldmbench run"})

    def test_a_folder_and_its_csv_read_alike(self):
        self.assertEqual(ldmrecords.read(self.folder), ldmrecords.read(os.path.join(self.folder, "records.csv")))
        self.assertEqual([r["config_id"] for r in ldmrecords.read(self.folder)], ["a", "b"])

    def test_numbers_absent_empty_or_text_are_the_default(self):
        a, b = ldmrecords.read(self.folder)
        self.assertEqual(ldmrecords.number(a, "mse"), 0.5)
        self.assertIsNone(ldmrecords.number(a, "bvh_ms"))            # empty: does not apply
        self.assertIsNone(ldmrecords.number(b, "mse"))               # not a number
        self.assertIsNone(ldmrecords.number(a, "no_such_column"))
        self.assertEqual(ldmrecords.number(a, "bvh_ms", -1.0), -1.0)
        self.assertTrue(math.isnan(ldmrecords.value(b, "mse")))
        self.assertEqual(ldmrecords.value(b, "bvh_ms"), 3.0)

    def test_status_filter_and_the_run_object(self):
        rows = ldmrecords.read(self.folder)
        self.assertEqual([r["config_id"] for r in ldmrecords.with_status(rows, "ok")], ["a"])
        self.assertEqual(len(ldmrecords.with_status(rows, "ok", "lossy")), 2)
        run, records = ldmrecords.read_run(self.folder)
        self.assertEqual(run["command"], "ldmbench run")
        self.assertEqual(len(records), 2)


# Scripts that parse JSON or CSV that is not a run's records, and why.
NOT_RECORDS = {
    "advise_vs_exhaustive.py": "json.load reads advise's result.json; records come through ldmadvise's reader",
    "regenerate_measured.py": "csv and json read a report's tidy.csv and manifest.json",
}


@unittest.skipUnless(os.environ.get("LDMBENCH"), "needs $LDMBENCH (the ctest passes it)")
class VariesBetweenRuns(unittest.TestCase):
    """The columns two runs of one configuration may differ in come from the schema's flag, for
    same_records.py and compare_runs.py alike (they kept two regexes that had drifted apart)."""

    def test_time_machine_state_and_job_vary_results_do_not(self):
        varying = ldmrecords.varies_between_runs()
        for column in ("frame_ms_median", "build_ms_ci_low", "rtao_gpu_bvh_ms", "load_average_start",
                       "time_calibration", "host", "slurm_node", "ref_from_cache"):
            self.assertTrue(varying.match(column), column)
        for column in ("mse", "n_views", "fragments_stored", "frames_measured", "ref_noise_mse", "status"):
            self.assertFalse(varying.match(column), column)


class EveryScriptReadsThroughIt(unittest.TestCase):
    """No script in scripts/ opens records.csv or records.json its own way: a script that
    mentions a records file and parses CSV or JSON by itself must import ldmrecords."""

    def test_no_script_keeps_its_own_reader(self):
        offenders = []
        for name in sorted(os.listdir(SCRIPTS)):
            if not name.endswith(".py") or name in NOT_RECORDS:
                continue
            source = open(os.path.join(SCRIPTS, name)).read()
            tree = ast.parse(source)
            calls = {f"{n.func.value.id}.{n.func.attr}" for n in ast.walk(tree)
                     if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute)
                     and isinstance(n.func.value, ast.Name)}
            parses = calls & {"csv.DictReader", "pd.read_csv", "json.load"}
            mentions = "records.csv" in source or "records.json" in source or "RECORDS" in source
            imports = any(isinstance(n, (ast.Import, ast.ImportFrom)) and
                          ("ldmrecords" in [a.name for a in n.names] or getattr(n, "module", "") == "ldmrecords")
                          for n in ast.walk(tree))
            if mentions and parses and not imports:
                offenders.append(f"{name}: {sorted(parses)}")
        self.assertEqual(offenders, [], "read records through scripts/ldmrecords")


if __name__ == "__main__":
    unittest.main()
