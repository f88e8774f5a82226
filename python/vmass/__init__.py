"""vmass: a vehicle's mass from the CAN data it already has, from Python.

    import vmass
    config = vmass.load_config("config.yaml")          # vmass.ConfigError: file, line, key
    estimates, summary = vmass.replay(config, "drive.log")

`replay` runs the estimator of `vmass-replay --log` (the native library, the GIL released) and
gives every tick's estimate as a pandas DataFrame (or an Arrow table) with the estimate CSV's
columns, and the summary `vmass-replay --json` prints as a dict. `vmass.fleet` replays a fleet's
logs on a Dask cluster (docs/fleet.md). The LCM message types vmassd publishes decode here as
they always have: `vmass.mass_estimate_t.decode(data)` (docs/python.md).
"""
import os
import sys
from pathlib import Path

# MDF4 logs are read through the converter shipped beside the extension, run by this Python
# (which has asammdf with `pip install vmass[mdf]`), unless the environment names another.
if "VMASS_LOG_CONVERT" not in os.environ:
    os.environ["VMASS_LOG_CONVERT"] = str(Path(__file__).resolve().parent / "log_convert.py")
    os.environ.setdefault("VMASS_PYTHON", sys.executable)

from ._vmass import __version__  # noqa: E402
from .lcmtypes import *  # noqa: E402,F401,F403  vmass.mass_estimate_t, status_t, pair_t, ...
from .replay import (  # noqa: E402
    Config,
    ConfigError,
    LogError,
    ReplayResult,
    load_config,
    replay,
    replay_log,
)

__all__ = ["__version__", "Config", "ConfigError", "LogError", "ReplayResult", "load_config",
           "replay", "replay_log"]
