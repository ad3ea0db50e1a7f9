"""A single property file at another inflation pressure: MF-Tyre 6.1/6.2's pressure terms.

An MF-Tyre 6.1/6.2 property file states how the tyre changes with its inflation pressure
(Besselink, Schmeitz & Pacejka, "An improved Magic Formula/Swift tyre model that can handle
inflation pressure changes", VSD 48 (2010)): every pressure term is written in
``dpi = (INFLPRES - NOMPRES) / NOMPRES``, and ``INFLPRES`` is the one value a user changes
("Modify this parameter to change inflation pressure", as the files say). So such a file is
moved to a pressure by setting ``INFLPRES``: the vertical law's ``1 + PFZ1 dpi``
(:mod:`tyrelab.tyre.tir_physics`) and the Magic Formula's ``PPX*``, ``PPY*``, ``PPZ*`` and
``PPMX1`` terms follow. Any other file describes its own pressure only.
"""

from __future__ import annotations

import copy
import math

import numpy as np

from ..errors import InputError
from .params import Tyre

#: MF-Tyre 6.1/6.2's pressure coefficients, where the sections keep them
PRESSURE_TERMS = {
    "VERTICAL": ("PFZ1",),
    "LONGITUDINAL_COEFFICIENTS": ("PPX1", "PPX2", "PPX3", "PPX4"),
    "LATERAL_COEFFICIENTS": ("PPY1", "PPY2", "PPY3", "PPY4", "PPY5"),
    "ALIGNING_COEFFICIENTS": ("PPZ1", "PPZ2"),
    "OVERTURNING_COEFFICIENTS": ("PPMX1",),
}
#: the Magic Formula versions with pressure terms (``[MODEL] FITTYP``)
PRESSURE_FITTYP = (61, 62)


def pressure_terms(tyre: Tyre) -> list[str]:
    """The pressure coefficients of ``tyre``'s file that are not zero, if it is an MF-Tyre
    6.1/6.2 file with ``NOMPRES``; else none."""
    tir = tyre.tir
    if tir.get("MODEL", "FITTYP") not in PRESSURE_FITTYP or not tir.get("OPERATING_CONDITIONS", "NOMPRES"):
        return []
    return [key for section, keys in PRESSURE_TERMS.items() for key in keys
            if tir.get(section, key) not in (None, 0, 0.0)]


def at_pressure(tyre: Tyre, pressure: float, source: str) -> Tyre:
    """``tyre`` (read from ``source``) at inflation ``pressure`` [Pa]: its file's INFLPRES set
    to it, when the file has pressure terms (:func:`pressure_terms`) and no part measured at
    its own pressure only, and the pressure is within its ``[INFLATION_PRESSURE_RANGE]``.
    Anything else is an :class:`InputError` saying why."""
    if not (np.isfinite(pressure) and pressure > 0):
        raise InputError(f"pressure must be a positive number, got {pressure}", field="pressure")
    tir = tyre.tir
    if not math.isfinite(tyre.pressure):
        raise InputError(f"{source} states no inflation pressure ([OPERATING_CONDITIONS] INFLPRES "
                         "or [TIRE_CONDITIONS] IP), so it cannot be run at a pressure given "
                         "apart from it: leave out the pressure, or state it in the file",
                         field="pressure")
    stated = f"{tyre.pressure / 1e3:g} kPa"
    if not pressure_terms(tyre):
        raise InputError(f"{source} describes {stated} only; a single property file cannot be moved "
                         "to another pressure unless it is an MF-Tyre 6.1/6.2 file with pressure "
                         "coefficients (PFZ1, PPX1, ...) and NOMPRES", field="pressure")
    if tir.has("DEFLECTION_LOAD_CURVE"):
        raise InputError(f"{source}'s [DEFLECTION_LOAD_CURVE] is measured at {stated} only, and it "
                         "replaces the pressure-dependent Q_FZ2 law; remove the table to move the "
                         "file to another pressure", field="pressure")
    low = tir.get("INFLATION_PRESSURE_RANGE", "PRESMIN")
    high = tir.get("INFLATION_PRESSURE_RANGE", "PRESMAX")
    if (low is not None and pressure < low) or (high is not None and pressure > high):
        span = f"{(low or 0) / 1e3:g}-{high / 1e3:g} kPa" if high is not None else f"from {low / 1e3:g} kPa"
        raise InputError(f"pressure {pressure / 1e3:g} kPa is outside {source}'s valid range "
                         f"[INFLATION_PRESSURE_RANGE] {span}", field="pressure")
    moved = copy.deepcopy(tir)
    moved.set("OPERATING_CONDITIONS", "INFLPRES", float(pressure))
    return Tyre.from_tir(moved, name=tyre.name)
