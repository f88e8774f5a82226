#!/usr/bin/env python3
"""vmass-accuracy-report's lifetime tables with known masses (--lifetime): which drives declared
one, by class where a heavy truck's differ (vmass-suite --truck-known-mass-drives), and the runs
without the sensor from drive 5 on by class and by scenario; every number computed from the
rows.

  accuracy_report_known_mass_test.py VMASS_ACCURACY_REPORT WORK_DIR
"""
import os
import sys

from report_check import check, report_text


def row(vehicle, drive, error, known, mode="lifetime", scenario="urban"):
    truck = vehicle.startswith("heavy_truck")
    return {"vehicle": vehicle, "class": vehicle.split("-")[0], "knowledge": "datasheet_scale",
            "estimator": "bayes", "deflection_sensor": False, "known_mass": known, "mode": mode,
            "drive": drive, "scenario": scenario, "supported": True, "restored": drive > 1,
            "known_mass_declared": known and mode == "lifetime" and drive <= (2 if truck else 1),
            "final_error_pct": error, "covered_20s": 1, "covered_60s": 1, "covered_end": 1,
            "halfwidth_end_pct": 4.0, "learnt_scale_std": 0.02}


def main():
    report, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    rows = []
    for vehicle in ("city_car-1", "heavy_truck-7"):
        for drive in range(1, 8):
            scenario = "highway" if drive % 2 else "urban"
            error = (1.0 if vehicle.startswith("heavy") else -0.5) * drive / 7
            for mode, known in (("lifetime", False), ("fresh", False), ("lifetime", True)):
                rows.append(row(vehicle, drive, error, known, mode, scenario))
    text = report_text(report, "--lifetime", rows, os.path.join(work, "lifetime.jsonl"))
    # From drive 5: the car's -5/14, -6/14, -7/14 %, the truck's 5/7, 6/7, 1 %; highway holds
    # drives 5 and 7, urban drive 6.
    expected = [
        "With a known mass declared on drive(s) 1 (heavy truck: 1, 2)",
        "without the deflection sensor, from drive 5 on, by class and by scenario",
        "| city car | 3 | 0.43 | 0.49 | -0.43 | 100 / 100 / 100 | 4.00 |",
        "| heavy truck | 3 | 0.86 | 0.97 | 0.86 | 100 / 100 / 100 | 4.00 |",
        "| highway | 4 | 0.61 | 0.91 | 0.18 | 100 / 100 / 100 | 4.00 |",
        "| urban | 2 | 0.64 | 0.81 | 0.21 | 100 / 100 / 100 | 4.00 |",
    ]
    check(text, expected)
    print("ok")


if __name__ == "__main__":
    main()
