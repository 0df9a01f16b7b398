"""Which record columns are work counters, which sub-pass each belongs to, and their units.

Nothing here lists counters: every `work_<subpass>_<name>` column a run has is a candidate,
and its unit comes from the schema (`ldmbench columns --json`, which `ldmbench model`
passes as --columns) or, for a column the schema does not know, from its name.
"""
import json
import re
import subprocess

TIME_SUFFIX = "_ms_median"
DISTRIBUTION_PARTS = ("mean", "p50", "p99", "max", "total")
# Sub-pass times that are sums of others: never fitted on their own counters.
SUM_SUBPASSES = ("build", "pass", "frame")
FRAME = "frame"


class ColumnsError(Exception):
    """The schema cannot be read; the message names the file or the binary."""


def load_schema(path=None, ldmbench=None):
    """{column: spec} from `ldmbench columns --json` (a file, else the binary), or {} when
    neither is available (units then come from the names)."""
    try:
        if path:
            with open(path) as f:
                document = json.load(f)
        elif ldmbench:
            out = subprocess.run([ldmbench, "columns", "--json"], check=True, capture_output=True,
                                 text=True, timeout=60).stdout
            document = json.loads(out)
        else:
            return {}
    except (OSError, ValueError, subprocess.SubprocessError) as e:
        if path:
            raise ColumnsError(f"{path}: cannot read the column schema: {e}")
        return {}
    return {c["name"]: c for c in document.get("columns", []) if "name" in c}


def subpasses_timed(header):
    """Every sub-pass with a `<subpass>_ms_median` column, in header order."""
    return [c[:-len(TIME_SUFFIX)] for c in header if c.endswith(TIME_SUFFIX)]


def subpass_of(column, subpasses):
    """The sub-pass of `work_<subpass>_<name>`: the longest timed sub-pass the name starts
    with (sub-pass names have underscores: prefix_sum, photon_tracing), else None."""
    best = None
    for s in subpasses:
        if column.startswith("work_" + s + "_") and (best is None or len(s) > len(best)):
            best = s
    return best


def work_columns(header, schema, driver_stats=False):
    """The work-counter columns of a header that can enter a linear model: totals (a
    distribution's `_total`; its mean, percentiles and max are not additive over a frame),
    never times (work_replay_ms) and, unless driver_stats, not the driver's pipeline
    statistics (`work_<subpass>_gl_*`: each driver counts its own way)."""
    names = set(header)
    distributions = {m.group(1) for c in header if (m := re.match(r"^(work_.+)_total$", c))
                     and m.group(1) + "_mean" in names}
    out = []
    for c in header:
        if not c.startswith("work_"):
            continue
        spec = schema.get(c)
        if spec is not None and (spec.get("group") not in (None, "work") or spec.get("unit") in ("ms", "s")):
            continue
        if c.endswith("_ms") or c == "work_replay_ms":
            continue
        base, _, part = c.rpartition("_")
        if base in distributions and part in DISTRIBUTION_PARTS and part != "total":
            continue
        if not driver_stats and re.match(r"^work_.+?_gl_", c):
            continue
        out.append(c)
    return out


def is_driver_stat(column):
    return re.match(r"^work_.+?_gl_", column) is not None


def singular(unit):
    """'fragments' -> 'fragment', 'entries' -> 'entry', 'bytes' -> 'byte'."""
    if not unit:
        return "count"
    words = unit.split()
    w = words[-1]
    if w.endswith("ies"):
        w = w[:-3] + "y"
    elif w.endswith("s") and not w.endswith("ss"):
        w = w[:-1]
    return " ".join(words[:-1] + [w])


# A column the schema does not describe: its unit from the counter's name, per the
# naming conventions of docs/reference/work-counters.md.
NAME_UNITS = (
    (r"bytes_", "bytes"), (r"atomic_", "atomics"), (r"fragments", "fragments"),
    (r"vertices", "vertices"), (r"invocations", "invocations"), (r"comparisons", "comparisons"),
    (r"moves", "moves"), (r"nodes_visited", "nodes"), (r"hash_probes", "slots"),
    (r"slots", "slots"), (r"pixels", "pixels"), (r"entries", "entries"), (r"steps", "steps"),
    (r"photons", "photons"), (r"rays", "rays"), (r"list_length", "entries"),
)


def unit_of(column, schema):
    """The counter's unit, singular ('fragment'), for 'ns per <unit>'."""
    spec = schema.get(column)
    if spec is not None and spec.get("unit"):
        return singular(spec["unit"])
    for pattern, unit in NAME_UNITS:
        if re.search(pattern, column):
            return singular(unit)
    return "count"
