#!/usr/bin/python3
"""vmass-plot's overlay keeps every run visible when runs coincide (RLS and Bayes over one drive
often give the same estimate): given two and three runs with identical data, when vmass-plot's
panels draw them, then each run's line differs from the others in colour, dash pattern and
marker (markers staggered), earlier runs are wider and below, and, rendered, each run's colour
still covers pixels of the mass panel (with lines drawn alike only the last run would show).

    plot_overlay_test.py PATH_TO_VMASS_PLOT
"""
import importlib.machinery
import importlib.util
import sys
import unittest

import matplotlib

matplotlib.use("Agg")
import matplotlib.colors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SCRIPT = sys.argv.pop(1) if len(sys.argv) > 1 else "vmass-plot"


def load_vmass_plot(path):
    loader = importlib.machinery.SourceFileLoader("vmass_plot", path)
    spec = importlib.util.spec_from_loader("vmass_plot", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


vp = load_vmass_plot(SCRIPT)


def coinciding_runs(labels, points=2000):
    """Runs with the very same estimates, as vmass-plot's load_run returns them."""
    t = [0.01 * i for i in range(points)]
    mass = [1600.0 + 60.0 * np.exp(-x / 4.0) * np.cos(x) for x in t]
    return [{"label": label, "path": label + ".csv", "skipped": 0, "status": None, "time_s": t,
             "mass_kg": mass, "mass_ci_low_kg": [m - 50.0 for m in mass],
             "mass_ci_high_kg": [m + 50.0 for m in mass], "mu_n": [0.5] * points,
             "initial_mass_kg": [1600.0] * points} for label in labels]


def dash_pattern(line):
    """(offset, on-off sequence) as set, before scaling by the width; None for a solid line.
    Line2D has no public getter for it (matplotlib 3.6: _unscaled_dash_pattern)."""
    return str(line._unscaled_dash_pattern)


def estimate_lines(ax, runs):
    by_label = {line.get_label(): line for line in ax.get_lines()}
    return [by_label[f"{r['label']}: estimate"] for r in runs]


def pixels_of(image, color, tolerance=0.12):
    """Pixels within `tolerance` (RGB, 0..1) of the colour drawn at the lines' alpha on white,
    or of the colour itself."""
    rgb = np.array(matplotlib.colors.to_rgb(color))
    counts = 0
    for alpha in (1.0, 0.9):
        want = alpha * rgb + (1.0 - alpha) * np.ones(3)
        counts = max(counts, int((np.abs(image[:, :, :3] - want).max(axis=2) < tolerance).sum()))
    return counts


class OverlayTest(unittest.TestCase):
    def draw(self, labels):
        runs = coinciding_runs(labels)
        fig, ax = plt.subplots(figsize=(10, 4))
        vp.draw_mass(ax, runs, None)
        self.addCleanup(plt.close, fig)
        return fig, ax, runs

    def test_each_run_has_its_own_colour_dashes_and_markers(self):
        for labels in (["rls", "bayes"], ["a", "b", "c"]):
            with self.subTest(runs=len(labels)):
                _, ax, runs = self.draw(labels)
                lines = estimate_lines(ax, runs)
                props = [(line.get_color(), dash_pattern(line), line.get_marker(),
                          str(line.get_markevery())) for line in lines]
                for i in range(len(props)):
                    for j in range(i + 1, len(props)):
                        for what, a, b in zip(("colour", "dashes", "marker", "markevery"),
                                              props[i], props[j]):
                            self.assertNotEqual(a, b, f"runs {i} and {j} share their {what}")
                for line in lines:  # markers every few points, not at each of 2000
                    start, every = line.get_markevery()
                    self.assertGreater(every, 50)
                widths = [line.get_linewidth() for line in lines]
                orders = [line.get_zorder() for line in lines]
                self.assertEqual(widths, sorted(widths, reverse=True), "earlier runs wider")
                self.assertEqual(len(set(widths)), len(widths))
                self.assertEqual(orders, sorted(orders), "later runs on top")
                legend = [t.get_text() for t in ax.get_legend().get_texts()]
                for r in runs:
                    self.assertIn(f"{r['label']}: estimate", legend)

    def test_coinciding_runs_each_stay_visible(self):
        for labels in (["rls", "bayes"], ["a", "b", "c"]):
            with self.subTest(runs=len(labels)):
                fig, ax, runs = self.draw(labels)
                ax.get_legend().remove()  # its swatches would show every colour anyway
                fig.canvas.draw()
                image = np.asarray(fig.canvas.buffer_rgba(), dtype=float) / 255.0
                lines = estimate_lines(ax, runs)
                counts = [pixels_of(image, line.get_color()) for line in lines]
                top = counts[-1]
                self.assertGreater(top, 500, f"the top run is not drawn: {counts}")
                for k, n in enumerate(counts[:-1]):
                    self.assertGreater(n, 0.15 * top,
                                       f"run {k} is hidden under the others: pixels {counts}")

    def test_one_run_is_plain(self):
        _, ax, runs = self.draw(["bayes"])
        (line,) = estimate_lines(ax, runs)
        self.assertEqual(line.get_linestyle(), "-")
        self.assertEqual(line.get_marker(), "None")


if __name__ == "__main__":
    unittest.main()
