#!/usr/bin/env python3
"""vmass-accuracy-report's new-tyres table (--tyre-lifetime) and another trailer's
(--trailer-lifetime): lifetime rows grouped before the change, its drive and the one after, and
after that; fresh rows left out; every number computed from the rows.

  accuracy_report_tyres_test.py VMASS_ACCURACY_REPORT WORK_DIR
"""
import os
import sys

from report_check import check, report_text


def row(drive, error, covered, known=True, mode="lifetime"):
    return {"vehicle": "van-5", "knowledge": "datasheet_scale", "estimator": "bayes",
            "deflection_sensor": True, "known_mass": known, "mode": mode, "drive": drive,
            "tyres_declared": drive == 4 and mode == "lifetime", "supported": True,
            "final_error_pct": error, "covered_20s": 1, "covered_60s": 1,
            "covered_end": covered, "halfwidth_end_pct": 3.0 + drive}


def main():
    report, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    rows = [row(1, 0.0, 1), row(2, -1.0, 1), row(3, 2.0, 1),  # before the change (drive 4)
            row(4, 3.0, 0), row(5, -1.0, 1),                   # its drive and the next
            row(6, 0.5, 1), row(7, -0.25, 1), row(8, 0.75, 1),  # after
            row(6, 9.0, 0, mode="fresh")]                      # not a lifetime row
    text = report_text(report, "--tyre-lifetime", rows, os.path.join(work, "tyres.jsonl"))
    expected = [
        "fitted before drive 4 and declared at its start",
        "| datasheet scale | yes | yes | 1-3 | 3 | 1.00 | 1.80 | 100 / 100 / 100 | 5.00 |",
        "| datasheet scale | yes | yes | 4-5 | 2 | 2.00 | 2.80 | 100 / 100 / 50 | 7.50 |",
        "| datasheet scale | yes | yes | 6+ | 3 | 0.50 | 0.70 | 100 / 100 / 100 | 10.00 |",
    ]
    check(text, expected)

    # Another trailer before drive 3 of a tractor's life, known masses on drives 1 and 2.
    trailer = [dict(r, vehicle="tractor-200001", tyres_declared=False,
                    known_mass_declared=r["drive"] <= 2 and r["mode"] == "lifetime",
                    car_change="another trailer (drag area +12.0 %, rolling -5.0 %)"
                    if r["drive"] == 3 else "") for r in rows]
    text = report_text(report, "--trailer-lifetime", trailer,
                       os.path.join(work, "trailer.jsonl"))
    check(text, [
        "coupled before drive 3; a known mass declared on drives 1, 2 where",
        "| datasheet scale | yes | yes | 1-2 | 2 | 0.50 | 0.90 | 100 / 100 / 100 | 4.50 |",
        "| datasheet scale | yes | yes | 3-4 | 2 | 2.50 | 2.90 | 100 / 100 / 50 | 6.50 |",
        "| datasheet scale | yes | yes | 5+ | 4 | 0.62 | 0.93 | 100 / 100 / 100 | 9.50 |",
    ])
    print("ok")


if __name__ == "__main__":
    main()
