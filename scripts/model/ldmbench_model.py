#!/usr/bin/env python3
"""ldmbench model: a cost model fitted on work counters. Per device, driver and sub-pass,
time ≈ c₀ + Σ cᵢ · counterᵢ (non-negative least squares, SciPy), with k-fold
cross-validation by configuration; prints the coefficients in ns per unit, R² and the
held-out median relative error. `ldmbench model` checks the options and runs this script;
the method and its limits are docs/guide/model.md.

Usage:
  ldmbench_model.py RUN... [--out FIT.json] [--folds K] [--by COLUMN]... [--subpass NAME]...
  ldmbench_model.py --predict RUN --fit FIT.json [--device NAME]
  ldmbench_model.py RUN... --predict RUN [--device NAME]     (fit, then predict)

RUN is a run folder (records.csv or records.json inside) or such a file. Exit 0 with the
tables printed, 2 for bad input (no records, no work columns, a fit for another device),
naming the file.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

EXIT_USAGE = 2


def fail(message):
    print(f"ldmbench model: error: {message}", file=sys.stderr)
    sys.exit(EXIT_USAGE)


def parse_arguments(argv):
    p = argparse.ArgumentParser(prog="ldmbench_model.py", description=__doc__.split("\n")[0])
    p.add_argument("runs", nargs="*", metavar="RUN", help="run folders (or records.csv / records.json) to fit on")
    p.add_argument("--out", metavar="FIT_JSON", help="save the fit")
    p.add_argument("--predict", metavar="RUN", help="predict this run's times from its counters")
    p.add_argument("--fit", metavar="FIT_JSON", help="the saved fit --predict applies")
    p.add_argument("--device", help="--predict: the device whose fits to apply (GL_RENDERER or driver name, or part of it)")
    p.add_argument("--folds", type=int, default=5, help="cross-validation folds (default 5; fewer configurations: one each)")
    p.add_argument("--by", action="append", default=[], metavar="COLUMN",
                   help="also fit separately per value of this record column (structure, scene), repeatable")
    p.add_argument("--subpass", action="append", default=[], metavar="NAME", help="fit only these sub-passes (frame: the whole frame)")
    p.add_argument("--no-intercept", action="store_true", help="no fixed cost per frame (time is counters alone)")
    p.add_argument("--absolute", action="store_true",
                   help="minimise the squared error in ms (default: the squared relative error)")
    p.add_argument("--driver-stats", action="store_true",
                   help="also use the driver's pipeline statistics (work_<subpass>_gl_*), which differ between drivers")
    p.add_argument("--columns", metavar="COLUMNS_JSON",
                   help="the record schema (`ldmbench columns --json`) for the counters' units; "
                        "default: ask $LDMBENCH or this checkout's build/ldmbench")
    a = p.parse_args(argv)
    if not a.runs and not a.predict:
        fail("give RUN... to fit, or --predict RUN --fit FIT.json")
    if a.runs and a.fit:
        fail("--fit: the fit to apply comes from RUN... or from --fit FIT.json, not both")
    if a.predict and not a.runs and not a.fit:
        fail("--predict: needs --fit FIT.json (a saved fit) or RUN... to fit on")
    if a.fit and not a.predict:
        fail("--fit: only with --predict RUN")
    if a.folds < 2:
        fail(f"--folds {a.folds}: at least 2")
    return a


def main(argv):
    a = parse_arguments(argv)
    from ldmmodel import columns, model, table  # numpy and scipy: after the usage checks
    try:
        import ldmrecords
        schema = columns.load_schema(a.columns, None if a.columns else ldmrecords.default_ldmbench()
                                     if os.access(ldmrecords.default_ldmbench(), os.X_OK) else None)
    except columns.ColumnsError as e:
        fail(str(e))
    try:
        if a.runs:
            runs = [model.read_run(r) for r in a.runs]
            document = model.fit_runs(runs, schema, folds=a.folds, by=a.by, intercept=not a.no_intercept,
                                      relative=not a.absolute, driver_stats=a.driver_stats,
                                      subpasses=a.subpass or None)
            fit_path = a.out or "the fit"
            print(f"cost model: time ≈ fixed + Σ coefficient · counter (NNLS, {document['weighting']} "
                  f"least squares; {len(document['fits'])} fits)\n")
            for f in document["fits"]:
                print(table.fit_table(f, a.by) + "\n")
            for s in document["skipped"]:
                print("not fitted: " + s)
            print("summary:\n" + table.summary_table(document))
            if a.out:
                with open(a.out, "w") as out:
                    json.dump(document, out, indent=1)
                    out.write("\n")
                print(f"\nfit: {a.out}")
        else:
            document = model.load_fit(a.fit)
            fit_path = a.fit
        if a.predict:
            run = model.read_run(a.predict)
            device, predictions = model.predict_run(document, fit_path, run, a.device)
            print(f"\nprediction for {device[1]} ({device[0]}) from the counters of {run.path}:\n")
            for f, lines, missing in predictions:
                print(table.prediction_table(f, lines, missing, document.get("by", [])) + "\n")
    except model.InputError as e:
        fail(str(e))
    except OSError as e:
        fail(f"{e.filename}: {e.strerror}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
