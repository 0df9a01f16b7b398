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
import numpy as np  # noqa: E402

from . import style  # noqa: E402
from .figures import safe_name  # noqa: E402
from .runs import RUN_DIR_COLUMN  # noqa: E402
from .table import axis_label, describe, sort_key  # noqa: E402

# Axes that are columns (structure, pass) or change no image (frames); the rest are held
# or run down the rows.
NOT_HELD = {"structure", "pass", "frames"}
# Axes held but never run down the rows (a grid compares images of one size and run).
NOT_ROWS = {"run", "sweep", "width", "height"}


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


def srgb_encode(linear):
    linear = np.clip(linear, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1 / 2.4) - 0.055)


def srgb_decode(encoded):
    return np.where(encoded <= 0.04045, encoded / 12.92, np.power((encoded + 0.055) / 1.055, 2.4))


def read_exr(path):
    """A linear EXR as floats (H x W [x C]), or None without OpenImageIO's Python module
    (Debian's python3-openimageio, which scripts/setup.sh installs)."""
    try:
        import OpenImageIO as oiio
    except ImportError:
        return None
    pixels = oiio.ImageBuf(path).get_pixels(oiio.FLOAT)
    if pixels is None or pixels.size == 0:
        return None
    return pixels[..., 0] if pixels.ndim == 3 and pixels.shape[2] == 1 else pixels[..., :3]


def tone_mapped(png_path, exr_path, exposure):
    """A linear HDR image as shown: value x exposure, clamped, sRGB-encoded; from its EXR
    where it can be read, else from the 8-bit PNG (written at exposure 1: its clipped pixels
    stay clipped). Returns (pixels, source)."""
    linear = read_exr(exr_path) if exr_path and os.path.isfile(exr_path) else None
    source = "EXR"
    if linear is None:
        encoded = mpimg.imread(png_path)
        linear = srgb_decode(encoded[..., :3] if encoded.ndim == 3 else encoded)
        source = "8-bit PNG"
    return srgb_encode(linear * exposure), source


def is_grey(pixels):
    """One channel, or three equal ones."""
    if pixels.ndim == 2:
        return True
    rgb = pixels[..., :3]
    return bool(np.all(rgb[..., 0] == rgb[..., 1]) and np.all(rgb[..., 1] == rgb[..., 2]))


VIRIDIS = None


def heat_map_values(png_path, top):
    """The values of a heat-map PNG (harness/metrics/heat_map.h: viridis at v / top, clamped)
    recovered by the nearest of viridis's 256 colours: v to 1/255 of `top`."""
    global VIRIDIS
    if VIRIDIS is None:
        VIRIDIS = plt.get_cmap("viridis")(np.linspace(0, 1, 256))[:, :3]
    pixels = mpimg.imread(png_path)
    # A heat map has at most 256 colours: match those, not every pixel (a 1280x720 map
    # against 256 colours pixel by pixel would take gigabytes)
    rgb = np.rint(pixels[..., :3].reshape(-1, 3) * 255).astype(np.int32)
    codes, inverse = np.unique((rgb[:, 0] << 16) | (rgb[:, 1] << 8) | rgb[:, 2], return_inverse=True)
    colours = np.stack([(codes >> 16) & 255, (codes >> 8) & 255, codes & 255], axis=1) / 255.0
    nearest = np.argmin(((colours[:, None, :] - VIRIDIS[None, :, :]) ** 2).sum(axis=2), axis=1)
    return (nearest[inverse.reshape(-1)] / 255.0 * top).reshape(pixels.shape[:2])


def blank_cell(ax):
    ax.set_xticks([])
    ax.set_yticks([])
    for spine in ax.spines.values():
        spine.set_linewidth(0.4)


def flag(ax, label):
    ax.text(0.03, 0.03, label, transform=ax.transAxes, fontsize=5, color="white",
            va="bottom", bbox={"facecolor": "black", "alpha": 0.6, "pad": 0.8, "lw": 0})


def draw_picture(ax, pixels):
    """An image as it is: grey ones in grey (black 0 .. white 1), colour ones as RGB."""
    blank_cell(ax)
    if pixels is None:
        ax.text(0.5, 0.5, "–", ha="center", va="center", transform=ax.transAxes)
    elif is_grey(pixels):
        ax.imshow(pixels if pixels.ndim == 2 else pixels[..., 0], cmap="gray", vmin=0, vmax=1,
                  interpolation="nearest")
    else:
        ax.imshow(np.clip(pixels[..., :3], 0, 1), interpolation="nearest")


class ReferenceGroup:
    """Methods whose records were scored against the same reference in every row (AO and
    HBAO; indirect light apart): one reference column, one error scale and colour bar."""

    def __init__(self, methods, passes, exposure):
        self.methods, self.passes, self.exposure = methods, passes, exposure

    @property
    def hdr(self):
        return np.isfinite(self.exposure) and self.exposure != 1.0


def reference_groups(table, values, cells, methods):
    """Methods grouped by the reference their cells name in each row."""
    def paths(m):
        return [table.text("reference_exr")[cells[(v, m)]] if (v, m) in cells else None
                for v in values]

    groups = []  # [(methods, row paths)]
    for m in methods:
        mine = paths(m)
        for members, theirs in groups:
            if all(a is None or b is None or a == b for a, b in zip(mine, theirs)):
                members.append(m)
                for k, p in enumerate(mine):
                    theirs[k] = theirs[k] or p
                break
        else:
            groups.append(([m], list(mine)))
    out = []
    for members, _ in groups:
        rows = [cells[k] for k in cells if k[1] in members]
        exposure = table.num("ssim_exposure")[rows].dropna()
        passes = list(dict.fromkeys(table.text("pass")[rows]))
        out.append(ReferenceGroup(members, passes, float(exposure.iloc[0]) if len(exposure) else 1.0))
    return out


def held_description(table, held):
    """The held settings for a grid's title: the image size once, not the timing's frames."""
    shown = {k: v for k, v in held.items() if k not in ("scene", "width", "height", "frames", "warmup")
             and (k != "run" or table.text("run").nunique() > 1)}
    if held.get("width") and held.get("height"):
        shown["image size"] = f"{held['width']}x{held['height']}"
    return shown


SUPTITLE_PT, COLUMN_TITLE_PT = 6.5, 5.5
LINE_IN = 1.25 / 72  # inches per point of a line of text (its leading)
TITLE_PAD_IN = 0.16  # above the title, between it and the column titles, below those


def column_title(kind, m, g, cell):
    """A column's title wrapped to its cell: the method, the reference, or its error map."""
    title = m if kind == "image" else f"reference: {', '.join(g.passes)}" \
        if kind == "reference" else f"|error|: {m}"
    title = textwrap.fill(title.replace("/", "/ "), max(8, int(cell * 13)),
                          break_long_words=False).replace("/ ", "/").replace("/\n", "/\n")
    if kind != "error" and g.hdr:
        title += f"\nexp. x{g.exposure:.3g}"
    return title


def render_grid(table, canvas, scene, row_axis, values, cells, held):
    methods = sorted({m for (_, m) in cells})
    groups = reference_groups(table, values, cells, methods)
    # Columns: per reference group its methods' images, then its reference; then every
    # method's error map, group by group (each group on one error scale).
    columns = []
    for g in groups:
        columns += [("image", m, g) for m in g.methods] + [("reference", None, g)]
    for g in groups:
        columns += [("error", m, g) for m in g.methods]
    # Square cells in a figure sized for them (no tight layout: it cannot know that the
    # images keep their aspect): margins for the row labels, titles and colour bars.
    left, bottom = 0.3, 0.45
    cell = min(1.3, (style.DOUBLE_COLUMN - left) / len(columns))
    # The top margin holds the figure's title and the columns' titles, each as many lines
    # as it wraps to: a fixed margin let a long title run into the "|error|:" headers.
    titles = [column_title(kind, m, g, cell) for kind, m, g in columns]
    suptitle = textwrap.fill(style.panel_title(scene, held_description(table, held),
                                               quantity=f"rows: {axis_label(row_axis)}"),
                             int(cell * len(columns) * 13))
    top = TITLE_PAD_IN + LINE_IN * (SUPTITLE_PT * (suptitle.count("\n") + 1) +
                                    COLUMN_TITLE_PT * max(t.count("\n") + 1 for t in titles))
    width, height = left + cell * len(columns) * 1.04, top + bottom + cell * len(values) * 1.04
    fig, axes = plt.subplots(len(values), len(columns), squeeze=False, figsize=(width, height))
    fig.subplots_adjust(left=left / width, right=0.995, bottom=bottom / height,
                        top=1 - top / height, wspace=0.04, hspace=0.04)
    status = table.status()
    top = {id(g): max([float(table.num("diff_png_max")[i]) for (v, m), i in cells.items()
                       if m in g.methods and np.isfinite(table.num("diff_png_max")[i])] or [1.0])
           for g in groups}
    sources = set()
    error_images = {}
    for r, value in enumerate(values):
        for c, (kind, m, g) in enumerate(columns):
            ax = axes[r][c]
            if kind == "reference":
                i = next((cells[(value, x)] for x in g.methods if (value, x) in cells
                          and image_path(table, cells[(value, x)], "reference_png")), None)
            else:
                i = cells.get((value, m))
            if i is None:
                draw_picture(ax, None)
                continue
            if kind == "error":
                path = image_path(table, i, "diff_png")
                blank_cell(ax)
                if path and np.isfinite(table.num("diff_png_max")[i]):
                    error_images[id(g)] = ax.imshow(
                        heat_map_values(path, float(table.num("diff_png_max")[i])),
                        cmap="viridis", vmin=0, vmax=top[id(g)], interpolation="nearest")
                continue
            png = image_path(table, i, "reference_png" if kind == "reference" else "image_png")
            if png is None:
                draw_picture(ax, None)
                continue
            if g.hdr:
                exr = os.path.join(table.text(RUN_DIR_COLUMN)[i], table.text(
                    "reference_exr" if kind == "reference" else "image_exr")[i])
                pixels, source = tone_mapped(png, exr, g.exposure)
                sources.add(source)
            else:
                pixels = mpimg.imread(png)
            draw_picture(ax, pixels)
            if kind == "image" and status[i] != "ok":
                flag(ax, status[i])
        axes[r][0].set_ylabel(f"{axis_label(row_axis)}={value}")
    for c, title in enumerate(titles):
        axes[0][c].set_title(title, fontsize=COLUMN_TITLE_PT)
    for g in groups:  # one colour bar under each group's error columns, with its scale
        first = next(c for c, col in enumerate(columns) if col[0] == "error" and col[2] is g)
        count = len(g.methods)
        if id(g) not in error_images:
            continue
        cax = axes[-1][first].inset_axes([0.05, -0.2, count - 0.1 + 0.02 * (count - 1), 0.07])
        bar = fig.colorbar(error_images[id(g)], cax=cax, orientation="horizontal")
        bar.ax.tick_params(labelsize=5, length=2)
        bar.set_label("|error| " + ("(linear radiance)" if g.hdr else "(AO, 0..1)"), fontsize=5.5,
                      labelpad=1)
    fig.suptitle(suptitle, fontsize=SUPTITLE_PT, y=1 - 0.04 / height, va="top")
    name = f"grid-{safe_name(scene)}-{safe_name(row_axis)}"
    exposures = "; ".join(f"{', '.join(g.passes)} tone-mapped: linear value x {g.exposure:.3g} "
                          f"(the exposure mapping the reference's 99th-percentile luminance to "
                          f"1), clamped, sRGB" for g in groups if g.hdr)
    canvas.save(fig, name, f"Images, {scene}, by {axis_label(row_axis)}",
                "Columns: each method's image and the reference it is scored against (one "
                "reference column per pass or group of passes sharing one); grey-scale images "
                "in grey; then each method's absolute error on one colour scale per reference "
                "(its colour bar below, from 0 to the largest error top of the group's maps)"
                + (f"; {exposures}" if exposures else "")
                + ("; tone-mapped from the 8-bit PNG (no python3-openimageio for the EXR)"
                   if "8-bit PNG" in sources else "")
                + "; labelled cells are not ok.", "Images",
                tight=False)


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
