"""Image grids in the manner of the thesis's Tables 3-9: one row per value of a parameter,
one column per structure / method, the reference, then each method's error map. Built from
the PNGs a run wrote (image_png, diff_png, and the reference's PNG beside reference_exr);
without them (a tidy CSV whose run folders are gone) the grids are skipped with a note."""
import os
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

from .figures import safe_name  # noqa: E402
from .runs import RUN_DIR_COLUMN  # noqa: E402
from .table import axis_label, describe, sort_key  # noqa: E402

# Axes that are columns (structure, pass) or change no image (frames); the rest are held
# or run down the rows.
NOT_HELD = {"structure", "pass", "frames"}
# Axes held but never run down the rows (a grid compares images of one size and run).
NOT_ROWS = {"run", "sweep", "width", "height"}
CELL_INCHES = 1.5


def image_path(table, i, column):
    """Absolute path of a record's image column, or None when absent or missing on disk."""
    rel = table.text(column)[i]
    if column == "reference_png":
        rel = table.text("reference_exr")[i]
        rel = rel[:-4] + ".png" if rel.endswith(".exr") else ""
    if not rel:
        return None
    path = os.path.join(table.text(RUN_DIR_COLUMN)[i], rel)
    return path if os.path.isfile(path) else None


def applicable(table, i, axis):
    """Whether a record has a value of `axis` (a pass without a structure has no N, ...)."""
    return table.axis_values(axis)[i] != ""


def plan_grid(table, rows_index, axes, row_axis):
    """The records of a grid over `row_axis`. The axes every record that depends on it
    has a value of ("shared": N, R_LDM, d_max, ...) are held at the setting that covers most
    of its values; an axis only some of them have (a structure's parameters, a pass's own
    settings) names a column instead ("ppfla (k=3)"); records that do not depend on
    `row_axis` (HBAO in a grid over N) appear in every row when they agree with the held
    setting. Returns (row values, {(value, column): index}, held setting) or None when fewer
    than two rows result."""
    methods = table.methods()
    dependent = [i for i in rows_index if applicable(table, i, row_axis)]
    independent = [i for i in rows_index if not applicable(table, i, row_axis)]
    others = [a for a in axes if a != row_axis]
    shared = [a for a in others if all(applicable(table, i, a) for i in dependent)]

    def own_axes(method):
        """Axes outside the held ones on which this method's records differ."""
        mine = [i for i in rows_index if methods[i] == method]
        return [a for a in others if a not in shared and
                len({table.axis_values(a)[i] for i in mine}) > 1]

    own = {m: own_axes(m) for m in set(methods[i] for i in rows_index)}

    def column(i):
        text = describe({a: table.axis_values(a)[i] for a in own[methods[i]]})
        return methods[i] + (f" ({text})" if text else "")

    groups = {}
    for i in dependent:
        key = tuple((a, table.axis_values(a)[i]) for a in shared)
        groups.setdefault(key, []).append(i)
    if not groups:
        return None
    best = max(groups, key=lambda k: (len({table.axis_values(row_axis)[i] for i in groups[k]}),
                                      len(groups[k])))
    values = sorted({table.axis_values(row_axis)[i] for i in groups[best]}, key=sort_key)
    if len(values) < 2:
        return None
    held = dict(best)
    cells = {}
    for i in groups[best]:
        cells.setdefault((table.axis_values(row_axis)[i], column(i)), i)
    for i in independent:
        if all(table.axis_values(a)[i] == v for a, v in held.items() if applicable(table, i, a)):
            for v in values:
                cells.setdefault((v, column(i)), i)
    return values, cells, held


def draw_cell(ax, path, label=None):
    ax.set_xticks([])
    ax.set_yticks([])
    if path:
        ax.imshow(mpimg.imread(path), interpolation="nearest")
    else:
        ax.text(0.5, 0.5, "–", ha="center", va="center", transform=ax.transAxes)
    if label:
        ax.text(0.02, 0.02, label, transform=ax.transAxes, fontsize=6, color="white",
                va="bottom", bbox={"facecolor": "black", "alpha": 0.5, "pad": 1, "lw": 0})


def render_grid(table, canvas, scene, row_axis, values, cells, held):
    methods = sorted({m for (_, m) in cells})
    columns = methods + ["reference"] + [f"error: {m}" for m in methods]
    fig, axes = plt.subplots(len(values), len(columns), squeeze=False,
                             figsize=(CELL_INCHES * len(columns), CELL_INCHES * len(values) + 0.6))
    status = table.status()
    for r, value in enumerate(values):
        row_cells = {m: cells.get((value, m)) for m in methods}
        reference = next((image_path(table, i, "reference_png") for i in row_cells.values()
                          if i is not None and image_path(table, i, "reference_png")), None)
        for c, m in enumerate(methods):
            i = row_cells[m]
            flag = None if i is None or status[i] == "ok" else status[i]
            draw_cell(axes[r][c], image_path(table, i, "image_png") if i is not None else None,
                      flag)
            diff_max = table.text("diff_png_max")[i] if i is not None else ""
            draw_cell(axes[r][len(methods) + 1 + c],
                      image_path(table, i, "diff_png") if i is not None else None,
                      f"max {float(diff_max):.2g}" if diff_max not in ("", "nan") else None)
        draw_cell(axes[r][len(methods)], reference)
        axes[r][0].set_ylabel(f"{axis_label(row_axis)} = {value}", fontsize=8)
    for c, title in enumerate(columns):
        axes[0][c].set_title(textwrap.fill(title, 22), fontsize=7)
    held_text = describe({k: v for k, v in held.items() if k != "scene" and
                          (k != "run" or table.text("run").nunique() > 1)})
    fig.suptitle(textwrap.fill(f"{scene}: rows {axis_label(row_axis)}" +
                               (f"; held: {held_text}" if held_text else ""),
                               int(CELL_INCHES * len(columns) * 12)), fontsize=8)
    name = f"grid-{safe_name(scene)}-{safe_name(row_axis)}"
    canvas.save(fig, name, f"Images, {scene}, by {axis_label(row_axis)}",
                "Columns: each method's image, the reference, each method's error "
                "(absolute difference heat map, its top value in the corner); labelled "
                "cells are not ok.", "Images")


def draw_image_grids(table, canvas):
    if not table.has("image_png"):
        canvas.note("image grids: skipped, the records name no images (run without --no-images)")
        return
    present = [i for i in table.df.index if image_path(table, i, "image_png")]
    if not present:
        canvas.note("image grids: skipped, the runs' images are not there (a report from "
                    "tidy.csv alone, whose run folders are gone or moved, has none)")
        return
    axes = [a for a in table.axes() if a not in NOT_HELD]
    scenes = list(dict.fromkeys(table.text("scene")[present]))
    for scene in scenes:
        in_scene = [i for i in present if table.text("scene")[i] == scene]
        drawn = 0
        mask = table.df.index.isin(in_scene)
        for row_axis in table.varying(mask, axes):
            if row_axis == "scene" or row_axis in NOT_ROWS:
                continue
            plan = plan_grid(table, in_scene, axes, row_axis)
            if plan:
                render_grid(table, canvas, scene, row_axis, *plan)
                drawn += 1
        if not drawn:
            canvas.note(f"image grid of {scene}: skipped, no parameter takes two values "
                        "there with the other parameters held")
