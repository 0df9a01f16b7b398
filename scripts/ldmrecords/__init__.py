"""Reading ldmbench's records from Python: one reader for every script (issue 32, item 5).

A run folder holds records.csv (one row per configuration, every column ldmbench declares:
`ldmbench columns`), records.json and records.jsonl. Scripts read records.csv as text rows
(csv.DictReader: every value a string, "" where a column does not apply) and convert the
numbers they need; this module does both once, so that every script agrees on what an
absent or non-numeric value is.

    import ldmrecords
    rows = ldmrecords.read("docs/measured/readme-main")          # a folder or its records.csv
    ok = ldmrecords.with_status(rows, "ok")
    ms = ldmrecords.number(rows[0], "frame_ms_median")            # None where absent or not a number
    ms = ldmrecords.number(rows[0], "frame_ms_median", math.nan)  # or a default of your choice

Scripts in scripts/ import it directly (their folder is on sys.path); others add scripts/ to
sys.path first.
"""
import csv
import json
import math
import os

RECORDS_CSV = "records.csv"


def records_path(path):
    """A run folder's records.csv, or PATH itself when it names a file."""
    return os.path.join(path, RECORDS_CSV) if os.path.isdir(path) else path


def read(path):
    """The records of a run folder or CSV file, in file order, as dicts of text."""
    with open(records_path(path), newline="") as f:
        return list(csv.DictReader(f))


def number(row, column, default=None):
    """The column's value as a float; DEFAULT where the row lacks the column, the value is
    empty ("" : the column does not apply) or is not a number."""
    try:
        return float(row[column])
    except (KeyError, TypeError, ValueError):
        return default


def with_status(rows, *statuses):
    """The rows whose status is one of STATUSES (ok, lossy, degenerate, invalid, failed)."""
    return [r for r in rows if r.get("status") in statuses]


def value(row, column):
    """The column's value as a float, NaN where number() gives None: for arithmetic and
    comparisons in which a missing value must propagate rather than raise."""
    return number(row, column, math.nan)


def read_run(path):
    """(run, records) of a run folder's records.json (or that file): the run object (command,
    device, commit, ...) and the records with their typed values (numbers as numbers)."""
    json_path = os.path.join(path, "records.json") if os.path.isdir(path) else path
    with open(json_path) as f:
        document = json.load(f)
    return document.get("run", {}), document["records"]


# What every record has: the columns a file must hold to be taken for ldmbench records.
REQUIRED_COLUMNS = ("config_id", "status")


class InputError(Exception):
    """A records file or folder that cannot be read as ldmbench records; the message names
    the path."""


def records_file_of(path):
    """The records file PATH names: a run folder's records.csv (else its records.json), or a
    records .csv / .json file itself; InputError otherwise."""
    if os.path.isdir(path):
        for name in (RECORDS_CSV, "records.json"):
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


def json_value_text(value):
    """A records.json value as records.csv writes it (null is a non-finite number there)."""
    if value is None:
        return "nan"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return format_double(value)
    return str(value)


def read_csv_table(path, required=REQUIRED_COLUMNS):
    """(columns, rows) of a records.csv (or a table in its format), checked: a header with
    the REQUIRED columns, every line as many fields as the header; InputError otherwise."""
    try:
        with open(path, newline="") as f:
            lines = list(csv.reader(f))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise InputError(f"{path}: cannot read: {e}")
    if not lines:
        raise InputError(f"{path}: empty (expected ldmbench records with a header line)")
    header = lines[0]
    missing = [c for c in required if c not in header]
    if missing:
        raise InputError(f"{path}: not ldmbench records (no column {', '.join(missing)})")
    rows = []
    for line_number, line in enumerate(lines[1:], start=2):
        if len(line) != len(header):
            raise InputError(f"{path}:{line_number}: {len(line)} fields, the header has {len(header)}")
        rows.append(dict(zip(header, line)))
    return header, rows


def read_json_table(path):
    """(columns, rows, run) of a records.json, checked, its values as records.csv writes
    them (text): the columns in order of first appearance, the `run` object ({} if none)."""
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
    """The `run` object of a folder's records.json (device, command, ...), {} if there is none."""
    try:
        with open(os.path.join(folder, "records.json")) as f:
            run = json.load(f).get("run", {})
        return run if isinstance(run, dict) else {}
    except (OSError, ValueError, AttributeError):
        return {}


def by_config_id(path):
    """The records of a run folder or CSV file (records.csv, a memory plan) as dicts of text,
    keyed by config_id."""
    with open(records_path(path), newline="", encoding="utf-8") as f:
        return {row.get("config_id"): row for row in csv.DictReader(f)}


def dataframe(path):
    """The records of a run folder or CSV file as a pandas DataFrame (pandas imported here,
    so that scripts without it can use the rest of the module)."""
    import pandas as pd
    return pd.read_csv(records_path(path))


def default_ldmbench():
    """$LDMBENCH, else the build in this checkout (build/ldmbench beside scripts/)."""
    return os.environ.get("LDMBENCH") or os.path.join(
        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "build", "ldmbench")


_flagged = {}


def columns_flagged(flag, ldmbench=None):
    """A compiled pattern of the columns whose `ldmbench columns --json` entry sets `flag`; a
    templated name such as <subpass>_ms_median matches any text in place of <subpass>. Read
    once per binary and flag."""
    import re
    import subprocess
    ldmbench = ldmbench or default_ldmbench()
    if ldmbench not in _flagged:
        out = subprocess.run([ldmbench, "columns", "--json"], check=True, capture_output=True, text=True).stdout
        _flagged[ldmbench] = json.loads(out)["columns"]
    key = (ldmbench, flag)
    if key not in _flagged:
        names = [c["name"] for c in _flagged[ldmbench] if c.get(flag)]
        parts = [".+".join(re.escape(p) for p in re.split(r"<[^>]+>", n)) for n in names]
        _flagged[key] = re.compile("^(" + "|".join(parts) + ")$" if parts else "(?!)")
    return _flagged[key]


def varies_between_runs(ldmbench=None):
    """The columns the schema declares as varying between two runs of one configuration
    (measured time, machine state, host and job, whether the reference came from the cache:
    flag varies_between_runs), as a compiled pattern (columns_flagged)."""
    return columns_flagged("varies_between_runs", ldmbench)


def summed_in_arrival_order(ldmbench=None):
    """The columns two runs agree in only within the record's image_order_tolerance
    (relative), where the pass sums in arrival order (flag summed_in_arrival_order)."""
    return columns_flagged("summed_in_arrival_order", ldmbench)
