#!/usr/bin/env python3
"""What each gear's longitudinal pairs say about the mass (docs/estimator.md, "Issue 30, step 3,
measured before building"): the rotating masses are configured per gear, and an error in them
moves every pair of that gear alike, so the gears' effective masses side by side show it.

    pairs_by_gear.py PAIRS.csv [PAIRS.csv ...] [--accepted] [--mass KG]

PAIRS.csv: `vmass-lcmlog-csv LOG --pairs PAIRS.csv` of a vmassd run with `lcm.publish_pairs:
true` (one row per candidate pair). For each gear (or derived-ratio plateau) with pairs:

    effective mass  the weighted least-squares slope of (y + rotating term) over the
                    differenced acceleration: M + m_rot(g) if the config's m_rot is right
    m_rot           the rotating mass the config gives that gear
    excess          with --mass (a known mass): effective - mass - m_rot, kg

and the line through the gears' effective masses against m_rot: its slope is the factor by which
the pairs see the configured rotating masses (1 if right; the intercept is the mass). Weights are
the estimator's (the pair's weight over its noise variance). The stds count every pair as
independent; consecutive pairs share their noise for a few ticks, so the true stds are wider.
Standard library only.
"""
import argparse
import csv
import math
import sys
from collections import defaultdict


class Sums:
    """Weighted sums of one gear's pairs for the slope of force over acceleration."""

    def __init__(self):
        self.n = 0
        self.aa = self.af = self.ff = 0.0
        self.rotating_kg = []

    def add(self, w, da, force, rotating_kg):
        self.n += 1
        self.aa += w * da * da
        self.af += w * da * force
        self.ff += w * force * force
        self.rotating_kg.append(rotating_kg)

    def slope(self):
        return self.af / self.aa

    def slope_std(self):
        if self.n < 3:
            return math.inf
        residual = max(self.ff - self.af * self.af / self.aa, 0.0)
        return math.sqrt(residual / (self.n - 1) / self.aa)

    def rotating_mass_kg(self):
        values = sorted(self.rotating_kg)
        return values[len(values) // 2]


def read_pairs(paths, accepted_only):
    by_gear = defaultdict(Sums)
    for path in paths:
        try:
            f = open(path, newline="")
        except OSError as e:
            sys.exit(f"pairs_by_gear: {path}: {e.strerror}")
        with f:
            for line, row in enumerate(csv.DictReader(f), start=2):
                try:
                    if row["block"] != "longitudinal" or (accepted_only and row["accepted"] != "1"):
                        continue
                    da = float(row["delta_accel_mps2"])
                    noise = float(row["noise_std_n"])
                    weight = float(row["weight"]) / (noise * noise if noise > 0 else 1.0)
                    force = float(row["y_n"]) + float(row["rotating_n"])
                    by_gear[int(row["gear"])].add(weight, da, force, float(row["rotating_mass_kg"]))
                except (KeyError, ValueError, TypeError) as e:  # a missing column or cell
                    sys.exit(f"pairs_by_gear: {path}:{line}: not a row of vmass-lcmlog-csv "
                             f"--pairs ({type(e).__name__}: {e})")
    return by_gear


def line_through(points):
    """Weighted line y = a + b x through (x, y, std) points; (a, b, std of b) or None."""
    kept = [(x, y, 1.0 / (s * s)) for x, y, s in points if s > 0 and math.isfinite(s)]
    if len(kept) < 2:
        return None
    xs, ys, w = zip(*kept)
    sw = sum(w)
    mx = sum(wi * x for wi, x in zip(w, xs)) / sw
    my = sum(wi * y for wi, y in zip(w, ys)) / sw
    sxx = sum(wi * (x - mx) ** 2 for wi, x in zip(w, xs))
    if sxx <= 0:
        return None
    b = sum(wi * (x - mx) * (y - my) for wi, x, y in zip(w, xs, ys)) / sxx
    return my - b * mx, b, math.sqrt(1.0 / sxx)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("pairs", nargs="+", help="vmass-lcmlog-csv --pairs CSV")
    p.add_argument("--accepted", action="store_true", help="only the pairs the regressor took")
    p.add_argument("--mass", type=float, help="the true (known) mass, kg: adds the excess column")
    a = p.parse_args()
    by_gear = read_pairs(a.pairs, a.accepted)
    usable = {g: s for g, s in sorted(by_gear.items()) if s.n >= 3 and s.aa > 0}
    if not usable:
        sys.exit("pairs_by_gear: no gear with 3 or more longitudinal pairs")
    header = "| gear | pairs | m_rot kg | effective mass kg | std kg |"
    print(header + (" excess over mass + m_rot, kg |" if a.mass else ""))
    print("|---:" * (6 if a.mass else 5) + "|")
    points = []
    for gear, s in usable.items():
        m_rot, eff, std = s.rotating_mass_kg(), s.slope(), s.slope_std()
        points.append((m_rot, eff, std))
        row = f"| {gear} | {s.n} | {m_rot:.1f} | {eff:.1f} | {std:.1f} |"
        print(row + (f" {eff - a.mass - m_rot:+.1f} |" if a.mass else ""))
    line = line_through(points)
    if line is None:
        print("\none gear (or one m_rot): the rotating masses cannot be told from the mass")
    else:
        intercept, slope, slope_std = line
        print(f"\nline through the gears: effective = {intercept:.1f} kg + {slope:.3f} "
              f"(+- {slope_std:.3f}) x m_rot")


if __name__ == "__main__":
    main()
