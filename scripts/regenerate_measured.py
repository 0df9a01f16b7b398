#!/usr/bin/env python3
"""Regenerates the measurement output that docs/ does not keep (issue 32, item 8).

  scripts/regenerate_measured.py [--list] [--images] [--reports] [--ldmbench BIN] [ROOT]

docs/ keeps what a reader needs: records (records.jsonl, .csv, .json), sweep files, per-frame
samples (the raw data behind committed medians, not reproducible by measuring again) and the
figures the pages show. A run's images/ folder (its AO and indirect images in EXR and PNG,
their difference and SSIM maps, the references) is not kept: the images are a deterministic
function of the run's command, which its records.json names ("run": {"command": ...}), so
this script measures that command again into a scratch folder and copies the images back,
leaving the committed records untouched (the new run's times are another measurement). Where
this build's records differ from the committed ones in anything but time (a reference or a
pass changed since the run was committed: its error images change with it), it says which
columns, so that nobody takes the images for the committed run's.

  --list     every committed run (a records.json under ROOT/docs with a command) and whether
             its images are present, and every committed report with the run folders it
             reads; the default when nothing else is asked
  --images   regenerate the images of every committed run that wrote images and lacks them
  --reports  rebuild every committed report whose runs are committed (after --images, since
             a report's image grids read its runs' images); a report built from runs that
             are not committed (results/runs/...) is named with the script that makes them

Exit status 0 when everything asked for was regenerated, 1 when something could not be.
"""
import argparse
import json
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import ldmrecords

# Options of a recorded command that name where it wrote, not what it measured.
OUT_OPTIONS = ("--out",)


def committed_runs(root):
    """(folder, command) of every run folder under docs/ whose records.json names its command."""
    runs = []
    for folder, _dirs, files in os.walk(os.path.join(root, "docs")):
        if "records.json" not in files:
            continue
        try:
            run, _records = ldmrecords.read_run(folder)
        except (OSError, ValueError, KeyError) as e:
            raise SystemExit(f"regenerate_measured.py: {os.path.join(folder, 'records.json')}: {e}")
        command = run.get("command", "")
        if command:
            runs.append((folder, command))
    return sorted(runs)


def writes_images(command):
    return "--no-images" not in shlex.split(command)


def has_images(folder):
    images = os.path.join(folder, "images")
    return os.path.isdir(images) and any(not n.startswith(".") for n in os.listdir(images))


def retargeted(command, ldmbench, out):
    """The recorded command with its binary replaced by LDMBENCH and its --out by OUT."""
    words = shlex.split(command)
    if not words or os.path.basename(words[0]) != "ldmbench":
        raise ValueError(f"not an ldmbench command: {command}")
    result, skip = [ldmbench], False
    for word in words[1:]:
        if skip:
            skip = False
            continue
        if word in OUT_OPTIONS:
            skip = True
            continue
        if any(word.startswith(o + "=") for o in OUT_OPTIONS):
            continue
        result.append(word)
    return result + ["--out", out]


def regenerate_images(folder, command, ldmbench):
    with tempfile.TemporaryDirectory(prefix="ldm-regenerate-") as scratch:
        out = os.path.join(scratch, "run")
        argv = retargeted(command, ldmbench, out)
        print("  " + " ".join(shlex.quote(a) for a in argv), flush=True)
        done = subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        # 3: finished with a failed or flagged configuration; the images of the others stand.
        if done.returncode not in (0, 3) or not has_images(out):
            print(f"  failed (exit {done.returncode}): {done.stderr.strip()[-600:]}", file=sys.stderr)
            return False
        # Images are this build's: say where its records differ from the committed ones (a
        # reference or pass changed since), so nobody takes them for the committed run's.
        same = subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                            "same_records.py"), folder, out],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if same.returncode != 0:
            lines = same.stdout.strip().split("\n")[1:]
            values = [l.strip() for l in lines if " != " in l]
            columns = sorted({l.split("column ")[1].split(" only in")[0] for l in lines if " only in " in l})
            # (The committed folder's image files are absent by design: not a difference.)
        if same.returncode != 0 and (values or columns):
            print(f"  note: the images are this build's, and its records differ from the committed ones: "
                  f"{len(values)} value(s) differ" + (f" (for example {values[0]})" if values else "")
                  + (f"; columns the committed build did not write: {', '.join(columns)}" if columns else ""),
                  flush=True)
        target = os.path.join(folder, "images")
        partial = target + ".partial"
        shutil.rmtree(partial, ignore_errors=True)
        shutil.copytree(os.path.join(out, "images"), partial)
        shutil.rmtree(target, ignore_errors=True)
        os.replace(partial, target)  # never a half-copied images/ folder
    return True


def committed_reports(root):
    """(report folder, [run folders it read]) for every report under docs/ (a manifest.json
    of ldmbench report beside a tidy.csv, whose run_dir column names its runs)."""
    import csv
    reports = []
    for folder, _dirs, files in os.walk(os.path.join(root, "docs")):
        if "manifest.json" not in files or "tidy.csv" not in files:
            continue
        with open(os.path.join(folder, "manifest.json")) as f:
            if "ldmbench_report" not in json.load(f):
                continue
        with open(os.path.join(folder, "tidy.csv"), newline="") as f:
            dirs = sorted({row.get("run_dir", "") for row in csv.DictReader(f)} - {""})
        reports.append((folder, [os.path.normpath(os.path.join(folder, d)) for d in dirs]))
    return sorted(reports)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("root", nargs="?", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser.add_argument("--list", action="store_true")
    parser.add_argument("--images", action="store_true")
    parser.add_argument("--reports", action="store_true")
    parser.add_argument("--ldmbench", default=None, help="the binary (default ROOT/build/ldmbench)")
    args = parser.parse_args()
    root = os.path.abspath(args.root)
    ldmbench = os.path.abspath(args.ldmbench or os.path.join(root, "build", "ldmbench"))
    listing = args.list or not (args.images or args.reports)
    ok = True
    runs = committed_runs(root)
    if listing:
        print(f"runs ({len(runs)}):")
        for folder, command in runs:
            state = ("images present" if has_images(folder) else "images absent: --images regenerates them") \
                if writes_images(command) else "no images (--no-images)"
            print(f"  {os.path.relpath(folder, root)}: {state}")
    if args.images:
        if not os.access(ldmbench, os.X_OK):
            raise SystemExit(f"regenerate_measured.py: {ldmbench} is not built (cmake --build build)")
        for folder, command in runs:
            if writes_images(command) and not has_images(folder):
                print(f"images of {os.path.relpath(folder, root)}:")
                ok = regenerate_images(folder, command, ldmbench) and ok
    reports = committed_reports(root)
    if listing:
        print(f"reports ({len(reports)}):")
    for report, run_dirs in reports:
        missing = [d for d in run_dirs if not os.path.isfile(os.path.join(d, "records.csv"))]
        if listing:
            state = ("rebuilt by --reports" if not missing else
                     "its runs are not committed: " + ", ".join(os.path.relpath(d, root) for d in missing)
                     + " (scripts/default-sweep.sh makes them; then ldmbench report)")
            print(f"  {os.path.relpath(report, root)}: {state}")
        if args.reports and not missing:
            argv = [ldmbench, "report", *run_dirs, "--out", report, "--format", "png,pdf"]
            print("  " + " ".join(shlex.quote(a) for a in argv), flush=True)
            ok = subprocess.run(argv).returncode == 0 and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
