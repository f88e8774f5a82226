"""A fleet's logs on a Dask cluster: each vehicle's logs one after the other (the state of one
log is the next one's input), the vehicles side by side; a LocalCluster unless a scheduler's
address or a client is given. Dask runs a task again when its worker is lost; a task's result
does not depend on where or when it runs (task.py), so the run's result does not either."""
from __future__ import annotations

import time
from contextlib import ExitStack
from dataclasses import dataclass
from typing import Dict, List, Optional

from .plan import LogSpec
from .report import FleetReport, build_report
from .task import replay_task


@dataclass
class ClusterSpec:
    scheduler: str = ""  # "" for a LocalCluster, else tcp://host:8786
    workers: int = 2  # LocalCluster only: worker processes, one thread each


def _client(spec: ClusterSpec, stack: ExitStack):
    from dask.distributed import Client, LocalCluster

    if spec.scheduler:
        return stack.enter_context(Client(spec.scheduler))
    cluster = stack.enter_context(LocalCluster(n_workers=spec.workers, threads_per_worker=1,
                                               processes=True, dashboard_address=None))
    return stack.enter_context(Client(cluster))


def submit_fleet(client, plan: Dict[str, List[LogSpec]], out_dir: str, carry_state: bool = True,
                 interface: str = "") -> list:
    """The tasks of every log on `client`, a future per log in plan order; with carry_state each
    log's task takes its vehicle's previous one's result (its state)."""
    futures = []
    for vehicle, logs in plan.items():
        previous = None
        for spec in logs:
            future = client.submit(replay_task, spec, previous if carry_state else None, out_dir,
                                   carry_state, interface,
                                   key=f"vmass-replay-{vehicle}-{spec.index}-{id(plan):x}",
                                   pure=False)
            futures.append(future)
            previous = future
    return futures


def collect_fleet(futures: list, plan: Dict[str, List[LogSpec]]) -> List[dict]:
    """Each log's row; a task that raised (not a bad log or config: those return their error)
    is reported on its row too."""
    specs = [spec for logs in plan.values() for spec in logs]
    rows = []
    for spec, future in zip(specs, futures):
        try:
            rows.append(future.result())
        except Exception as e:  # noqa: BLE001 - reported for the log, the others go on
            rows.append({"vehicle": spec.vehicle, "index": spec.index, "log": spec.log,
                         "config": spec.config, "ok": False, "state": None,
                         "error": f"task failed: {type(e).__name__}: {e}"})
    return rows


def run_fleet(plan: Dict[str, List[LogSpec]], out_dir: str, cluster: Optional[ClusterSpec] = None,
              client=None, carry_state: bool = True, interface: str = "") -> FleetReport:
    """Replays the fleet and writes its outputs under out_dir (report.py); returns the report."""
    started = time.perf_counter()
    with ExitStack() as stack:
        client = client or _client(cluster or ClusterSpec(), stack)
        futures = submit_fleet(client, plan, out_dir, carry_state, interface)
        rows = collect_fleet(futures, plan)
    report = build_report(rows, wall_s=time.perf_counter() - started)
    report.write(out_dir)
    return report
