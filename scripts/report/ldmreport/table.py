"""Typed views of the tidy table (kept as text, as ldmbench writes it): numbers, statuses,
methods, the axes a sweep varies, the metric columns and the sub-passes a run timed.

Everything is discovered from the columns, so that a new pass, its sub-passes
(`<subpass>_ms_median`) and its prefixed metrics (`<prefix>_mse`, `<prefix>_mssim`) appear in
the report without a change here."""
import math
import re

import numpy as np
import pandas as pd

MEASURED_STATUS = "ok"  # lossy, invalid and failed are flagged, never ranked
# An `ok` record whose `degenerate` column names a reason measures nothing (a reference
# without noise, no surface in view, an AO range below a few LDM pixels): flagged as this.
DEGENERATE_STATUS = "degenerate"

# The axes come from ldmbench's axis registry (`ldmbench axes --json`, which `ldmbench report`
# hands the script; a report keeps it as axes.json): each axis names the record column(s)
# holding its value, its label (N, R_LDM), and whether only records with an LDM structure have
# it. `run` (a report's run label) and `sweep` (a sweep's name) tell runs apart besides.
RUN_AXES = ["run", "sweep"]
# Structure parameters are one column (key=value;...) whatever their owner.
STRUCTURE_PARAMS = "structure_params"
# Labels of columns that are not axes but serve as a plot's x.
OTHER_LABELS = {"fragments": "fragments"}


class AxisDeclarations:
    """The axes of a registry dump: columns in registry order, the LDM-only ones, labels."""

    def __init__(self, declaration):
        self.columns, self.structure_columns, self.labels = list(RUN_AXES), {STRUCTURE_PARAMS}, {}
        for axis in declaration["axes"]:
            structure_parameter = axis.get("owner_kind") == "structure"
            names = [STRUCTURE_PARAMS] if structure_parameter else \
                [c for c in axis.get("column", "").split(",") if c]
            for c in names:
                if c not in self.columns:
                    self.columns.append(c)
                if axis.get("ldm_only") or structure_parameter:
                    self.structure_columns.add(c)
                if axis.get("label") and axis["label"] != axis["key"]:
                    self.labels.setdefault(c, axis["label"])
        if STRUCTURE_PARAMS not in self.columns:
            self.columns.append(STRUCTURE_PARAMS)


_declared = None


def declare_axes(declaration):
    """Sets the axes every Table uses (once per report, from the registry's JSON)."""
    global _declared
    _declared = AxisDeclarations(declaration)


def declared():
    if _declared is None:
        raise RuntimeError("the axes are not declared: call declare_axes() with `ldmbench axes --json`")
    return _declared


# <subpass>_ms_median columns that are not sub-passes of a frame: the sums, and the raster
# baselines (timed beside the frame, not part of it).
NOT_STACKED = {"build", "pass", "frame", "raster_baseline", "raster_touch"}
# The structures' and sizing policies' sub-passes (docs/reference/records.md), stacked first in this
# order so that a bar reads build, then pass; any other sub-pass (a pass's) follows in
# column order.
BUILD_SUBPASSES = ["census", "clear", "count", "prefix_sum", "construct", "sort", "readback",
                   "reallocate", "rebuild"]
NO_STRUCTURE = ("", "none")
METRIC = re.compile(r"^(?:(?P<prefix>.+)_)?(?P<metric>mse|mssim)$")
NOT_METRIC = re.compile(r"(^|_)ref_noise_")  # a reference's own noise, <prefix>_ref_noise_mse


def axis_label(column):
    return declared().labels.get(column, OTHER_LABELS.get(column, column))


class Table:
    """The tidy rows as a DataFrame of text, with typed accessors."""

    def __init__(self, columns, rows, extra_axes=()):
        self.columns = list(columns)
        self.df = pd.DataFrame(rows, columns=self.columns).fillna("")
        # Titles, groups and file names show a scene file by its name (scene_name:
        # "cubes_with_names", not /usr/share/assimp/models/FBX/cubes_with_names.fbx);
        # tidy.csv keeps the --scene value (runs.py writes the rows, not this table).
        if self.has("scene") and self.has("scene_name"):
            named = self.df["scene_name"].astype(str) != ""
            self.df.loc[named, "scene"] = self.df.loc[named, "scene_name"]
        self.extra_axes = [a for a in extra_axes if a not in declared().columns]

    def __len__(self):
        return len(self.df)

    def has(self, column):
        return column in self.df.columns

    def text(self, column):
        if not self.has(column):
            return pd.Series([""] * len(self.df), index=self.df.index, dtype=object)
        return self.df[column].astype(str)

    def platform(self):
        """What a record ran on, as rankings and panels group it: "driver: device" (gl_driver
        and GL_RENDERER), or the device alone for records from before gl_driver. GPUs of one
        model share it (their device_id differs): a sweep's shards on several GPUs of a node
        rank together."""
        driver, device = self.text("gl_driver"), self.text("device")
        return (driver + ": " + device).where(driver != "", device)

    def drivers(self):
        """The drivers the records ran on, in order (those from before gl_driver left out)."""
        return [d for d in dict.fromkeys(self.text("gl_driver")) if d]

    def num(self, column):
        """The column as floats: NaN where absent, empty or not a number."""
        if not self.has(column):
            return pd.Series(np.nan, index=self.df.index)
        return pd.to_numeric(self.df[column], errors="coerce")

    def status(self):
        """The record's status, with `ok` records that measure nothing (a non-empty
        `degenerate` column, harness/measuring/scene_profile.h) as "degenerate": flagged like
        lossy, invalid and failed ones, never ranked, off the fronts and fits."""
        status = self.text("status")
        degenerate = self.text("degenerate").replace("nan", "")
        return status.where(~((status == MEASURED_STATUS) & (degenerate != "")), DEGENERATE_STATUS)

    def measured(self):
        """Rows that may be ranked and put on a Pareto front: status ok."""
        return self.status() == MEASURED_STATUS

    def has_structure(self):
        return ~self.text("structure").isin(NO_STRUCTURE)

    def query_ms(self):
        """The pass's share of a frame: the record's "pass" sum (summed per frame, so it has
        its own interval), else frame minus build (older runs; a pass without a structure
        has no build, so its whole frame)."""
        if self.has("pass_ms_median"):
            return self.num("pass_ms_median")
        return self.num("frame_ms_median") - self.num("build_ms_median").fillna(0)

    def time_interval(self, subpass):
        """(low, high) of a sub-pass's 95 % interval per row (NaN where the run has none)."""
        return self.num(f"{subpass}_ms_ci_low"), self.num(f"{subpass}_ms_ci_high")

    def methods(self):
        """structure/pass per row ("psppsll/ao"), the pass alone for a pass without a
        structure ("hbao"), the structure alone when every structure ran one pass."""
        structure, pass_ = self.text("structure"), self.text("pass")
        with_structure = self.has_structure()
        one_pass = pass_[with_structure].nunique() <= 1
        labels = []
        for s, p, w in zip(structure, pass_, with_structure):
            labels.append((s if one_pass else f"{s}/{p}") if w else (p or "?"))
        return pd.Series(labels, index=self.df.index)

    def axes(self):
        return [a for a in declared().columns + self.extra_axes if self.has(a)]

    def axis_values(self, column):
        """An axis's value per row, "" where it does not apply (structure axes of a pass
        without a structure)."""
        values = self.text(column)
        if column in declared().structure_columns:
            values = values.where(self.has_structure(), "")
        return values

    def varying(self, rows, candidates):
        """The candidate axes taking more than one value over `rows` (a boolean mask)."""
        return [a for a in candidates if self.has(a) and self.axis_values(a)[rows].nunique() > 1]

    def subpasses(self):
        """Timed sub-passes of a frame: every <name>_ms_median column but the sums and the
        raster baselines; the known build sub-passes first, the rest in column order."""
        names = []
        for c in self.columns:
            if c.endswith("_ms_median"):
                name = c[: -len("_ms_median")]
                if name not in NOT_STACKED:
                    names.append(name)
        known = [n for n in BUILD_SUBPASSES if n in names]
        return known + [n for n in names if n not in known]

    def metric_columns(self):
        """[(prefix, metric, column)] for every image metric a pass scored: mse and mssim
        against the pass's reference, <prefix>_mse / <prefix>_mssim against other ones."""
        found = []
        for c in self.columns:
            m = METRIC.match(c)
            if m and not NOT_METRIC.search(c):
                found.append((m.group("prefix") or "", m.group("metric"), c))
        return found

    def reference_key_column(self, prefix):
        """The column naming the reference a metric was scored against, if the run wrote one."""
        for c in ([f"{prefix}_ref_cache_key", f"ref_{prefix}_cache_key"] if prefix else []) + \
                ["ref_cache_key"]:
            if self.has(c):
                return c
        return None


def sort_key(value):
    """Axis values in numeric order where they are numbers, else text order."""
    try:
        return (0, float(value), "")
    except (TypeError, ValueError):
        return (1, 0.0, str(value))


SHOWN_DIGITS = 4  # significant digits of a derived value in titles and labels
GUESS = re.compile(r"^guess: (\d+) fragment\(s\) per LDM pixel$")


def shown_value(value):
    """An axis value as titles and labels show it, to the digits it supports: a value the
    harness derived in double (d_max from a scene's size: 4.393941402435303) to
    SHOWN_DIGITS significant digits (4.394), a value given as typed (0.5, 1e-3, 128) as it
    is; the previous-frame policy's "guess: 1 fragment(s) per LDM pixel" as "1 fragment/LDM
    pixel" (its axis is already called the initial guess)."""
    text = str(value)
    guess = GUESS.match(text)
    if guess:
        n = guess.group(1)
        return f"{n} fragment{'' if n == '1' else 's'}/LDM pixel"
    try:
        number = float(text)
    except ValueError:
        return text
    if not math.isfinite(number) or "e" in text.lower():
        return text
    digits = len(text.lstrip("+-").replace(".", "").lstrip("0").rstrip("0") if "." in text
                 else text.lstrip("+-").lstrip("0"))
    return f"{number:.{SHOWN_DIGITS}g}" if "." in text and digits > SHOWN_DIGITS + 2 else text


def describe(values):
    """k=v pairs of a dict of axis values, for legends and titles (a structure's parameters
    as they are: "k=3"; each value by shown_value)."""
    parts = []
    for k, v in values.items():
        if v == "":
            continue
        part = v if k == "structure_params" else f"{axis_label(k)}={shown_value(v)}"
        # One axis written as several columns (image size: width and height) reads once,
        # "image size=64x48", not "image size=64, image size=48".
        if parts and k != "structure_params" and parts[-1][0] == axis_label(k):
            parts[-1] = (axis_label(k), parts[-1][1] + "x" + shown_value(v))
        else:
            parts.append((axis_label(k) if k != "structure_params" else None, part))
    return ", ".join(p for _, p in parts)
