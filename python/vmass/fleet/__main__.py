"""python -m vmass.fleet: a fleet's logs replayed on a Dask cluster (docs/fleet.md).

    python -m vmass.fleet (--table FLEET.csv | --folders ROOT) --out DIR
                          [--scheduler tcp://HOST:8786 | --workers N] [--fresh] [--interface NAME]

Exit status: 0 every log replayed, 1 some logs failed (failures.csv says why), 2 bad usage or an
input that names no fleet.
"""
from __future__ import annotations

import argparse
import sys

from .plan import PlanError, read_folders, read_table
from .run import ClusterSpec, run_fleet


def _arguments(argv):
    p = argparse.ArgumentParser(prog="python -m vmass.fleet",
                                description="Replay a fleet's CAN logs on a Dask cluster.")
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--table", help="CSV or Parquet: vehicle, config, log[, start]")
    source.add_argument("--folders", help="ROOT/<vehicle>/config.yaml and its logs")
    p.add_argument("--out", required=True, help="output folder (estimates, summary, ...)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", default="", help="a running cluster's scheduler address")
    where.add_argument("--workers", type=int, default=2,
                       help="worker processes of the LocalCluster (default 2)")
    p.add_argument("--fresh", action="store_true",
                   help="replay every log from a fresh state (no state carried from log to log)")
    p.add_argument("--interface", default="", help="one interface of multi-interface logs")
    args = p.parse_args(argv)
    if args.workers < 1:
        p.error("--workers must be at least 1")
    return args


def main(argv=None) -> int:
    args = _arguments(argv)
    try:
        plan = read_table(args.table) if args.table else read_folders(args.folders)
    except PlanError as e:
        print(f"vmass.fleet: {e}", file=sys.stderr)
        return 2
    cluster = ClusterSpec(scheduler=args.scheduler, workers=args.workers)
    report = run_fleet(plan, args.out, cluster, carry_state=not args.fresh,
                       interface=args.interface)
    for row in report.failures.itertuples(index=False):
        print(f"vmass.fleet: {row.vehicle}: {row.error}", file=sys.stderr)
    logs = len(report.summary)
    print(f"vmass.fleet: {len(plan)} vehicles, {logs} logs ({len(report.failures)} failed), "
          f"{report.driving_h:.2f} h of driving in {report.wall_s:.2f} s: "
          f"{logs / report.wall_s:.1f} logs/s, {report.driving_h / report.wall_s:.2f} h of "
          f"driving per second; {len(report.overloads)} overloaded logs; results in {args.out}",
          file=sys.stderr)
    return 1 if len(report.failures) else 0


if __name__ == "__main__":
    sys.exit(main())
