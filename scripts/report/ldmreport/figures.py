"""The report's plots, each drawn from the tidy table alone (matplotlib, Agg backend).

Every function takes the Table and a Canvas (which names, saves and lists figures and
collects notes) and draws what the data supports; a plot whose x axis has fewer than two
distinct values is skipped with a note, never drawn empty. Records that are not `ok`
(lossy, invalid, failed) are drawn hollow, hatched or faded, stay off Pareto fronts and out
of fitted slopes."""
import math
import os
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import matplotlib.transforms  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
import numpy as np  # noqa: E402

from . import style, ties  # noqa: E402
from .table import axis_label, describe, sort_key  # noqa: E402

MIB = float(1 << 20)
MARKERS = "osD^vP*Xph<>"
RUN_MARKERS = "o^sDvP"  # one per run when several are drawn
LINE_STYLES = ["-", "--", "-.", (0, (1, 1))]
LABEL_OFFSETS = [(2, 2), (2, -2), (-2, 2), (-2, -2)]  # points; one per run
HOLLOW_NOTE = "hollow markers: lossy / invalid / failed / degenerate (not ranked, off the front and fits)"


class Canvas:
    """Where figures go: <out>/figures/<name>.<format> for each output format (style.py:
    PNG, SVG, PDF), listed for the pages."""

    def __init__(self, out_dir, formats=("png",), dpi=200):
        self.out_dir, self.formats, self.dpi = out_dir, style.written_formats(formats), dpi
        self.figures, self.notes = [], []
        os.makedirs(os.path.join(out_dir, "figures"), exist_ok=True)

    def save(self, fig, name, title, caption, section, tight=True):
        if tight:  # titles and labels of stacked panels must not overlap
            fig.tight_layout()
        thin_tick_labels(fig)
        files = []
        for ext in self.formats:
            rel = f"figures/{name}.{ext}"
            # PDF and SVG without a creation date: the same data gives the same file
            metadata = {"CreationDate": None} if ext == "pdf" else {"Date": None} if ext == "svg" else None
            fig.savefig(os.path.join(self.out_dir, rel), dpi=self.dpi, bbox_inches="tight",
                        metadata=metadata)
            files.append(rel)
        self.inspect(fig, name)
        plt.close(fig)
        self.figures.append({"section": section, "name": name, "title": title,
                             "caption": caption, "files": files})

    def inspect(self, fig, name):
        """Called with every figure before it is closed (tests look at its artists)."""

    def note(self, text):
        self.notes.append(text)


def thin_tick_labels(fig):
    """Minor tick labels (a narrow log axis labels them: 0.8, 0.9, 1) left out where they
    would overlap a major tick label or a minor one kept before them: the formatter is
    wrapped to give "" at those values (tick labels are made anew at every draw)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            drawn = [t for t in axis._update_ticks() if t.label1.get_visible() and t.label1.get_text().strip()]
            majors = set(axis.get_majorticklocs())
            kept = [t.label1.get_window_extent(renderer) for t in drawn if t.get_loc() in majors]
            hidden = []
            for t in drawn:
                if t.get_loc() in majors:
                    continue
                box = t.label1.get_window_extent(renderer)
                if any(box.overlaps(k) for k in kept):
                    hidden.append(t.get_loc())
                else:
                    kept.append(box)
            if hidden:
                original = axis.get_minor_formatter()
                axis.set_minor_formatter(matplotlib.ticker.FuncFormatter(
                    lambda v, pos, f=original, h=tuple(hidden): "" if any(
                        math.isclose(v, x, rel_tol=1e-9) for x in h) else f(v, pos)))


def method_styles(table):
    """One colour and marker per method, the same in every figure."""
    methods = sorted(set(table.methods()))
    colours = series_colours(len(methods))  # tab20 past ten: no two methods share a colour
    return {m: (colours[i], MARKERS[i % len(MARKERS)]) for i, m in enumerate(methods)}


def run_markers(table):
    """One marker per run when the report draws several (colour stays the method's), so that
    the runs of a two-run report are told apart in every scatter; {} for one run."""
    runs = list(dict.fromkeys(table.text("run")))
    return {r: RUN_MARKERS[i % len(RUN_MARKERS)] for i, r in enumerate(runs)} if len(runs) > 1 else {}


def series_colours(n):
    cmap = plt.get_cmap("tab10" if n <= 10 else "tab20")
    return [cmap(i % cmap.N) for i in range(n)]


def series_styles(n):
    """(colour, marker, line style) per series: neighbours differ in all three, so that two
    series that run close (or on top of each other) both stay visible."""
    return [(c, MARKERS[i % len(MARKERS)], LINE_STYLES[i % len(LINE_STYLES)])
            for i, c in enumerate(series_colours(n))]


def subplot_grid(count, max_columns=2, height=style.PANEL_HEIGHT, width=None):
    """Panels at a paper's sizes (style.py): one column wide for one panel, the text width
    for two side by side (or `width`), more rows below."""
    columns = min(count, max_columns)
    rows = math.ceil(count / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(width or style.figure_width(columns), height * rows),
                             squeeze=False)
    for extra in axes.flat[count:]:
        extra.set_visible(False)
    return fig, list(axes.flat[:count])


def plain_log_ticks(ax, axis_values=None):
    """Tick labels as plain numbers on log axes (8, 16, 32 rather than 8x10^0), at the data's
    own x values where there are few."""
    formatter = matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}")
    for axis, limits in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
        if axis.get_scale() == "log":
            axis.set_major_formatter(formatter)
            # within a decade the minor ticks are the only ones: label them
            narrow = limits[0] > 0 and limits[1] / limits[0] < 10
            axis.set_minor_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:.2g}")
                                     if narrow else matplotlib.ticker.NullFormatter())
    if axis_values is not None and ax.xaxis.get_scale() == "log":
        values = sorted(set(v for v in axis_values if np.isfinite(v) and v > 0))
        if len(values) <= 8:
            ax.set_xticks(values)
            ax.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())


LEGEND_CHARS_PER_INCH = 22  # characters of a 6 pt legend entry per inch, about (style.RC)
LEGEND_DROP_PT = 30  # a legend below the axes starts this far below them


def set_panel_title(ax, title):
    """The panel's title wrapped to the panel's width: a long one (scene, settings, passes)
    would otherwise run into the title of the panel beside it."""
    width_in = ax.get_position().width * ax.figure.get_size_inches()[0]
    size_pt = matplotlib.font_manager.FontProperties(size=matplotlib.rcParams["axes.titlesize"]).get_size_in_points()
    # 0.6 em a character on average, and 10 % spare: the layout may narrow the axes later
    chars = max(16, int(0.9 * width_in * 72 / (0.6 * size_pt)))
    ax.set_title(textwrap.fill(title, chars, break_long_words=False))


def place_legend(ax, inside=4, columns=1):
    """A legend inside the axes when short, below them when long (never beside: the figure
    keeps its paper width), so that it never hides the data."""
    labels = ax.get_legend_handles_labels()[1]
    entries = len(labels)
    if not entries:
        return
    if entries <= inside and max(len(t) for t in labels) <= 32:
        ax.legend(loc="best", framealpha=0.8)
    else:
        # Below the axes, each entry wrapped to the axes' width (its columns' share): a long
        # entry would run into the legend of the panel beside it.
        handles, labels = ax.get_legend_handles_labels()
        width_in = ax.get_position().width * ax.figure.get_size_inches()[0]
        chars = max(16, int(width_in * LEGEND_CHARS_PER_INCH / columns) - 4)
        wrapped = [textwrap.fill(t, chars, break_long_words=False) for t in labels]
        # its top a fixed distance below the axes: under the tick labels and the axis label
        # (7 pt and 8 pt with their pads), whatever the panel's height
        below = matplotlib.transforms.offset_copy(ax.transAxes, fig=ax.figure, y=-LEGEND_DROP_PT, units="points")
        ax.legend(handles, wrapped, loc="upper center", bbox_to_anchor=(0.5, 0.0), bbox_transform=below,
                  ncol=columns, frameon=False)


def figure_legend(fig, handles):
    """One legend for every panel of a figure, below them (the figure keeps its width)."""
    if handles:  # as many columns as the figure's width holds (a column of entries: ~2.3 in)
        columns = max(1, min(3, int(fig.get_size_inches()[0] / 2.3)))
        fig.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                   ncol=min(columns, len(handles)), frameon=False)


def wide_span(values):
    """Whether positive values span enough for a log axis to read better."""
    values = values[np.isfinite(values) & (values > 0)]
    return len(values) > 1 and values.max() / values.min() > 30


def scatter(ax, x, y, colour, marker, measured):
    """Filled markers for ok records, hollow ones for the rest (HOLLOW_NOTE)."""
    ax.scatter(x[measured], y[measured], color=colour, marker=marker, s=16, zorder=3)
    if (~measured).any():
        ax.scatter(x[~measured], y[~measured], facecolors="none", edgecolors=[colour],
                   marker=marker, s=16, zorder=3, linewidths=0.8)


RING_SIZE = 45  # points^2: the ring around a point the front table lists


def error_bands(table, rows, column, prefix, metric, values):
    """Error bars (2 x n) of an error axis: the reference's own noise, the tie band of
    ties.error_measure (ref_noise_mse for MSE; (1 - ref_noise_mssim) / 4 for MSSIM); the
    lower bar kept above zero (log axes). Zeros where a record has none."""
    band = np.array([ties.error_measure(table, r, column, prefix, metric).band for r in rows], dtype=float)
    band = np.nan_to_num(band)
    below = np.minimum(band, np.abs(values) * 0.999) if metric == "mse" else band
    return np.nan_to_num(np.vstack([below, band]))


def time_errors(table, subpass, rows, values):
    """Asymmetric error bars (2 x n) of a sub-pass's 95 % interval over `rows`; zeros where
    a record has none."""
    low, high = table.time_interval(subpass)
    below = (values - low[rows].to_numpy()).clip(min=0)
    above = (high[rows].to_numpy() - values).clip(min=0)
    return np.nan_to_num(np.vstack([below, above]))


# Axes a point's label never repeats: they are the panel's (scene), the legend's (structure,
# pass, run: marker and colour) or always shown (N, R_LDM).
NOT_IN_POINT_LABELS = {"scene", "structure", "pass", "run", "sweep", "n_views", "r_ldm"}


def set_varying(table, rows, candidates):
    """The candidate axes taking two or more values over the `rows` (a mask) that have one:
    an axis only some records have (d_max of AO beside indirect light) does not split them."""
    out = []
    for a in candidates:
        if table.has(a):
            values = table.axis_values(a)[rows]
            if values[values != ""].nunique() > 1:
                out.append(a)
    return out


def label_axes(table, rows):
    """The axes besides N and R_LDM whose values differ among `rows` (a mask): the
    parameter a panel varies, which each point's label then names."""
    return [a for a in set_varying(table, rows, table.axes()) if a not in NOT_IN_POINT_LABELS]


def point_label(table, i, varying=(), several_runs=None):
    """What tells a point from its neighbours: N and R_LDM for a structure (the pass for a
    pass without one), the values of the `varying` axes, and the run when the panel draws
    several (`several_runs`; default: whether the table holds several)."""
    parts = []
    if table.has_structure()[i]:
        parts += [f"N{table.text('n_views')[i]}", f"R{table.text('r_ldm')[i]}"]
    else:
        parts.append(table.text("pass")[i])
    parts += [describe({a: table.axis_values(a)[i]}) for a in varying if table.axis_values(a)[i]]
    if several_runs if several_runs is not None else table.text("run").nunique() > 1:
        parts.append(table.text("run")[i])
    return " ".join(p for p in parts if p)


def comparable_groups(table, prefix, column):
    """Rows scored against one reference, per scene (and per driver and device when the
    records span several: Table.platform): their errors and times compare. Returns
    [(title, mask)], titles after style.panel_title."""
    scored = table.num(column).notna() & np.isfinite(table.num("frame_ms_median"))
    key_column = table.reference_key_column(prefix)
    scene = table.text("scene")
    if table.platform()[scored].nunique() > 1:
        scene = scene + " on " + table.platform()
    keys = scene + "|" + (table.text(key_column) if key_column else
                          table.text("width") + "x" + table.text("height"))
    masks = [scored & (keys == k) for k in dict.fromkeys(keys[scored])]
    firsts = [m[m].index[0] for m in masks]
    candidates = ["width", "height", "visibility", "d_max"] + table.extra_axes
    differing = [a for a in candidates
                 if len({table.axis_values(a)[i] for i in firsts}) > 1]
    passes = [", ".join(dict.fromkeys(table.text("pass")[m])) for m in masks]
    titles = []
    for i, m, p in zip(firsts, masks, passes):
        titles.append(style.panel_title(scene[i],
                                        {a: table.axis_values(a)[i] for a in differing},
                                        p if len(set(passes)) > 1 else None))
    return list(zip(titles, masks))


def legend_handles(entries):
    """Legend handles for (label, colour, marker, line style, filled) entries."""
    return [Line2D([], [], color=colour, marker=marker, linestyle=line or "none",
                   markerfacecolor=colour if filled else "none", markersize=4, label=label)
            for label, colour, marker, line, filled in entries]


def draw_tradeoffs(table, canvas):
    """Time per frame against each image metric, per method (colour) and run (marker), each
    point labelled and with its time interval as an error bar, and the Pareto front of the
    ok records (faster and better)."""
    from .pages import front_table_members
    styles = method_styles(table)
    markers_of_run = run_markers(table)
    listed = front_table_members(table)  # ringed: the front table lists them
    methods = table.methods()
    runs = table.text("run")
    measured = table.measured().to_numpy()
    time = table.num("frame_ms_median")
    if not table.metric_columns():
        canvas.note("time vs image metrics: skipped, the records hold no mse or mssim "
                    "(a run with --no-reference)")
    for prefix, metric, column in table.metric_columns():
        groups = comparable_groups(table, prefix, column)
        if not groups:
            canvas.note(f"time vs {column}: skipped, no record has both a frame time and {column}")
            continue
        higher = metric == "mssim"
        fig, axes = subplot_grid(len(groups))
        drawn_methods, drawn_runs, any_hollow, any_ringed = [], [], False, False
        for ax, (title, mask) in zip(axes, groups):
            x, y = time[mask].to_numpy(), table.num(column)[mask].to_numpy()
            ok, m, rn = measured[mask.to_numpy()], methods[mask].to_numpy(), runs[mask].to_numpy()
            any_hollow |= not ok.all()
            rows = list(mask[mask].index)
            errors = time_errors(table, "frame", mask, x)
            y_errors = error_bands(table, rows, column, prefix, metric, y)
            for method in sorted(set(m)):
                colour, marker = styles[method]
                drawn_methods += [method] if method not in drawn_methods else []
                for run in dict.fromkeys(rn):
                    sel = (m == method) & (rn == run)
                    if not sel.any():
                        continue
                    drawn_runs += [run] if run not in drawn_runs else []
                    ax.errorbar(x[sel], y[sel], xerr=errors[:, sel], yerr=y_errors[:, sel], fmt="none",
                                ecolor=colour, elinewidth=0.7, capsize=1.5, alpha=0.8, zorder=2)
                    scatter(ax, x[sel], y[sel], colour, markers_of_run.get(run, marker), ok[sel])
            ok_rows = [r for r, good in zip(rows, ok) if good]
            if ok_rows:
                xs = [ties.time_measure(table, r, "frame") for r in ok_rows]
                ys = [ties.error_measure(table, r, column, prefix, metric) for r in ok_rows]
                front = ties.pareto_front(xs, ys, higher)
                px = np.array([xs[k].value for k in front])
                py = np.array([ys[k].value for k in front])
                ax.step(px, py, where="post", color="black", linestyle="--", linewidth=0.8, zorder=2)
            ringed = [k for k, r in enumerate(rows) if r in listed]
            if ringed:
                ax.scatter(x[ringed], y[ringed], s=RING_SIZE, facecolors="none", edgecolors="black",
                           linewidths=0.7, zorder=4)
                any_ringed = True
            # Every point is labelled in small panels; in crowded ones the front's.
            varying = label_axes(table, mask)
            labelled = rows if len(rows) <= 30 else [ok_rows[k] for k in front] if ok_rows else []
            run_index = {run: k for k, run in enumerate(dict.fromkeys(runs))}
            for r in labelled:
                # each run's labels on its own side of the point, so that two runs' don't overlap
                offset = LABEL_OFFSETS[run_index[runs[r]] % len(LABEL_OFFSETS)]
                ax.annotate(point_label(table, r, varying, len(set(rn)) > 1),
                            (time[r], table.num(column)[r]),
                            fontsize=style.POINT_LABEL_SIZE, xytext=offset,
                            ha="left" if offset[0] >= 0 else "right",
                            va="bottom" if offset[1] >= 0 else "top",
                            textcoords="offset points", alpha=0.85)
            if wide_span(x):
                ax.set_xscale("log")
            if metric == "mse" and wide_span(y):
                ax.set_yscale("log")
            plain_log_ticks(ax)
            ax.set_xlabel("frame time, median (ms)")
            ax.set_ylabel(column + (" (higher is better)" if higher else " (lower is better)"))
            set_panel_title(ax, title)
            ax.grid(alpha=0.3)
        entries = [(method, styles[method][0], styles[method][1] if not markers_of_run else "s",
                    None, True) for method in drawn_methods]
        entries += [(f"run {run}", "0.35", markers_of_run[run], None, True)
                    for run in drawn_runs if markers_of_run]
        entries.append(("Pareto front, time and this error (ok; ties kept)", "black", None, "--", True))
        handles = legend_handles(entries)
        if any_ringed:
            handles.append(Line2D([], [], color="black", marker="o", linestyle="none", markerfacecolor="none",
                                  markersize=RING_SIZE ** 0.5, markeredgewidth=0.7,
                                  label="ringed: on the front table (time, memory, error)"))
        if any_hollow:
            handles += legend_handles([("hollow: not ok", "0.35", "o", None, False)])
        figure_legend(fig, handles)
        name = f"tradeoff-time-vs-{column}"
        canvas.save(fig, name, f"Frame time vs {column}",
                    f"Per method (colour{', and run: marker' if markers_of_run else ''}), frame "
                    f"time with its 95 % interval as horizontal error bars, the error with the "
                    f"reference's own noise (its tie band: ref_noise_mse, or (1 - ref_noise_mssim) / 4) "
                    f"as vertical ones; the dashed line is the Pareto "
                    f"front of the ok records in time and this error: nothing is faster or better beyond the "
                    f"uncertainty (overlapping time intervals, errors within the reference "
                    f"noise are ties, and tied records all stay on it); ringed: the configurations "
                    f"the front table lists (its front is over time, memory and error at once, so it "
                    f"holds every point of the dashed front and may hold more); points are labelled "
                    f"N, R_LDM, the parameters that vary in the panel"
                    f"{' and the run' if markers_of_run else ''}; {HOLLOW_NOTE}.", "Trade-offs")


def series_masks(table, rows, series_axes):
    """Split `rows` into series by method and the axes among `series_axes` that vary there:
    [(label, mask)] in a stable order."""
    methods = table.methods()
    varying = set_varying(table, rows, series_axes)
    keys = methods.copy()
    for a in varying:
        keys = keys + "|" + table.axis_values(a)
    out = []
    for key in sorted(set(keys[rows]), key=lambda k: [sort_key(p) for p in k.split("|")]):
        mask = rows & (keys == key)
        first = mask[mask].index[0]
        values = {a: table.axis_values(a)[first] for a in varying}
        text = describe(values)
        out.append((methods[first] + (f" ({text})" if text else ""), mask))
    return out


def x_is_a_range(table, canvas, rows, x_column, what):
    """Whether `x_column` takes two or more values over `rows`; else a note."""
    values = sorted(set(table.num(x_column)[rows].dropna()))
    if len(values) >= 2:
        return True
    shown = ", ".join(f"{v:g}" for v in values) or "none"
    canvas.note(f"{what}: skipped, {axis_label(x_column)} takes fewer than two values "
                f"({shown})")
    return False


def merge_coinciding(curves):
    """Curves [(label, data)] whose data (a tuple of arrays) are equal merged into one, their
    labels joined with " = ": a line drawn on top of another would hide it, and two legend
    entries for one line would say nothing."""
    merged = []
    for label, data in curves:
        for entry in merged:
            if len(entry[1]) == len(data) and all(
                    a.shape == b.shape and np.allclose(a, b, rtol=1e-9, atol=0, equal_nan=True)
                    for a, b in zip(entry[1], data)):
                entry[0].append(label)
                break
        else:
            merged.append(([label], data))
    return [(merged_label(labels), data) for labels, data in merged]


def merged_label(labels):
    """"a (x) = b (x) = a (y)" written once per method and qualifier: "a = b (x; y)"."""
    if len(labels) == 1:
        return labels[0]
    methods, qualifiers = [], []
    for label in labels:
        method, _, qualifier = label.partition(" (")
        methods += [method] if method not in methods else []
        qualifier = qualifier.rstrip(")")
        qualifiers += [qualifier] if qualifier and qualifier not in qualifiers else []
    return " = ".join(methods) + (f" ({'; '.join(qualifiers)})" if qualifiers else "")


def draw_memory(table, canvas):
    """Bytes allocated (solid) and used (dashed) by the structures against N and R_LDM."""
    allocated, used = table.num("bytes_allocated") / MIB, table.num("bytes_used") / MIB
    measured = table.measured()
    for x_column, other in (("n_views", "r_ldm"), ("r_ldm", "n_views")):
        what = f"memory vs {axis_label(x_column)}"
        rows = table.has_structure() & (table.num(x_column) > 0) & allocated.notna()
        if not x_is_a_range(table, canvas, rows, x_column, what):
            continue
        scenes = list(dict.fromkeys(table.text("scene")[rows]))
        fig, axes = subplot_grid(len(scenes), max_columns=1, height=style.PANEL_HEIGHT + 0.6)
        for ax, scene in zip(axes, scenes):
            in_scene = rows & (table.text("scene") == scene)
            curves = []
            for label, mask in series_masks(table, in_scene, [other, "structure_params",
                                                              "sizing_policy", "payload", "run"]):
                x = table.num(x_column)[mask]
                first = ~x.duplicated()  # memory does not depend on the pass's settings
                order = np.argsort(x[first].to_numpy())
                curves.append((label, (x[first].to_numpy()[order],
                                       allocated[mask][first].to_numpy()[order],
                                       used[mask][first].to_numpy()[order],
                                       measured[mask][first].to_numpy()[order].astype(float))))
            curves = merge_coinciding(curves)
            for (colour, marker, _), (label, (xs, ys_allocated, ys_used, ok)) in zip(
                    series_styles(len(curves)), curves):
                ok = ok.astype(bool)
                # used = allocated (a structure sized exactly): one line, said in the legend
                same = np.allclose(ys_allocated, ys_used, rtol=1e-9, atol=0, equal_nan=True)
                for ys, line in ((ys_allocated, "-"),) + ((() if same else ((ys_used, "--"),))):
                    ax.plot(xs, ys, line, color=colour, linewidth=1.0,
                            label=(label + (" (used = allocated)" if same else "")) if line == "-" else None)
                    scatter(ax, xs, ys, colour, marker, ok)
            if wide_span(table.num(x_column)[in_scene].to_numpy()):
                ax.set_xscale("log", base=2)
            if wide_span(allocated[in_scene].to_numpy()):
                ax.set_yscale("log")
            plain_log_ticks(ax, table.num(x_column)[in_scene].to_numpy())
            ax.set_xlabel(axis_label(x_column))
            ax.set_ylabel("MiB (solid allocated, dashed used)")
            set_panel_title(ax, style.panel_title(scene))
            ax.grid(alpha=0.3)
            place_legend(ax)
        canvas.save(fig, f"memory-vs-{x_column}", f"Memory vs {axis_label(x_column)}",
                    f"Bytes allocated (solid) and used after the build (dashed) per structure; "
                    f"structures with the same bytes at every point share one line and legend "
                    f"entry (\"a = b\"); {HOLLOW_NOTE}.", "Memory")


def parse_histogram(text):
    """`depth_histogram` ("1:812;2-3:340;...") as [(label, pixels)]."""
    bins = []
    for item in str(text).split(";"):
        if ":" not in item:
            continue
        label, pixels = item.rsplit(":", 1)
        try:
            bins.append((label, int(pixels)))
        except ValueError:
            return []
    return bins


def draw_depth_histograms(table, canvas):
    """One histogram of list lengths per scene (the census's `depth_histogram`): the share
    of the occupied LDM pixels per power-of-two bin of lengths, at the scene's most measured
    N and R_LDM (the profile depends on both), with p50/p90/p99 and the deepest pixel."""
    if not table.has("depth_histogram"):
        canvas.note("depth histograms: no record carries depth_histogram (runs before issue 22)")
        return
    rows = table.has_structure() & (table.text("depth_histogram").replace("nan", "") != "")
    scenes = list(dict.fromkeys(table.text("scene_name" if table.has("scene_name") else "scene")[rows]))
    if not scenes:
        canvas.note("depth histograms: no record of an LDM structure carries a histogram")
        return
    scene_of = table.text("scene_name" if table.has("scene_name") else "scene")
    fig, axes = subplot_grid(len(scenes))
    panels = []
    for ax, scene in zip(axes, scenes):
        in_scene = rows & (scene_of == scene)
        views_res = table.text("n_views")[in_scene] + "/" + table.text("r_ldm")[in_scene]
        common = views_res.value_counts().index[0]
        i = views_res[views_res == common].index[0]
        bins = parse_histogram(table.text("depth_histogram")[i])
        total = sum(p for _, p in bins) or 1
        labels = [label for label, _ in bins]
        ax.bar(range(len(bins)), [p / total for _, p in bins], color="tab:blue")
        ax.set_xticks(range(len(bins)))
        ax.set_xticklabels(labels, rotation=45 if len(labels) > 6 else 0)
        ax.set_xlabel("fragments in the pixel's list")
        ax.set_ylabel("share of occupied LDM pixels")
        n, r = common.split("/")
        title = style.panel_title(scene, {"n_views": n, "r_ldm": r})
        set_panel_title(ax, title)
        panels.append(title)
        quantiles = ", ".join(f"{q} {table.text(c)[i]}" for q, c in
                              (("p50", "depth_p50"), ("p90", "depth_p90"), ("p99", "depth_p99"),
                               ("max", "max_depth_complexity")) if table.has(c))
        ax.text(0.98, 0.95, quantiles, transform=ax.transAxes, ha="right", va="top", fontsize=6,
                bbox={"facecolor": "white", "alpha": 0.85, "edgecolor": "none"})
        ax.grid(alpha=0.3, axis="y")
    canvas.save(fig, "depth-histograms", "Depth complexity per scene",
                "Share of the occupied LDM pixels per bin of list lengths (powers of two), one "
                "panel per scene at its most measured N and R_LDM, from the fragment census: what "
                "explains a ranking (a fixed array is sized for the deepest pixel; lists follow "
                "the total). Panels: " + "; ".join(panels) + ".", "Depth complexity")


LONE_COLOUR = "0.6"
MANY_SERIES = 10  # past this, a cost figure stacks its panels (legends need the width)
MIN_FIT_POINTS = 3  # two points always fit a line exactly: a slope from them is no finding


def fitted_slope(x, y):
    """Least-squares slope of log y over log x, or (None, None) with fewer than
    MIN_FIT_POINTS distinct x."""
    keep = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
    x, y = x[keep], y[keep]
    if len(set(x)) < MIN_FIT_POINTS:
        return None, None
    slope, intercept = np.polyfit(np.log(x), np.log(y), 1)
    return slope, intercept


def slope_text(label, slope, x):
    """The legend entry of a series: its slope, or why it has none."""
    if slope is not None:
        return f"{label}: slope {round(slope, 2) + 0:.2f}"
    points = len(set(v for v in x if np.isfinite(v) and v > 0))
    return f"{label}: no slope ({points} ok point{'s' if points != 1 else ''}, a fit needs {MIN_FIT_POINTS})"


SCALING_SERIES = {
    # x axis: the axes that split series (the others generate the x values or are the x)
    "n_views": ["scene", "r_ldm", "structure_params", "sizing_policy", "trace", "ao_estimator",
                "d_max", "width", "height", "run"],
    "r_ldm": ["scene", "n_views", "structure_params", "sizing_policy", "trace",
              "ao_estimator", "d_max", "width", "height", "run"],
    "fragments": ["structure_params", "sizing_policy", "trace", "ao_estimator", "run"],
    # the indirect pass's light resolution, where a run has it
    "r_light": ["scene", "n_views", "r_ldm", "structure_params", "sizing_policy",
                "splat_scale", "topological_bias", "width", "height", "run"],
}


def draw_scaling(table, canvas):
    """Build and query cost against N, R_LDM and the census's fragments on log-log axes,
    each series with its fitted slope (cost ~ work^slope) in the legend where it has at
    least MIN_FIT_POINTS x values, and says why not where it has fewer."""
    costs = [("build", table.num("build_ms_median"), "build median (ms)", "build"),
             ("query", table.query_ms(), "query median (ms)", "pass")]
    measured = table.measured()
    for x_column, series_axes in SCALING_SERIES.items():
        if x_column == "r_light" and not table.has(x_column):
            continue
        what = f"cost vs {axis_label(x_column)}"
        x_all = table.num(x_column)
        rows = (x_all > 0) & table.has_structure()
        if not x_is_a_range(table, canvas, rows, x_column, what):
            continue
        # the legend's entries: series over two or more x values, and one for the lone points
        entries = 1 + sum(table.num(x_column)[m].nunique() > 1
                          for _, m in series_masks(table, rows, series_axes + table.extra_axes))
        # Many series: the panels one above the other at the text width, each legend in two
        # columns below it (side by side, long legends would run into each other).
        many = entries > MANY_SERIES
        fig, axes = subplot_grid(len(costs), max_columns=1 if many else 2,
                                 width=style.DOUBLE_COLUMN if many else None,
                                 height=style.PANEL_HEIGHT + 0.12 * (entries / 2 if many else entries))
        for ax, (cost_name, cost, ylabel, subpass) in zip(axes, costs):
            in_plot = rows & (cost > 0)
            curves = []
            for label, mask in series_masks(table, in_plot, series_axes + table.extra_axes):
                x, y = x_all[mask].to_numpy(), cost[mask].to_numpy()
                order = np.argsort(x, kind="stable")
                curves.append((label, (x[order], y[order],
                                       measured[mask].to_numpy()[order].astype(float),
                                       time_errors(table, subpass, mask, y)[:, order])))
            curves = merge_coinciding(curves)
            # A series at one x value is a point, not a scaling: drawn small and grey, one
            # legend entry for them all, so that the legend names what has a slope.
            lone = [c for c in curves if len(set(c[1][0])) < 2]
            curves = [c for c in curves if len(set(c[1][0])) >= 2]
            for _, (x, y, ok, errors) in lone:
                scatter(ax, x, y, LONE_COLOUR, "o", ok.astype(bool))
            if lone:
                ax.scatter([], [], color=LONE_COLOUR, marker="o", s=16,
                           label=f"{len(lone)} series at one {axis_label(x_column)} value "
                                 "(points only, no slope)")
            for (colour, marker, line), (label, (x, y, ok, errors)) in zip(
                    series_styles(len(curves)), curves):
                ok = ok.astype(bool)
                slope, intercept = fitted_slope(x[ok], y[ok])
                ax.plot(x, y, color=colour, linestyle=line, linewidth=0.8, alpha=0.7,
                        marker=None, label=slope_text(label, slope, x[ok]))
                ax.errorbar(x, y, yerr=errors, fmt="none", ecolor=colour, elinewidth=0.6,
                            capsize=1.5, alpha=0.7)
                scatter(ax, x, y, colour, marker, ok)
                if slope is not None:
                    xs = np.array([x[ok].min(), x[ok].max()])
                    ax.plot(xs, np.exp(intercept) * xs ** slope, ":", color=colour, linewidth=1.2)
            ax.set_xscale("log")
            ax.set_yscale("log")
            plain_log_ticks(ax, x_all[in_plot].to_numpy())
            ax.set_xlabel(axis_label(x_column))
            ax.set_ylabel(ylabel)
            scenes = list(dict.fromkeys(table.text("scene")[in_plot]))
            set_panel_title(ax, style.panel_title(scenes[0] if len(scenes) == 1 else None,
                                           quantity=cost_name))
            ax.grid(alpha=0.3, which="both")
            place_legend(ax, inside=0, columns=2 if many else 1)
        canvas.save(fig, f"cost-vs-{x_column}", f"Cost vs {axis_label(x_column)} (log-log)",
                    "Medians per configuration with their 95 % intervals; each series has its own "
                    "colour, marker and line style, and series with the same values share one "
                    "line (\"a = b\"); dotted: least-squares fit in log space over the ok records, "
                    f"its slope in the legend, only for series with at least {MIN_FIT_POINTS} x "
                    f"values (the legend says so otherwise); grey points: series measured at "
                    f"one x value only; {HOLLOW_NOTE}.", "Scaling")


def draw_subpass_bars(table, canvas, per_figure=60):
    """Each configuration's frame as stacked sub-pass medians (every <subpass>_ms_median
    column but the sums and the raster baselines), one figure per scene."""
    subpasses = [s for s in table.subpasses() if table.num(f"{s}_ms_median").notna().any()]
    if not subpasses:
        canvas.note("sub-pass bars: skipped, no record has sub-pass times")
        return
    colours = dict(zip(subpasses, series_colours(len(subpasses))))
    intervals = {s: table.time_interval(s) for s in subpasses}
    timed = table.num("frame_ms_median").notna()
    several_runs = table.text("run").nunique() > 1
    status = table.status()
    for scene in dict.fromkeys(table.text("scene")[timed]):
        index = table.df.index[timed & (table.text("scene") == scene)]
        for part, start in enumerate(range(0, len(index), per_figure)):
            chunk = index[start:start + per_figure]
            suffix = f"-{part + 1}" if len(index) > per_figure else ""
            fig, ax = plt.subplots(figsize=(style.DOUBLE_COLUMN, 0.9 + 0.16 * len(chunk)))
            labels = []
            for row, i in enumerate(chunk):
                left = 0.0
                ok = status[i] == "ok"
                for s in subpasses:
                    value = table.num(f"{s}_ms_median")[i]
                    if not np.isfinite(value) or value <= 0:
                        continue
                    ax.barh(row, value, left=left, color=colours[s], alpha=1 if ok else 0.45,
                            hatch=None if ok else "//", edgecolor="white" if ok else "black",
                            linewidth=0.3)
                    # the sub-pass's own 95 % interval, at the end of its segment
                    below, above = intervals[s][0][i], intervals[s][1][i]
                    if np.isfinite(below) and np.isfinite(above) and (below > 0 or above > 0):
                        ax.errorbar([left + value], [row], xerr=[[max(value - below, 0)], [max(above - value, 0)]],
                                    fmt="none", ecolor="black", elinewidth=0.6, capsize=1.2, alpha=0.8)
                    left += value
                build = table.num("build_ms_median")[i]
                if np.isfinite(build):  # where the structure's build ends and the pass begins
                    ax.plot([build, build], [row - 0.45, row + 0.45], color="black", linewidth=1)
                label = (table.text("run")[i] + ": " if several_runs else "") + \
                    table.text("config_id")[i]
                labels.append(label if ok else f"{label} [{status[i]}]")
            ax.set_yticks(range(len(chunk)))
            ax.set_yticklabels(labels, fontsize=5.5)
            ax.invert_yaxis()
            ax.set_xlabel("median time per frame (ms), stacked by sub-pass")
            handles = [plt.Rectangle((0, 0), 1, 1, color=colours[s]) for s in subpasses]
            handles += [Line2D([], [], color="black", marker="|", markersize=7, linestyle="none"),
                        Line2D([], [], color="black", marker="|", markersize=3, linestyle="-", linewidth=0.6)]
            fig.legend(handles, subpasses + ["build median", "95 % interval"], loc="upper center",
                       bbox_to_anchor=(0.5, 0.0), ncol=min(6, len(subpasses) + 2), frameon=False)
            set_panel_title(ax, style.panel_title(scene, quantity="sub-pass medians" + suffix.replace("-", ", part ")))
            ax.grid(alpha=0.3, axis="x")
            canvas.save(fig, f"subpasses-{safe_name(scene)}{suffix}",
                        f"Sub-pass times, {scene}{suffix.replace('-', ' part ')}",
                        "Median of every timed sub-pass per configuration, each with its 95 % "
                        "interval as a bar at the end of its segment, the structure's "
                        "build first (the black tick marks the build median), then the "
                        "pass's; the raster baselines are timed beside the frame and not "
                        "stacked; hatched: lossy / invalid / failed / degenerate.", "Sub-passes")


def safe_name(text):
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in text)[:60] or "scene"
