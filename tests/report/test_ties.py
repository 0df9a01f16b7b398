"""Unit tests of the report's ties (scripts/report/ldmreport/ties.py) and its time
digits: what may be ranked and what must be shown as a tie. Run by tests/report (ctest)."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "report"))

import pandas as pd  # noqa: E402

from ldmreport import pages, ties  # noqa: E402
from ldmreport.table import Table, declare_axes  # noqa: E402

M = ties.Measure

# The axes these tables are told apart by (a few of `ldmbench axes --json`'s).
declare_axes({"axes": [
    {"key": "scenes", "label": "scene", "owner": "harness", "owner_kind": "harness", "column": "scene"},
    {"key": "passes", "label": "pass", "owner": "harness", "owner_kind": "harness", "column": "pass"},
    {"key": "structures", "label": "structure", "owner": "harness", "owner_kind": "harness",
     "column": "structure"},
    {"key": "views", "label": "N", "owner": "harness", "owner_kind": "harness", "column": "n_views",
     "ldm_only": True},
    {"key": "r_ldm", "label": "R_LDM", "owner": "harness", "owner_kind": "harness", "column": "r_ldm",
     "ldm_only": True}]})


class Ties(unittest.TestCase):
    def test_times_tie_when_their_intervals_overlap(self):
        self.assertTrue(ties.tied(M(10, 9, 11), M(10.5, 10.8, 12)))
        self.assertFalse(ties.tied(M(10, 9, 10.5), M(11, 10.6, 12)))
        # touching ends tie: neither is faster beyond the uncertainty
        self.assertTrue(ties.tied(M(10, 9, 10.5), M(11, 10.5, 12)))

    def test_errors_tie_within_the_reference_noise_or_float_order(self):
        # The case the timing issue found: a fixed array "lowest MSE" by a relative 7e-9.
        self.assertTrue(ties.tied(M(1e-4, band=3.9e-6), M(1e-4 * (1 + 7e-9), band=3.9e-6)))
        self.assertTrue(ties.tied(M(1e-4), M(1e-4 * (1 + 7e-9))))  # no noise known: float order
        self.assertTrue(ties.tied(M(1.00e-4, band=3.9e-6), M(1.03e-4, band=3.9e-6)))
        self.assertFalse(ties.tied(M(1.00e-4, band=3.9e-6), M(1.05e-4, band=3.9e-6)))

    def test_memory_is_exact(self):
        self.assertFalse(ties.tied(ties.exact_measure(1 << 20), ties.exact_measure((1 << 20) + 1)))
        self.assertTrue(ties.tied(ties.exact_measure(4096), ties.exact_measure(4096)))

    def test_a_best_names_every_record_tied_with_it(self):
        measures = [M(12, 11.5, 12.5), M(10, 9.5, 10.4), M(10.2, 10.3, 11), M(11, 10.5, 11.5)]
        self.assertEqual(ties.best_and_tied(measures, False), [1, 2])
        self.assertEqual(ties.best_and_tied([M(0.9, band=0.01), M(0.895, band=0.01), M(0.5)], True), [0, 1])
        self.assertEqual(ties.best_and_tied([], False), [])

    def test_the_front_keeps_ties_and_drops_the_dominated(self):
        times = [M(1.0, 0.9, 1.1), M(1.05, 1.0, 1.1), M(2.0, 1.9, 2.1), M(3.0, 2.9, 3.1)]
        errors = [M(5, band=0.1), M(3, band=0.1), M(2.95, band=0.1), M(1, band=0.1)]
        # 1 dominates 0 (tied time, lower error) and 2 (faster, tied error); 3 is slower
        # but better beyond the band: the front is 1 and 3.
        self.assertEqual(ties.pareto_front(times, errors, False), [1, 3])
        # Two records tied in both criteria are both on the front.
        self.assertEqual(ties.pareto_front([M(1, 0.9, 1.1), M(1.02, 0.95, 1.1)],
                                           [M(3, band=0.1), M(3.05, band=0.1)], False), [0, 1])

    def test_the_front_over_three_criteria_keeps_ties(self):
        E = ties.exact_measure
        points = [[M(1, 0.9, 1.1), E(100), M(5, band=0.1)],    # fastest
                  [M(1, 0.95, 1.05), E(100), M(5, band=0.1)],  # tied with 0 in all
                  [M(3, 2.9, 3.1), E(50), M(5, band=0.1)],     # least memory
                  [M(3, 2.9, 3.1), E(100), M(5, band=0.1)],    # dominated by 2
                  [M(9, 8.9, 9.1), E(400), M(1, band=0.1)]]    # least error
        front = ties.pareto_front_all(points, [False, False, False])
        self.assertEqual(sorted(front), [0, 1, 2, 4])
        self.assertTrue(ties.tied_in_all(points[0], points[1]))
        self.assertFalse(ties.tied_in_all(points[0], points[2]))


class BestTable(unittest.TestCase):
    def table(self, rows):
        columns = list(rows[0].keys())
        return Table(columns, [[str(r[c]) for c in columns] for r in rows])

    def test_a_tie_is_shown_as_a_tie(self):
        common = {"status": "ok", "scene": "cornell", "pass": "ao", "structure": "psppsll", "ref_cache_key": "k",
                  "bytes_allocated": 100, "bytes_used": 50, "ref_noise_mse": 3.9e-6, "ref_noise_mssim": 0.99}
        rows = [dict(common, config_id="a", build_ms_median=10, build_ms_ci_low=9.8, build_ms_ci_high=10.4,
                     frame_ms_median=20, frame_ms_ci_low=19, frame_ms_ci_high=21, mse=1e-4, mssim=0.9),
                dict(common, config_id="b", build_ms_median=10.2, build_ms_ci_low=10.0, build_ms_ci_high=10.5,
                     frame_ms_median=30, frame_ms_ci_low=29, frame_ms_ci_high=31, mse=1e-4 * (1 + 7e-9), mssim=0.9),
                dict(common, config_id="c", build_ms_median=20, build_ms_ci_low=19, build_ms_ci_high=21,
                     frame_ms_median=40, frame_ms_ci_low=39, frame_ms_ci_high=41, mse=2e-4, mssim=0.8,
                     bytes_allocated=90)]
        best = {row[0]: row for row in pages.best_rows(self.table(rows))}
        self.assertIn("tied with b", best["fastest build"][2])
        self.assertNotIn("tied", best["fastest frame"][2])
        self.assertIn("tied with b", best["lowest mse"][2])
        self.assertNotIn("c", best["lowest mse"][2].split("tied with")[1])
        self.assertTrue(best["least memory allocated"][2].startswith("c"))
        self.assertEqual(best["fastest build"][4], "10.0 ±4.0% ms")


class TimeDigits(unittest.TestCase):
    def test_like_the_end_of_run_table(self):
        self.assertEqual(pages.fmt_time(12.34, 11.94, 12.74), "12.3 ±3.2%")
        self.assertEqual(pages.fmt_time(123.4, 80, 170), "120 ±38%")
        self.assertEqual(pages.fmt_time(9.4, 3.3, 15.5), "9.4 ±65%")
        self.assertEqual(pages.fmt_time(12.0, float("nan"), float("nan")), "12.00")


if __name__ == "__main__":
    unittest.main()
