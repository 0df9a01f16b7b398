#!/usr/bin/env python3
"""Coverage of other widening forms, from the records of a pooled coverage run (docs/timing.md,
"Coverage", 2026-12-05): each record's repetitions' own variance is recovered from its
interval as the pooled form widened it (a build of that day pooled the t interval of
--isolation process repetitions with the calibration's variance; the form was measured and
rejected), and the intervals of the unpooled form (the one ldmbench writes), the pooled
form, the pooled form unless an F test rejects pooling, and the wider of the two are
judged against the other run's median.

  scripts/timing_coverage_forms.py DIR    (DIR/first/records.csv, DIR/second/records.csv)

The calibration's processes are read from the time_calibration text (calibration.cpp's
describe(): "... from N processes ..."), the one place a record states them; the pooled form
took its degrees of freedom from the same count. A record without it is refused by the
regular expression, not guessed.
"""
import math
import re
import statistics
import sys

from scipy import stats

import ldmrecords

Z = stats.norm.ppf(0.975)
SUBPASSES = ("build", "pass", "frame")


def calibration_dof(row):
    """The calibration's degrees of freedom as the pooled form took them: its processes less one."""
    found = re.search(r"from (\d+) processes", row["time_calibration"])
    if not found:
        raise SystemExit(f"{row['config_id']}: time_calibration names no probe processes")
    return int(found.group(1)) - 1


def recovered(row, sub):
    """(spread, repetitions, dof, median, own variance, other run's share) of a pooled record."""
    spread, k, dof = float(row["time_run_to_run_spread"]), int(row["repetitions"]), calibration_dof(row)
    median = float(row[f"{sub}_ms_median"])
    h = max(math.log(median / float(row[f"{sub}_ms_ci_low"])), math.log(float(row[f"{sub}_ms_ci_high"]) / median))
    other = Z * spread / math.sqrt(2 * k)
    pooled_half = math.sqrt(max(h * h - other * other, 0))
    t = stats.t.ppf(0.975, dof + k - 1)
    variance = ((pooled_half / t) ** 2 * k * (dof + k - 1) - dof * spread * spread / 2) / (k - 1)
    return spread, k, dof, median, max(variance, 0.0), other


def half_widths(spread, k, dof, variance, other):
    """The log half-width of each form."""
    own = stats.t.ppf(0.975, k - 1) * math.sqrt(variance / k)
    pooled = stats.t.ppf(0.975, dof + k - 1) * math.sqrt(((k - 1) * variance + dof * spread * spread / 2)
                                                          / (dof + k - 1) / k)
    poolable = variance / (spread * spread / 2) <= stats.f.ppf(0.95, k - 1, dof)
    return {"unpooled": math.hypot(own, other), "pooled": math.hypot(pooled, other),
            "pooled_unless_F": math.hypot(pooled if poolable else own, other),
            "max(pooled,own)": math.hypot(max(pooled, own), other)}


def main(folder):
    first, second = (ldmrecords.by_config_id(f"{folder}/{run}") for run in ("first", "second"))
    for sub in SUBPASSES:
        for name, these, others in (("first", first, second), ("second", second, first)):
            held, widths, log_ratios = {}, {}, []
            for key, row in these.items():
                if key not in others:
                    continue
                spread, k, dof, median, variance, other = recovered(row, sub)
                log_ratio = math.log(float(others[key][f"{sub}_ms_median"]) / median)
                log_ratios.append(log_ratio)
                for form, h in half_widths(spread, k, dof, variance, other).items():
                    held[form] = held.get(form, 0) + (abs(log_ratio) <= h)
                    widths.setdefault(form, []).append(h)
            rms = math.sqrt(sum(r * r for r in log_ratios) / len(log_ratios))
            print(sub, name, "n", len(log_ratios), "rms", round(rms, 3), " ".join(
                f"{form}:{held[form]}/{len(log_ratios)} w{statistics.median(widths[form]):.3f}"
                f"({statistics.median(widths[form]) / rms:.2f}x)" for form in held))


if __name__ == "__main__":
    main(sys.argv[1])
