"""Static press: the non-rolling tyre pushed onto a plate or a cleat (thesis 3.3).

The rim is held level at a fixed position and pressed down; the load is the
vertical force the plate or cleat takes. Deflection is counted from first
touch of the obstacle's top, as the lab measured it. ``press`` accepts
``"plate"`` (the flat steel plate of 3.3.1) or ``"cleat:WxH"`` with a
direction: ``"lateral"`` (cleat axis across the wheel plane, as a tyre rolls
over it) or ``"longitudinal"`` (cleat axis in the wheel plane).
"""

from __future__ import annotations

import re

import numba as nb
import numpy as np
import pandas as pd

from ..errors import InputError
from ..road.obstacles import Cleat, Flat, Ridge
from ..tyre.contact.point import GEO_SIZE
from ..tyre.kernel import OUT_SIZE, TyreModel, wheel_force

DIRECTIONS = ("lateral", "longitudinal")


@nb.njit(cache=True)
def press_sweep(model, handling, vp, kn, co, cp, hp, gp, z, zi, ts, centre_z, out):
    """Static wheel loads for each centre height: ``out[k] = (Fx, Fy, Fz, rho)``.

    For analytic contact models only (no internal state): the ring model
    finds its static shape by its own relaxation (:mod:`tyrelab.tyre.ring`).
    """
    geo = np.empty(GEO_SIZE)
    f = np.empty(OUT_SIZE)
    for k in range(centre_z.shape[0]):
        wheel_force(model, handling, vp, kn, co, cp, hp, gp, z, zi, ts, 0.0, 0.0, centre_z[k],
                    0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, geo, f)
        out[k, 0] = f[0]
        out[k, 1] = f[1]
        out[k, 2] = f[2]
        out[k, 3] = f[9]


def press_road(test: str = "plate", direction: str = "lateral"):
    """The plate or cleat of a static test, and the height of its top [m]."""
    if test == "plate":
        return Flat(), 0.0
    m = re.fullmatch(r"cleat:(\d+(?:\.\d*)?)x(\d+(?:\.\d*)?)", test)
    if not m:
        raise InputError(f"unknown static test '{test}', expected 'plate' or 'cleat:WxH' (mm)",
                         field="test")
    w, h = float(m.group(1)) / 1e3, float(m.group(2)) / 1e3
    if direction not in DIRECTIONS:
        raise InputError(f"unknown direction '{direction}', expected {' or '.join(DIRECTIONS)}",
                         field="direction")
    if direction == "lateral":
        return Cleat(w, h, angle=0.0, start=-w / 2), h
    return Ridge(w, h), h


def static_press(model: TyreModel, deflection, test: str = "plate",
                 direction: str = "lateral") -> pd.DataFrame:
    """Load [N] on the plate or cleat at each press ``deflection`` [m].

    Returns a table with ``deflection``, ``load`` (vertical force on the
    tyre), ``FX``, ``FY`` (road on tyre) and the model's own tyre deflection
    ``DEFLECT``.
    """
    d = np.atleast_1d(np.asarray(deflection, float))
    if np.any(~np.isfinite(d)) or np.any(d < 0):
        raise InputError("press deflections must be finite and >= 0", field="deflection")
    road, top = press_road(test, direction)
    grid = road.grid()
    if model.is_ring:
        from ..tyre.ring.static import ring_static_press
        return ring_static_press(model, grid, top, d)
    args = model.kernel_args(grid)
    zc = top + model.tyre.unloaded_radius - d
    out = np.zeros((d.size, 4))
    from ._entries import entry
    entry("press", model)(*args, model.initial_state(0.0), zc, out)
    return pd.DataFrame({"deflection": d, "load": out[:, 2], "FX": out[:, 0], "FY": out[:, 1],
                         "DEFLECT": np.maximum(out[:, 3], 0.0)})
