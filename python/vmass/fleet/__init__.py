"""vmass.fleet: a fleet's logs replayed on a Dask cluster (docs/fleet.md).

    from vmass.fleet import read_table, run_fleet, ClusterSpec
    report = run_fleet(read_table("fleet.csv"), "out", ClusterSpec(workers=2))
    report.mass_history, report.overloads, report.failures

or `python -m vmass.fleet --table fleet.csv --out out` (`--scheduler tcp://host:8786` for a
running cluster).
"""
from .plan import LogSpec, PlanError, read_folders, read_table
from .report import FleetReport, build_report
from .run import ClusterSpec, collect_fleet, run_fleet, submit_fleet
from .task import estimates_path, replay_task

__all__ = ["ClusterSpec", "FleetReport", "build_report", "collect_fleet", "LogSpec", "PlanError", "estimates_path",
           "read_folders", "read_table", "replay_task", "run_fleet", "submit_fleet"]
