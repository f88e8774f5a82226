"""The fleet layer's throughput against vmass-replay --logs (docs/performance.md, "A fleet on
Dask"): the same logs of an hour each, the estimates written by the workers (Parquet) and by
vmass-replay (--out-dir, CSV), runs alternated, medians. A worker holds one core, as a
vmass-replay job does. The cluster is started (and vmass imported on its workers) before the
clock starts: what is timed is the replay of the logs, scheduling included.

    fleet_bench.py BIN_DIR HOUR_LOG CONFIG WORK [--logs 16] [--runs 3]
(run with the Python that has vmass installed; scripts/fleet-benchmark.sh runs it)
"""
import argparse
import shutil
import statistics
import subprocess
import time
from pathlib import Path


def timed_replay(bin_dir: Path, config: Path, folder: Path, out: Path, jobs: int) -> float:
    shutil.rmtree(out, ignore_errors=True)
    start = time.perf_counter()
    subprocess.run([str(bin_dir / "vmass-replay"), "--config", str(config), "--logs", str(folder),
                    "--jobs", str(jobs), "--out-dir", str(out)], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def timed_fleet(client, plan, out: Path) -> float:
    from vmass.fleet import run_fleet

    shutil.rmtree(out, ignore_errors=True)
    start = time.perf_counter()
    report = run_fleet(plan, str(out), client=client, carry_state=False)
    elapsed = time.perf_counter() - start
    assert not len(report.failures), report.failures
    return elapsed


def main() -> None:
    p = argparse.ArgumentParser()
    for name in ("bin_dir", "hour_log", "config", "work"):
        p.add_argument(name, type=Path)
    p.add_argument("--logs", type=int, default=16)
    p.add_argument("--runs", type=int, default=3)
    a = p.parse_args()
    from dask.distributed import Client, LocalCluster
    from vmass.fleet import LogSpec

    folder = a.work / "logs"
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    for i in range(a.logs):
        (folder / f"hour{i:03d}.log").symlink_to(a.hour_log.resolve())
    logs = sorted(folder.iterdir())
    plan = {f"v{i:03d}": [LogSpec(f"v{i:03d}", str(a.config), str(log), 0)]
            for i, log in enumerate(logs)}
    times = {}
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            client.run(lambda: __import__("vmass.fleet"))
            for _ in range(a.runs):
                times.setdefault(("vmass-replay", workers), []).append(
                    timed_replay(a.bin_dir, a.config, folder, a.work / "csv", workers))
                times.setdefault(("vmass.fleet", workers), []).append(
                    timed_fleet(client, plan, a.work / "parquet"))
    hours = a.logs * 1.0
    print(f"{a.logs} logs of an hour each, {a.runs} runs of each, alternated; medians\n")
    print("| run | workers (jobs) | wall s | logs/s | h of driving/s | per worker, h/s |")
    print("|---|---:|---:|---:|---:|---:|")
    med = {k: statistics.median(v) for k, v in times.items()}
    for (name, workers), wall in sorted(med.items()):
        print(f"| `{name}` | {workers} | {wall:.2f} | {a.logs / wall:.2f} | {hours / wall:.2f} "
              f"| {hours / wall / workers:.2f} |")
    for workers in (1, 2):
        overhead = med[("vmass.fleet", workers)] / med[("vmass-replay", workers)] - 1
        print(f"\nvmass.fleet against vmass-replay --logs, {workers} worker(s): "
              f"{100 * overhead:+.1f} % wall time")
    print(f"vmass.fleet 1 -> 2 workers: {med[('vmass.fleet', 1)] / med[('vmass.fleet', 2)]:.2f}x;"
          f" vmass-replay 1 -> 2 jobs: "
          f"{med[('vmass-replay', 1)] / med[('vmass-replay', 2)]:.2f}x")


if __name__ == "__main__":
    main()
