"""The estimate CSV (docs/formats.md) of a replay's estimates: the bytes `vmass-replay --out`
writes for the same ticks, from the full-precision columns vmass.replay returns (times with 2
decimals, masses and mu with 3, availabilities with 5, as printf rounds them; the belief cells
empty before the first estimate)."""
from __future__ import annotations

import numpy as np
import pandas as pd

COLUMNS = ["time_s", "mass_kg", "mass_ci_low_kg", "mass_ci_high_kg", "mu_n", "status",
           "mass_std_kg", "reason", "longitudinal_pairs", "lateral_pairs",
           "longitudinal_availability", "lateral_availability", "initial_mass_kg"]
_DECIMALS = {"time_s": 2, "mass_kg": 3, "mass_ci_low_kg": 3, "mass_ci_high_kg": 3, "mu_n": 3,
             "mass_std_kg": 3, "longitudinal_availability": 5, "lateral_availability": 5,
             "initial_mass_kg": 3}
_BELIEF = {"mass_kg", "mass_ci_low_kg", "mass_ci_high_kg", "mu_n", "mass_std_kg",
           "initial_mass_kg"}


def _cells(estimates: pd.DataFrame, name: str, has_mass: np.ndarray) -> np.ndarray:
    values = estimates[name].to_numpy()
    if name not in _DECIMALS:
        return values.astype(str)
    cells = np.char.mod(f"%.{_DECIMALS[name]}f", values.astype(float))
    return np.where(has_mass, cells, "") if name in _BELIEF else cells


def to_estimate_csv(estimates: pd.DataFrame) -> str:
    """The estimate CSV's text, header and one line per tick."""
    has_mass = estimates["mass_kg"].notna().to_numpy()
    columns = [_cells(estimates, name, has_mass) for name in COLUMNS]
    rows = [",".join(cells) for cells in zip(*columns)]
    return "\n".join([",".join(COLUMNS)] + rows) + "\n"
