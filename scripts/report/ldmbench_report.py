#!/usr/bin/env python3
"""ldmbench report: a folder of tables, plots and pages from one or more ldmbench runs.

Usage:
  ldmbench_report.py RUN... --out DIR [--format png|svg|pdf]... [--title TEXT] [--axis COLUMN]...
  ldmbench_report.py --from-csv tidy.csv --out DIR [--format ...] [--title TEXT] [--axis COLUMN]...

RUN is a run folder (records.csv or records.json inside) or a records.csv / records.json.
DIR receives tidy.csv (every run's records, one row per configuration and run, the run a
column), figures/ (each in every --format: PNG by default; SVG and PDF for a paper, sized
for a two-column layout), summary.md and index.html. `--from-csv` redraws
everything from a tidy.csv alone; the image grids then need the run folders it names and
are skipped with a note without them. `ldmbench report` runs this script.

DIR must be missing, empty or an earlier report (its manifest.json), which is replaced.
Bad arguments exit with status 2 before anything is written.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

AXES_FILE = "axes.json"  # the axis registry the report was made with
MANIFEST = "manifest.json"
EXIT_USAGE = 2


def fail(message):
    print(f"ldmbench report: error: {message}", file=sys.stderr)
    sys.exit(EXIT_USAGE)


def import_plotting():
    """matplotlib, pandas and numpy, or a message saying how to install them."""
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
        import pandas  # noqa: F401
    except ImportError as e:
        fail(f"{sys.executable}: {e}; install python3-matplotlib and python3-pandas "
             "(scripts/setup.sh installs every package ldmbench needs)")


def parse_arguments(argv):
    parser = argparse.ArgumentParser(prog="ldmbench_report.py", description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="*", metavar="RUN", help="run folder, records.csv or records.json")
    parser.add_argument("--from-csv", metavar="TIDY_CSV", help="redraw from a report's tidy.csv")
    parser.add_argument("--out", required=True, metavar="DIR", help="the report folder")
    parser.add_argument("--format", action="append", default=[], metavar="FORMATS",
                        help="png, svg or pdf, repeatable or a comma list (default png); the "
                             "pages show the SVG, else the PNG, which is added when neither is asked for")
    parser.add_argument("--svg", action="store_true", help="the same as --format png,svg")
    parser.add_argument("--dpi", type=int, default=200,
                        help="resolution of the PNG figures (e.g. 50 for a report to commit)")
    parser.add_argument("--title", default="ldmbench report", help="title of the pages")
    parser.add_argument("--axes", metavar="AXES_JSON",
                        help="the axis registry (`ldmbench axes --json`; `ldmbench report` passes "
                             "it); default: axes.json beside --from-csv's tidy.csv")
    parser.add_argument("--axis", action="append", default=[], metavar="COLUMN",
                        help="another record column that tells configurations apart (a new "
                             "pass's setting), repeatable")
    args = parser.parse_args(argv)
    if bool(args.runs) == bool(args.from_csv):
        parser.print_usage(sys.stderr)
        fail("give either RUN... or --from-csv TIDY_CSV")
    from ldmreport import style  # matplotlib's name only: no plotting is imported
    try:
        args.formats = style.parse_formats(args.format + (["png,svg"] if args.svg else []))
    except ValueError as e:
        fail(str(e))
    if args.dpi <= 0:
        fail(f"--dpi: {args.dpi} is not a positive number of dots per inch")
    return args


def check_out_folder(out, inputs):
    """DIR must be missing, empty, or an earlier report; never one of the inputs' folders.
    Returns the files the earlier report listed (to be replaced)."""
    out_abs = os.path.abspath(out)
    for path in inputs:
        folder = os.path.abspath(path if os.path.isdir(path) else os.path.dirname(path) or ".")
        if out_abs == folder:
            fail(f"--out: '{out}' is the folder of {path}; choose another folder")
    if not os.path.exists(out):
        return []
    if not os.path.isdir(out):
        fail(f"--out: '{out}' exists and is not a folder")
    entries = os.listdir(out)
    if not entries:
        return []
    try:
        with open(os.path.join(out, MANIFEST)) as f:
            manifest = json.load(f)
        if manifest.get("ldmbench_report"):
            return manifest.get("files", [])
    except (OSError, ValueError, AttributeError):
        pass
    fail(f"--out: '{out}' is not empty and holds no earlier report ({MANIFEST}); "
         "choose an empty or new folder")


def remove_earlier_report(out, files):
    """Removes what an earlier report wrote, so that no stale figure survives."""
    for rel in files + [MANIFEST]:
        path = os.path.normpath(os.path.join(out, rel))
        if os.path.commonpath([os.path.abspath(path), os.path.abspath(out)]) == \
                os.path.abspath(out) and os.path.isfile(path):
            os.remove(path)


def collision_note(table):
    """Configurations the known axes cannot tell apart (a setting the report does not know):
    their points share series and cells; --axis names the column that differs."""
    axes = table.axes()
    keys = table.df[axes].astype(str).agg("|".join, axis=1)
    per_key = table.df.groupby(keys)["config_id"].nunique()
    clashing = per_key[per_key > 1]
    if clashing.empty:
        return None
    ids = sorted(table.df["config_id"][keys.isin(clashing.index)])[:4]
    return (f"{int(clashing.sum())} configurations differ in no known axis ({', '.join(ids)}, "
            "...): they share series and grid cells; pass --axis COLUMN for the setting that "
            "differs")


def cross_platform_note(table):
    """Records of several drivers (or GPU models) compared in one report: said once, since
    what differs between them is the driver's or device's doing, not a regression."""
    platforms = list(dict.fromkeys(table.platform()))
    if len(platforms) < 2:
        return None
    where = "; ".join(f"{p} (run {', '.join(dict.fromkeys(table.text('run')[table.platform() == p]))})"
                      for p in platforms)
    kind = "cross-driver" if len(table.drivers()) > 1 else "cross-device"
    return (f"the records ran on {len(platforms)} drivers or devices: {where}. A {kind} comparison: "
            "rankings and panels are per driver and device, and differences between them are "
            "not regressions")


def runs_info_from_runs(runs):
    return [{"label": r.label, "records_file": r.records_file,
             "records": len(r.rows), **{k: str(r.metadata.get(k, "")) for k in
                                         ("device", "gl_driver", "git_commit", "command", "started",
                                          "resumed_records")}} for r in runs]


def runs_info_from_table(table, tidy_path):
    info = []
    for label in dict.fromkeys(table.text("run")):
        rows = table.df[table.text("run") == label]
        info.append({"label": label, "records_file": f"{tidy_path} ({rows['run_dir'].iloc[0]})",
                     "records": len(rows),
                     "device": ", ".join(dict.fromkeys(rows.get("device", []))),
                     "gl_driver": ", ".join(d for d in dict.fromkeys(rows.get("gl_driver", [])) if d),
                     "git_commit": ", ".join(dict.fromkeys(rows.get("git_commit", []))),
                     "command": ""})
    return info


def read_axes(args):
    """The axis registry's JSON: --axes, else the axes.json a report keeps beside its tidy.csv."""
    path = args.axes or (os.path.join(os.path.dirname(args.from_csv) or ".", AXES_FILE)
                         if args.from_csv else None)
    if not path:
        fail("--axes AXES_JSON is required with run folders (`ldmbench axes --json`; "
             "`ldmbench report` passes it)")
    try:
        with open(path) as f:
            axes = json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{path}: cannot read the axis registry ({e}); write it with `ldmbench axes --json`"
             + ("" if args.axes else " and pass --axes"))
    if not isinstance(axes, dict) or not isinstance(axes.get("axes"), list):
        fail(f"{path}: not the output of `ldmbench axes --json` (no \"axes\" list)")
    return axes


def main(argv):
    args = parse_arguments(argv)
    from ldmreport import runs  # the standard library only: checks need no plotting

    inputs = [args.from_csv] if args.from_csv else args.runs
    try:
        if args.from_csv:
            if not os.path.isfile(args.from_csv):
                raise runs.InputError(f"{args.from_csv}: no such file")
            columns, rows = runs.read_tidy_csv(args.from_csv)
            loaded = None
        else:
            loaded = runs.read_runs(args.runs)
            columns, rows = runs.tidy_rows(loaded)
    except runs.InputError as e:
        fail(str(e))
    axes = read_axes(args)
    earlier = check_out_folder(args.out, inputs)
    import_plotting()
    from ldmreport import figures, grids, pages, style
    from ldmreport.table import Table, declare_axes
    declare_axes(axes)
    style.apply()

    os.makedirs(args.out, exist_ok=True)
    remove_earlier_report(args.out, earlier)
    tidy_path = os.path.join(args.out, "tidy.csv")
    runs.write_tidy_csv(tidy_path, columns, rows)
    with open(os.path.join(args.out, AXES_FILE), "w") as f:  # what the tidy table's axes are
        json.dump(axes, f, indent=1)

    table = Table(columns, rows, extra_axes=args.axis)
    canvas = figures.Canvas(args.out, formats=args.formats, dpi=args.dpi)
    for note in (cross_platform_note(table), collision_note(table)):
        if note:
            canvas.note(note)
    figures.draw_tradeoffs(table, canvas)
    figures.draw_memory(table, canvas)
    figures.draw_depth_histograms(table, canvas)
    figures.draw_subpass_bars(table, canvas)
    figures.draw_scaling(table, canvas)
    grids.draw_image_grids(table, canvas)

    info = runs_info_from_runs(loaded) if loaded else runs_info_from_table(table, args.from_csv)
    pages.write_markdown(os.path.join(args.out, "summary.md"), args.title, info, table,
                         canvas.figures, canvas.notes)
    pages.write_html(os.path.join(args.out, "index.html"), args.title, info, table,
                     canvas.figures, canvas.notes)
    files = ["tidy.csv", AXES_FILE, "summary.md", "index.html"] + \
        [f for figure in canvas.figures for f in figure["files"]]
    with open(os.path.join(args.out, MANIFEST), "w") as f:
        json.dump({"ldmbench_report": 1, "files": files, "figures": canvas.figures,
                   "notes": canvas.notes}, f, indent=1)
    print(f"report: {len(table)} configurations from {len(info)} run(s), "
          f"{len(canvas.figures)} figures, {len(canvas.notes)} skipped or noted")
    for n in canvas.notes:
        print(f"  note: {n}")
    print(f"open: {os.path.join(args.out, 'index.html')}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
