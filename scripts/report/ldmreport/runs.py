"""Reading ldmbench runs into one tidy table, and reading that table back.

The tidy table keeps every value as the text ldmbench wrote (records.csv's format), so that
tidy.csv holds the runs' columns unchanged; two columns are added in front: `run` (a label
per run) and `run_dir` (the run folder, relative to the folder of tidy.csv, so that image
paths, which records store relative to their run folder, still resolve when the two are
moved together).
"""
import csv
import os
import sys

# The one records reader (scripts/ldmrecords, installed beside the report folder).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
import ldmrecords  # noqa: E402
from ldmrecords import (REQUIRED_COLUMNS, InputError, format_double, json_value_text,  # noqa: E402,F401
                        records_file_of, run_metadata)

RUN_COLUMN = "run"
RUN_DIR_COLUMN = "run_dir"


class Run:
    """One run: its label, folder, records file, column order, rows (dicts of text), metadata."""

    def __init__(self, label, folder, records_file, columns, rows, metadata):
        # records_file as the argument named it (for messages and the pages)
        self.label, self.folder, self.records_file = label, folder, records_file
        self.columns, self.rows, self.metadata = columns, rows, metadata


read_csv_records = ldmrecords.read_csv_table
read_json_records = ldmrecords.read_json_table


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
