#!/usr/bin/env python3
"""Checks a vmass-suite subset against regression thresholds.

  check_thresholds.py RESULTS.jsonl THRESHOLDS.json
  check_thresholds.py --runs-only RESULTS.jsonl    (a sanitizer build: no run failed, no figure)

THRESHOLDS.json: {"cells": [{"scenario", "estimator", "knowledge", "min_supported",
"max_median_abs_final_pct", "min_coverage_end_pct" (optional), "max_p90_abs_final_pct"
(optional)}, ...], "excited_runs_take_pairs": true (optional)}. A cell's scenario "*" pools every
scenario. Every cell must have at least min_supported supported runs, a median (and p90) |final
error| at most the maximum, and (when given) at least that share of runs whose interval covers
the truth at the end. With excited_runs_take_pairs, every supported run with at least 5 s of
|dv/dt| > 0.3 m/s^2 above 2 m/s (excited_s) must have used pairs. Any failed run fails.
Prints one line per cell with the measured values; exit 1 on any violation.
"""
import json
import sys


def median(values):
    v = sorted(values)
    if not v:
        return None
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def p90(values):
    v = sorted(values)
    if not v:
        return None
    k = 0.9 * (len(v) - 1)
    i = int(k)
    return v[i] if i + 1 >= len(v) else v[i] + (k - i) * (v[i + 1] - v[i])


def starved_runs(rows):
    """Supported runs with 5 s of excitation that used no pair (issue 29's rule)."""
    starved = [r for r in rows if r.get("supported") and (r.get("excited_s") or 0) >= 5.0
               and not r.get("pairs_used")]
    for r in starved:
        print(f"NO PAIR {r['vehicle']} {r['scenario']} {r['estimator']} {r['knowledge']}: "
              f"{r['excited_s']:.1f} s excited, refused {r.get('refused_longitudinal')}")
    return len(starved)


def runs_only(path):
    """Under a sanitizer the figures are the optimized build's to check: here every run must
    have finished and every vmass result be supported."""
    rows = [json.loads(line) for line in open(path, encoding="utf-8") if line.strip()]
    failed = [r for r in rows if "error" in r]
    unsupported = [r for r in rows if "error" not in r and not r.get("supported")]
    for r in failed:
        print(f"FAILED RUN {r['vehicle']} {r['scenario']} seed {r['seed']}: {r['error']}")
    for r in unsupported:
        print(f"UNSUPPORTED {r['vehicle']} {r['scenario']} {r['estimator']}: {r.get('unsupported_reason')}")
    print(f"{len(rows)} results, {len(failed)} failed runs, {len(unsupported)} unsupported")
    sys.exit(1 if failed or unsupported or not rows else 0)


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--runs-only":
        runs_only(sys.argv[2])
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = [json.loads(line) for line in open(sys.argv[1], encoding="utf-8") if line.strip()]
    cells = json.load(open(sys.argv[2], encoding="utf-8"))["cells"]
    failures = [r for r in rows if "error" in r]
    for r in failures:
        print(f"FAILED RUN {r['vehicle']} {r['scenario']} seed {r['seed']}: {r['error']}")
    bad = len(failures)
    for c in cells:
        runs = [r for r in rows if c["scenario"] in ("*", r.get("scenario"))
                and r.get("estimator") == c["estimator"] and r.get("knowledge") == c["knowledge"]]
        ok = [r for r in runs if r.get("supported")]
        errs = [abs(r["final_error_pct"]) for r in ok if r.get("final_error_pct") is not None]
        errs += [float("inf")] * (len(ok) - len(errs))
        med = median(errs)
        cov = [r.get("covered_end") for r in ok if r.get("covered_end") in (0, 1)]
        cov_pct = 100.0 * sum(cov) / len(cov) if cov else None
        problems = []
        if len(ok) < c["min_supported"]:
            problems.append(f"supported {len(ok)} < {c['min_supported']}")
        if med is None or med > c["max_median_abs_final_pct"]:
            problems.append(f"median |final| {med} > {c['max_median_abs_final_pct']}")
        if "max_p90_abs_final_pct" in c and (not errs or p90(errs) > c["max_p90_abs_final_pct"]):
            problems.append(f"p90 |final| {p90(errs)} > {c['max_p90_abs_final_pct']}")
        if "min_coverage_end_pct" in c and (cov_pct is None or cov_pct < c["min_coverage_end_pct"]):
            problems.append(f"coverage at the end {cov_pct} < {c['min_coverage_end_pct']}")
        status = "FAIL " + "; ".join(problems) if problems else "ok"
        med_text = "-" if med is None else f"{med:.2f}"
        cov_text = "-" if cov_pct is None else f"{cov_pct:.0f}"
        print(f"{c['scenario']:<16} {c['estimator']:<11} {c['knowledge']:<15} supported "
              f"{len(ok)}/{len(runs)}  median |final| {med_text} %  covers at end {cov_text} %  {status}")
        bad += 1 if problems else 0
    if json.load(open(sys.argv[2], encoding="utf-8")).get("excited_runs_take_pairs"):
        starved = starved_runs(rows)
        print(f"excited runs without a pair: {starved}")
        bad += starved
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
