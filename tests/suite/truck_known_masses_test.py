"""vmass-suite --truck-known-mass-drives: a heavy truck's lifetime declares its true mass at
those drives (issue 30: two known masses at different loads for a truck), every other class at
--known-mass-drives; the variants without a known mass declare nothing.

Usage: truck_known_masses_test.py VMASS-SUITE WORK-DIR"""
import json
import pathlib
import subprocess
import sys


def main():
    suite, work = sys.argv[1], pathlib.Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    out = work / "lives.jsonl"
    subprocess.run([suite, "--lifetime", "3", "--vehicle-ids", "heavy_truck-7,city_car-1",
                    "--known-mass-drives", "1", "--truck-known-mass-drives", "1,2",
                    "--knowledge", "known_scale", "--estimators", "bayes", "--jobs", "2",
                    "--out", str(out)], check=True)
    declared, loads = {}, {}
    for line in out.read_text().splitlines():
        r = json.loads(line)
        if r["mode"] != "lifetime":
            continue
        loads[(r["vehicle"], r["drive"])] = r["true_final_mass_kg"]
        if r["known_mass"]:
            declared.setdefault(r["vehicle"], set())
            if r["known_mass_declared"]:
                declared[r["vehicle"]].add(r["drive"])
        elif r["known_mass_declared"]:
            sys.exit(f"{r['vehicle']} drive {r['drive']}: declared without a known mass")
    want = {"heavy_truck-7": {1, 2}, "city_car-1": {1}}
    if declared != want:
        sys.exit(f"declared at {declared}, expected {want}")
    # The truck's two known masses are at different loads (every even drive's load changes).
    m1, m2 = loads[("heavy_truck-7", 1)], loads[("heavy_truck-7", 2)]
    if abs(m2 - m1) < 0.05 * m1:
        sys.exit(f"heavy_truck-7's known masses {m1:.0f} and {m2:.0f} kg are one load")
    print(f"heavy_truck-7 declared at drives 1 and 2 ({m1:.0f}, {m2:.0f} kg), city_car-1 at 1")


if __name__ == "__main__":
    main()
