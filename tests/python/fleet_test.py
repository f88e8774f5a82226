"""vmass.fleet on a LocalCluster of 2 workers, over 50 logs of 5 vehicles (two simulated drives
of each, cut into the files a logger rotates), each log's result against the single-machine run
of the same logs in the same order (common.reference_run): the estimates Parquet equal to the
reference DataFrame, value for value, and the summary identical.

    fleet_test.py BIN_DIR DATA_DIR data              makes the fleet: DATA_DIR/fleet.csv
    fleet_test.py BIN_DIR DATA_DIR cluster WORK_DIR  python -m vmass.fleet --table, 2 workers
    fleet_test.py BIN_DIR DATA_DIR killed WORK_DIR   a worker killed (SIGKILL) during the run
    fleet_test.py BIN_DIR DATA_DIR bad WORK_DIR      a broken log and a broken config among
                                                     good ones
"""
import json
import os
import shutil
import signal
import sys
import time
from pathlib import Path

import pandas as pd
import vmass
from vmass.fleet import build_report, collect_fleet, read_table, submit_fleet

from common import fail, reference_run, run, simulate, split_log

VEHICLES = ["city_car-1", "compact-2", "saloon-3", "suv-4", "van-5"]
SCENARIOS = ["urban", "highway"]
PARTS = 5



def make_fleet(bin_dir: Path, work: Path) -> Path:
    """fleet.csv: 5 vehicles, 10 logs each; van-5's config rates it at 50 kg over its kerb
    mass, so that its loaded drives are overloads."""
    rows = []
    for vehicle in VEHICLES:
        folder = work / "fleet" / vehicle
        folder.mkdir(parents=True)
        for scenario in SCENARIOS:
            sim = simulate(bin_dir, work / "sim" / f"{vehicle}_{scenario}", "--vehicle", vehicle,
                           "--scenario", scenario, "--seed", "3")
            for log in split_log(sim / "drive.log", PARTS, folder, scenario):
                rows.append((vehicle, f"fleet/{vehicle}/config.yaml",
                             str(log.relative_to(work))))
        shutil.copy(sim / "vehicle.dbc", folder)
        config = (sim / "config.yaml").read_text()
        if vehicle == "van-5":
            empty = next(line.split(":")[1].split("#")[0].strip() for line in config.splitlines()
                         if "empty_mass_kg:" in line)
            config = "\n".join(f"  max_mass_kg: {float(empty) + 50}" if "max_mass_kg:" in line else line
                               for line in config.splitlines()) + "\n"
        (folder / "config.yaml").write_text(config)
    table = work / "fleet.csv"
    # highway before urban in name order: the start column says the order they were driven
    pd.DataFrame([(v, c, l, SCENARIOS.index(Path(l).stem.split("_")[0]) * 100 +
                   int(Path(l).stem.split("_")[1])) for v, c, l in rows],
                 columns=["vehicle", "config", "log", "start"]).to_csv(table, index=False)
    return table


def check_against_reference(plan, out: Path, reference: dict) -> None:
    summary = pd.read_parquet(out / "summary.parquet")
    if len(summary) != sum(len(logs) for logs in plan.values()):
        fail(f"{len(summary)} summary rows for {sum(len(l) for l in plan.values())} logs")
    for row in summary.itertuples(index=False):
        expected = reference[(row.vehicle, row.index)]
        if isinstance(expected, str):
            if row.ok or row.error != expected:
                fail(f"{row.log}: expected the error {expected!r}, got {row.error!r}")
            continue
        if not row.ok:
            fail(f"{row.log}: failed: {row.error}")
        estimates = pd.read_parquet(row.estimates)
        pd.testing.assert_frame_equal(estimates, expected.estimates, check_exact=True,
                                      check_categorical=False)
        if json.loads(row.summary_json) != expected.summary:
            fail(f"{row.log}: summary differs from the single-machine run's")
    history = pd.read_csv(out / "mass_history.csv")
    ok = [(k, r) for k, r in reference.items() if not isinstance(r, str)]
    overloaded = sorted(k for k, r in ok if r.summary["mass_kg"] > vmass.load_config(
        plan[k[0]][k[1]].config).max_mass_kg)
    listed = sorted(zip(*pd.read_csv(out / "overloads.csv")[["vehicle", "index"]].T.values))
    if not overloaded or listed != overloaded:
        fail(f"overloads {listed}, expected {overloaded}")
    if len(history) != len(ok):
        fail(f"mass history of {len(history)} logs, {len(ok)} replayed")
    print(f"ok: {len(summary)} logs identical to the single-machine run; "
          f"{len(overloaded)} overloaded logs listed")


def kill_a_worker_during(client, futures) -> int:
    """Waits until some logs are done (not all), then kills one worker process."""
    while sum(f.done() for f in futures) < len(futures) // 5:
        time.sleep(0.02)
    pids = client.run(os.getpid)
    victim = sorted(pids.values())[0]
    os.kill(victim, signal.SIGKILL)
    return victim


def main() -> None:
    bin_dir, data, mode = Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3]
    work = Path(sys.argv[4]) if mode != "data" else data
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    if mode == "data":
        make_fleet(bin_dir, data)
        print(f"ok: {data / 'fleet.csv'}")
        return
    table = data / "fleet.csv"
    if mode == "bad":  # a copy of the table, with absolute paths, beside the bad inputs
        rows = pd.read_csv(table)
        rows[["config", "log"]] = rows[["config", "log"]].map(lambda p: str(data / p))
        broken = work / "broken.log"
        broken.write_bytes(b"\x00garbage, not a CAN log\n" * 10)
        (work / "bus-9.yaml").write_text("vehicle:\n  empty_mass_kg: [\n")
        extra = pd.DataFrame([("suv-4", rows.config[rows.vehicle == "suv-4"].iloc[0], broken, 102),
                              ("bus-9", work / "bus-9.yaml", rows.log[0], 0),
                              ("bus-9", work / "bus-9.yaml", rows.log[1], 1)], columns=rows.columns)
        table = work / "fleet.csv"
        pd.concat([rows, extra]).to_csv(table, index=False)
    plan = read_table(table)
    reference = reference_run(plan, work)
    out = work / "out"
    if mode == "killed":
        from dask.distributed import Client, LocalCluster

        with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
                Client(cluster) as client:
            futures = submit_fleet(client, plan, str(out))
            victim = kill_a_worker_during(client, futures)
            rows = collect_fleet(futures, plan)
            if victim in client.run(os.getpid).values():
                fail("the worker was not killed")
        build_report(rows, wall_s=0.0).write(str(out))
        print(f"ok: worker process {victim} killed during the run")
    else:
        done = run(sys.executable, "-m", "vmass.fleet", "--table", table, "--out", out,
                   "--workers", "2", check=False)
        expected_rc = 1 if mode == "bad" else 0
        if done.returncode != expected_rc:
            fail(f"python -m vmass.fleet: exit {done.returncode}, expected {expected_rc}: "
                 f"{done.stderr[-3000:]}")
        print(done.stderr.strip().splitlines()[-1])
    if mode == "bad":
        failures = pd.read_csv(out / "failures.csv")
        if sorted(failures.log.str.rsplit("/", n=1).str[-1]) != sorted(
                ["broken.log", Path(rows.log[0]).name, Path(rows.log[1]).name]):
            fail(f"failures: {failures.to_dict('records')}")
        located = [e.startswith(f"{work / 'bus-9.yaml'}:3: ") or e.startswith(f"{broken}: ")
                   for e in failures.error]
        if not all(located):
            fail(f"failures not located: {failures.error.tolist()}")
        print(f"ok: {len(failures)} bad inputs reported, the other logs done")
    check_against_reference(plan, out, reference)


if __name__ == "__main__":  # the LocalCluster's worker processes import this file
    main()
