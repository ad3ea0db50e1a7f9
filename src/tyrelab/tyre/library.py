"""Built-in tyres, loadable by name.

``load_tyre("xzl-16.00R20", pressure=300e3)`` returns the Michelin XZL
16.00R20 of the seed thesis at an inflation pressure [Pa]. Its property files
exist at the three measured pressures (100, 300 and 550 kPa); in between, the
load-deflection table and the linear stiffness are interpolated linearly in
pressure, point by point. Any other name is taken as a path to a ``.tir`` or to a
Project Chrono ``.json`` tyre file, at the pressure it states; an MF-Tyre 6.1/6.2 file
with pressure terms may be moved to another (:func:`tyrelab.tyre.pressure.at_pressure`).
"""

from __future__ import annotations

import copy
from importlib import resources
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import InputError
from .params import Tyre
from .pressure import at_pressure
from .tir import read_tir

#: built-in tyre -> measured pressures [Pa]
BUILT_IN = {"xzl-16.00R20": (100e3, 300e3, 550e3)}
#: built-in tyres described at one pressure only, by their file in tyre/data
SINGLE_FILE = {"hmmwv-pac89": "hmmwv-pac89.tir"}
DEFAULT_TYRE = "xzl-16.00R20"
DEFAULT_PRESSURE = 300e3


def _data(name: str):
    return resources.files("tyrelab.tyre").joinpath("data", name)


def _built_in_file(name: str, pressure: float) -> Tyre:
    with resources.as_file(_data(f"{name}_{pressure / 1e3:.0f}kPa.tir")) as path:
        return Tyre.from_tir(read_tir(path), name=name)


def load_tyre(name: str | Path = DEFAULT_TYRE, pressure: float | None = None) -> Tyre:
    """A built-in tyre by name at ``pressure`` [Pa], or a ``.tir`` or Project Chrono ``.json``
    file by path (:func:`tyrelab.tyre.chrono_json.read_chrono_tyre`)."""
    key = str(name)
    single = {k.lower(): k for k in SINGLE_FILE}.get(key.lower())
    if single is not None:
        with resources.as_file(_data(SINGLE_FILE[single])) as path:
            tyre = Tyre.from_tir(read_tir(path), name=single)
        if pressure is not None and not (np.isfinite(tyre.pressure) and np.isclose(pressure, tyre.pressure)):
            raise InputError(f"{single} is described at one pressure only", field="pressure")
        return tyre
    match = {k.lower(): k for k in BUILT_IN}.get(key.lower())
    if match is None:
        path = Path(key)
        if path.suffix.lower() not in (".tir", ".json") and not path.exists():
            raise InputError(f"unknown tyre '{key}'; expected a built-in tyre "
                             f"({', '.join([*BUILT_IN, *SINGLE_FILE])}), a .tir file or a "
                             "Project Chrono .json tyre file", field="tyre")
        if path.suffix.lower() == ".json":  # Project Chrono's JSON tyre files
            from .chrono_json import read_chrono_tyre
            tyre = read_chrono_tyre(path)
        else:
            tyre = Tyre.from_tir(read_tir(path), name=path.stem)
        if pressure is not None and not (np.isfinite(tyre.pressure) and np.isclose(pressure, tyre.pressure)):
            tyre = at_pressure(tyre, float(pressure), str(path))   # MF-Tyre 6.x; else refused
        return tyre
    pressures = BUILT_IN[match]
    p = DEFAULT_PRESSURE if pressure is None else float(pressure)
    if not (pressures[0] <= p <= pressures[-1]):
        raise InputError(f"pressure {p / 1e3:g} kPa is outside the measured range "
                         f"{pressures[0] / 1e3:g}-{pressures[-1] / 1e3:g} kPa of {match}",
                         field="pressure")
    for q in pressures:
        if np.isclose(p, q):
            return _built_in_file(match, q)
    hi = int(np.searchsorted(pressures, p))
    lo_t, hi_t = _built_in_file(match, pressures[hi - 1]), _built_in_file(match, pressures[hi])
    w = (p - pressures[hi - 1]) / (pressures[hi] - pressures[hi - 1])
    tyre = copy.deepcopy(lo_t)
    tyre.vertical_stiffness = (1 - w) * lo_t.vertical_stiffness + w * hi_t.vertical_stiffness
    table = lo_t.load_deflection.copy()
    table[:, 1] = (1 - w) * lo_t.load_deflection[:, 1] + w * hi_t.load_deflection[:, 1]
    tyre.load_deflection = table
    tyre.pressure = p
    tyre.tir.set("OPERATING_CONDITIONS", "INFLPRES", p)
    tyre.tir.set_table("DEFLECTION_LOAD_CURVE", table, ["pen", "fz"])
    return tyre


def load_cases(name: str = DEFAULT_TYRE) -> pd.DataFrame:
    """The trailer load cases of thesis Table 3-4 (wheel load in kg and N)."""
    with resources.as_file(_data(f"{name}_load_cases.csv")) as path:
        df = pd.read_csv(path)
    df["wheel_load_N"] = df["wheel_load_kg"] * 9.80665
    return df.set_index("load_case")


def modal_table(name: str = DEFAULT_TYRE) -> pd.DataFrame:
    """Measured modal frequencies and damping (thesis Table 3-3)."""
    with resources.as_file(_data(f"{name}_modal.csv")) as path:
        return pd.read_csv(path)
