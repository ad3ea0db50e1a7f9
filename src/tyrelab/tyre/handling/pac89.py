"""Pacejka '89 handling forces: Fx, Fy and Mz (thesis 2.3, the PAC89 of ADAMS/Tire).

The Magic Formula of Bakker, Nyborg and Pacejka (1989), "Tyre modelling for
use in vehicle dynamics studies", SAE 870421 / 890087, with the coefficient
names of the ADAMS/Tire PAC89 property file (A0-A13 lateral, B0-B10
longitudinal, C0-C17 aligning). Every curve has the form::

    y(X) = D sin(C atan(B X1 - E (B X1 - atan(B X1)))) + Sv,   X1 = X + Sh

with, **inside the formula only**, the load Fz in kN, the slip angle alpha
and camber gamma in degrees and the longitudinal slip kappa in percent;
forces come out in N and the moment in N m.

Sign conventions
----------------
The coefficients are written for the "modified SAE" axes of Bakker et al.
(x forward, y right, z down, slip angle positive when the wheel moves to
the left of its heading, so that a positive cornering stiffness gives a
positive Fy). The interface of this module is the ISO / TYDEX W-axis of
:mod:`tyrelab.tyre.handling.slip` (x forward, y left, z up; kappa > 0 when
driving; alpha = atan(V_sy/|V_x|) > 0 when the contact point slides left).
The two slip angles are the same number, so the conversion is on the
outputs only::

    Fx_W = Fx_pac(kappa_% = 100 kappa)
    Fy_W = -Fy_pac(alpha_deg = degrees(alpha))
    Mz_W = -Mz_pac(alpha_deg)

Camber is passed unchanged (degrees): positive camber is the top of the
wheel leaning to the right (-y) in both systems. This is the conversion of
Project Chrono's ``ChPac89Tire`` (which reads the same coefficients).

Chrono's additions
------------------
ADAMS's PAC89 gives Fx, Fy and Mz. Project Chrono's ``ChPac89Tire`` adds two terms from
its JSON's ``Rolling Resistance`` and ``Lateral Stiffness``, which a property file states as
``[ROLLING_COEFFICIENTS] QSY1`` (MF-Tyre's key for the same term, as for TMeasy) and
``[STRUCTURAL] LATERAL_STIFFNESS`` [N/m] (MF-Tyre's); a file without them has neither:

* the rolling resistance ``My = -f_r Fz R_l`` about the W-axis y, ``R_l`` the loaded
  radius, turned over through standstill as tyrelab's other models turn theirs
  (``tanh(omega / 1 rad/s)``, :mod:`.rolling_resistance`; Chrono switches it by the spin's
  sign, faded in between 0.125 and 0.5 m/s);
* the overturning moment ``Mx = Fz FYW / k_y`` about the W-axis x at the contact point: the
  lateral force deflects the carcass by ``FYW / k_y`` and the normal force acts there.
  Chrono also adds ``Fx`` times that deflection to Mz, with the sign opposite to the moment
  of ``Fx`` acting at the deflected point (``-Fx FYW / k_y`` about z); that term is left
  out.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from ...errors import InputError
from ..registry import HandlingModel, register_handling
from .rolling_resistance import ROLLING_SECTION, rolling_resistance_moment
from .slip import DKAPPA, slip

#: the section of the carcass's lateral stiffness (MF-Tyre's; module docstring)
STRUCTURAL_SECTION = "STRUCTURAL"

#: property-file sections and key counts of the three curves (ADAMS PAC89 layout)
SECTIONS = (("LATERAL_COEFFICIENTS", "A", 14), ("LONGITUDINAL_COEFFICIENTS", "B", 11),
            ("ALIGNING_COEFFICIENTS", "C", 18))


class Pac89Params(NamedTuple):
    """PAC89 coefficients: ``lateral`` A0-A13, ``longitudinal`` B0-B10, ``aligning`` C0-C17;
    Project Chrono's two additions (0: none): the rolling resistance coefficient and the
    carcass's lateral stiffness [N/m] (module docstring, "Chrono's additions")."""

    lateral: np.ndarray
    longitudinal: np.ndarray
    aligning: np.ndarray
    rolling_resistance: float = 0.0
    lateral_stiffness: float = 0.0


def pac89_params(tyre) -> Pac89Params:
    """The three coefficient sets from the tyre's property file.

    Parameters
    ----------
    tyre : Tyre
        Its ``tir`` must hold ``[LATERAL_COEFFICIENTS]`` A0-A13,
        ``[LONGITUDINAL_COEFFICIENTS]`` B0-B10 and ``[ALIGNING_COEFFICIENTS]``
        C0-C17 (keys are case-insensitive, as the reader upper-cases them).

    Raises
    ------
    InputError
        Naming the file, the section and the first missing key.
    """
    tir = tyre.tir
    sets = []
    for section, letter, count in SECTIONS:
        out = np.zeros(count)
        for i in range(count):
            key = f"{letter}{i}"
            value = tir.get(section, key)
            if value is None:
                raise InputError(f"no PAC89 coefficient {key} in section [{section}]; the "
                                 "pac89 handling model needs A0-A13, B0-B10 and C0-C17",
                                 source=tir.source, field=key)
            out[i] = tir.number(section, key)
        sets.append(out)
    rolling = tir.number(ROLLING_SECTION, "QSY1", 0.0)
    stiffness = tir.number(STRUCTURAL_SECTION, "LATERAL_STIFFNESS", 0.0)
    for section, key, value in ((ROLLING_SECTION, "QSY1", rolling),
                                (STRUCTURAL_SECTION, "LATERAL_STIFFNESS", stiffness)):
        if not (math.isfinite(value) and value >= 0.0):
            raise InputError(f"expected a number >= 0 (0: none), got {value:g}", source=tir.source,
                             line=tir.line_of(section, key), field=key)
    return Pac89Params(*sets, rolling_resistance=rolling, lateral_stiffness=stiffness)


@nb.njit(cache=True)
def pac89_rolling_moment(params, fz, fx, v_long, omega, kappa, gamma, radius):
    """Chrono's PAC89 rolling resistance ``My = -f_r Fz R_l tanh(omega)`` [N m] about the
    W-axis y, ``f_r`` the file's ``QSY1``, ``R_l`` the loaded radius ``radius`` [m]
    (:func:`.rolling_resistance.rolling_resistance_moment`; module docstring)."""
    return rolling_resistance_moment(params.rolling_resistance * radius, fz, omega)


@nb.njit(cache=True)
def pac89_overturning(params, fz, fy, v_long, gamma):
    """Chrono's PAC89 overturning moment ``Mx = Fz FYW / k_y`` [N m] about the W-axis x at the
    contact point: the lateral force deflects the carcass by ``FYW / k_y`` and the normal force
    acts there (module docstring); 0 without a lateral stiffness."""
    if params.lateral_stiffness > 0.0:
        return fz * fy / params.lateral_stiffness
    return 0.0


@nb.njit(cache=True)
def magic_formula(x, b, c, d, e):
    """``D sin(C atan(B x - E (B x - atan(B x))))`` (Bakker et al. 1989, eq. 1)."""
    bx = b * x
    return d * math.sin(c * math.atan(bx - e * (bx - math.atan(bx))))


@nb.njit(cache=True)
def _stiffness_factor(bcd, c, d):
    """B = BCD / (C D), zero when the peak or shape factor vanishes (no NaN)."""
    cd = c * d
    if cd == 0.0 or not math.isfinite(bcd / cd):
        return 0.0
    return bcd / cd


@nb.njit(cache=True)
def pac89_longitudinal(b, fz_kn, kappa_pct):
    """Fx [N] in the PAC89 axes from Fz [kN] and kappa [%] (coefficients ``b`` = B0-B10)."""
    c = b[0]
    d = max((b[1] * fz_kn + b[2]) * fz_kn, 0.0)
    bcd = (b[3] * fz_kn * fz_kn + b[4] * fz_kn) * math.exp(-b[5] * fz_kn)
    e = b[6] * fz_kn * fz_kn + b[7] * fz_kn + b[8]
    sh = b[9] * fz_kn + b[10]
    return magic_formula(kappa_pct + sh, _stiffness_factor(bcd, c, d), c, d, e)


@nb.njit(cache=True)
def pac89_lateral(a, fz_kn, alpha_deg, gamma_deg):
    """Fy [N] in the PAC89 axes from Fz [kN], alpha and gamma [deg] (``a`` = A0-A13)."""
    c = a[0]
    d = max((a[1] * fz_kn + a[2]) * fz_kn, 0.0)
    bcd = 0.0
    if a[4] != 0.0:
        bcd = a[3] * math.sin(2.0 * math.atan(fz_kn / a[4])) * (1.0 - a[5] * abs(gamma_deg))
    e = a[6] * fz_kn + a[7]
    sh = a[8] * gamma_deg + a[9] * fz_kn + a[10]
    sv = a[11] * fz_kn * gamma_deg + a[12] * fz_kn + a[13]
    return magic_formula(alpha_deg + sh, _stiffness_factor(bcd, c, d), c, d, e) + sv


@nb.njit(cache=True)
def pac89_aligning(q, fz_kn, alpha_deg, gamma_deg):
    """Mz [N m] in the PAC89 axes from Fz [kN], alpha and gamma [deg] (``q`` = C0-C17)."""
    c = q[0]
    d = q[1] * fz_kn * fz_kn + q[2] * fz_kn
    bcd = ((q[3] * fz_kn * fz_kn + q[4] * fz_kn) * (1.0 - q[6] * abs(gamma_deg))
           * math.exp(-q[5] * fz_kn))
    e = (q[7] * fz_kn * fz_kn + q[8] * fz_kn + q[9]) * (1.0 - q[10] * abs(gamma_deg))
    sh = q[11] * gamma_deg + q[12] * fz_kn + q[13]
    sv = (q[14] * fz_kn * fz_kn + q[15] * fz_kn) * gamma_deg + q[16] * fz_kn + q[17]
    return magic_formula(alpha_deg + sh, _stiffness_factor(bcd, c, d), c, d, e) + sv


@nb.njit(cache=True)
def pac89_forces(hp, fz, kappa, alpha, gamma):
    """Pure-slip PAC89 forces in the W-axis system.

    Parameters
    ----------
    hp : Pac89Params
        :func:`pac89_params`.
    fz : float
        Normal load [N] (no force at fz <= 0).
    kappa : float
        Longitudinal slip [-], > 0 driving; clipped to [-1, 1].
    alpha : float
        Slip angle [rad], > 0 when the contact point slides left; clipped
        to +-89.5 deg.
    gamma : float
        Camber [rad].

    Returns
    -------
    (Fx, Fy, Mz) : floats
        [N], [N], [N m]; road on tyre, x forward, y left, z up (see the
        module docstring for the conversion from the PAC89 axes).
    """
    if not (fz > 0.0) or not math.isfinite(fz):
        return 0.0, 0.0, 0.0
    fz_kn = fz * 1e-3
    kappa_pct = 100.0 * min(1.0, max(-1.0, kappa))
    alpha_deg = min(89.5, max(-89.5, math.degrees(alpha)))
    gamma_deg = math.degrees(gamma)
    fx = pac89_longitudinal(hp.longitudinal, fz_kn, kappa_pct)
    fy = pac89_lateral(hp.lateral, fz_kn, alpha_deg, gamma_deg)
    mz = pac89_aligning(hp.aligning, fz_kn, alpha_deg, gamma_deg)
    if not (math.isfinite(fx) and math.isfinite(fy) and math.isfinite(mz)):
        return 0.0, 0.0, 0.0
    return fx, -fy, -mz


@nb.njit(cache=True)
def pac89_wheel_forces(hp, fz, v_long, v_slip_x, v_slip_y, gamma):
    """PAC89 from the contact point's slip velocities, with the slip stiffness.

    Returns ``(FXW, FYW, MZW, kappa, alpha, dFXW/dkappa)`` (forward difference). Rolling
    backwards (``v_long < 0``) the aligning moment turns over: its pneumatic trail lies behind
    the contact centre in the direction of travel, which is then ahead of it along the wheel's
    x (as the Magic Formula's factor ``cos(alpha') = Vcx / Vc'`` turns its trail and residual
    moment, Pacejka 2012 eqs. 4.E6, 4.E33, 4.E36).
    """
    kappa, alpha = slip(v_long, v_slip_x, v_slip_y)
    fx, fy, mz = pac89_forces(hp, fz, kappa, alpha, gamma)
    fx2, _, _ = pac89_forces(hp, fz, kappa + DKAPPA, alpha, gamma)
    if v_long < 0.0:
        mz = -mz
    return fx, fy, mz, kappa, alpha, (fx2 - fx) / DKAPPA


register_handling(HandlingModel("pac89", Pac89Params, pac89_params, pac89_wheel_forces,
                                "Pacejka '89 (Bakker et al.), pure slip",
                                rolling_resistance=pac89_rolling_moment,
                                overturning=pac89_overturning))
