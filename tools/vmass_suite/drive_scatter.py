#!/usr/bin/env python3
"""drive_scatter.py: how far a car's drives read from each other, against what each drive's
interval says, from vmass-suite's lifetime JSON lines (its `fresh` rows).

  drive_scatter.py RUNS.jsonl [RUNS.jsonl ...] [--floors 0,0.25,0.5,0.75,1]

A kappa learnt from one drive on a known mass holds everything every drive of that car reads
alike. What it cannot hold is what moves from one drive to the next: the drive's regression
(its std is in the JSON line: mass_std_end_pct beyond model_std_end_pct) and a per-drive share
of the model error, f (estimator.learning.drive_error_std_fraction). For each candidate f this
prints how often a drive lies beyond 1.96 sigma of the mean of its car's other drives (leave
one out): 5 % when f is right, more when it is too small. A car is a (vehicle, load sensor,
knowledge, trailer) group: another trailer is another car.
"""
import argparse
import collections
import math
import sys

import accuracy_report  # beside this script

Z95 = 1.959963984540054


def load(paths):
    """Every JSON line of every file; a broken line stops with its file and line."""
    return [row for path in paths for row in accuracy_report.load(path)]


def usable(r):
    keys = ("final_error_pct", "mass_std_end_pct", "model_std_end_pct")
    return r.get("mode") == "fresh" and all(isinstance(r.get(k), (int, float)) for k in keys)


def regression_var(r):
    """The drive's own regression variance, in %^2: its published std beyond the model's."""
    return max(r["mass_std_end_pct"] ** 2 - r["model_std_end_pct"] ** 2, 0.0)


def cars(rows):
    groups = collections.defaultdict(list)
    for r in filter(usable, rows):
        trailer = r.get("car_change", "") != "" or r.get("trailer_drag_factor", 1.0) != 1.0
        key = (r["vehicle"], r.get("deflection_sensor"), r.get("knowledge"), trailer)
        groups[key].append((r["final_error_pct"], regression_var(r)))
    return [drives for drives in groups.values() if len(drives) >= 3]


def share_beyond(groups, floor_pct):
    """Leave-one-out share of drives beyond 1.96 sigma, and how many drives were tried."""
    beyond = total = 0
    f2 = floor_pct * floor_pct
    for drives in groups:
        n = len(drives)
        for i, (error, var) in enumerate(drives):
            others = drives[:i] + drives[i + 1:]
            mean = sum(e for e, _ in others) / (n - 1)
            mean_var = sum(v + f2 for _, v in others) / (n - 1) ** 2
            z = (error - mean) / math.sqrt(var + f2 + mean_var)
            beyond += abs(z) > Z95
            total += 1
    return beyond, total


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("runs", nargs="+")
    p.add_argument("--floors", default="0,0.25,0.5,0.75,1",
                   help="candidate per-drive floors, in %% of the mass")
    a = p.parse_args()
    try:
        floors = [float(x) for x in a.floors.split(",")]
    except ValueError:
        sys.exit(f"drive_scatter.py: --floors {a.floors!r}: not a list of numbers")
    groups = cars(load(a.runs))
    if not groups:
        sys.exit("drive_scatter.py: no car with 3 fresh drives that carry mass_std_end_pct")
    print(f"{len(groups)} cars, {sum(len(g) for g in groups)} fresh drives")
    print("| per-drive floor | drives beyond 1.96 sigma of their car's others |")
    print("|---:|---:|")
    for f in floors:
        beyond, total = share_beyond(groups, f)
        print(f"| {f:.2f} % | {100.0 * beyond / total:.1f} % ({beyond} of {total}) |")


if __name__ == "__main__":
    main()
