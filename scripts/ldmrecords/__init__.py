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


def dataframe(path):
    """The records of a run folder or CSV file as a pandas DataFrame (pandas imported here,
    so that scripts without it can use the rest of the module)."""
    import pandas as pd
    return pd.read_csv(records_path(path))


def default_ldmbench():
    """$LDMBENCH, else the build in this checkout (build/ldmbench beside scripts/)."""
    return os.environ.get("LDMBENCH") or os.path.join(
        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "build", "ldmbench")


_varying = {}


def varies_between_runs(ldmbench=None):
    """A compiled pattern of the columns the schema declares as varying between two runs of one
    configuration (measured time, machine state, host and job, whether the reference came from
    the cache: `ldmbench columns --json`, flag varies_between_runs); a templated name such as
    <subpass>_ms_median matches any text in place of <subpass>. Read once per binary."""
    import re
    import subprocess
    ldmbench = ldmbench or default_ldmbench()
    if ldmbench not in _varying:
        out = subprocess.run([ldmbench, "columns", "--json"], check=True, capture_output=True, text=True).stdout
        names = [c["name"] for c in json.loads(out)["columns"] if c.get("varies_between_runs")]
        parts = [".+".join(re.escape(p) for p in re.split(r"<[^>]+>", n)) for n in names]
        _varying[ldmbench] = re.compile("^(" + "|".join(parts) + ")$")
    return _varying[ldmbench]
