"""One log through the estimator: vmass.load_config, vmass.replay and vmass.replay_log.

The numbers are those of `vmass-replay --log LOG` (and, with `state=`, of `vmassd --replay LOG
--speed max --state-file STATE`): the native library does the replay (python/src), this module
only names the results.
"""
from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field
from typing import Any, Iterable, Optional, Union

import numpy as np
import pandas as pd

from . import _vmass

PathLike = Union[str, "os.PathLike[str]"]

# "file:line: key: message", "file:line: message" or "file: message" (vmass/config/config.hpp).
_LOCATED = re.compile(r"^(?P<file>.+?):(?P<line>\d+): (?:(?P<key>[A-Za-z_][\w.\[\]-]*): )?")
_FILE_ONLY = re.compile(r"^(?P<file>[^:]+): ")


class ConfigError(ValueError):
    """A config the tools refuse, with where: `file`, `line` (None when the whole file is at
    fault) and `key` (None when no key is), and the tools' message as str(error)."""

    def __init__(self, message: str):
        super().__init__(message)
        self.file: Optional[str] = None
        self.line: Optional[int] = None
        self.key: Optional[str] = None
        located = _LOCATED.match(message) or _FILE_ONLY.match(message)
        if located:
            groups = located.groupdict()
            self.file = groups["file"]
            self.line = int(groups["line"]) if groups.get("line") else None
            self.key = groups.get("key")


class LogError(ValueError):
    """A log that could not be replayed: unreadable, no frame, a truth of another time base
    (`bad_input` True, vmass-replay's exit 2), or not readable to its end (False, exit 1)."""

    def __init__(self, message: str, bad_input: bool):
        super().__init__(message)
        self.bad_input = bad_input


class Config:
    """A vehicle's config as the tools read it (the YAML, its DBC and the daemon's sections)."""

    def __init__(self, native: Any, path: str):
        self._native = native
        self.path = path

    @property
    def max_mass_kg(self) -> float:
        """vehicle.max_mass_kg (inf when the config does not give it)."""
        return self._native.max_mass_kg

    @property
    def empty_mass_kg(self) -> float:
        return self._native.empty_mass_kg

    @property
    def tick_rate_hz(self) -> float:
        return self._native.tick_rate_hz

    def __repr__(self) -> str:
        return f"vmass.Config({self.path!r})"

    def __reduce__(self):
        # A Dask worker gets the path and reads the file itself (the native object is not
        # picklable; the file is what every tool reads).
        return (load_config, (self.path,))


def load_config(path: PathLike) -> Config:
    """Reads a config as vmass-replay and vmassd do; ConfigError names the file, line and key."""
    path = os.fspath(path)
    native, error = _vmass.load_config(path)
    if native is None:
        raise ConfigError(error)
    return Config(native, path)


@dataclass
class ReplayResult:
    """Everything one replay gave; `vmass.replay` returns (estimates, summary) of it."""

    log: str
    estimates: Any  # pandas.DataFrame, or pyarrow.Table with arrow=True
    summary: dict
    log_format: str
    frames: int
    corrupt_lines: int
    other_interface_frames: int
    warnings: list = field(default_factory=list)
    state_message: str = ""
    state_restored: bool = False
    state_saved: bool = False
    state_save_error: str = ""


_STATUS_NAMES = _vmass.status_names()
_REASON_NAMES = _vmass.reason_names()
_CODED = {"status": _STATUS_NAMES, "reason": _REASON_NAMES}


def _as_dataframe(columns: dict) -> pd.DataFrame:
    data = {}
    for name, values in columns.items():
        names = _CODED.get(name)
        data[name] = (pd.Categorical.from_codes(values.astype(np.int16), categories=names)
                      if names else values)
    return pd.DataFrame(data)


def _as_arrow(columns: dict):
    import pyarrow as pa

    arrays = []
    for name, values in columns.items():
        names = _CODED.get(name)
        arrays.append(pa.DictionaryArray.from_arrays(pa.array(values.astype(np.int8)),
                                                     pa.array(names))
                      if names else pa.array(values))
    return pa.Table.from_arrays(arrays, names=list(columns))


def _known_mass_text(event: Union[str, Iterable[float]]) -> str:
    if isinstance(event, str):
        return event
    return ":".join(repr(float(v)) for v in event)


def replay_log(config: Union[Config, PathLike], log: PathLike, *, interface: str = "",
               estimator: str = "", truth: Optional[PathLike] = None,
               known_masses: Iterable[Union[str, Iterable[float]]] = (),
               state: Optional[PathLike] = None, arrow: bool = False) -> ReplayResult:
    """Replays one CAN log (candump -l, Vector ASC or BLF, PEAK TRC, ASAM MDF4: the format found
    from the content) as `vmass-replay --log` does, the GIL released while it runs.

    interface: one interface of a multi-interface log ("can1"); estimator: "rls" or "bayes"
    instead of the config's; truth: a truth CSV (adds the error and coverage to the summary);
    known_masses: "TIME:KG[:STD]" or (time_s, kg[, std_kg]), as --known-mass; state: vmassd's
    state file, restored before the log and saved after it, as `vmassd --replay LOG --speed max
    --state-file STATE` does; arrow: estimates as a pyarrow.Table instead of a DataFrame.
    Raises ConfigError for a refused config and LogError for a log that could not be replayed.
    """
    if not isinstance(config, Config):
        config = load_config(config)
    options = _vmass.ReplayOptions()
    options.interface = interface
    options.estimator = estimator
    options.truth_path = os.fspath(truth) if truth is not None else ""
    options.known_masses = [_known_mass_text(e) for e in known_masses]
    options.state_path = os.fspath(state) if state is not None else ""
    log = os.fspath(log)
    out = _vmass.replay_log(config._native, log, options)
    if out["error"]:
        raise LogError(out["error"], out["bad_input"])
    columns = out["columns"]
    return ReplayResult(
        log=log,
        estimates=_as_arrow(columns) if arrow else _as_dataframe(columns),
        summary=json.loads(out["summary_json"]),
        log_format=out["log_format"],
        frames=out["frames"],
        corrupt_lines=out["corrupt_lines"],
        other_interface_frames=out["other_interface_frames"],
        warnings=list(out["warnings"]),
        state_message=out["state_message"],
        state_restored=out["state_restored"],
        state_saved=out["state_saved"],
        state_save_error=out["state_save_error"],
    )


def replay(config: Union[Config, PathLike], log: PathLike, **options: Any):
    """(estimates, summary) of replay_log(config, log, **options)."""
    result = replay_log(config, log, **options)
    return result.estimates, result.summary
