#!/usr/bin/env python3
"""The cost model (scripts/model/ldmmodel) on synthetic records whose coefficients are known:
the fit recovers them, its held-out error is small, no coefficient is ever negative,
constant and collinear counters are dropped and named, distributions enter by their totals,
a saved fit predicts another run, and bad input fails naming the file. Run by
tests/work/model_test.cpp (ctest work.ModelFit.SyntheticRecords)."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts")
sys.path.insert(0, os.path.join(SCRIPTS, "model"))
sys.path.insert(0, SCRIPTS)

from ldmmodel import columns, fit, model  # noqa: E402

SCRIPT = os.path.join(SCRIPTS, "model", "ldmbench_model.py")
# ns per unit: the truth the fits must recover
TRUE = {"work_construct_fragments": 20.0, "work_construct_atomic_add": 5.0, "work_ao_hash_probes_total": 3.0}
FIXED_CONSTRUCT, FIXED_AO = 50_000.0, 20_000.0
SCHEMA = {
    "work_construct_fragments": {"group": "work", "unit": "fragments"},
    "work_construct_atomic_add": {"group": "work", "unit": "atomics"},
    "work_construct_bytes_stored_heads": {"group": "work", "unit": "bytes"},
    "work_ao_hash_probes_total": {"group": "work", "unit": "slots"},
    "work_replay_ms": {"group": "time", "unit": "ms"},
}


def synthetic_rows(n=60, noise=0.01, seed=1, device="llvmpipe (LLVM 15)", driver="llvmpipe"):
    rng = np.random.RandomState(seed)
    rows = []
    for i in range(n):
        frags = float(rng.randint(1_000, 200_000))
        atomics = float(rng.randint(0, 300_000))
        probes = float(rng.randint(1_000, 100_000))
        construct_ns = FIXED_CONSTRUCT + TRUE["work_construct_fragments"] * frags + TRUE["work_construct_atomic_add"] * atomics
        ao_ns = FIXED_AO + TRUE["work_ao_hash_probes_total"] * probes
        construct_ms = construct_ns * (1 + noise * rng.randn()) / 1e6
        ao_ms = ao_ns * (1 + noise * rng.randn()) / 1e6
        rows.append({
            "config_id": f"cfg{i}", "status": "ok", "structure": "s", "pass": "ao",
            "device": device, "gl_driver": driver,
            "clear_ms_median": "0.01",                      # timed, no counters: not fitted
            "construct_ms_median": repr(construct_ms), "ao_ms_median": repr(ao_ms),
            "build_ms_median": repr(construct_ms), "frame_ms_median": repr(construct_ms + ao_ms),
            "work_replay_ms": "100",                        # a time, not a counter
            "work_construct_fragments": repr(frags),
            "work_construct_atomic_add": repr(atomics),
            "work_construct_bytes_stored_heads": repr(4 * frags),   # collinear with fragments
            "work_construct_vertices": "360",                       # constant
            "work_construct_fragments_dropped": "0",                # all zero
            "work_construct_gl_fragment_invocations": repr(frags * 1.3),  # the driver's: left out
            "work_ao_hash_probes_mean": repr(probes / 1000), "work_ao_hash_probes_p50": "1",
            "work_ao_hash_probes_p99": "4", "work_ao_hash_probes_max": "9",
            "work_ao_hash_probes_total": repr(probes),
        })
    return rows


def write_run(folder, rows):
    os.makedirs(folder, exist_ok=True)
    header = list(rows[0].keys())
    with open(os.path.join(folder, "records.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, header)
        w.writeheader()
        w.writerows(rows)
    return folder


def run_script(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True)


class FitMaths(unittest.TestCase):
    def test_recovers_known_coefficients(self):
        rng = np.random.RandomState(3)
        X = rng.randint(1, 10_000, size=(80, 3)).astype(float)
        c = np.array([7.0, 0.5, 120.0])
        y_ms = (2_000 + X @ c) / 1e6
        r = fit.fit(X, y_ms, ["a", "b", "c"], [f"g{i}" for i in range(80)])
        self.assertAlmostEqual(r["intercept_ns"], 2_000, delta=1)
        for name, want in zip("abc", c):
            self.assertAlmostEqual(r["coefficients_ns"][name], want, delta=want * 1e-6)
        self.assertLess(r["heldout_median_error"], 1e-6)
        self.assertGreater(r["r2"], 0.999999)
        self.assertEqual(r["folds"], 5)

    def test_never_negative(self):
        rng = np.random.RandomState(4)
        X = rng.randint(1, 10_000, size=(50, 2)).astype(float)
        y_ms = (100_000 + 10 * X[:, 0] - 4 * X[:, 1]).clip(1) / 1e6   # b would take a negative cost
        r = fit.fit(X, y_ms, ["a", "b"], list(range(50)))
        self.assertTrue(all(v >= 0 for v in r["coefficients_ns"].values()))
        self.assertGreaterEqual(r["intercept_ns"], 0)
        self.assertEqual(r["coefficients_ns"]["b"], 0.0)

    def test_drops_constant_zero_and_collinear_columns(self):
        x = np.arange(1, 21, dtype=float)
        X = np.column_stack([x, 4 * x, np.full(20, 7.0), np.zeros(20), x ** 2])
        kept, dropped = fit.drop_uninformative(X, ["f", "bytes", "const", "zero", "sq"], intercept=True)
        self.assertEqual(kept, [0, 4])
        reasons = dict(dropped)
        self.assertIn("collinear: = 4·f", reasons["bytes"])
        self.assertIn("constant", reasons["const"])
        self.assertEqual(reasons["zero"], "all zero")

    def test_folds_keep_a_configuration_together(self):
        groups = ["a", "a", "b", "c", "c", "c", "d", "e"]
        folds = fit.folds_of(groups, 3)
        for g in set(groups):
            self.assertEqual(len({f for f, h in zip(folds, groups) if h == g}), 1)
        self.assertEqual(set(folds), {0, 1, 2})

    def test_repeat_spread_is_the_noise_floor(self):
        X = np.array([[1.0], [1.0], [2.0], [2.0], [3.0], [3.0]])
        y_ms = np.array([1.0, 1.2, 2.0, 2.4, 3.0, 3.6])
        r = fit.fit(X, y_ms, ["a"], ["x", "x", "y", "y", "z", "z"], folds=3)
        # each record against the other of its pair: |1 - 1.2| / 1, |1.2 - 1| / 1.2, ...
        self.assertAlmostEqual(r["repeat_spread"], float(np.median([0.2, 0.2 / 1.2] * 3)), places=6)


class Columns(unittest.TestCase):
    def test_work_columns_take_totals_and_leave_times_and_driver_statistics(self):
        header = list(synthetic_rows(1)[0].keys())
        work = columns.work_columns(header, SCHEMA)
        self.assertIn("work_ao_hash_probes_total", work)
        for left in ("work_ao_hash_probes_mean", "work_ao_hash_probes_max", "work_replay_ms",
                     "work_construct_gl_fragment_invocations"):
            self.assertNotIn(left, work)
        self.assertIn("work_construct_gl_fragment_invocations", columns.work_columns(header, SCHEMA, driver_stats=True))
        self.assertNotIn("work_replay_ms", columns.work_columns(header, {}))

    def test_subpass_is_the_longest_timed_prefix(self):
        self.assertEqual(columns.subpass_of("work_photon_tracing_rays", ["photon", "photon_tracing"]), "photon_tracing")
        self.assertEqual(columns.subpass_of("work_prefix_sum_invocations", ["prefix_sum", "sort"]), "prefix_sum")
        self.assertIsNone(columns.subpass_of("work_census_fragments", ["sort"]))

    def test_units(self):
        self.assertEqual(columns.unit_of("work_construct_atomic_add", SCHEMA), "atomic")
        self.assertEqual(columns.unit_of("work_ao_hash_probes_total", SCHEMA), "slot")
        self.assertEqual(columns.unit_of("work_sort_nodes_visited_total", {}), "node")
        self.assertEqual(columns.singular("entries"), "entry")


class Runs(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def fit_synthetic(self):
        run = model.read_run(write_run(os.path.join(self.dir, "a"), synthetic_rows()))
        return model.fit_runs([run], SCHEMA)

    def test_fit_per_subpass_recovers_the_truth(self):
        document = self.fit_synthetic()
        fits = {f["subpass"]: f for f in document["fits"]}
        self.assertEqual(sorted(fits), ["ao", "construct", "frame"])   # clear has no counters
        construct = fits["construct"]
        for name in ("work_construct_fragments", "work_construct_atomic_add"):
            self.assertAlmostEqual(construct["coefficients_ns"][name], TRUE[name], delta=0.05 * TRUE[name])
        self.assertAlmostEqual(construct["intercept_ns"], FIXED_CONSTRUCT, delta=0.2 * FIXED_CONSTRUCT)
        self.assertAlmostEqual(fits["ao"]["coefficients_ns"]["work_ao_hash_probes_total"], 3.0, delta=0.15)
        for f in document["fits"]:
            self.assertLess(f["heldout_median_error"], 0.02, f["subpass"])
            self.assertGreater(f["r2"], 0.99, f["subpass"])
            self.assertTrue(all(c >= 0 for c in f["coefficients_ns"].values()))
        dropped = {d["column"]: d["reason"] for d in construct["dropped"]}
        self.assertIn("collinear", dropped["work_construct_bytes_stored_heads"])
        self.assertIn("constant", dropped["work_construct_vertices"])
        self.assertEqual(dropped["work_construct_fragments_dropped"], "all zero")
        self.assertEqual(construct["units"]["work_construct_atomic_add"], "atomic")

    def test_cli_fits_saves_and_predicts(self):
        a = write_run(os.path.join(self.dir, "a"), synthetic_rows())
        b = write_run(os.path.join(self.dir, "b"), synthetic_rows(20, seed=9))
        cpu = write_run(os.path.join(self.dir, "cpu"), synthetic_rows(10, seed=5, device="other", driver="zink"))
        fit_json = os.path.join(self.dir, "fit.json")
        r = run_script(a, "--out", fit_json)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("ns per fragment", r.stdout)
        self.assertIn("held-out median error", r.stdout)
        self.assertIn("dropped: bytes_stored_heads (collinear: = 4·work_construct_fragments)", r.stdout)
        with open(fit_json) as f:
            self.assertEqual(json.load(f)["format"], model.FORMAT)
        r = run_script("--predict", b, "--fit", fit_json)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("cfg19", r.stdout)
        self.assertIn("over 20 measured on this device", r.stdout)
        # another device's counters: predictions only, no measured time to compare
        r = run_script("--predict", cpu, "--fit", fit_json)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("none measured on this device", r.stdout)
        # a fit for another device
        r = run_script("--predict", b, "--fit", fit_json, "--device", "nvidia")
        self.assertEqual(r.returncode, 2)
        self.assertIn(fit_json, r.stderr)
        self.assertIn("a fit for another device", r.stderr)

    def test_bad_input_fails_naming_the_file(self):
        rows = [{k: v for k, v in row.items() if not k.startswith("work_")} for row in synthetic_rows(5)]
        no_work = write_run(os.path.join(self.dir, "nowork"), rows)
        r = run_script(no_work)
        self.assertEqual(r.returncode, 2)
        self.assertIn(os.path.join(no_work, "records.csv"), r.stderr)
        self.assertIn("no work columns", r.stderr)
        empty = os.path.join(self.dir, "empty")
        os.makedirs(empty)
        with open(os.path.join(empty, "records.csv"), "w") as f:
            f.write("config_id,status\n")
        r = run_script(empty)
        self.assertEqual(r.returncode, 2)
        self.assertIn("no records", r.stderr)
        r = run_script(os.path.join(self.dir, "missing"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("no such file or folder", r.stderr)
        not_a_fit = os.path.join(self.dir, "x.json")
        with open(not_a_fit, "w") as f:
            f.write("{}")
        r = run_script("--predict", write_run(os.path.join(self.dir, "a"), synthetic_rows()), "--fit", not_a_fit)
        self.assertEqual(r.returncode, 2)
        self.assertIn(not_a_fit + ": not a fit", r.stderr)


if __name__ == "__main__":
    unittest.main()
