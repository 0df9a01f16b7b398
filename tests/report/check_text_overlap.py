#!/usr/bin/env python3
"""No overlapping text in the report's figures (issue 37): draws the report of real runs
(`ldmbench_report.py RUN... --axes AXES --out OUT`, the run folders made by
tests/report/report_test.cpp) and, in every figure as it is saved, takes matplotlib's own
bounding box of every drawn text (titles, suptitles, axis labels, tick labels, legend
entries, annotations, colour-bar labels: Text.get_window_extent with the figure's
renderer) and fails naming the figure and both texts where two overlap.

Point labels (the trade-off's annotations) are checked against every other text but not
against each other: two configurations measured alike sit on one spot, and their labels
with them, which says what the data is (the figure's caption says so)."""
import argparse
import itertools
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts", "report"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
from matplotlib.text import Annotation, Text  # noqa: E402

import ldmbench_report  # noqa: E402
from ldmreport import figures  # noqa: E402

SLACK_PX = 0.5  # boxes touching within this are not an overlap (rounding of the extents)


def drawn_tick_labels(fig):
    """The tick labels matplotlib draws (those of ticks inside the view), by id."""
    ids = set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            for tick in axis._update_ticks():  # the ticks the axis draws
                for label in (tick.label1, tick.label2):
                    if label.get_visible() and label.get_text().strip():
                        ids.add(id(label))
    return ids


def all_tick_labels(fig):
    ids = set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                ids.update((id(tick.label1), id(tick.label2)))
    return ids


def visible(text):
    """Whether the text is drawn: visible itself and in every ancestor axes or legend."""
    if not text.get_visible() or not text.get_text().strip():
        return False
    ax = text.axes
    return ax is None or ax.get_visible()


def texts_of(fig):
    """[(description, Text, bbox)] of every drawn text of the figure."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    drawn_ticks, ticks = drawn_tick_labels(fig), all_tick_labels(fig)
    out = []
    for t in fig.findobj(Text):
        if id(t) in ticks and id(t) not in drawn_ticks:
            continue
        if not visible(t):
            continue
        box = t.get_window_extent(renderer)
        if box.width <= 0 or box.height <= 0:
            continue
        kind = "point label" if isinstance(t, Annotation) else "tick label" if id(t) in ticks else "text"
        out.append((kind, t, box))
    return out


def overlaps(fig):
    """Pairs of drawn texts whose boxes overlap by more than SLACK_PX both ways."""
    found = []
    for (ka, a, ba), (kb, b, bb) in itertools.combinations(texts_of(fig), 2):
        if ka == kb == "point label":
            continue
        dx = min(ba.x1, bb.x1) - max(ba.x0, bb.x0)
        dy = min(ba.y1, bb.y1) - max(ba.y0, bb.y0)
        if dx > SLACK_PX and dy > SLACK_PX:
            found.append(f"{ka} {a.get_text()!r} overlaps {kb} {b.get_text()!r} ({dx:.1f} x {dy:.1f} px)")
    return found


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("runs", nargs="+")
    p.add_argument("--axes", required=True)
    p.add_argument("--out", required=True)
    a = p.parse_args()
    problems, seen = [], []

    def inspect(canvas, fig, name):
        seen.append(name)
        problems.extend(f"{name}: {o}" for o in overlaps(fig))

    figures.Canvas.inspect = inspect
    status = ldmbench_report.main(a.runs + ["--axes", a.axes, "--out", a.out, "--dpi", "100"])
    if status:
        print(f"the report failed: {status}")
        return 1
    print(f"{len(seen)} figures checked: {', '.join(seen)}")
    for line in problems:
        print("OVERLAP " + line)
    if not seen:
        print("no figure drawn")
        return 1
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
