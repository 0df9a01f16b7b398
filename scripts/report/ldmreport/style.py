"""How every figure of the report looks: sizes for a two-column paper, fonts readable at
that size, the output formats, and the one scheme panel titles follow.

Sizes: a figure is either one column of a two-column paper (SINGLE_COLUMN, 3.5 in) or the
full text width (DOUBLE_COLUMN, 7 in); it is never drawn wider and scaled down, so that the
fonts below are the sizes printed (8 pt text, 7 pt ticks, 6 pt legends and point labels).

Panel titles (the one scheme, panel_title): the scene, then the settings that tell this
panel from the other panels of its figure as `label=value` in the axis registry's order,
then, after " | ", the quantity only when the panels of one figure show different
quantities ("cornell, d_max=0.5 | build"). Figure titles, on the pages, say what is plotted
against what ("Frame time vs mse"); axis labels carry the units."""
SINGLE_COLUMN = 3.5  # inches: one column of a two-column paper
DOUBLE_COLUMN = 7.0  # inches: the text width
PANEL_HEIGHT = 2.5   # inches per row of panels

FORMATS = ("png", "svg", "pdf")
# The pages show a figure as an <img>: SVG where written, else PNG (a browser shows no PDF
# in an <img>), so that a report always has one of the two.
PAGE_FORMATS = ("svg", "png")

RC = {
    "font.size": 8,
    "axes.titlesize": 8,
    "axes.labelsize": 8,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "legend.fontsize": 6,
    "figure.titlesize": 8,
    "lines.markersize": 4,
    "savefig.pad_inches": 0.02,
    "pdf.fonttype": 42,  # TrueType in PDFs: editable, and accepted by publishers' checks
    "svg.fonttype": "none",  # text stays text in SVGs
}
POINT_LABEL_SIZE = 5.5


def apply():
    """Sets the fonts and sizes for every figure (matplotlib is imported here, not above:
    the arguments are checked before any plotting package is)."""
    import matplotlib
    matplotlib.use("Agg")
    matplotlib.rcParams.update(RC)


def parse_formats(values):
    """`--format png,svg --format pdf` as an ordered list without repeats; raises
    ValueError naming a value that is not one of FORMATS."""
    formats = []
    for value in values:
        for f in value.split(","):
            f = f.strip().lower()
            if f not in FORMATS:
                raise ValueError(f"--format: '{f}' is not one of {', '.join(FORMATS)}")
            if f not in formats:
                formats.append(f)
    return formats


def written_formats(requested):
    """The formats written for `requested`: those asked for, plus PNG when neither PNG nor
    SVG is among them (the pages need one to show)."""
    formats = list(requested) or ["png"]
    if not any(f in formats for f in PAGE_FORMATS):
        formats.append("png")
    return formats


def page_file(files):
    """The file of a figure the pages show: its SVG, else its PNG."""
    for ext in PAGE_FORMATS:
        for f in files:
            if f.endswith("." + ext):
                return f
    return files[0]


def figure_width(columns):
    """One column's width for a single panel, the text width for two or more side by side."""
    return SINGLE_COLUMN if columns <= 1 else DOUBLE_COLUMN


def panel_title(scene, settings=None, quantity=None):
    """The one scheme for panel titles (module docstring): scene, distinguishing settings,
    then the quantity when panels of a figure differ in it."""
    from .table import describe
    title = scene or "all scenes"
    described = describe(settings or {})
    if described:
        title += ", " + described
    if quantity:
        title += " | " + quantity
    return title
