#!/usr/bin/env python3
"""Calibrates ldmbench's time verdicts on this machine (docs/timing.md, "Calibration").

  scripts/timing_calibration.py [--trials N] [--out DIR] [--ldmbench PATH] [--only KIND,...]

Each kind runs N trials of one experiment on the calibration sweep (the Cornell box and the
knot, each with the structures of --structures (default psppsll,habuffer: a list and the
hash table, 4 configurations; the 4-structure sweep of 8 configurations doubles the time),
N = 16, R_LDM = 64, 96x96 images, no reference) and counts what `ldmbench compare` (or
`ldmbench interleave`) concludes:

  aa-single       two runs of the same command at `ldmbench run`'s defaults (one repetition),
                  compared: a trial is false when any configuration or sub-pass is FAST/SLOW.
  aa-repetitions  the same with --repetitions 5 (--repetitions).
  aa-interleaved  `ldmbench interleave B B --repetitions 8` (--pairs): the build against itself.
  power-repetitions   -N 16 against -N 20 (25 % more views: a genuinely slower configuration),
                  --repetitions 5, compared with --ignore-param n_views: a trial finds the
                  slowdown when every configuration's frame time is SLOW.
  power-interleaved   the same pair interleaved (--a-args "-N 16" --b-args "-N 20"), 8 pairs.
  isolation       what keeps repetitions independent: --repetitions 6 with --isolation context
                  and with --isolation process, one after the other; the spread between the
                  repetitions' frame medians (frame_ms_rep_spread) of each, per configuration.
                  Process offsets that a fresh context does not reproduce would show as a
                  larger spread under process isolation.

Every trial's comparison JSON is kept under DIR/<kind>/<trial>/ (its result.json once the trial
has ended: --resume keeps those and measures the rest); DIR/summary.json and
DIR/summary.md hold the counts, the detection rate per configuration, the estimated true
slowdown (median over trials) and the minimum detectable changes. Takes long on 2 cores
(10 trials of aa-single, aa-interleaved and power-interleaved: about 65 minutes at the
default structures; everything: about 2 hours); --trials 2 shows the shape in minutes.
"""
import argparse
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import time
import ldmrecords

HERE = os.path.dirname(os.path.abspath(__file__))
CALIBRATION = ["--scene", "cornell," + os.path.join(HERE, "..", "scenes", "knot_in_box.json"),
               "--structure", "psppsll,habuffer", "-R", "64",
               "--width", "96", "--height", "96", "--no-reference", "--no-images"]
REPETITIONS, PAIRS = "5", "8"  # set from the options
KINDS = ["aa-single", "aa-repetitions", "aa-interleaved", "power-repetitions", "power-interleaved",
         "isolation"]


def run(argv, log):
    started = time.time()
    result = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    with open(log, "a") as out:
        out.write("$ " + " ".join(argv) + "\n" + result.stdout + f"\n(exit {result.returncode}, "
                  f"{time.time() - started:.1f} s)\n")
    if result.returncode not in (0, 3):
        sys.exit(f"timing_calibration: {' '.join(argv[:3])}... exited {result.returncode}; see {log}")
    return result.stdout


def compare(ldmbench, a, b, out_json, log, ignored=()):
    argv = [ldmbench, "compare", a, b, "--json"]
    for p in ignored:
        argv += ["--ignore-param", p]
    text = run(argv, log)
    with open(out_json, "w") as f:
        f.write(text)
    return json.loads(text)


def verdicts(comparison):
    """[(configuration, sub-pass, verdict, relative change, MDE)] of a comparison JSON."""
    out = []
    for c in comparison["configurations"]:
        for t in c["time"]:
            out.append((c["identity"], t["subpass"], t["verdict"], t["relative_change"],
                        t["minimum_detectable_change"]))
    return out


def trial(kind, index, ldmbench, root, resume=False):
    folder = os.path.join(root, kind, f"{index:02d}")
    result_path = os.path.join(folder, "result.json")
    if resume and os.path.isfile(result_path):  # a finished trial of an earlier invocation
        with open(result_path) as f:
            return json.load(f)
    result = measure_trial(kind, folder, ldmbench)
    result["calibration_load_average"] = os.getloadavg()[0]  # how busy the machine was
    with open(result_path + ".tmp", "w") as f:  # written whole, then renamed: a killed
        json.dump(result, f)                     # calibration resumes from its last trial
    os.replace(result_path + ".tmp", result_path)
    return result


def measure_trial(kind, folder, ldmbench):
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    log = os.path.join(folder, "log.txt")
    if kind == "isolation":
        spreads = {}
        for isolation in ("context", "process"):
            out = os.path.join(folder, isolation)
            run([ldmbench, "run", *CALIBRATION, "-N", "16", "--repetitions", "6", "--isolation", isolation,
                 "--out", out], log)
            spreads[isolation] = {r["config_id"]: r.get("frame_ms_rep_spread") for r in ldmrecords.read_run(out)[1]}
        return {"isolation": spreads}
    if kind in ("aa-single", "aa-repetitions", "power-repetitions"):
        reps = [] if kind == "aa-single" else ["--repetitions", REPETITIONS]
        views = ("16", "20") if kind.startswith("power") else ("16", "16")
        for side, n in zip("ab", views):
            run([ldmbench, "run", *CALIBRATION, "-N", n, *reps, "--out", os.path.join(folder, side)], log)
        ignored = ["n_views"] if kind.startswith("power") else []
        return compare(ldmbench, os.path.join(folder, "a"), os.path.join(folder, "b"),
                       os.path.join(folder, "comparison.json"), log, ignored)
    argv = [ldmbench, "interleave", ldmbench, ldmbench, "--out", os.path.join(folder, "session"),
            "--repetitions", PAIRS]
    if kind == "power-interleaved":
        argv += ["--a-args=-N 16", "--b-args=-N 20", "--ignore-param", "n_views"]
        argv += ["--", "run", *CALIBRATION]
    else:
        argv += ["--", "run", *CALIBRATION, "-N", "16"]
    run(argv, log)
    with open(os.path.join(folder, "session", "comparison.json")) as f:
        return json.load(f)


def summarise(kind, comparisons):
    if kind == "isolation":
        out = {"kind": kind, "trials": len(comparisons), "frame_mde_median": None}
        for isolation in ("context", "process"):
            values = [v for c in comparisons for v in c["isolation"][isolation].values() if v is not None]
            out[f"{isolation}_spread_median"] = statistics.median(values) if values else None
            out[f"{isolation}_spread_range"] = [min(values), max(values)] if values else None
        return out
    rows = [verdicts(c) for c in comparisons]
    summary = {"kind": kind, "trials": len(rows)}
    mdes = [v[4] for r in rows for v in r if v[1] == "frame" and v[4] is not None]
    summary["frame_mde_median"] = statistics.median(mdes) if mdes else None
    summary["frame_mde_range"] = [min(mdes), max(mdes)] if mdes else None
    if kind.startswith("aa"):
        false = [sum(v[2] in ("FAST", "SLOW") for v in r) for r in rows]
        summary["trials_with_a_false_verdict"] = sum(f > 0 for f in false)
        summary["false_verdicts_per_trial"] = false
        summary["tests_per_trial"] = len(rows[0]) if rows else 0
    else:
        frame = [[v for v in r if v[1] == "frame"] for r in rows]
        found = [sum(v[2] == "SLOW" for v in r) for r in frame]
        summary["configurations"] = len(frame[0]) if frame else 0
        summary["slow_found_per_trial"] = found
        summary["trials_finding_every_configuration"] = sum(f == len(r) for f, r in zip(found, frame))
        summary["detection_rate"] = sum(found) / max(1, sum(len(r) for r in frame))
        changes = [v[3] for r in frame for v in r]
        summary["estimated_slowdown_median"] = statistics.median(changes) if changes else None
        summary["estimated_slowdown_range"] = [min(changes), max(changes)] if changes else None
        wrong = [v for r in rows for v in r if v[2] == "FAST"]
        summary["fast_verdicts"] = len(wrong)
    return summary


def markdown(summaries, meta):
    lines = ["# Timing calibration", "", f"`{meta['command']}` on {meta['machine']}, {meta['date']}, "
             f"{meta['seconds'] / 60:.0f} min.", "",
             "| experiment | trials | result | frame MDE (median, range) | load (1-min, median) |",
             "| --- | --- | --- | --- | --- |"]
    for s in summaries:
        mde = "–" if s["frame_mde_median"] is None else \
            f"{100 * s['frame_mde_median']:.0f}% ({100 * s['frame_mde_range'][0]:.0f}–{100 * s['frame_mde_range'][1]:.0f}%)"
        if s["kind"] == "isolation":
            result = "; ".join(
                f"{iso}: spread between repetitions median {100 * s[f'{iso}_spread_median']:.1f}% "
                f"({100 * s[f'{iso}_spread_range'][0]:.1f}–{100 * s[f'{iso}_spread_range'][1]:.1f}%)"
                for iso in ("context", "process") if s[f"{iso}_spread_median"] is not None)
        elif s["kind"].startswith("aa"):
            result = (f"{s['trials'] - s['trials_with_a_false_verdict']} of {s['trials']} trials without "
                      f"a FAST/SLOW verdict ({s['tests_per_trial']} tests each)")
        else:
            result = (f"{s['trials_finding_every_configuration']} of {s['trials']} trials find all "
                      f"{s['configurations']} configurations SLOW; detection rate "
                      f"{100 * s['detection_rate']:.0f}%; estimated slowdown median "
                      f"{100 * s['estimated_slowdown_median']:+.1f}% "
                      f"({100 * s['estimated_slowdown_range'][0]:+.0f} to {100 * s['estimated_slowdown_range'][1]:+.0f}%)")
        load = "–" if s.get("load_average_median") is None else f"{s['load_average_median']:.1f}"
        lines.append(f"| {s['kind']} | {s['trials']} | {result} | {mde} | {load} |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--trials", type=int, default=10)
    parser.add_argument("--out", default="results/runs/timing-calibration")
    parser.add_argument("--ldmbench", default=os.path.join(HERE, "..", "build", "ldmbench"))
    parser.add_argument("--only", default=",".join(KINDS), help="comma list of " + ", ".join(KINDS))
    parser.add_argument("--trials-of", action="append", default=[], metavar="KIND=N",
                        help="another number of trials for one kind (repeatable)")
    parser.add_argument("--repetitions", type=int, default=5,
                        help="repetitions of the *-repetitions kinds (default 5)")
    parser.add_argument("--resume", action="store_true",
                        help="keep the trials an earlier invocation finished in --out (each "
                        "trial's result.json) and measure only the rest")
    parser.add_argument("--structures", default="psppsll,habuffer",
                        help="the calibration sweep's structures (default psppsll,habuffer)")
    parser.add_argument("--pairs", type=int, default=8,
                        help="repetitions (pairs) of the *-interleaved kinds (default 8)")
    args = parser.parse_args()
    kinds = args.only.split(",")
    for k in kinds:
        if k not in KINDS:
            sys.exit(f"timing_calibration: --only: unknown kind '{k}' (known: {', '.join(KINDS)})")
    trials = {k: args.trials for k in kinds}
    for item in args.trials_of:
        kind, _, count = item.partition("=")
        if kind not in trials or not count.isdigit():
            sys.exit(f"timing_calibration: --trials-of '{item}': expected KIND=N with KIND one of {', '.join(kinds)}")
        trials[kind] = int(count)
    global REPETITIONS, PAIRS
    REPETITIONS, PAIRS = str(args.repetitions), str(args.pairs)
    CALIBRATION[CALIBRATION.index("--structure") + 1] = args.structures
    ldmbench = os.path.abspath(args.ldmbench)
    os.makedirs(args.out, exist_ok=True)
    started = time.time()
    comparisons = {k: [] for k in kinds}
    loads = {k: [] for k in kinds}
    # Trials interleaved over the kinds, so that a loaded hour does not fall on one kind.
    for index in range(max(trials.values())):
        for kind in kinds:
            if index >= trials[kind]:
                continue
            comparisons[kind].append(trial(kind, index, ldmbench, args.out, args.resume))
            loads[kind].append(comparisons[kind][-1]["calibration_load_average"])
            print(f"{kind} trial {index + 1}/{trials[kind]}: {summarise(kind, comparisons[kind][-1:])}",
                  flush=True)
    summaries = [summarise(k, comparisons[k]) for k in kinds]
    for s in summaries:
        s["load_average_median"] = statistics.median(loads[s["kind"]]) if loads[s["kind"]] else None
    meta = {"command": " ".join([os.path.relpath(sys.argv[0])] + sys.argv[1:]),
            "machine": f"{platform.node()}, {os.cpu_count()} cores", "seconds": time.time() - started,
            "date": time.strftime("%Y-%m-%d")}
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump({"meta": meta, "summaries": summaries}, f, indent=2)
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write(markdown(summaries, meta))
    print(markdown(summaries, meta))


if __name__ == "__main__":
    main()
