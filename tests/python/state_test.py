"""A vehicle's state carried from log to log: vmass.replay_log(state=FILE) over a vehicle's logs
in order gives what `vmassd --replay LOG --speed max --state-file FILE` gives over the same
logs: after each log the same state file, byte for byte, and every tick the estimate vmassd
published (its LCM messages, recorded through LCM's file provider).

    state_test.py BIN_DIR WORK_DIR
"""
import shutil
import sys
from pathlib import Path

import lcm
import numpy as np
import vmass

from common import fail, run, simulate, split_log

bin_dir, work = Path(sys.argv[1]), Path(sys.argv[2])
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)


def published_estimates(lcm_log: Path) -> list:
    events = lcm.EventLog(str(lcm_log), "r")
    return [vmass.mass_estimate_t.decode(e.data) for e in events if e.channel == "VMASS_ESTIMATE"]


def check_ticks(log: Path, estimates, published: list) -> None:
    if len(published) != len(estimates):
        fail(f"{log}: vmassd published {len(published)} estimates, the package has "
             f"{len(estimates)}")
    known = np.array([m.mass_known for m in published])
    if not np.array_equal(known, estimates["mass_kg"].notna().to_numpy()):
        fail(f"{log}: the ticks with a mass differ")
    for column, field in (("mass_kg", "mass_kg"), ("mass_std_kg", "mass_std_kg"),
                          ("mass_ci_low_kg", "mass_ci_low_kg"), ("mu_n", "mu_n"),
                          ("initial_mass_kg", "initial_mass_kg")):
        sent = np.array([getattr(m, field) for m in published])[known]
        if not np.array_equal(sent, estimates[column].to_numpy()[known]):
            fail(f"{log}: {column} differs from vmassd's {field}")
    times = np.array([m.utime for m in published]) * 1e-6
    if not np.array_equal(times, estimates["time_s"].to_numpy()):
        fail(f"{log}: tick times differ")
    names = [m.reason_name for m in published]
    if names != list(estimates["reason"].astype(str)):
        fail(f"{log}: reasons differ")


drive = simulate(bin_dir, work / "sim", "--vehicle", "suv-4", "--scenario", "urban", "--seed",
                 "5")
second = simulate(bin_dir, work / "sim2", "--vehicle", "suv-4", "--scenario", "highway",
                  "--seed", "5")
config = drive / "config.yaml"
logs = split_log(drive / "drive.log", 2, work, "urban") + \
    split_log(second / "drive.log", 2, work, "highway")
daemon_state, package_state = work / "vmassd.state", work / "package.state"
for n, log in enumerate(logs):
    lcm_log = work / f"{log.stem}.lcmlog"
    run(bin_dir / "vmassd", "--config", config, "--replay", log, "--speed", "max",
        "--lcm-url", f"file://{lcm_log}?mode=w", "--state-file", daemon_state)
    result = vmass.replay_log(config, log, state=package_state)
    if n > 0 and not result.state_restored:
        fail(f"{log}: the state was not restored: {result.state_message}")
    if daemon_state.read_bytes() != package_state.read_bytes():
        fail(f"{log}: the state file differs from vmassd's")
    check_ticks(log, result.estimates, published_estimates(lcm_log))
    print(f"ok: {log.name}: {len(result.estimates)} ticks and the state file after it "
          f"identical to vmassd's (restored: {result.state_restored})")
