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
from numba.core import types
from numba.core.errors import TypingError
from numba.extending import overload

from ...errors import InputError
from .mf.kernel import mf_forces
from .pac89 import pac89_forces, pac89_params

#: speed below which slip is computed with this speed instead [m/s]
VXLOW = 1.0
#: slip step of the forward difference giving the slip stiffness
DKAPPA = 1e-5


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
def slip(v_long, v_slip_x, v_slip_y):
    """``(kappa, alpha)`` from the contact point's velocities (module docstring)."""
    vx = abs(v_long)
    if vx < VXLOW:
        vx = VXLOW
    return -v_slip_x / vx, math.atan(v_slip_y / vx)


def handling_forces(handling, hp, fz, v_long, v_slip_x, v_slip_y, gamma):
    """``(FXW, FYW, MZW, kappa, alpha, dFXW/dkappa)`` of handling model ``handling``.

    ``handling`` is a compile-time constant. The slip stiffness dFXW/dkappa
    (a forward difference) lets a rig integrate the wheel spin implicitly.
    """
    raise NotImplementedError("compiled only")


@overload(handling_forces, prefer_literal=True)
def _handling_forces(handling, hp, fz, v_long, v_slip_x, v_slip_y, gamma):
    if not isinstance(handling, types.IntegerLiteral):
        raise TypingError("the handling model id must be a compile-time constant")
    h = handling.literal_value
    if h == 0:
        def impl(handling, hp, fz, v_long, v_slip_x, v_slip_y, gamma):
            return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    elif h == 1:
        def impl(handling, hp, fz, v_long, v_slip_x, v_slip_y, gamma):
            kappa, alpha = slip(v_long, v_slip_x, v_slip_y)
            fx, fy, mz = pac89_forces(hp, fz, kappa, alpha, gamma)
            fx2, _, _ = pac89_forces(hp, fz, kappa + DKAPPA, alpha, gamma)
            return fx, fy, mz, kappa, alpha, (fx2 - fx) / DKAPPA
    elif h == 2:
        def impl(handling, hp, fz, v_long, v_slip_x, v_slip_y, gamma):
            kappa, alpha = slip(v_long, v_slip_x, v_slip_y)
            out = np.empty(6)
            mf_forces(hp[2:], int(hp[0]), fz, kappa + DKAPPA, alpha, gamma, v_long, hp[1], out)
            fx2 = out[0]
            mf_forces(hp[2:], int(hp[0]), fz, kappa, alpha, gamma, v_long, hp[1], out)
            return out[0], out[1], out[4], kappa, alpha, (fx2 - out[0]) / DKAPPA
    else:
        raise TypingError(f"unknown handling model {h}")
    return impl
