"""Unit tests of what the report's figures and front table show (scripts/report/ldmreport:
style, figures, grids, pages), on hand-made tables: each test names the issue-23 item it
holds. Run by tests/report (ctest report.ReportFigures.*)."""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "report"))

import numpy as np  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

from ldmreport import figures, grids, pages, style  # noqa: E402
from ldmreport.table import Table, declare_axes  # noqa: E402

declare_axes({"axes": [
    {"key": "scenes", "label": "scene", "owner_kind": "harness", "column": "scene"},
    {"key": "passes", "label": "pass", "owner_kind": "harness", "column": "pass"},
    {"key": "structures", "label": "structure", "owner_kind": "harness", "column": "structure"},
    {"key": "views", "label": "N", "owner_kind": "harness", "column": "n_views", "ldm_only": True},
    {"key": "r_ldm", "label": "R_LDM", "owner_kind": "harness", "column": "r_ldm", "ldm_only": True},
    {"key": "image_size", "label": "image size", "owner_kind": "harness", "column": "width,height"},
    {"key": "d_max", "label": "d_max", "owner_kind": "harness", "column": "d_max"}]})
style.apply()


def collections(fig, kind):
    """The figure's collections of this matplotlib class ("PathCollection": scatter points,
    "LineCollection": error bars), every axes'."""
    return [c for ax in fig.axes for c in ax.collections if type(c).__name__ == kind]


class Inspecting(figures.Canvas):
    """A canvas that keeps, per figure, what the tests look at before the figure closes."""

    def __init__(self, formats=("png",)):
        super().__init__(tempfile.mkdtemp(prefix="ldm-report-figures-"), formats=formats, dpi=30)
        self.seen = {}

    def inspect(self, fig, name):
        self.seen[name] = {
            "size": tuple(fig.get_size_inches()),
            "titles": [ax.get_title() for ax in fig.axes if ax.get_title()],
            "annotations": [t.get_text() for ax in fig.axes for t in ax.texts],
            "legend": [t.get_text() for ax in fig.axes if ax.get_legend()
                       for t in ax.get_legend().get_texts()] +
                      [t.get_text() for lg in fig.legends for t in lg.get_texts()],
            "markers": {tuple(c.get_paths()[0].vertices.round(3).flatten())
                        for c in collections(fig, "PathCollection") if len(c.get_offsets()) and c.get_paths()},
            "error_bars": len(collections(fig, "LineCollection")),
        }


def record(**values):
    base = {"run": "a", "run_dir": ".", "status": "ok", "scene": "cornell", "pass": "ao",
            "structure": "psppsll", "n_views": 8, "r_ldm": 32, "d_max": 1.5, "ref_cache_key": "k",
            "bytes_allocated": 1 << 20, "bytes_used": 1 << 19, "ref_noise_mse": 1e-6,
            "ref_noise_mssim": 0.999, "build_ms_median": 1.0, "build_ms_ci_low": 0.9,
            "build_ms_ci_high": 1.1, "pass_ms_median": 5.0, "pass_ms_ci_low": 4.5,
            "pass_ms_ci_high": 5.5, "frame_ms_median": 6.0, "frame_ms_ci_low": 5.5,
            "frame_ms_ci_high": 6.5, "mse": 1e-3}
    base.update(values)
    base.setdefault("config_id", f"{base['structure']}-n{base['n_views']}-{base['run']}")
    return base


def table(rows):
    columns = list(dict.fromkeys(c for r in rows for c in r))
    return Table(columns, [[str(r.get(c, "")) for c in columns] for r in rows])


class TradeOffs(unittest.TestCase):
    """Item 1: labelled points, time intervals as error bars, one marker per run."""

    def two_runs(self):
        rows = []
        for run, slower in (("before", 1.0), ("after", 1.3)):
            for n, mse in ((4, 4e-3), (8, 2e-3), (16, 1e-3)):
                rows.append(record(run=run, n_views=n, mse=mse, frame_ms_median=n * slower,
                                   frame_ms_ci_low=n * slower * 0.9, frame_ms_ci_high=n * slower * 1.1))
        return table(rows)

    def test_two_runs_get_two_markers_and_labelled_points(self):
        canvas = Inspecting()
        figures.draw_tradeoffs(self.two_runs(), canvas)
        seen = canvas.seen["tradeoff-time-vs-mse"]
        self.assertIn("run before", seen["legend"])
        self.assertIn("run after", seen["legend"])
        self.assertIn("N16 R32 after", seen["annotations"])
        self.assertIn("N4 R32 before", seen["annotations"])
        self.assertGreaterEqual(len(seen["markers"]), 2, "the runs share one marker")
        self.assertGreater(seen["error_bars"], 0, "no time interval drawn")

    def test_the_varying_parameter_is_in_the_label(self):
        rows = [record(d_max=d, mse=m, frame_ms_median=t, config_id=f"d{d}")
                for d, m, t in ((0.5, 3e-3, 5), (1.5, 2e-3, 6), (3.0, 1e-3, 9))]
        canvas = Inspecting()
        figures.draw_tradeoffs(table(rows), canvas)
        self.assertIn("N8 R32 d_max=0.5", canvas.seen["tradeoff-time-vs-mse"]["annotations"])


class Scaling(unittest.TestCase):
    """Item 3: slopes only from three points; coinciding series merged."""

    def test_a_slope_needs_three_points(self):
        self.assertEqual(figures.fitted_slope(np.array([4.0, 8.0]), np.array([1.0, 2.0])), (None, None))
        slope, _ = figures.fitted_slope(np.array([4.0, 8.0, 16.0]), np.array([1.0, 2.0, 4.0]))
        self.assertAlmostEqual(slope, 1.0)
        self.assertIn("no slope (2 ok points, a fit needs 3)",
                      figures.slope_text("x", None, np.array([4.0, 8.0])))

    def test_a_two_point_series_says_so_in_the_legend(self):
        rows = [record(n_views=n, structure=s, build_ms_median=b, pass_ms_median=5 * b)
                for s, ns in (("psppsll", (4, 8, 16)), ("ppsll", (4, 8)))
                for n, b in zip(ns, (1.0, 2.1, 3.9))]
        canvas = Inspecting()
        figures.draw_scaling(table(rows), canvas)
        legend = canvas.seen["cost-vs-n_views"]["legend"]
        self.assertTrue(any(t.startswith("psppsll: slope") for t in legend), legend)
        self.assertIn("ppsll: no slope (2 ok points, a fit needs 3)", legend)

    def test_series_at_one_x_share_one_entry(self):
        rows = [record(n_views=n, structure="psppsll", build_ms_median=n / 4) for n in (4, 8, 16)]
        rows += [record(n_views=8, structure=s, build_ms_median=b) for s, b in (("ppsll", 2.0), ("dfbuffer", 3.0))]
        canvas = Inspecting()
        figures.draw_scaling(table(rows), canvas)
        legend = canvas.seen["cost-vs-n_views"]["legend"]
        self.assertIn("2 series at one N value (points only, no slope)", legend)
        self.assertFalse(any(t.startswith(("ppsll", "dfbuffer")) for t in legend), legend)

    def test_coinciding_series_share_one_line_and_entry(self):
        x = np.array([4.0, 8.0])
        merged = figures.merge_coinciding([("a", (x, x * 2)), ("b", (x, x * 2)), ("c", (x, x * 3))])
        self.assertEqual([label for label, _ in merged], ["a = b", "c"])
        self.assertEqual(figures.merged_label(["ppfla/ao (run=1)", "ppfla/indirect (run=1)", "ppfla/ao (run=2)"]),
                         "ppfla/ao = ppfla/indirect (run=1; run=2)")

    def test_memory_lines_that_coincide_are_merged_and_said(self):
        # psppsll and ppsll: the same bytes, used = allocated; dfbuffer: twice, half used
        rows = [record(structure=s, n_views=n, bytes_allocated=(n << 21) if s == "dfbuffer" else n << 20,
                       bytes_used=n << 20) for s in ("psppsll", "ppsll", "dfbuffer") for n in (4, 8)]
        canvas = Inspecting()
        figures.draw_memory(table(rows), canvas)
        legend = canvas.seen["memory-vs-n_views"]["legend"]
        self.assertEqual(sorted(legend), ["dfbuffer", "ppsll = psppsll (used = allocated)"])


class Grids(unittest.TestCase):
    """Item 2: grey images in grey, HDR tone-mapped, one reference per pass."""

    def test_a_grey_image_is_drawn_in_grey(self):
        fig, ax = plt.subplots()
        grids.draw_picture(ax, np.linspace(0, 1, 16).reshape(4, 4))
        self.assertEqual(ax.images[0].get_cmap().name, "gray")
        self.assertEqual(ax.images[0].get_clim(), (0, 1))
        grids.draw_picture(ax, np.dstack([np.full((4, 4), 0.5)] * 3))  # three equal channels
        self.assertEqual(ax.images[1].get_cmap().name, "gray")
        plt.close(fig)

    def test_tone_mapping_applies_the_exposure(self):
        encoded = grids.srgb_encode(np.array([0.02 * 10, 0.5 * 10]))
        self.assertAlmostEqual(float(grids.srgb_decode(encoded)[0]), 0.2, places=6)
        self.assertAlmostEqual(float(encoded[1]), 1.0)  # clamped
        # without an EXR, from the PNG written at exposure 1: linear 0.1 shown as 0.4 at x4
        png = os.path.join(tempfile.mkdtemp(), "hdr.png")
        plt.imsave(png, np.dstack([np.full((4, 4), float(grids.srgb_encode(np.array(0.1))))] * 3))
        pixels, source = grids.tone_mapped(png, None, 4.0)
        self.assertEqual(source, "8-bit PNG")
        self.assertAlmostEqual(float(grids.srgb_decode(pixels[0, 0, 0])), 0.4, delta=0.01)

    def test_error_maps_are_read_back_on_their_scale(self):
        # a heat map as the harness writes it (viridis at v / top): its values come back
        # within two of viridis's 256 steps, so that maps of one group share one colour bar
        values = np.random.default_rng(1).random((40, 60))
        png = os.path.join(tempfile.mkdtemp(), "diff.png")
        plt.imsave(png, values, cmap="viridis", vmin=0, vmax=1)
        recovered = grids.heat_map_values(png, 0.5)
        self.assertEqual(recovered.shape, values.shape)
        self.assertLess(float(np.abs(recovered - 0.5 * values).max()), 0.5 * 2.5 / 255)

    def test_each_pass_has_its_reference_column(self):
        rows = [record(structure="psppsll", n_views=n, config_id=f"ao{n}", reference_exr="ao.exr")
                for n in (4, 8)]
        rows += [record(structure="none", **{"pass": "hbao"}, config_id="hbao", reference_exr="ao.exr")]
        rows += [record(structure="psppsll", n_views=n, config_id=f"in{n}", reference_exr="in.exr",
                        ssim_exposure=25, **{"pass": "indirect"}) for n in (4, 8)]
        t = table(rows)
        methods = sorted(set(t.methods()))
        cells = {}
        for i in t.df.index:
            for v in ("4", "8"):
                if t.text("n_views")[i] in (v, "nan") or t.text("structure")[i] == "none":
                    cells.setdefault((v, t.methods()[i]), i)
        groups = grids.reference_groups(t, ["4", "8"], cells, methods)
        self.assertEqual(sorted(tuple(g.passes) for g in groups), [("ao", "hbao"), ("indirect",)])
        self.assertEqual([g.hdr for g in groups if g.passes == ["indirect"]], [True])
        self.assertEqual([g.exposure for g in groups if g.passes == ["indirect"]], [25.0])


class Warnings(unittest.TestCase):
    """Issue 37: the page says first when its intervals cover one run only, or a run was resumed."""

    def test_single_repetition_and_resumed_runs_are_named(self):
        once = table([record(config_id="a", repetitions=1), record(config_id="b", repetitions=1)])
        said = pages.warnings(once, [{"label": "run1", "resumed_records": "2", "started": "t0"}])
        self.assertTrue(any("2 of 2 records were measured in one repetition" in w and
                            "not between runs" in w for w in said), said)
        self.assertTrue(any("run run1 was resumed" in w and "t0" in w for w in said), said)
        widened = table([record(config_id="a", repetitions=1, time_run_to_run_spread=0.2)])
        said = pages.warnings(widened, [])
        self.assertTrue(any("widened by the machine's calibrated run-to-run spread" in w for w in said), said)
        self.assertFalse(any("not between runs" in w for w in said), said)
        repeated = table([record(config_id="a", repetitions=3)])
        self.assertEqual(pages.warnings(repeated, [{"label": "run1", "resumed_records": "0"}]), [])


class SceneNames(unittest.TestCase):
    """Issue 37: a scene file is shown (titles, groups, file names) by its name, not its path."""

    def test_a_scene_file_is_shown_by_its_name(self):
        t = table([record(scene="/usr/share/assimp/models/FBX/cubes_with_names.fbx",
                          scene_name="cubes_with_names")])
        self.assertEqual(list(t.text("scene")), ["cubes_with_names"])
        self.assertTrue(all("/usr/share" not in label for label, _ in pages.ranking_groups(t)))


class FrontTable(unittest.TestCase):
    """Item 5: per scene the non-dominated configurations (time, memory, error), ties shown."""

    def test_the_dominated_go_and_ties_stay_marked(self):
        rows = [record(config_id="fast", frame_ms_median=1, frame_ms_ci_low=0.9, frame_ms_ci_high=1.1, mse=4e-3),
                record(config_id="twin", frame_ms_median=1.05, frame_ms_ci_low=0.95, frame_ms_ci_high=1.15, mse=4e-3),
                record(config_id="good", frame_ms_median=5, frame_ms_ci_low=4.9, frame_ms_ci_high=5.1, mse=1e-3),
                record(config_id="worse", frame_ms_median=6, frame_ms_ci_low=5.9, frame_ms_ci_high=6.1, mse=2e-3),
                record(config_id="small", frame_ms_median=9, frame_ms_ci_low=8.9, frame_ms_ci_high=9.1, mse=3e-3,
                       bytes_allocated=1000)]
        shown, cut = pages.choose_rows(table(rows))
        by_config = {r[1]: r for r in shown}
        self.assertEqual(set(by_config), {"fast", "twin", "good", "small"})
        self.assertIn("time (tied)", by_config["fast"][-1])
        self.assertIn("tied in all with twin", by_config["fast"][-1])
        self.assertEqual(by_config["good"][-1], "error")
        self.assertEqual(by_config["small"][-1], "memory")
        self.assertEqual(cut, [])


class Issue37(unittest.TestCase):
    """Issue 37: numbers to the digits they support, error bars on error axes and sub-pass
    bars, a legend that matches the markers (every front-table member ringed, the ring in
    the legend)."""

    def front_rows(self):
        # "small" is on the front table only by its memory: on no time/error front
        return [record(config_id="fast", frame_ms_median=1, frame_ms_ci_low=0.9, frame_ms_ci_high=1.1, mse=4e-3),
                record(config_id="good", frame_ms_median=5, frame_ms_ci_low=4.9, frame_ms_ci_high=5.1, mse=1e-3),
                record(config_id="worse", frame_ms_median=6, frame_ms_ci_low=5.9, frame_ms_ci_high=6.1, mse=2e-3),
                record(config_id="small", frame_ms_median=9, frame_ms_ci_low=8.9, frame_ms_ci_high=9.1, mse=3e-3,
                       bytes_allocated=1000)]

    def test_derived_values_are_shown_to_their_digits(self):
        from ldmreport.table import describe, shown_value
        self.assertEqual(shown_value("4.393941402435303"), "4.394")
        for typed in ("0.5", "1e-3", "128", "1.25", "plane"):
            self.assertEqual(shown_value(typed), typed)
        self.assertEqual(describe({"d_max": "4.393941402435303"}), "d_max=4.394")
        # one axis written as two columns (image size: width, height) reads once
        self.assertEqual(describe({"scene": "cornell", "width": "64", "height": "48", "d_max": "1.5"}),
                         "scene=cornell, image size=64x48, d_max=1.5")
        self.assertEqual(shown_value("guess: 1 fragment(s) per LDM pixel"), "1 fragment/LDM pixel")
        self.assertEqual(shown_value("guess: 4 fragment(s) per LDM pixel"), "4 fragments/LDM pixel")
        rows = [record(d_max=4.393941402435303, config_id="a"), record(d_max=4.393941402435303, n_views=16, config_id="b")]
        groups = [g for g, _ in pages.ranking_groups(table(rows))]
        self.assertEqual(groups, ["cornell: ao at d_max 4.394"])

    def test_every_front_table_member_is_ringed_and_the_ring_is_in_the_legend(self):
        t = table(self.front_rows())
        listed = pages.front_table_members(t)
        self.assertEqual({t.text("config_id")[i] for i in listed}, {"fast", "good", "small"})
        rings = []

        class Rings(Inspecting):
            def inspect(self, fig, name):
                super().inspect(fig, name)
                for c in collections(fig, "PathCollection"):
                    if len(c.get_sizes()) and c.get_sizes()[0] == figures.RING_SIZE:
                        rings.extend(tuple(p) for p in c.get_offsets())

        canvas = Rings()
        figures.draw_tradeoffs(t, canvas)
        seen = canvas.seen["tradeoff-time-vs-mse"]
        self.assertEqual(sorted(rings), sorted([(1.0, 4e-3), (5.0, 1e-3), (9.0, 3e-3)]))
        self.assertIn("ringed: on the front table (time, memory, error)", seen["legend"])
        self.assertIn("Pareto front, time and this error (ok; ties kept)", seen["legend"])

    def test_error_axes_carry_the_reference_noise(self):
        t = table(self.front_rows())
        bars = []

        class Bars(Inspecting):
            def inspect(self, fig, name):
                super().inspect(fig, name)
                for seg in (seg for c in collections(fig, "LineCollection") for seg in c.get_segments()):
                    if len(seg) == 2 and seg[0][0] == seg[1][0]:  # vertical: an error bar
                        bars.append(abs(seg[1][1] - seg[0][1]))

        figures.draw_tradeoffs(t, Bars())
        # each point's bar spans its reference noise either side (ref_noise_mse 1e-6)
        self.assertEqual(len(bars), 4)
        for b in bars:
            self.assertAlmostEqual(b, 2e-6, places=12)

    def test_sub_pass_bars_carry_their_intervals(self):
        seen = {}

        class Bars(Inspecting):
            def inspect(self, fig, name):
                super().inspect(fig, name)
                seen[name] = [seg for c in collections(fig, "LineCollection") for seg in c.get_segments()]

        rows = [dict(r, construct_ms_median=1.0, construct_ms_ci_low=0.9, construct_ms_ci_high=1.1,
                     ao_ms_median=5.0, ao_ms_ci_low=4.5, ao_ms_ci_high=5.5) for r in self.front_rows()]
        figures.draw_subpass_bars(table(rows), Bars())
        # construct and ao of each of the 4 records: an interval at the end of each segment
        segments = seen["subpasses-cornell"]
        self.assertEqual(len(segments), 8)
        first = sorted(((s[0][0], s[1][0]) for s in segments if s[0][1] == 0))
        self.assertEqual(first, [(0.9, 1.1), (5.5, 6.5)])  # construct 1 [0.9, 1.1]; ao 5 [4.5, 5.5] from 1


class Style(unittest.TestCase):
    """Items 4 and 6: one title scheme; formats; paper widths."""

    def test_formats(self):
        self.assertEqual(style.parse_formats(["png,svg", "pdf", "svg"]), ["png", "svg", "pdf"])
        with self.assertRaisesRegex(ValueError, "'tiff' is not one of png, svg, pdf"):
            style.parse_formats(["tiff"])
        self.assertEqual(style.written_formats(["pdf"]), ["pdf", "png"])
        self.assertEqual(style.page_file(["figures/a.png", "figures/a.svg"]), "figures/a.svg")

    def test_titles_follow_one_scheme(self):
        self.assertEqual(style.panel_title("cornell"), "cornell")
        self.assertEqual(style.panel_title("cornell", {"d_max": "0.5"}, "build"), "cornell, d_max=0.5 | build")
        self.assertEqual(style.panel_title(None, quantity="query"), "all scenes | query")

    def test_figures_fit_a_two_column_page(self):
        rows = [record(n_views=n, mse=1e-3 / n, frame_ms_median=n) for n in (4, 8, 16)]
        rows += [record(n_views=n, mse=2e-3 / n, frame_ms_median=n, **{"pass": "indirect"},
                        ref_cache_key="other") for n in (4, 8, 16)]
        canvas = Inspecting(formats=("pdf",))
        figures.draw_tradeoffs(table(rows), canvas)
        figures.draw_scaling(table(rows), canvas)
        for name, seen in canvas.seen.items():
            self.assertIn(seen["size"][0], (style.SINGLE_COLUMN, style.DOUBLE_COLUMN), name)
            for title in seen["titles"]:
                self.assertTrue(title.startswith("cornell"), f"{name}: {title}")
        files = [f for fig in canvas.figures for f in fig["files"]]
        self.assertIn("figures/tradeoff-time-vs-mse.pdf", files)
        with open(os.path.join(canvas.out_dir, "figures/tradeoff-time-vs-mse.pdf"), "rb") as f:
            self.assertEqual(f.read(5), b"%PDF-")


class Drivers(unittest.TestCase):
    """Issue 31: records of two drivers (llvmpipe, zink) or GPU models are ranked and drawn
    apart, and the report says the comparison is across drivers, not a regression."""

    def two_drivers(self, with_driver_column=True):
        rows = []
        for run, driver, device in (("a", "llvmpipe", "llvmpipe (LLVM 15.0.6, 256 bits)"),
                                    ("z", "zink", "zink (llvmpipe (LLVM 15.0.6, 256 bits))")):
            for n in (4, 8):
                extra = {"gl_driver": driver} if with_driver_column else {}
                rows.append(record(run=run, n_views=n, device=device, frame_ms_median=n, **extra))
        return table(rows)

    def test_rankings_and_panels_are_per_driver(self):
        t = self.two_drivers()
        labels = [label for label, _ in pages.ranking_groups(t)]
        self.assertEqual(len(labels), 2, labels)
        self.assertTrue(labels[0].startswith("cornell on llvmpipe: llvmpipe"), labels)
        self.assertTrue(labels[1].startswith("cornell on zink: zink"), labels)
        titles = [title for title, _ in figures.comparable_groups(t, "", "mse")]
        self.assertEqual(len(titles), 2, titles)
        self.assertIn("on zink", titles[1])

    def test_one_driver_is_one_group(self):
        rows = [record(n_views=n, device="llvmpipe", gl_driver="llvmpipe") for n in (4, 8)]
        self.assertEqual(len(pages.ranking_groups(table(rows))), 1)

    def test_the_report_says_it_is_a_cross_driver_comparison(self):
        sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "report"))
        import ldmbench_report
        note = ldmbench_report.cross_platform_note(self.two_drivers())
        self.assertIn("A cross-driver comparison", note)
        self.assertIn("not regressions", note)
        self.assertIn("llvmpipe: llvmpipe (LLVM 15.0.6, 256 bits) (run a)", note)
        # Records from before gl_driver: grouped by their device (GL_RENDERER) alone.
        old = self.two_drivers(with_driver_column=False)
        self.assertEqual(len(pages.ranking_groups(old)), 2)
        self.assertIn("cross-device", ldmbench_report.cross_platform_note(old))
        one = table([record(n_views=n, device="llvmpipe", gl_driver="llvmpipe") for n in (4, 8)])
        self.assertIsNone(ldmbench_report.cross_platform_note(one))
        self.assertEqual(pages.device_cell({"device": "zink (llvmpipe)", "gl_driver": "zink"}), "zink: zink (llvmpipe)")
        self.assertEqual(pages.device_cell({"device": "llvmpipe"}), "llvmpipe")


if __name__ == "__main__":
    unittest.main()
