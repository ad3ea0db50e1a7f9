"""Slip of the contact point and the handling model that turns it into forces.

Slip definitions (ISO / TYDEX W-axis, as the Magic Formula uses them)::

    kappa = -V_sx / |V_x|          (> 0 when driving)
    alpha = atan(V_sy / |V_x|)     (> 0 when the contact point slides left)

with V_x the wheel-centre speed along the W-axis x, V_sx and V_sy the slip
velocity of the tyre material at the contact point, and |V_x| held at or
above ``VXLOW`` so slip stays finite at standstill.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ...errors import InputError
from .mf.kernel import mf_forces
from .pac89 import pac89_forces, pac89_params

#: speed below which slip is computed with this speed instead [m/s]
VXLOW = 1.0


def handling_params(tyre, handling: str) -> np.ndarray:
    """Handling parameters packed for :func:`handling_forces`."""
    if handling == "none":
        return np.zeros(1)
    if handling == "pac89":
        return np.ascontiguousarray(pac89_params(tyre), dtype=np.float64)
    if handling == "mf":
        from .mf import MagicFormula
        mf = MagicFormula.from_tir(tyre.tir)
        pressure = tyre.pressure if np.isfinite(tyre.pressure) else 0.0
        return np.r_[111.0, pressure, np.asarray(mf.coefficients, dtype=np.float64)]
    raise InputError(f"unknown handling model '{handling}'", field="handling")


@nb.njit(cache=True)
def _mf(hp, fz, kappa, alpha, gamma, vx):
    out = np.empty(6)
    mf_forces(hp[2:], int(hp[0]), fz, kappa, alpha, gamma, vx, hp[1], out)
    return out[0], out[1], out[4]


@nb.njit(cache=True)
def handling_forces(handling, hp, fz, v_long, v_slip_x, v_slip_y, gamma):
    """``(FXW, FYW, MZW, kappa, alpha)`` of the handling model ``handling``."""
    vx = abs(v_long)
    if vx < VXLOW:
        vx = VXLOW
    kappa = -v_slip_x / vx
    alpha = math.atan(v_slip_y / vx)
    if handling == 1:
        fx, fy, mz = pac89_forces(hp, fz, kappa, alpha, gamma)
    elif handling == 2:
        fx, fy, mz = _mf(hp, fz, kappa, alpha, gamma, v_long)
    else:
        fx, fy, mz = 0.0, 0.0, 0.0
    return fx, fy, mz, kappa, alpha
