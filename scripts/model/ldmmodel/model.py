"""Fits per device, driver and sub-pass from runs' records, saved as FIT.json, and applied to
another run's counters.

A sub-pass's fit takes its time `<subpass>_ms_median` and the work counters of that sub-pass
(`work_<subpass>_*`); the whole-frame fit takes `frame_ms_median` and every counter. A record
enters a fit when its status is ok or lossy, its time is a positive number and it has at
least one of the fit's counters; a counter it lacks (the column does not apply to its
structure or pass) counts 0.
"""
import json
import os
import sys

import numpy as np

from . import columns as cols
from . import fit as fitting

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
import ldmrecords  # noqa: E402

FORMAT = "ldmbench-model/1"
MEASURED = ("ok", "lossy")
DEVICE_COLUMNS = ("device", "gl_driver")


class InputError(Exception):
    """A run or fit file that cannot be used; the message names the file."""


class Run:
    def __init__(self, path, header, rows):
        self.path, self.header, self.rows = path, header, rows


def read_run(path):
    """The records of a run folder, records.csv or records.json (typed values or text)."""
    if os.path.isdir(path):
        if os.path.isfile(os.path.join(path, "records.csv")):
            file = os.path.join(path, "records.csv")
        elif os.path.isfile(os.path.join(path, "records.json")):
            file = os.path.join(path, "records.json")
        else:
            raise InputError(f"{path}: a folder without records.csv or records.json (expected an ldmbench run folder)")
    elif os.path.isfile(path):
        file = path
    else:
        raise InputError(f"{path}: no such file or folder")
    try:
        if file.endswith(".json"):
            _, rows = ldmrecords.read_run(file)
            header = []
            seen = set()
            for r in rows:
                for k in r:
                    if k not in seen:
                        seen.add(k)
                        header.append(k)
        else:
            rows = ldmrecords.read(file)
            header = list(rows[0].keys()) if rows else []
    except (OSError, ValueError, KeyError, UnicodeDecodeError) as e:
        raise InputError(f"{file}: cannot read ldmbench records: {e}")
    if not rows:
        raise InputError(f"{file}: no records")
    return Run(file, header, rows)


def text(row, column):
    v = row.get(column)
    return "" if v is None else str(v)


def group_key(row, by):
    return tuple(text(row, c) for c in DEVICE_COLUMNS + tuple(by))


def time_of(row, subpass):
    return ldmrecords.number(row, subpass + cols.TIME_SUFFIX)


def counters(row, names):
    """The row's values of NAMES (0 where absent or empty), and whether any was present."""
    values, present = [], False
    for n in names:
        v = ldmrecords.number(row, n)
        present |= v is not None
        values.append(0.0 if v is None or v != v else v)
    return values, present


def fit_plan(runs, schema, driver_stats=False, subpasses=None):
    """[(subpass, [counter columns])]: each timed sub-pass that has counters, then 'frame'
    with all of them. Raises InputError naming the runs when none has any work column."""
    header, seen = [], set()
    for run in runs:
        for c in run.header:
            if c not in seen:
                seen.add(c)
                header.append(c)
    work = cols.work_columns(header, schema, driver_stats)
    if not work:
        names = ", ".join(r.path for r in runs)
        raise InputError(f"{names}: no work columns (work_<subpass>_<counter>): the run was made before "
                         "work counters, or with the counting replay off (settings.work false)")
    timed = [s for s in cols.subpasses_timed(header) if s not in cols.SUM_SUBPASSES]
    plan = []
    for s in timed:
        mine = [c for c in work if cols.subpass_of(c, timed) == s]
        if mine:
            plan.append((s, mine))
    if cols.FRAME + cols.TIME_SUFFIX in seen:
        plan.append((cols.FRAME, work))
    if subpasses:
        unknown = [s for s in subpasses if s not in [p[0] for p in plan]]
        if unknown:
            raise InputError(f"--subpass {', '.join(unknown)}: no such sub-pass with work counters in "
                             f"{', '.join(r.path for r in runs)} (those with counters: "
                             f"{', '.join(p[0] for p in plan)})")
        plan = [p for p in plan if p[0] in subpasses]
    return plan


def fit_runs(runs, schema, folds=5, by=(), intercept=True, relative=True, driver_stats=False, subpasses=None):
    """The FIT.json document: one fit per (device, driver, BY..., sub-pass) with records."""
    plan = fit_plan(runs, schema, driver_stats, subpasses)
    rows = [(run, r) for run in runs for r in run.rows if text(r, "status") in MEASURED]
    if not rows:
        raise InputError(f"{', '.join(r.path for r in runs)}: no measured records (status ok or lossy)")
    keys = []
    for _, r in rows:
        k = group_key(r, by)
        if k not in keys:
            keys.append(k)
    fits, skipped = [], []
    for key in keys:
        mine = [(run, r) for run, r in rows if group_key(r, by) == key]
        for subpass, names in plan:
            X, y, ids, kinds, notes = [], [], [], [], 0
            for run, r in mine:
                t = time_of(r, subpass)
                values, present = counters(r, names)
                if not present:
                    continue
                if t is None or not t > 0:
                    notes += 1
                    continue
                X.append(values)
                y.append(t)
                ids.append(text(r, "config_id"))
                kinds.append(text(r, "structure"))
            label = describe_group(key, by) + " · " + subpass
            if len(y) < 2:
                if y or notes:
                    skipped.append(f"{label}: {len(y)} record(s) with a positive time (at least 2 needed)")
                continue
            result = fitting.fit(np.array(X), np.array(y), names, ids, folds, intercept, relative)
            fits.append({
                "group": dict(zip(DEVICE_COLUMNS + tuple(by), key)),
                "subpass": subpass,
                "time_column": subpass + cols.TIME_SUFFIX,
                "counters": names,
                "units": {n: cols.unit_of(n, schema) for n in names},
                "records": len(y),
                "configurations": len(set(ids)),
                "left_out_zero_time": notes,
                "config_ids": ids,
                "structures": kinds,
                "measured_ms": y,
                "intercept": intercept,
                "mean_counts": {n: float(v) for n, v in zip(names, np.mean(np.array(X), axis=0))},
                "applies_to": applies_to(mine, names),
                **result,
            })
    if not fits:
        raise InputError(f"{', '.join(r.path for r in runs)}: no sub-pass has 2 or more measured records with "
                         "work counters" + ("; " + "; ".join(skipped) if skipped else ""))
    return {
        "format": FORMAT,
        "runs": [os.path.abspath(r.path) for r in runs],
        "by": list(by),
        "weighting": "relative" if relative else "absolute",
        "intercept": intercept,
        "driver_stats": driver_stats,
        "fits": fits,
        "skipped": skipped,
    }


def kind_of(row):
    """What a record measured, for which counters apply to it: structure/pass."""
    return text(row, "structure") + "/" + text(row, "pass")


def applies_to(rows, names):
    """{counter: [structure/pass...]}: the kinds of record that had a value of the counter."""
    out = {}
    for n in names:
        out[n] = sorted({kind_of(r) for _, r in rows if ldmrecords.number(r, n) is not None})
    return out


def describe_group(key_or_group, by=()):
    if isinstance(key_or_group, dict):
        values = [key_or_group.get(c, "") for c in DEVICE_COLUMNS + tuple(by)]
    else:
        values = list(key_or_group)
    device, driver, rest = values[0], values[1], values[2:]
    head = f"{driver or '?'} ({device or 'unknown device'})"
    return " · ".join([head] + [f"{c}={v}" for c, v in zip(by, rest)])


def load_fit(path):
    try:
        with open(path) as f:
            document = json.load(f)
    except (OSError, ValueError) as e:
        raise InputError(f"{path}: cannot read the fit: {e}")
    if not isinstance(document, dict) or document.get("format") != FORMAT or not document.get("fits"):
        raise InputError(f"{path}: not a fit of `ldmbench model --out` (format {FORMAT})")
    return document


def devices_of(document):
    out = []
    for f in document["fits"]:
        d = (f["group"].get("device", ""), f["group"].get("gl_driver", ""))
        if d not in out:
            out.append(d)
    return out


def choose_device(document, fit_path, run, device=None):
    """The (device, driver) whose fits to apply: --device (GL_RENDERER, its driver name or a
    part of either), else the fit's only device, else the run's own if the fit has it."""
    devices = devices_of(document)
    listed = "; ".join(f"{drv} ({dev})" for dev, drv in devices)
    if device:
        d = device.lower()
        matches = [x for x in devices if d in (x[0].lower(), x[1].lower())] or \
                  [x for x in devices if d in x[0].lower() or d in x[1].lower()]
        if not matches:
            raise InputError(f"{fit_path}: a fit for another device: it holds {listed}, not --device {device}")
        if len(matches) > 1:
            raise InputError(f"{fit_path}: --device {device} matches several devices ({listed}); name one")
        return matches[0]
    if len(devices) == 1:
        return devices[0]
    own = {(text(r, "device"), text(r, "gl_driver")) for r in run.rows}
    matches = [x for x in devices if x in own]
    if len(matches) == 1:
        return matches[0]
    raise InputError(f"{fit_path}: fits for several devices ({listed}) and {run.path} was measured on none "
                     "of them alone: choose one with --device")


def predict_run(document, fit_path, run, device=None):
    """(device, [(fit, [(config_id, predicted_ms, measured_ms or None)], missing)]) for the chosen
    device's fits; `missing` names the counters the fit weighs that the run has no column of
    (counted 0: the prediction is then low).
    Measured times are compared only where the run was measured on that device and driver."""
    chosen = choose_device(document, fit_path, run, device)
    by = document.get("by", [])
    header = set(run.header)
    fits = [f for f in document["fits"] if (f["group"].get("device", ""), f["group"].get("gl_driver", "")) == chosen]
    used = {c for f in fits for c in f["counters"]}
    if not used & header:
        raise InputError(f"{run.path}: none of the work columns the fit {fit_path} uses (no work counters, "
                         "or counted by a build without them)")
    rows = run.rows
    out = []
    for f in fits:
        want = {c: f["group"][c] for c in by}
        lines = []
        for r in rows:
            if any(text(r, c) != v for c, v in want.items()):
                continue
            values, present = counters(r, f["counters"])
            if not present:
                continue
            x = dict(zip(f["counters"], values))
            p_ns = f["intercept_ns"] + sum(c * x[n] for n, c in f["coefficients_ns"].items())
            same = (text(r, "device"), text(r, "gl_driver")) == chosen and text(r, "status") in MEASURED
            measured = time_of(r, f["subpass"]) if same else None
            lines.append((text(r, "config_id"), p_ns / fitting.NS_PER_MS, measured))
        if lines:
            # a counter the fit weighs, which records of this kind had, absent here: counted by
            # a build without it (counted 0, the prediction low)
            kinds = {kind_of(r) for r in rows if all(text(r, c) == v for c, v in want.items())}
            missing = [n for n, c in f["coefficients_ns"].items()
                       if c > 0 and n not in header and kinds & set(f.get("applies_to", {}).get(n, []))]
            out.append((f, lines, missing))
    if not out:
        raise InputError(f"{run.path}: no record has the counters of any sub-pass the fit {fit_path} models"
                         + (f" (with its groups by {', '.join(by)})" if by else ""))
    return chosen, out
