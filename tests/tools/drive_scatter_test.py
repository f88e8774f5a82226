#!/usr/bin/env python3
"""tools/vmass_suite/drive_scatter.py: cars whose drives scatter by their regression's std and a
per-drive share f of 1 % are told apart from f = 0; lifetime rows are left out, another trailer
is another car, and a broken line is named by its file and line.

  drive_scatter_test.py SOURCE_DIR WORK_DIR
"""
import json
import os
import random
import re
import subprocess
import sys


def row(vehicle, error, mode="fresh", trailer=""):
    return {"vehicle": vehicle, "knowledge": "datasheet_scale", "deflection_sensor": False,
            "mode": mode, "car_change": trailer, "final_error_pct": error,
            "mass_std_end_pct": (0.5 ** 2 + 1.2 ** 2) ** 0.5, "model_std_end_pct": 1.2}


def shares(script, path):
    out = subprocess.run([sys.executable, script, path, "--floors", "0,1"], check=True,
                         capture_output=True, text=True).stdout
    found = dict(re.findall(r"\| (\d\.\d\d) % \| (\d+\.\d) % ", out))
    return out, float(found["0.00"]), float(found["1.00"])


def main():
    source, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    script = os.path.join(source, "tools", "vmass_suite", "drive_scatter.py")
    rng = random.Random(7)
    rows = []
    for car in range(30):
        bias = rng.gauss(0.0, 3.0)  # the car's own: a learnt kappa holds it
        for _ in range(10):
            rows.append(row(f"van-{car}", bias + rng.gauss(0.0, (0.5 ** 2 + 1.0) ** 0.5)))
        rows.append(row(f"van-{car}", 40.0, mode="lifetime"))  # not a fresh drive
        # Another trailer is another car: its bias alone would wreck the pooled scatter.
        rows += [row(f"van-{car}", bias + 30.0, trailer="another trailer")] * 3
    path = os.path.join(work, "runs.jsonl")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(json.dumps(r) for r in rows) + "\n")
    out, none, one = shares(script, path)
    failures = []
    if "60 cars, 390 fresh drives" not in out:
        failures.append("the groups: " + out)
    if not none > 20.0:
        failures.append(f"without a floor {none} % beyond, expected far more than 5 %")
    if not 2.0 <= one <= 9.0:
        failures.append(f"with the true 1 % floor {one} % beyond, expected about 5 %")
    with open(path, "a", encoding="utf-8") as f:
        f.write("{broken\n")
    broken = subprocess.run([sys.executable, script, path], capture_output=True, text=True)
    if broken.returncode == 0 or f"{path}:421" not in broken.stderr:
        failures.append("a broken line: " + broken.stderr)
    for failure in failures:
        print("FAIL:", failure)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
