"""The Magic Formula as a handling model of the wheel interface."""

from __future__ import annotations

from typing import NamedTuple

import numba as nb
import numpy as np

from ...registry import HandlingModel, register_handling
from ..slip import DKAPPA, slip
from . import coefficient_index as C
from .geometry import free_radius, radius_drop
from .kernel import MFO, mf_forces, mf_relaxation_lengths, mirror_sign
from .moments import overturning_moment, rolling_resistance

#: the MFeval use mode the rigs run (limit checks and low-speed model on)
RIG_USE_MODE = 111


class MagicFormulaParams(NamedTuple):
    """Packed MF coefficients (:func:`~.coefficients.pack`), use mode and pressure [Pa]."""

    coefficients: np.ndarray
    use_mode: int
    pressure: float


def magic_formula_params(tyre) -> MagicFormulaParams:
    """The Magic Formula record of ``tyre`` (MF 5.2 / 6.1 / 6.2 property files)."""
    from .model import MagicFormula
    mf = MagicFormula.from_tir(tyre.tir)
    pressure = float(tyre.pressure) if np.isfinite(tyre.pressure) else 0.0
    return MagicFormulaParams(np.asarray(mf.coefficients, dtype=np.float64), RIG_USE_MODE,
                              pressure)


@nb.njit(cache=True)
def mf_wheel_forces(params, fz, v_long, v_slip_x, v_slip_y, gamma):
    """``(FXW, FYW, MZW, kappa, alpha, dFXW/dkappa)`` of the Magic Formula.

    ``kappa`` is the rigs' slip, ``-V_sx / |V_x|`` (:func:`~..slip.slip`); the Magic Formula
    takes ``-V_sx / V_x`` with the signed speed (MFeval: ``omega = (kappa Vcx + Vcx) / Re``), so
    rolling backwards it is given ``-kappa``: given the rigs' slip there, a reversing wheel
    driven backwards would be pushed forwards.
    """
    kappa, alpha = slip(v_long, v_slip_x, v_slip_y)
    sense = 1.0 if v_long >= 0.0 else -1.0
    out = np.empty(MFO.flags + 1)  # mf_forces's row: Fx ... Mz and the flag word
    # the slope's difference step stays inside the file's slip range: the rigs' use mode clips
    # the slip to KPUMIN..KPUMAX, and a step across the clip reads the flat side (a file
    # measured in braking only, KPUMAX = 0, gave the free-rolling wheel no slope at all)
    step = DKAPPA
    c = params.coefficients
    if not c[C.KPUMIN] <= sense * (kappa + DKAPPA) <= c[C.KPUMAX]:
        step = -DKAPPA
    mf_forces(c, params.use_mode, fz, sense * (kappa + step), alpha, gamma, v_long,
              params.pressure, out)
    fx2 = out[MFO.Fx]
    mf_forces(c, params.use_mode, fz, sense * kappa, alpha, gamma, v_long, params.pressure, out)
    return out[MFO.Fx], out[MFO.Fy], out[MFO.Mz], kappa, alpha, (fx2 - out[MFO.Fx]) / step


@nb.njit(cache=True)
def mf_rolling_radius(params, fz, omega):
    """The effective rolling radius Re [m] the Magic Formula defines its slip with, at load
    ``fz`` [N] and spin ``omega`` [rad/s] (Besselink et al. 2010, eqs. 1, 5 and 7; MFeval's
    ``calculateRe`` with the spin given)::

        Re = R_omega - (FNOMIN / Cz) (DREFF atan(BREFF Fz / FNOMIN) + FREFF Fz / FNOMIN)

    with the free radius R_omega grown by Q_V1 with the spin and Cz = VERTICAL_STIFFNESS
    (1 + PFZ1 dpi) at the record's pressure (its INFLPRES when 0).
    """
    c = params.coefficients
    pressure = params.pressure if params.pressure > 0.0 else c[C.INFLPRES]
    return free_radius(c, omega) - radius_drop(c, max(fz, 0.0), (pressure - c[C.NOMPRES]) / c[C.NOMPRES])


@nb.njit(cache=True)
def mf_wheel_relaxation(params, fz, v_long, gamma):
    """The Magic Formula's relaxation lengths ``(sigma_kappa, sigma_alpha)`` [m] at load
    ``fz`` [N] (:func:`.kernel.mf_relaxation_lengths`; MF 5.2: PTX1-3, PTY1-2; MF 6.1/6.2:
    the slip stiffness over LONGITUDINAL_STIFFNESS / LATERAL_STIFFNESS)."""
    return mf_relaxation_lengths(params.coefficients, params.use_mode, fz, gamma, v_long,
                                 params.pressure)


@nb.njit(cache=True)
def mf_rolling_moment(params, fz, fx, v_long, omega, kappa, gamma, radius):
    """The Magic Formula's rolling resistance moment My [N m] (:func:`.moments.rolling_resistance`:
    QSY1-QSY8, as MFeval), at the load, longitudinal force, speed and the rigs' slip (given
    with the Magic Formula's sign, as :func:`mf_wheel_forces` gives it)."""
    c = params.coefficients
    pressure = params.pressure if params.pressure > 0.0 else c[C.INFLPRES]
    sense = 1.0 if v_long >= 0.0 else -1.0
    return rolling_resistance(c, fz, fx, sense * kappa, mirror_sign(c) * gamma, v_long, pressure)


@nb.njit(cache=True)
def mf_overturning(params, fz, fy, v_long, gamma):
    """The Magic Formula's overturning moment Mx [N m] about the W-axis x at the contact point
    (:func:`.moments.overturning_moment`: QSX1-QSX14, as MFeval) at the load, the lateral
    force the wheel carries and its inclination."""
    c = params.coefficients
    pressure = params.pressure if params.pressure > 0.0 else c[C.INFLPRES]
    m = mirror_sign(c)  # a mirrored tyre's: the file's at the mirrored force and inclination
    return m * overturning_moment(c, fz, m * fy, m * gamma, (pressure - c[C.NOMPRES]) / c[C.NOMPRES])


def mf_mirrored(params: MagicFormulaParams) -> MagicFormulaParams:
    """The record of the same tyre mirrored (its ``MIRRORED`` slot turned over: a file already
    mirrored by a negative USE_MODE comes back to itself), :func:`.kernel.mirror_sign`."""
    coefficients = params.coefficients.copy()
    coefficients[C.MIRRORED] = 0.0 if coefficients[C.MIRRORED] != 0.0 else 1.0
    return params._replace(coefficients=coefficients)


register_handling(HandlingModel("mf", MagicFormulaParams, magic_formula_params, mf_wheel_forces,
                                "Magic Formula 5.2 / 6.1 / 6.2 (MFeval 4.3.1 agreement)",
                                rolling_radius=mf_rolling_radius,
                                relaxation_lengths=mf_wheel_relaxation,
                                rolling_resistance=mf_rolling_moment,
                                overturning=mf_overturning, mirror=mf_mirrored))
