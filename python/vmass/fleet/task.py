"""One log of a vehicle replayed on a Dask worker: the vehicle's state from the log before
carried in (as vmassd's state file carries it from drive to drive) and out, the estimates
written to Parquet. A task gives the same answer whenever and wherever it runs, so that a task
lost with its worker runs again to the same result."""
from __future__ import annotations

import os
import tempfile
import time
from pathlib import Path
from typing import Optional

import numpy as np
import pyarrow.parquet as pq

from ..replay import ConfigError, LogError, load_config, replay_log
from .plan import LogSpec

STATE_FILE = "vmassd.state"


def estimates_path(out_dir: str, spec: LogSpec) -> Path:
    """out/estimates/<vehicle>/<index>_<log stem>.parquet (the index keeps equal stems apart)."""
    return Path(out_dir) / "estimates" / spec.vehicle / f"{spec.index:05d}_{Path(spec.log).stem}.parquet"


def _write_atomically(table, path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_name(f".{path.name}.{os.getpid()}.partial")
    pq.write_table(table, partial)
    os.replace(partial, path)  # a re-run task replaces it whole: never a torn file


def _overload(estimates, max_mass_kg: float, tick_rate_hz: float) -> dict:
    mass = estimates.column("mass_kg").to_numpy(zero_copy_only=False)
    over = np.nan_to_num(mass, nan=-np.inf) > max_mass_kg
    return {"peak_mass_kg": float(np.nanmax(mass)) if np.isfinite(mass).any() else None,
            "time_over_max_s": float(over.sum() / tick_rate_hz)}


def _row(spec: LogSpec) -> dict:
    return {"vehicle": spec.vehicle, "index": spec.index, "log": spec.log, "config": spec.config,
            "ok": False, "error": ""}


def replay_task(spec: LogSpec, previous: Optional[dict], out_dir: str, carry_state: bool,
                interface: str = "") -> dict:
    """Replays spec.log after `previous` (this vehicle's task before, None for its first log);
    returns the log's summary row and, in "state", the vehicle's state file after it (bytes, or
    None before the first estimate). A log or config that cannot be replayed gives a row with
    its error, and the state passes through unchanged."""
    state_in = previous["state"] if previous is not None else None
    row = _row(spec)
    row["state"] = state_in
    started = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="vmass-fleet-") as tmp:
        state_path = os.path.join(tmp, STATE_FILE)
        if state_in is not None:
            Path(state_path).write_bytes(state_in)
        try:
            config = load_config(spec.config)
            result = replay_log(config, spec.log, interface=interface, arrow=True,
                                state=state_path if carry_state else None)
        except (ConfigError, LogError) as e:
            row["error"] = str(e)
            return row
        target = estimates_path(out_dir, spec)
        _write_atomically(result.estimates, target)
        if carry_state and os.path.exists(state_path):
            row["state"] = Path(state_path).read_bytes()
    times = result.estimates.column("time_s")
    row.update(ok=True, estimates=str(target), log_format=result.log_format,
               frames=result.frames, corrupt_lines=result.corrupt_lines,
               start_s=times[0].as_py() if len(times) else None,
               end_s=times[-1].as_py() if len(times) else None,
               max_mass_kg=config.max_mass_kg, state_restored=result.state_restored,
               state_message=result.state_message.replace(state_path, "the vehicle's state"), warnings=len(result.warnings),
               replay_s=time.perf_counter() - started,
               **_overload(result.estimates, config.max_mass_kg, config.tick_rate_hz),
               summary=result.summary)
    return row
