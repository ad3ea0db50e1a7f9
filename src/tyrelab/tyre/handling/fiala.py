"""Fiala handling forces: Fx, Fy and Mz of the brush model (E. Fiala 1954; the ADAMS/Tire
and Project Chrono ``ChFialaTire`` form).

A tread of elastic bristles on a rigid carcass, with a friction coefficient that falls from
``UMAX`` at rest to ``UMIN`` in full sliding as the combined slip
``S = min(1, hypot(kappa, tan alpha))`` grows: ``U = UMAX - (UMAX - UMIN) S``. Then (kappa and
alpha the ISO slips of :func:`~.slip.slip`, W-axis)::

    Fx = CSLIP kappa                                     |kappa| < U Fz / (2 CSLIP)
       = sign(kappa) (U Fz - (U Fz)^2 / (4 |kappa| CSLIP))   beyond
    H  = 1 - CALPHA |tan alpha| / (3 U Fz)
    Fy = -U Fz (1 - H^3) sign(alpha),  Mz = U Fz w (1 - H) H^3 sign(alpha)
                                                          |alpha| <= atan(3 U Fz / CALPHA)
    Fy = -U Fz sign(alpha),            Mz = 0             beyond

with ``w`` the tyre's width. The longitudinal and lateral forces are each their pure-slip
value (the combined slip only lowers U), as in ADAMS and Chrono. Rolling backwards the
aligning moment turns over (its trail then lies ahead of the contact centre along x), as
PAC89's does. ``ROLLING_RESISTANCE`` [m] (optional, 0 when absent), the shift of the
vertical load's centre, gives the rolling resistance moment (:mod:`.rolling_resistance`).
The relaxation lengths ``RELAX_LENGTH_X``, ``RELAX_LENGTH_Y`` [m] (optional, 0 when absent)
are the model's own for the transient slip (``--relaxation file``,
:mod:`~.relaxation`); by default the forces are steady, as Chrono's 2023 template has them.

Parameters from ``[PARAMETER]`` ``CSLIP`` [N], ``CALPHA`` [N/rad], ``UMIN``, ``UMAX`` (the
ADAMS Fiala property file; a Chrono ``FialaTire`` JSON is written so by
:mod:`tyrelab.tyre.chrono_json`, its X and Y Relaxation Length as ``RELAX_LENGTH_X``,
``RELAX_LENGTH_Y``); the width is ``[DIMENSION] WIDTH``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb

from ...errors import InputError
from ..registry import HandlingModel, register_handling
from .rolling_resistance import rolling_resistance_moment
from .slip import DKAPPA, slip

#: the property-file section of the Fiala parameters (ADAMS's layout)
SECTION = "PARAMETER"
#: its relaxation lengths [m], longitudinal and lateral (optional)
RELAXATION_KEYS = ("RELAX_LENGTH_X", "RELAX_LENGTH_Y")


class FialaParams(NamedTuple):
    """``slip_stiffness`` CSLIP [N] (per unit slip), ``cornering_stiffness`` CALPHA [N/rad],
    ``friction_sliding`` UMIN and ``friction_static`` UMAX [-], ``width`` [m], the relaxation
    lengths RELAX_LENGTH_X and RELAX_LENGTH_Y [m] (0: none given), the rolling resistance's
    load-centre shift ROLLING_RESISTANCE [m] (0: none)."""

    slip_stiffness: float
    cornering_stiffness: float
    friction_sliding: float
    friction_static: float
    width: float
    relaxation_x: float = 0.0
    relaxation_y: float = 0.0
    rolling_resistance: float = 0.0


def fiala_params(tyre) -> FialaParams:
    """The Fiala record from the tyre's property file (module docstring).

    Raises
    ------
    InputError
        Naming the file, line and key: a missing key, a stiffness that is not positive, a
        friction coefficient that is not positive or ``UMIN > UMAX``, a tyre without a width,
        a negative relaxation length.
    """
    tir = tyre.tir
    values = []
    for key in ("CSLIP", "CALPHA", "UMIN", "UMAX"):
        if not tir.has(SECTION, key):
            raise InputError(f"no Fiala parameter {key} in section [{SECTION}]; the fiala handling "
                             "model needs CSLIP, CALPHA, UMIN and UMAX", source=tir.source, field=key)
        value = tir.number(SECTION, key)
        if not value > 0:
            raise InputError(f"expected a positive {key}", source=tir.source,
                             line=tir.line_of(SECTION, key), field=key)
        values.append(value)
    if not values[2] <= values[3]:
        raise InputError("expected UMIN <= UMAX: the sliding friction is at most the static",
                         source=tir.source, line=tir.line_of(SECTION, "UMIN"), field="UMIN")
    width = tyre.require_width("the fiala handling model's aligning moment").width
    lengths = []
    for key in (*RELAXATION_KEYS, "ROLLING_RESISTANCE"):
        length = tir.number(SECTION, key, 0.0)
        if not length >= 0.0:
            what = "relaxation length" if key in RELAXATION_KEYS else "load-centre shift"
            raise InputError(f"expected a {what} >= 0 m, got {length:g} m",
                             source=tir.source, line=tir.line_of(SECTION, key), field=key)
        lengths.append(length)
    return FialaParams(*values, float(width), *lengths)


@nb.njit(cache=True)
def fiala_forces(fp, fz, kappa, alpha):
    """``(FXW, FYW, MZW)`` [N, N, N m] of the Fiala model at load ``fz`` [N], longitudinal
    slip ``kappa`` and slip angle ``alpha`` [rad] (module docstring); zero without load."""
    if not (fz > 0.0) or not math.isfinite(fz):
        return 0.0, 0.0, 0.0
    tan_alpha = math.tan(min(max(alpha, -1.5), 1.5))
    combined = min(1.0, math.sqrt(kappa * kappa + tan_alpha * tan_alpha))
    u = fp.friction_static - (fp.friction_static - fp.friction_sliding) * combined
    grip = u * fz
    if abs(kappa) < grip / (2.0 * fp.slip_stiffness):
        fx = fp.slip_stiffness * kappa
    else:
        fx = math.copysign(grip - grip * grip / (4.0 * abs(kappa) * fp.slip_stiffness), kappa)
    h = 1.0 - fp.cornering_stiffness * abs(tan_alpha) / (3.0 * grip)
    if h >= 0.0:
        sign = 1.0 if alpha > 0.0 else (-1.0 if alpha < 0.0 else 0.0)
        fy = -grip * (1.0 - h * h * h) * sign
        mz = grip * fp.width * (1.0 - h) * h * h * h * sign
    else:
        fy = -math.copysign(grip, alpha)
        mz = 0.0
    return fx, fy, mz


@nb.njit(cache=True)
def fiala_wheel_forces(fp, fz, v_long, v_slip_x, v_slip_y, gamma):
    """Fiala from the contact point's slip velocities: ``(FXW, FYW, MZW, kappa, alpha,
    dFXW/dkappa)`` (forward difference). Camber is not used (ADAMS's Fiala has none either)."""
    kappa, alpha = slip(v_long, v_slip_x, v_slip_y)
    fx, fy, mz = fiala_forces(fp, fz, kappa, alpha)
    fx2, _, _ = fiala_forces(fp, fz, kappa + DKAPPA, alpha)
    if v_long < 0.0:
        mz = -mz
    return fx, fy, mz, kappa, alpha, (fx2 - fx) / DKAPPA


@nb.njit(cache=True)
def fiala_relaxation(fp, fz, v_long, gamma):
    """The file's relaxation lengths ``(RELAX_LENGTH_X, RELAX_LENGTH_Y)`` [m], at every load."""
    return fp.relaxation_x, fp.relaxation_y


@nb.njit(cache=True)
def fiala_rolling_moment(fp, fz, fx, v_long, omega, kappa, gamma, radius):
    """The rolling resistance moment [N m] of the file's ROLLING_RESISTANCE
    (:func:`.rolling_resistance.rolling_resistance_moment`)."""
    return rolling_resistance_moment(fp.rolling_resistance, fz, omega)


register_handling(HandlingModel("fiala", FialaParams, fiala_params, fiala_wheel_forces,
                                "Fiala brush model (ADAMS; Chrono), friction falling with slip",
                                relaxation_lengths=fiala_relaxation,
                                rolling_resistance=fiala_rolling_moment))
