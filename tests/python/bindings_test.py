"""vmass.replay against vmass-replay: on the demo drive and on a population drive, each written
as candump -l, Vector ASC, Vector BLF, PEAK TRC and ASAM MDF4 by independent writers
(tests/logs/write_logs.py), the estimates give the tool's estimate CSV byte for byte
(vmass.estimate_csv) and the summary is its --json object; the Arrow table holds the same.
Then: located config errors, a log that cannot be replayed, the GIL released during a replay
(a FIFO the main thread feeds while the replay reads it), and the LCM types.

    bindings_test.py BIN_DIR WORK_DIR
"""
import faulthandler
import json
import os
import shutil
import sys
import threading
from pathlib import Path

import vmass
from vmass.estimate_csv import to_estimate_csv

from common import fail, run, simulate

bin_dir, work = Path(sys.argv[1]), Path(sys.argv[2])
here = Path(__file__).resolve().parent
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)


def formats_of(drive: Path) -> list:
    """The drive's log in every format (the MDF4 one read through the package's converter)."""
    out = drive / "formats"
    run(sys.executable, here.parent / "logs" / "write_logs.py", drive / "drive.log", out,
        env=dict(os.environ, TZ="UTC"))
    return [drive / "drive.log"] + [out / f"drive.{ext}" for ext in ("asc", "blf", "trc", "mf4")]


def check_against_tool(config: Path, log: Path, *extra: str, **options) -> None:
    ref_csv = work / "ref.csv"
    tool = run(bin_dir / "vmass-replay", "--config", config, "--log", log, "--json", "--out",
               ref_csv, *extra)
    result = vmass.replay_log(config, log, **options)
    if to_estimate_csv(result.estimates) != ref_csv.read_text():
        fail(f"{log}: the estimates differ from vmass-replay's CSV")
    if result.summary != json.loads(tool.stdout):
        fail(f"{log}: summary {result.summary} != vmass-replay --json {tool.stdout}")
    table, _ = vmass.replay(config, log, arrow=True, **options)
    if to_estimate_csv(table.to_pandas()) != ref_csv.read_text():
        fail(f"{log}: the Arrow table differs from vmass-replay's CSV")
    print(f"ok: {log.relative_to(work)} ({result.log_format}): {len(result.estimates)} ticks "
          f"identical to vmass-replay, summary identical")


def check_config_errors(config: Path) -> None:
    lines = config.read_text().splitlines()
    line = next(i for i, text in enumerate(lines, 1) if "empty_mass_kg:" in text)
    lines[line - 1] = "  empty_mass_kg: heavy"
    bad = work / "bad.yaml"
    bad.write_text("\n".join(lines) + "\n")
    tool = run(bin_dir / "vmass-replay", "--config", bad, "--log", "x", check=False)
    try:
        vmass.load_config(bad)
        fail("a config with a bad number was loaded")
    except vmass.ConfigError as e:
        if (e.file, e.line, e.key) != (str(bad), line, "vehicle.empty_mass_kg"):
            fail(f"config error located at {(e.file, e.line, e.key)}: {e}")
        if tool.returncode != 2 or tool.stderr.strip() != f"vmass-replay: {e}":
            fail(f"the tool said {tool.stderr!r}, the package {e}")
    try:
        vmass.replay(work / "missing.yaml", "x.log")
        fail("a missing config was loaded")
    except vmass.ConfigError as e:
        if e.file != str(work / "missing.yaml") or e.line is not None:
            fail(f"missing config located at {(e.file, e.line, e.key)}")
    print("ok: config errors located (file, line, key) as the tool locates them")


def check_log_errors(config: Path) -> None:
    garbage = work / "garbage.log"
    garbage.write_text("this is no CAN log\nnor is this\n")
    tool = run(bin_dir / "vmass-replay", "--config", config, "--log", garbage, check=False)
    try:
        vmass.replay(config, garbage)
        fail("a garbage log was replayed")
    except vmass.LogError as e:
        if not e.bad_input or tool.returncode != 2 or f"vmass-replay: {e}" not in tool.stderr:
            fail(f"the tool said {tool.stderr!r} ({tool.returncode}), the package {e}")
    print(f"ok: a log that is no log: LogError, as the tool says it")


def check_gil_released(config: Path, log: Path) -> None:
    """The replay thread blocks on a FIFO that only this (Python) thread writes: with the GIL
    held during the replay, neither could go on (the watchdog fails the test after 120 s)."""
    fifo = work / "drive.fifo"
    os.mkfifo(fifo)
    result = {}
    reader = threading.Thread(target=lambda: result.update(run=vmass.replay(config, fifo)))
    faulthandler.dump_traceback_later(120, exit=True)
    reader.start()
    with open(fifo, "wb") as w:  # blocks until the native reader opens it
        w.write(log.read_bytes())
    reader.join()
    faulthandler.cancel_dump_traceback_later()
    estimates, _ = vmass.replay(config, log)
    if "run" not in result or not result["run"][0].equals(estimates):
        fail("the replay of the FIFO differs from the file's")
    print("ok: the GIL is released while a log replays (a FIFO fed by the Python thread)")


def check_lcm_types() -> None:
    e = vmass.mass_estimate_t()
    e.mass_known, e.mass_kg, e.status_name = True, 1650.5, "converged"
    back = vmass.mass_estimate_t.decode(e.encode())
    if (back.mass_known, back.mass_kg, back.status_name) != (True, 1650.5, "converged"):
        fail("mass_estimate_t does not round-trip")
    print("ok: the LCM types decode to Python objects (vmass.mass_estimate_t, status_t, ...)")


demo = simulate(bin_dir, work / "demo", "--scenario", "paper_exp2", "--seed", "1", "--noise",
                "eps3")
population = simulate(bin_dir, work / "van", "--vehicle", "van-5", "--scenario", "urban",
                      "--seed", "1")
for drive in (demo, population):
    for log in formats_of(drive):
        check_against_tool(drive / "config.yaml", log)
check_against_tool(demo / "config.yaml", demo / "drive.log", "--truth", demo / "truth.csv",
                   "--estimator", "rls", truth=demo / "truth.csv", estimator="rls")
check_config_errors(demo / "config.yaml")
check_log_errors(demo / "config.yaml")
check_gil_released(demo / "config.yaml", demo / "drive.log")
check_lcm_types()
