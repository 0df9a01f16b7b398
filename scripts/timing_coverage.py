#!/usr/bin/env python3
"""Does a record's time interval hold the next run's median? (issue 34; docs/timing.md, "Coverage")

  scripts/timing_coverage.py [--out DIR] [--gap SECONDS] [--ldmbench PATH] [--repetitions R]
                             [--resume] [-- EXTRA RUN OPTIONS]

Measures the coverage sweep (three scenes of different depth, every structure, N = 8 and 32,
R_LDM = 64, 128x128, ldmbench run's defaults otherwise; no reference and no images, which
change no time) twice, in two processes GAP seconds apart (default 180), with default options
(or --repetitions R, or what follows --), and counts, per sub-pass (build, pass, frame), the
configurations whose first record's 95 % interval holds the second record's median, and the
other way round. Also the median relative half-width of the intervals and the spread between
the two runs (the standard deviation of the log ratio of their medians), which an interval
that covers another run's median cannot be much narrower than. Writes DIR/first, DIR/second
(the runs), DIR/summary.json and DIR/summary.md. Not part of CI: it measures this machine.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time
import ldmrecords
from ldmrecords import number

HERE = os.path.dirname(os.path.abspath(__file__))
SWEEP = ["--scene", "cornell,atrium," + os.path.join(HERE, "..", "scenes", "teapots.json"), "--structure", "all", "-N", "8,32", "-R", "64",
         "--image-size", "128x128", "--no-reference", "--no-images"]
SUBPASSES = ["build", "pass", "frame"]


def run(ldmbench, out, extra, log):
    argv = [ldmbench, "run", *SWEEP, *extra, "--out", out]
    started = time.time()
    result = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    with open(log, "a") as f:
        f.write("$ " + " ".join(argv) + "\n" + result.stdout +
                f"\n(exit {result.returncode}, {time.time() - started:.1f} s)\n")
    if result.returncode not in (0, 3):
        sys.exit(f"timing_coverage: ldmbench exited {result.returncode}; see {log}")
    return time.time() - started


def records(folder):
    return {r["config_id"]: r for r in ldmrecords.with_status(ldmrecords.read(folder), "ok")}


def coverage(a, b, subpass):
    """How often a's interval holds b's median, over the configurations both measured."""
    held = total = 0
    half_widths, log_half_widths, log_ratios = [], [], []
    for cid, ra in a.items():
        rb = b.get(cid)
        if rb is None:
            continue
        low, high = number(ra, f"{subpass}_ms_ci_low"), number(ra, f"{subpass}_ms_ci_high")
        median_a, median_b = number(ra, f"{subpass}_ms_median"), number(rb, f"{subpass}_ms_median")
        if None in (low, high, median_a, median_b) or median_a <= 0 or median_b <= 0:
            continue
        total += 1
        held += low <= median_b <= high
        half_widths.append((high - low) / 2 / median_a)
        log_half_widths.append(max(math.log(high / median_a), math.log(median_a / low)) if low > 0 else math.inf)
        log_ratios.append(math.log(median_b / median_a))
    return {"configurations": total, "held": held,
            "coverage": held / total if total else None,
            "median_half_width": statistics.median(half_widths) if half_widths else None,
            "between_run_spread": statistics.pstdev(log_ratios) if len(log_ratios) > 1 else None,
            # What the intervals must cover: the RMS log ratio (drift between the runs included),
            # and how wide they are in the same terms (the bound: at most twice it).
            "rms_log_ratio": math.sqrt(sum(x * x for x in log_ratios) / len(log_ratios)) if log_ratios else None,
            "median_log_half_width": statistics.median(log_half_widths) if log_half_widths else None,
            "ratio_range": [math.exp(min(log_ratios)), math.exp(max(log_ratios))] if log_ratios else None}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="results/runs/timing-coverage")
    parser.add_argument("--gap", type=float, default=180)
    parser.add_argument("--ldmbench", default=os.path.join(HERE, "..", "build", "ldmbench"))
    parser.add_argument("--repetitions", type=int, default=None)
    parser.add_argument("--resume", action="store_true", help="keep runs already measured")
    parser.add_argument("extra", nargs="*", help="more ldmbench run options (after --)")
    args = parser.parse_args()
    extra = list(args.extra)
    if args.repetitions:
        extra += ["--repetitions", str(args.repetitions)]
    os.makedirs(args.out, exist_ok=True)
    log = os.path.join(args.out, "log.txt")
    seconds = {}
    for i, name in enumerate(["first", "second"]):
        folder = os.path.join(args.out, name)
        if args.resume and os.path.exists(os.path.join(folder, "records.csv")):
            continue
        if i > 0:
            time.sleep(args.gap)
        seconds[name] = run(args.ldmbench, folder, extra, log)
    first, second = records(os.path.join(args.out, "first")), records(os.path.join(args.out, "second"))
    calibrations = sorted({r.get("time_calibration", "") for r in first.values()})
    summary = {"options": extra, "gap_s": args.gap, "run_seconds": seconds, "time_calibration": calibrations,
               "load_average": os.getloadavg(),
               "first_holds_second": {s: coverage(first, second, s) for s in SUBPASSES},
               "second_holds_first": {s: coverage(second, first, s) for s in SUBPASSES}}
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
    lines = [f"Options: {' '.join(extra) or '(defaults)'}; runs {args.gap:.0f} s apart; "
             f"run seconds {', '.join(f'{k} {v:.0f}' for k, v in seconds.items())}.",
             "Calibration of the first run: " + "; ".join(c or "(none)" for c in calibrations), "",
             "| interval of | sub-pass | holds the other's median | coverage | median half-width | median log half-width | RMS log ratio | log half-width / RMS | ratio range |",
             "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
    for direction, label in [("first_holds_second", "first"), ("second_holds_first", "second")]:
        for s in SUBPASSES:
            c = summary[direction][s]
            if not c["configurations"]:
                continue
            lines.append(f"| {label} | {s} | {c['held']} of {c['configurations']} | {100 * c['coverage']:.0f} % "
                         f"| {100 * c['median_half_width']:.1f} % | {c['median_log_half_width']:.3f} | {c['rms_log_ratio']:.3f} "
                         f"| {c['median_log_half_width'] / c['rms_log_ratio']:.2f} "
                         f"| {c['ratio_range'][0]:.2f}-{c['ratio_range'][1]:.2f} |")
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
