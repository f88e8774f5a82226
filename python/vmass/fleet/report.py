"""What a fleet run gives (under its output folder):

    estimates/<vehicle>/<index>_<stem>.parquet   every tick's estimate of each log (task.py)
    summary.parquet, summary.csv     one row per log: where it is, ok or its error, frames, the
                                     final estimate (vmass-replay --json's keys; the nested
                                     per-block counts in summary_json), overload figures
    mass_history.csv                 each vehicle's mass log after log: the final estimate and
                                     its interval, in time order
    overloads.csv                    the logs whose final mass exceeds the vehicle's
                                     max_mass_kg (overloaded), or whose whole 95 % interval does
                                     (overload_certain)
    failures.csv                     each log that could not be replayed, and why
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import List

import pandas as pd

_SCALARS = ["estimator", "duration_s", "ticks", "has_estimate", "mass_kg", "ci_low_kg",
            "ci_high_kg", "mass_std_kg", "mu_n", "initial_mass_kg", "prior", "status", "reason",
            "pairs_used", "pairs_accepted", "longitudinal_availability", "lateral_availability",
            "reinitialisations"]
_HISTORY = ["vehicle", "index", "log", "start_s", "end_s", "mass_kg", "ci_low_kg", "ci_high_kg",
            "mass_std_kg", "status", "max_mass_kg", "overloaded", "overload_certain",
            "peak_mass_kg", "time_over_max_s"]


def _flat(row: dict) -> dict:
    flat = {k: v for k, v in row.items() if k not in ("summary", "state")}
    summary = row.get("summary") or {}
    for key in _SCALARS:
        flat[key] = summary.get(key)
    flat["summary_json"] = json.dumps(summary, sort_keys=True) if summary else ""
    return flat


def _overload_flags(table: pd.DataFrame) -> pd.DataFrame:
    mass = pd.to_numeric(table.get("mass_kg"), errors="coerce")
    low = pd.to_numeric(table.get("ci_low_kg"), errors="coerce")
    limit = pd.to_numeric(table.get("max_mass_kg"), errors="coerce")
    table["overloaded"] = (mass > limit).fillna(False).astype(bool)
    table["overload_certain"] = (low > limit).fillna(False).astype(bool)
    return table


@dataclass
class FleetReport:
    summary: pd.DataFrame  # one row per log, in plan order
    wall_s: float

    @property
    def failures(self) -> pd.DataFrame:
        return self.summary.loc[~self.summary["ok"], ["vehicle", "index", "log", "error"]]

    @property
    def mass_history(self) -> pd.DataFrame:
        ok = self.summary[self.summary["ok"]]
        return ok[[c for c in _HISTORY if c in ok]].sort_values(["vehicle", "index"])

    @property
    def overloads(self) -> pd.DataFrame:
        history = self.mass_history
        return history[history["overloaded"] | history["overload_certain"]]

    @property
    def driving_h(self) -> float:
        return float(pd.to_numeric(self.summary.get("duration_s"), errors="coerce").sum()) / 3600

    def write(self, out_dir: str) -> None:
        out = Path(out_dir)
        out.mkdir(parents=True, exist_ok=True)
        self.summary.to_parquet(out / "summary.parquet", index=False)
        self.summary.to_csv(out / "summary.csv", index=False)
        self.mass_history.to_csv(out / "mass_history.csv", index=False)
        self.overloads.to_csv(out / "overloads.csv", index=False)
        self.failures.to_csv(out / "failures.csv", index=False)


def build_report(rows: List[dict], wall_s: float) -> FleetReport:
    table = pd.DataFrame([_flat(r) for r in rows])
    return FleetReport(summary=_overload_flags(table), wall_s=wall_s)
