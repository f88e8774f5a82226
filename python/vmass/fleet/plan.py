"""What a fleet run replays: each vehicle's config and its logs in time order.

Two inputs give it: a table (CSV or Parquet) with the columns vehicle, config, log and, when the
log names do not sort in time order, start (any sortable value: a time stamp, a drive number);
or folders, one per vehicle, each holding its config.yaml and its logs (*.log, *.asc, *.blf,
*.trc, *.mf4, *.mdf, in any sub-folder), whose names sort in time order (loggers name files by
date). Relative paths in a table are relative to the table's folder.
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List

import pandas as pd

LOG_SUFFIXES = {".log", ".asc", ".blf", ".trc", ".mf4", ".mdf"}


class PlanError(ValueError):
    """An input that names no fleet: the table or folder and what is wrong with it."""


@dataclass(frozen=True)
class LogSpec:
    vehicle: str
    config: str
    log: str
    index: int  # the log's place in its vehicle's time order, from 0


def _by_vehicle(rows: pd.DataFrame) -> Dict[str, List[LogSpec]]:
    plan: Dict[str, List[LogSpec]] = {}
    order = ["vehicle", "log"]
    if "start" in rows:
        order.insert(1, "start")
        numbers = pd.to_numeric(rows["start"], errors="coerce")
        if numbers.notna().all():  # drive numbers or epoch seconds: by value, not as text
            rows = rows.assign(start=numbers)
    for vehicle, logs in rows.sort_values(order, kind="stable").groupby("vehicle", sort=True):
        plan[str(vehicle)] = [LogSpec(str(vehicle), row.config, row.log, i)
                              for i, row in enumerate(logs.itertuples(index=False))]
    return plan


def read_table(path: os.PathLike | str) -> Dict[str, List[LogSpec]]:
    """The fleet a table names, each vehicle's logs in time order."""
    path = Path(path)
    try:
        rows = pd.read_parquet(path) if path.suffix == ".parquet" else pd.read_csv(
            path, dtype=str, keep_default_na=False)
    except (OSError, ValueError) as e:
        raise PlanError(f"{path}: cannot read the table: {e}") from e
    missing = {"vehicle", "config", "log"} - set(rows.columns)
    if missing:
        raise PlanError(f"{path}: no column {', '.join(sorted(missing))} "
                        "(expected vehicle, config, log and optionally start)")
    if rows.empty:
        raise PlanError(f"{path}: no logs")
    for column in ("vehicle", "config", "log"):
        blank = rows[column].astype(str).str.strip() == ""
        if blank.any():
            raise PlanError(f"{path}:{int(blank.idxmax()) + 2}: {column}: empty")
    base = path.parent
    for column in ("config", "log"):
        rows[column] = [str(base / p) for p in rows[column].astype(str)]
    return _by_vehicle(rows)


def read_folders(root: os.PathLike | str) -> Dict[str, List[LogSpec]]:
    """The fleet in ROOT/<vehicle>/config.yaml and ROOT/<vehicle>/**/<log>."""
    root = Path(root)
    if not root.is_dir():
        raise PlanError(f"{root}: not a folder")
    rows = []
    for vehicle_dir in sorted(p for p in root.iterdir() if p.is_dir()):
        logs = sorted(p for p in vehicle_dir.rglob("*")
                      if p.suffix.lower() in LOG_SUFFIXES and p.is_file())
        rows += [(vehicle_dir.name, str(vehicle_dir / "config.yaml"), str(log)) for log in logs]
    if not rows:
        raise PlanError(f"{root}: no vehicle folder with logs ({', '.join(sorted(LOG_SUFFIXES))})")
    return _by_vehicle(pd.DataFrame(rows, columns=["vehicle", "config", "log"]))
