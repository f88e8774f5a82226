"""What the tests of the Python package share: running the project's tools, simulated drives
(vmass-sim) cut into the files a logger rotates, and the single-machine reference run."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Dict, List

import vmass


def fail(message: str) -> None:
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def run(*args, check: bool = True, **kwargs) -> subprocess.CompletedProcess:
    done = subprocess.run([str(a) for a in args], capture_output=True, text=True, **kwargs)
    if check and done.returncode != 0:
        fail(f"{' '.join(map(str, args))}: exit {done.returncode}: {done.stderr[-2000:]}")
    return done


def simulate(bin_dir: Path, out: Path, *args: str) -> Path:
    """A drive of vmass-sim into `out` (config.yaml, vehicle.dbc, drive.log, truth.csv)."""
    run(bin_dir / "vmass-sim", *args, "--out", out)
    return out


def split_log(log: Path, parts: int, out_dir: Path, stem: str) -> List[Path]:
    """The candump log cut into `parts` consecutive files, as a logger rotating its files."""
    lines = log.read_text().splitlines(keepends=True)
    size = -(-len(lines) // parts)
    paths = []
    for i in range(parts):
        path = out_dir / f"{stem}_{i:02d}.log"
        path.write_text("".join(lines[i * size:(i + 1) * size]))
        paths.append(path)
    return paths


def reference_run(plan: Dict[str, list], work: Path) -> Dict[tuple, vmass.ReplayResult]:
    """The single-machine run: each vehicle's logs in order in this process, its state carried
    through a state file; {(vehicle, index): result}, or the LogError/ConfigError text."""
    results = {}
    for vehicle, specs in plan.items():
        state = work / f"{vehicle}.state"
        if state.exists():
            state.unlink()
        for spec in specs:
            try:
                results[(vehicle, spec.index)] = vmass.replay_log(spec.config, spec.log,
                                                                  state=state)
            except (vmass.ConfigError, vmass.LogError) as e:
                results[(vehicle, spec.index)] = str(e)
    return results

