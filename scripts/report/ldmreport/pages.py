"""The report's tables and its two pages, summary.md and index.html (relative links only).

Only `ok` records are ranked; lossy, invalid, failed and degenerate ones are listed as flagged, never as
measurements."""
import html
import math

import numpy as np

from . import style, ties


MIB = float(1 << 20)


def fmt_time(median, low, high):
    """A time to the digits its interval supports, with the interval's relative
    half-width ("12.3 ±3.2%"), as ldmbench's own tables print it; 4 digits without one."""
    if median is None or not np.isfinite(median):
        return "–"
    if low is None or high is None or not (np.isfinite(low) and np.isfinite(high)) or median <= 0:
        return fmt(median)
    half = max(median - low, high - median)
    if half <= 0:
        return fmt(median) + " ±0%"
    decimals = -math.floor(math.log10(half) + 1e-9)
    decimals = min(max(decimals, 1 - math.floor(math.log10(median) + 1e-9)), 9)
    text = f"{median:.{decimals}f}" if decimals >= 0 else f"{round(median, decimals):.0f}"
    relative = 100 * half / median
    return f"{text} ±{relative:.1f}%" if relative < 10 else f"{text} ±{relative:.0f}%"


def fmt(value, digits=4):
    """A number to `digits` significant digits ("–" for none), text unchanged."""
    if isinstance(value, str):
        return value
    if value is None or not np.isfinite(value):
        return "–"
    if value == 0:
        return "0"
    magnitude = math.floor(math.log10(abs(value)))
    if magnitude < -3 or magnitude >= 6:
        return f"{value:.{digits - 1}e}"
    return f"{value:.{max(digits - 1 - magnitude, 0)}f}"


def ranking_groups(table):
    """Rows that compare: per scene (and per device when the runs span several), and per
    reference image. Records scored against the same reference (the same ref_cache_key)
    estimate the same image, so their errors and times compare; an AO record and an
    indirect-light record, or AO at two d_max, do not. Without a reference: per pass."""
    scene = table.text("scene")
    if table.text("device").nunique() > 1:
        scene = scene + " on " + table.text("device")
    reference = table.text("ref_cache_key").replace("nan", "")
    passes = table.text("pass")
    identity = reference.where(reference != "", "pass " + passes)
    keys = scene + "|" + identity
    groups = []
    for key in dict.fromkeys(keys):
        in_group = keys == key
        label = scene[in_group].iloc[0] + ": " + "/".join(sorted(set(passes[in_group])))
        d_max = table.text("d_max")[in_group].replace("nan", "")
        if d_max.nunique() == 1 and d_max.iloc[0] and passes[in_group].isin(["ao", "hbao", "rtao"]).all():
            label += f" at d_max {d_max.iloc[0]}"
        if identity[in_group].iloc[0].startswith("pass "):
            label += " (no reference)"
        groups.append((label, in_group))
    return groups


def criteria(table):
    """[(name, values, restrict, higher_is_better, unit, measure(row))] of the best table:
    each criterion with the tie band of its values (ties.py)."""
    structure = table.has_structure()
    out = [
        ("fastest build", table.num("build_ms_median"), structure, False, "ms",
         lambda i: ties.time_measure(table, i, "build")),
        ("fastest query", table.query_ms(), None, False, "ms",
         lambda i: ties.time_measure(table, i, "pass")),
        ("fastest frame", table.num("frame_ms_median"), None, False, "ms",
         lambda i: ties.time_measure(table, i, "frame")),
        ("least memory allocated", table.num("bytes_allocated") / MIB, structure, False, "MiB",
         lambda i: ties.exact_measure(table.num("bytes_allocated")[i])),
        ("least memory used", table.num("bytes_used") / MIB, structure, False, "MiB",
         lambda i: ties.exact_measure(table.num("bytes_used")[i])),
    ]
    for prefix, metric, column in table.metric_columns():
        out.append((("best " if metric == "mssim" else "lowest ") + column, table.num(column), None,
                    metric == "mssim", "",
                    lambda i, c=column, p=prefix, m=metric: ties.error_measure(table, i, c, p, m)))
    return out


def shown_value(table, name, values, i, unit):
    if unit == "ms":
        subpass = {"fastest build": "build", "fastest query": "pass", "fastest frame": "frame"}[name]
        low, high = table.time_interval(subpass)
        return f"{fmt_time(values[i], low[i], high[i])} ms"
    return f"{fmt(values[i])} {unit}".strip()


def best_rows(table):
    """The best-per-criterion table: [criterion, group, configuration(s), run, value]. A
    record within the best's tie band (ties.py: overlapping time intervals, errors within
    the reference noise, equal bytes) is named beside it: a tie is shown as a tie."""
    measured = table.measured()
    rows = []
    for group, in_group in ranking_groups(table):
        for name, values, restrict, higher, unit, measure in criteria(table):
            mask = in_group & measured & values.notna()
            if restrict is not None:
                mask &= restrict
            if not mask.any():
                continue
            index = list(values[mask].index)
            winners = [index[k] for k in ties.best_and_tied([measure(i) for i in index], higher)]
            best = winners[0]
            names = table.text("config_id")[best]
            if len(winners) > 1:
                others = [table.text("config_id")[i] for i in winners[1:]]
                shown = others[:4] + ([f"{len(others) - 4} more"] if len(others) > 4 else [])
                names += " — tied with " + ", ".join(shown)
            rows.append([name, group, names, table.text("run")[best], shown_value(table, name, values, best, unit)])
    return rows


CHOOSE_HEADER = ["compared within", "configuration", "run", "frame ms", "MiB allocated", "error",
                 "best in (tied: within the uncertainty)"]
CHOOSE_CAP = 8  # rows per group shown in the front table; the details list the rest


def choose_criteria(table):
    """The three criteria of the front table: frame time (with its interval), memory (the
    structure's bytes allocated: none for a pass without a structure), and the error (mse,
    else mssim, within the reference noise). Returns [(name, higher, measure(row), shown(row))]."""
    allocated = table.num("bytes_allocated").fillna(0)
    low, high = table.time_interval("frame")
    time = table.num("frame_ms_median")
    out = [("time", False, lambda i: ties.time_measure(table, i, "frame"),
            lambda i: fmt_time(time[i], low[i], high[i])),
           ("memory", False, lambda i: ties.exact_measure(allocated[i]),
            lambda i: fmt(allocated[i] / MIB) if table.has_structure()[i] else "– (no structure)")]
    metrics = {metric: (prefix, column) for prefix, metric, column in table.metric_columns()
               if prefix == ""}
    for metric in ("mse", "mssim"):
        if metric in metrics:
            prefix, column = metrics[metric]
            values = table.num(column)
            out.append((column, metric == "mssim",
                        lambda i, c=column, p=prefix, m=metric: ties.error_measure(table, i, c, p, m),
                        lambda i, c=column, v=values: f"{c} {fmt(v[i])}"))
            break
    return out


def choose_rows(table):
    """The front table: per scene and reference (ranking_groups), the ok configurations no
    other beats in time, memory and error at once beyond the tie bands (ties.py), fastest
    first; each with the criteria it is best in, "(tied)" where another front member cannot
    be told from it there. Returns (rows, notes about cut groups)."""
    criteria = choose_criteria(table)
    higher = [h for _, h, _, _ in criteria]
    measured = table.measured() & table.num("frame_ms_median").notna()
    rows, cut = [], []
    for group, in_group in ranking_groups(table):
        index = list(table.df.index[in_group & measured])
        if len(criteria) == 3:
            error_column = criteria[2][0]
            index = [i for i in index if np.isfinite(table.num(error_column)[i])]
        if not index:
            continue
        points = [[measure(i) for _, _, measure, _ in criteria] for i in index]
        front = ties.pareto_front_all(points, higher)
        best = [set(front[k] for k in ties.best_and_tied([points[f][c] for f in front], higher[c]))
                for c in range(len(criteria))]
        for f in front[:CHOOSE_CAP]:
            i = index[f]
            best_in = [criteria[c][0] if criteria[c][0] in ("time", "memory") else "error"
                       for c in range(len(criteria)) if f in best[c]]
            tied_in = [c for c in range(len(criteria)) if f in best[c] and len(best[c]) > 1]
            text = ", ".join(name + (" (tied)" if c in tied_in else "")
                             for c, name in zip([c for c in range(len(criteria)) if f in best[c]], best_in))
            several_runs = table.text("run").nunique() > 1
            same = [table.text("config_id")[index[g]] +
                    (f" ({table.text('run')[index[g]]})" if several_runs else "")
                    for g in front if g != f and ties.tied_in_all(points[f], points[g])]
            if same:
                text += ("; " if text else "") + "tied in all with " + ", ".join(same[:2]) + \
                    (f" and {len(same) - 2} more" if len(same) > 2 else "")
            rows.append([group, table.text("config_id")[i], table.text("run")[i],
                         *[shown(i) for _, _, _, shown in criteria]] + [""] * (3 - len(criteria)) +
                        [text or "trade-off (none best alone)"])
        if len(front) > CHOOSE_CAP:
            cut.append(f"{group}: {len(front)} configurations on the front, the {CHOOSE_CAP} "
                       "fastest shown (the rest: All configurations)")
    return rows, cut


def choose_table(table):
    """The front table's header and rows; without the run column for a single run."""
    rows, cut = choose_rows(table)
    if table.text("run").nunique() > 1:
        return CHOOSE_HEADER, rows, cut
    drop = CHOOSE_HEADER.index("run")
    return ([h for k, h in enumerate(CHOOSE_HEADER) if k != drop],
            [[c for k, c in enumerate(r) if k != drop] for r in rows], cut)


CHOOSE_INTRO = ("Per scene and reference image, the `ok` configurations that no other beats "
                "in frame time, memory (bytes the structure allocates) and error at once: "
                "choose among these. A difference within the measurement's uncertainty is a "
                "tie (overlapping 95 % time intervals, errors within the reference's noise, "
                "equal bytes), and tied configurations all stay; \"best in\" names the "
                "criteria a configuration is best in, \"(tied)\" where other rows cannot be "
                "told from it there. The details follow: best per criterion, flagged "
                "configurations, figures, every configuration.")


def flagged_rows(table):
    """Every record not ranked: lossy, invalid, failed, and degenerate (measured, but of
    nothing: its `degenerate` column says why)."""
    status = table.status()
    return [[table.text("run")[i], table.text("config_id")[i], status[i],
             table.text("status_detail")[i]] for i in table.df.index if status[i] != "ok"]


def configuration_rows(table):
    """Every configuration: the compact columns of the end-of-run table."""
    metric_columns = [c for _, _, c in table.metric_columns()]
    header = ["run", "configuration", "status", "build ms", "query ms", "frame ms",
              "MiB allocated", "MiB used"] + metric_columns
    rows = []
    times = {s: (table.num(f"{s}_ms_median") if s != "pass" else table.query_ms(), *table.time_interval(s))
             for s in ("build", "pass", "frame")}
    allocated, used = table.num("bytes_allocated") / MIB, table.num("bytes_used") / MIB
    for i in table.df.index:
        status = table.status()[i]
        shown = [fmt_time(median[i], low[i], high[i]) for median, low, high in times.values()]
        rows.append([table.text("run")[i], table.text("config_id")[i],
                     status if status == "ok" else f"⚠ {status}",
                     *shown, fmt(allocated[i]),
                     fmt(used[i])] + [fmt(table.num(c)[i]) for c in metric_columns])
    return header, rows


def warnings(table, runs_info):
    """What the reader must know before reading any number: records measured once (their
    intervals cover the frame-to-frame variation within one process, not run-to-run), and
    runs resumed by another process (whose times are ranked as one run)."""
    out = []
    repetitions = table.num("repetitions")
    once = table.df.index[(repetitions.fillna(1) <= 1)]
    if len(once):
        out.append(f"{len(once)} of {len(table.df)} records were measured in one repetition: "
                   "their time intervals cover the variation between frames within one run, not "
                   "between runs (another run of the same sweep may differ by more); measure with "
                   "--repetitions 3 or more before trusting a ranking by time.")
    for r in runs_info:
        resumed = str(r.get("resumed_records", "") or "")
        if resumed not in ("", "0"):
            out.append(f"run {r['label']} was resumed: {resumed} of its records come from an earlier "
                       f"process than the one started {r.get('started', '') or '(unknown)'}, and "
                       "their times are ranked with this one's as one run.")
    return out


def runs_rows(runs_info):
    return [[r["label"], r["records_file"], str(r["records"]), r.get("device", ""),
             r.get("git_commit", ""), r.get("command", "")] for r in runs_info]


RUNS_HEADER = ["run", "records", "configurations", "device", "commit", "command"]
BEST_HEADER = ["criterion", "compared within", "configuration (and those tied with it)", "run", "value"]
FLAGGED_HEADER = ["run", "configuration", "status", "why"]


def markdown_table(header, rows):
    def cell(text):
        return str(text).replace("|", "\\|").replace("\n", " ")
    lines = ["| " + " | ".join(cell(h) for h in header) + " |",
             "| " + " | ".join("---" for _ in header) + " |"]
    lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def html_table(header, rows, flag_column=None):
    out = ['<div class="scroll"><table>', "<tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in header) + "</tr>"]
    for row in rows:
        flagged = flag_column is not None and str(row[flag_column]).startswith("⚠")
        cls = ' class="flagged"' if flagged else ""
        out.append(f"<tr{cls}>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>")
    out.append("</table></div>")
    return "\n".join(out)


def sections(figures):
    order = []
    for f in figures:
        if f["section"] not in order:
            order.append(f["section"])
    return [(s, [f for f in figures if f["section"] == s]) for s in order]


def write_markdown(path, title, runs_info, table, figures, notes):
    header, config_rows = configuration_rows(table)
    flagged = flagged_rows(table)
    choose_header, choose, cut = choose_table(table)
    parts = [f"# {title}", "",
             *[f"> **Warning:** {w}\n" for w in warnings(table, runs_info)],
             "## Choose a structure", "", CHOOSE_INTRO, "",
             markdown_table(choose_header, choose) if choose else "No ok record to choose from.", ""]
    parts += [f"- {c}" for c in cut] + ([""] if cut else [])
    parts += ["Generated by `ldmbench report`; every figure regenerates from `tidy.csv` "
             "(`scripts/report/ldmbench_report.py --from-csv tidy.csv --out DIR`). "
             "Only `ok` records are ranked; lossy, invalid, failed and degenerate ones are flagged.", "",
             "## Runs", "", markdown_table(RUNS_HEADER, runs_rows(runs_info)), "",
             "## Best per criterion (ok records only)", "",
             markdown_table(BEST_HEADER, best_rows(table)) if best_rows(table) else
             "No ok record to rank.", "",
             f"## Flagged configurations ({len(flagged)}: not ranked)", ""]
    parts += [markdown_table(FLAGGED_HEADER, flagged) if flagged else "None.", ""]
    parts += ["## Notes", ""] + ([f"- {n}" for n in notes] or ["None."]) + [""]
    for section, figs in sections(figures):
        parts += [f"## {section}", ""]
        for f in figs:
            parts += [f"### {f['title']}", "", f"![{f['title']}]({style.page_file(f['files'])})", "",
                      f["caption"], ""]
    parts += ["## All configurations", "", markdown_table(header, config_rows), ""]
    with open(path, "w") as out:
        out.write("\n".join(parts))


# Readable from a phone's width up: wide tables scroll in their own box, images shrink.
STYLE = """body{font-family:sans-serif;margin:2em auto;padding:0 1em;max-width:1400px}
.scroll{overflow-x:auto;max-width:100%}
@media (max-width:600px){body{margin:0.5em auto}}
table{border-collapse:collapse;font-size:12px;margin-bottom:1em}
td,th{border:1px solid #ccc;padding:2px 6px;text-align:left}
tr.flagged td{background:#fde8e8}
p.warning{background:#fff3cd;border:1px solid #e0c060;padding:0.5em}
img{max-width:100%;border:1px solid #eee}
figure{margin:1em 0 2em 0}figcaption{font-size:12px;color:#444}"""


def write_html(path, title, runs_info, table, figures, notes):
    header, config_rows = configuration_rows(table)
    flagged = flagged_rows(table)
    best = best_rows(table)
    choose_header, choose, cut = choose_table(table)
    e = html.escape
    parts = ["<!DOCTYPE html>", "<html><head><meta charset=\"utf-8\">",
             '<meta name="viewport" content="width=device-width, initial-scale=1">',
             f"<title>{e(title)}</title><style>{STYLE}</style></head><body>",
             f"<h1>{e(title)}</h1>",
             *[f'<p class="warning"><b>Warning:</b> {e(w)}</p>' for w in warnings(table, runs_info)],
             "<p>Generated by <code>ldmbench report</code>. Data: <a href=\"tidy.csv\">tidy.csv</a> "
             "(every figure regenerates from it); summary: <a href=\"summary.md\">summary.md</a>. "
             "Only <code>ok</code> records are ranked; lossy, invalid, failed and degenerate ones are "
             "flagged (hollow markers, hatched bars, red rows).</p>",
             "<h2>Choose a structure</h2>", f"<p>{e(CHOOSE_INTRO.replace('`', ''))}</p>",
             html_table(choose_header, choose) if choose else "<p>No ok record to choose from.</p>",
             "".join(f"<p>{e(c)}</p>" for c in cut),
             "<h2>Runs</h2>", html_table(RUNS_HEADER, runs_rows(runs_info)),
             "<h2>Best per criterion (ok records only)</h2>",
             html_table(BEST_HEADER, best) if best else "<p>No ok record to rank.</p>",
             f"<h2>Flagged configurations ({len(flagged)}: not ranked)</h2>",
             html_table(FLAGGED_HEADER, flagged) if flagged else "<p>None.</p>",
             "<h2>Notes</h2>",
             "<ul>" + "".join(f"<li>{e(n)}</li>" for n in notes) + "</ul>" if notes else "<p>None.</p>"]
    for section, figs in sections(figures):
        parts.append(f"<h2>{e(section)}</h2>")
        for f in figs:
            links = " ".join(f'<a href="{e(p)}">{e(p.rsplit(".", 1)[1])}</a>' for p in f["files"])
            parts.append(f'<figure><img src="{e(style.page_file(f["files"]))}" alt="{e(f["title"])}">'
                         f'<figcaption><b>{e(f["title"])}</b>: {e(f["caption"])} {links}'
                         "</figcaption></figure>")
    parts += ["<h2>All configurations</h2>", html_table(header, config_rows, flag_column=2),
              "</body></html>"]
    with open(path, "w") as out:
        out.write("\n".join(parts) + "\n")



