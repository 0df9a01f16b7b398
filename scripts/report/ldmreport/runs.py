"""Reading ldmbench runs into one tidy table, and reading that table back.

The tidy table keeps every value as the text ldmbench wrote (records.csv's format), so that
tidy.csv holds the runs' columns unchanged; two columns are added in front: `run` (a label
per run) and `run_dir` (the run folder, relative to the folder of tidy.csv, so that image
paths, which records store relative to their run folder, still resolve when the two are
moved together).
"""
import csv
import json
import os

RUN_COLUMN = "run"
RUN_DIR_COLUMN = "run_dir"
REQUIRED_COLUMNS = ("config_id", "status")


class InputError(Exception):
    """A RUN argument or tidy CSV that cannot be used; the message names the path."""


class Run:
    """One run: its label, folder, records file, column order, rows (dicts of text), metadata."""

    def __init__(self, label, folder, records_file, columns, rows, metadata):
        # records_file as the argument named it (for messages and the pages)
        self.label, self.folder, self.records_file = label, folder, records_file
        self.columns, self.rows, self.metadata = columns, rows, metadata


def records_file_of(path):
    """The records file a RUN argument names: a run folder's records.csv (else its
    records.json), or a records .csv / .json file itself."""
    if os.path.isdir(path):
        for name in ("records.csv", "records.json"):
            candidate = os.path.join(path, name)
            if os.path.isfile(candidate):
                return candidate
        raise InputError(f"{path}: a folder without records.csv or records.json "
                         "(expected an ldmbench run folder)")
    if not os.path.exists(path):
        raise InputError(f"{path}: no such file or folder")
    if not path.endswith((".csv", ".json")):
        raise InputError(f"{path}: expected a run folder, a records.csv or a records.json")
    return path


def json_value_text(value):
    """A records.json value as records.csv writes it (null is a non-finite number there)."""
    if value is None:
        return "nan"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return format_double(value)
    return str(value)


def format_double(x):
    """As ldmbench's format_double: the shortest %.Ng (N >= 6) that reads back to x."""
    if x != x:
        return "nan"
    if x in (float("inf"), float("-inf")):
        return "inf" if x > 0 else "-inf"
    for precision in range(6, 18):
        text = "%.*g" % (precision, x)
        if float(text) == x:
            return text
    return text


def read_csv_records(path):
    try:
        with open(path, newline="") as f:
            lines = list(csv.reader(f))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise InputError(f"{path}: cannot read: {e}")
    if not lines:
        raise InputError(f"{path}: empty (expected ldmbench records with a header line)")
    header = lines[0]
    missing = [c for c in REQUIRED_COLUMNS if c not in header]
    if missing:
        raise InputError(f"{path}: not ldmbench records (no column {', '.join(missing)})")
    rows = []
    for number, line in enumerate(lines[1:], start=2):
        if len(line) != len(header):
            raise InputError(f"{path}:{number}: {len(line)} fields, the header has {len(header)}")
        rows.append(dict(zip(header, line)))
    return header, rows


def read_json_records(path):
    try:
        with open(path) as f:
            root = json.load(f)
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise InputError(f"{path}: not JSON: {e}")
    if not isinstance(root, dict) or not isinstance(root.get("records"), list):
        raise InputError(f"{path}: not an ldmbench records.json (no \"records\" array)")
    columns, rows = [], []
    for i, record in enumerate(root["records"]):
        if not isinstance(record, dict) or not all(c in record for c in REQUIRED_COLUMNS):
            raise InputError(f"{path}: record {i} has no {' or '.join(REQUIRED_COLUMNS)}")
        for key in record:
            if key not in columns:
                columns.append(key)
        rows.append({k: json_value_text(v) for k, v in record.items()})
    return columns, rows, root.get("run", {}) if isinstance(root.get("run"), dict) else {}


def run_metadata(folder):
    """The `run` object of a folder's records.json (device, command, ...), if there is one."""
    path = os.path.join(folder, "records.json")
    try:
        with open(path) as f:
            run = json.load(f).get("run", {})
        return run if isinstance(run, dict) else {}
    except (OSError, ValueError, AttributeError):
        return {}


def read_run(path):
    records_file = records_file_of(path)
    folder = os.path.dirname(os.path.abspath(records_file))
    if records_file.endswith(".csv"):
        columns, rows = read_csv_records(records_file)
        metadata = run_metadata(folder)
    else:
        columns, rows, metadata = read_json_records(records_file)
    for reserved in (RUN_COLUMN, RUN_DIR_COLUMN):
        if reserved in columns:
            raise InputError(f"{records_file}: has a column '{reserved}', which the report adds")
    return Run(None, folder, records_file, columns, rows, metadata)


def read_runs(paths):
    """Every RUN argument read and checked before anything is written; labels are the
    folder names, made unique."""
    runs, seen = [], {}
    for path in paths:
        run = read_run(path)
        if run.records_file in seen:
            raise InputError(f"{path}: the same records as {seen[run.records_file]}")
        seen[run.records_file] = path
        runs.append(run)
    labels = [os.path.basename(r.folder) or r.folder for r in runs]
    for i, run in enumerate(runs):
        run.label = labels[i] if labels.count(labels[i]) == 1 else f"{labels[i]}#{i + 1}"
    return runs


def tidy_rows(runs):
    """(columns, rows) of the tidy table: every run's records, `run` and `run_dir` first.
    In memory run_dir is absolute; tidy.csv stores it relative to its own folder."""
    columns = [RUN_COLUMN, RUN_DIR_COLUMN]
    for run in runs:
        columns += [c for c in run.columns if c not in columns]
    rows = []
    for run in runs:
        for row in run.rows:
            rows.append({RUN_COLUMN: run.label, RUN_DIR_COLUMN: run.folder, **row})
    return columns, rows


def write_tidy_csv(path, columns, rows):
    here = os.path.dirname(os.path.abspath(path))
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns, restval="", lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({**row, RUN_DIR_COLUMN: os.path.relpath(row[RUN_DIR_COLUMN], here)})


def read_tidy_csv(path):
    """(columns, rows) of a tidy.csv a report wrote, run_dir made absolute again."""
    columns, rows = read_csv_records(path)
    for needed in (RUN_COLUMN, RUN_DIR_COLUMN):
        if needed not in columns:
            raise InputError(f"{path}: not a report's tidy CSV (no column '{needed}')")
    here = os.path.dirname(os.path.abspath(path))
    for row in rows:
        row[RUN_DIR_COLUMN] = os.path.normpath(os.path.join(here, row[RUN_DIR_COLUMN]))
    return columns, rows
