"""Compiled entry points of the Magic Formula: one sample and arrays.

:func:`mf_forces` is the function other compiled kernels call in their time
step loop; :func:`mf_evaluate_many` fills every output MFeval reports for
arrays of inputs.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

from ....core.named_index import named_index
from . import coefficient_index as C
from .forces import (combined_fx_weight, combined_fy_weight, friction_ellipse_weights, kappa_induced_fy,
                     pure_fx, pure_fy, sign)
from .geometry import contact_patch, deflection_61, deflection_62, effective_rolling_radius, relaxation
from .limits import NEGATIVE_MUY, NON_FINITE, decode_use_mode, prepare_inputs
from .moments import aligning_moment, overturning_moment, rolling_resistance, trail_and_residual

#: columns of the full output row written by :func:`mf_evaluate`; :func:`mf_forces`
#: writes the first six (Fx ... Mz and the flag word)
OUTPUTS = ("Fx", "Fy", "Mx", "My", "Mz", "flags", "Fz", "kappa", "alpha", "gamma", "Vx", "P",
           "Re", "rho", "contact_length_2a", "t", "mux", "muy", "omega", "Rl",
           "contact_width_2b", "Mzr", "Cx", "Cy", "Cz", "Kya", "sigmax", "sigmay", "Kxk",
           "alpha_used")
N_OUTPUTS = len(OUTPUTS)
#: positions of :data:`OUTPUTS` in an output row (``out[MFO.Fx]``), and as a dict for
#: names known only at run time
MFO = named_index("MFOutputIndex", OUTPUTS)
COL = MFO._asdict()


class SteadyState(NamedTuple):
    """What :func:`_steady_state` finds for one sample (the inputs as used, the loads,
    the friction and the stiffnesses the other outputs are made from)."""

    fx: float
    fy: float
    mx: float
    my: float
    mz: float
    flags: int
    fz_u: float
    fz: float
    fz_low: float
    kappa_out: float
    alpha: float
    alpha_out: float
    gamma: float
    p: float
    dpi: float
    t: float
    mux: float
    muy: float
    mzr: float
    kya: float
    kxk: float


@numba.njit(cache=True, error_model="numpy")
def _steady_state(c, use_mode, fz, kappa, alpha, gamma, vx, pressure):
    """All steady-state quantities of one sample, a :class:`SteadyState` (see ``mf_evaluate``)."""
    check, star = decode_use_mode(use_mode)
    p = pressure if pressure > 0.0 else c[C.INFLPRES]
    kappa_in = kappa
    (fz_u, fz, fz_low, kappa, kappa_out, alpha, alpha_out, gamma, p,
     low, smooth, flags) = prepare_inputs(c, check, fz, kappa, alpha, gamma, vx, p)
    fz0p = c[C.FNOMIN] * c[C.LFZO]  # (4.E1)
    dfz = (fz - fz0p) / fz0p  # (4.E2a)
    dpi = (p - c[C.NOMPRES]) / c[C.NOMPRES]  # (4.E2b)
    if star:
        alpha_s = math.tan(alpha) * sign(vx)  # (4.E3)
        gamma_s = math.sin(gamma)  # (4.E4)
    else:
        alpha_s, gamma_s = alpha, gamma
    vc = math.sqrt(vx * vx + (math.tan(alpha) * abs(vx)) ** 2)
    cos_alpha_prime = vx / (vc + 1e-6)  # cos(alpha') (4.E6, 4.E6a), |Vx| <= Vc

    fx0, mux, kxk, shx, svx, flags = pure_fx(c, fz, kappa, gamma, dfz, dpi, vx, smooth, check, flags)
    fy0, muy, kya, shy, svy, by, cy, flags = pure_fy(c, fz, alpha_s, gamma_s, dfz, dpi, vx,
                                                     smooth, star, check, flags)
    if c[C.FRICTION_ELLIPSE] != 0.0:  # FE_METHOD = 'YES' (coefficients module docstring)
        gxa, gyk = friction_ellipse_weights(fz, kappa, alpha_s, vx, star, fx0, fy0, mux, muy, kxk,
                                            kya, shx, svx, shy, svy)
        svyk = 0.0
    else:
        gxa, flags = combined_fx_weight(c, kappa, alpha_s, gamma_s, dfz, check, flags)
        gyk, flags = combined_fy_weight(c, kappa, alpha_s, gamma_s, dfz, check, flags)
        svyk = kappa_induced_fy(c, fz, muy, kappa, alpha_s, gamma_s, dfz, smooth)
    fx = gxa * fx0  # (4.E50)
    fy = gyk * fy0 + svyk  # (4.E58)

    alphar, alphat, dt, bt, ct, et, dr, br, kya_p, flags = trail_and_residual(
        c, fz, fz_low, check, alpha_s, gamma, gamma_s, dfz, dpi, vx, kya, shy, svy, by, cy, flags)
    if gamma_s == 0.0 or c[C.VERSION] == 52.0:
        fy0_flat = fy0  # Fy0 at zero camber (4.E74) is Fy0 itself; MF5.2 does not use it
    else:
        fy0_flat = pure_fy(c, fz, alpha_s, 0.0, dfz, dpi, vx, smooth, star, check, 0)[0]
    mx = overturning_moment(c, fz, fy, gamma, dpi)
    my = rolling_resistance(c, fz_u, fx, kappa_in, gamma, vx, p)
    mz, t, mzr = aligning_moment(c, kappa, gamma, dfz, cos_alpha_prime, smooth, alphar, alphat, kxk,
                                 kya_p, dt, bt, ct, et, dr, br, fx, fy, gyk * fy0_flat, svyk)
    if check and muy < 0.0:
        flags |= NEGATIVE_MUY
    return SteadyState(fx, fy, mx, my, mz, flags, fz_u, fz, fz_low, kappa_out, alpha, alpha_out,
                       gamma, p, dpi, t, mux, muy, mzr, kya, kxk)


@numba.njit(cache=True, error_model="numpy")
def mirror_sign(c):
    """-1 for a mirrored tyre (``MIRRORED``: a negative USE_MODE, or mounted on the other side
    than its TYRESIDE), else 1. A mirrored tyre is the file's seen in a mirror through its
    wheel plane: at slip angle ``alpha`` and inclination ``gamma`` it gives the file's tyre's
    Fx, My and -Fy, -Mx, -Mz at ``-alpha`` and ``-gamma`` (every asymmetry -- conicity,
    ply-steer, the residual moment -- turned over; MF-Tyre's and Chrono's mirroring, which
    flip the odd coefficients instead)."""
    return -1.0 if c[C.MIRRORED] != 0.0 else 1.0


@numba.njit(cache=True, error_model="numpy")
def _finite(value, flags):
    """(value, flags), or (0, flags | NON_FINITE) for an infinite or NaN value."""
    if math.isfinite(value):
        return value, flags
    return 0.0, flags | NON_FINITE


@numba.njit(cache=True, error_model="numpy")
def mf_forces(coefficients, use_mode, fz, kappa, alpha, gamma, vx, pressure, out):
    """Steady-state Magic Formula forces and moments of one sample.

    Writes Fx, Fy, Mx, My, Mz (N, N m) into ``out[MFO.Fx]`` ... ``out[MFO.Mz]``
    (the first five :data:`OUTPUTS`); if ``out`` has room for it,
    ``out[MFO.flags]`` receives the limit flag word (bits in :mod:`.limits`).
    No allocation, no Python objects: call it from other ``njit`` kernels.

    Sign convention: ISO-W (TYDEX W) axes as MFeval -- forces and moments
    of the road on the tyre, x forward along the wheel heading in the road
    plane, y to the left, z up; kappa > 0 when driving (Fx > 0); alpha > 0
    when the contact centre slides to the left, Vy/Vx > 0 (a normal tyre
    then gives Fy < 0); gamma > 0 with the wheel top tilted to the left
    (about +x); Mz > 0 anticlockwise seen from above.

    Inputs: ``coefficients`` from :func:`.coefficients.pack`; ``fz`` (N,
    negative read as 0), ``kappa`` (-), ``alpha``, ``gamma`` (rad), ``vx``
    (m/s), ``pressure`` (Pa; <= 0 means the file's INFLPRES).

    ``use_mode`` is MFeval's 3-digit useMode: hundreds 1 = limit checks
    (clip to ALPMIN/ALPMAX, CAMMIN/CAMMAX, FZMAX, PRESMIN/PRESMAX,
    KPUMIN/KPUMAX, FZMIN in moments, curvature factors <= 1, low-speed model
    below VXLOW), 2 = none; tens 1 = alpha* = alpha, gamma* = gamma (TNO
    MF-Tyre), 2 = alpha* = tan(alpha) sign(Vx), gamma* = sin(gamma) (Pacejka
    2012 4.E3-4.E4); units 1 = combined slip without turn slip (turn slip,
    2, is not implemented and is evaluated as 1). 111 and 121 are the modes
    checked against MFeval.
    """
    m = mirror_sign(coefficients)
    r = _steady_state(coefficients, use_mode, fz, kappa, m * alpha, m * gamma, vx, pressure)
    flags = r.flags
    out[MFO.Fx], flags = _finite(r.fx, flags)
    out[MFO.Fy], flags = _finite(m * r.fy, flags)
    out[MFO.Mx], flags = _finite(m * r.mx, flags)
    out[MFO.My], flags = _finite(r.my, flags)
    out[MFO.Mz], flags = _finite(m * r.mz, flags)
    if out.shape[0] > MFO.flags:
        out[MFO.flags] = flags


@numba.njit(cache=True, error_model="numpy")
def mf_evaluate(c, use_mode, fz, kappa, alpha, gamma, vx, pressure, out):
    """Every MFeval output of one sample, in the order of ``OUTPUTS``, into ``out`` (a mirrored
    tyre's, :func:`mirror_sign`, with its Fy, Mx, Mz, Mzr and slip angles turned over)."""
    m = mirror_sign(c)
    (fx, fy, mx, my, mz, flags, fz_u, fz_c, fz_low, kappa_out, alpha_c, alpha_out, gamma_c, p,
     dpi, t, mux, muy, mzr, kya, kxk) = _steady_state(c, use_mode, fz, kappa, m * alpha, m * gamma,
                                                        vx, pressure)
    check = decode_use_mode(use_mode)[0]
    re, r_omega, omega = effective_rolling_radius(c, fz_u, kappa, vx, dpi)
    if c[C.VERSION] == 62.0:
        rho, rl, cz = deflection_62(c, fz_u, fz_c, gamma_c, fx, fy, omega, r_omega, dpi)
    else:
        rho, rl, cz = deflection_61(c, fz_low, fx, fy, omega, r_omega, dpi)
    a, b = contact_patch(c, fz_u, dpi)
    cx, cy, sx, sy = relaxation(c, fz_c, gamma_c, dpi, kxk, kya)
    out[MFO.Fx] = fx
    out[MFO.Fy] = m * fy
    out[MFO.Mx] = m * mx
    out[MFO.My] = my
    out[MFO.Mz] = m * mz
    out[MFO.flags] = float(flags)
    out[MFO.Fz] = fz_u
    out[MFO.kappa] = kappa_out
    out[MFO.alpha] = m * alpha_out
    out[MFO.gamma] = gamma
    out[MFO.Vx] = vx
    out[MFO.P] = p
    out[MFO.Re] = re
    out[MFO.rho] = rho
    out[MFO.contact_length_2a] = 2.0 * a
    out[MFO.t] = t
    out[MFO.mux] = mux
    out[MFO.muy] = abs(muy) if check else muy
    out[MFO.omega] = omega
    out[MFO.Rl] = rl
    out[MFO.contact_width_2b] = 2.0 * b
    out[MFO.Mzr] = m * mzr
    out[MFO.Cx] = cx
    out[MFO.Cy] = cy
    out[MFO.Cz] = cz
    out[MFO.Kya] = kya
    out[MFO.sigmax] = sx
    out[MFO.sigmay] = sy
    out[MFO.Kxk] = kxk
    out[MFO.alpha_used] = m * alpha_c
    bad = False
    for i in range(N_OUTPUTS):  # a non-finite output is reported as 0 and flagged
        if not math.isfinite(out[i]):
            out[i] = 0.0
            bad = True
    if bad:
        out[MFO.flags] = float(flags | NON_FINITE)


@numba.njit(cache=True, error_model="numpy")
def mf_relaxation_lengths(c, use_mode, fz, gamma, vx, pressure):
    """``(sigma_kappa, sigma_alpha)`` [m], the relaxation lengths at load ``fz`` [N], camber
    ``gamma`` [rad], speed ``vx`` [m/s] and ``pressure`` [Pa] (MFeval's ``sigmax``,
    ``sigmay``: :func:`.geometry.relaxation` with the slip stiffnesses at the load, which
    do not depend on the slip)."""
    r = _steady_state(c, use_mode, fz, 0.0, 0.0, mirror_sign(c) * gamma, vx, pressure)
    sx, sy = relaxation(c, r.fz, r.gamma, r.dpi, r.kxk, r.kya)[2:]
    return (sx if math.isfinite(sx) else 0.0), (sy if math.isfinite(sy) else 0.0)


@numba.njit(cache=True, error_model="numpy")
def mf_evaluate_many(c, use_mode, fz, kappa, alpha, gamma, vx, pressure, out):
    """``mf_evaluate`` over 1-D arrays of equal length; ``out`` has shape (n, N_OUTPUTS)."""
    for i in range(fz.shape[0]):
        mf_evaluate(c, use_mode, fz[i], kappa[i], alpha[i], gamma[i], vx[i], pressure[i], out[i])


@numba.njit(cache=True, error_model="numpy")
def mf_forces_many(c, use_mode, fz, kappa, alpha, gamma, vx, pressure, out):
    """``mf_forces`` over 1-D arrays; ``out`` has shape (n, 5) or (n, 6) (:data:`OUTPUTS`' first)."""
    for i in range(fz.shape[0]):
        mf_forces(c, use_mode, fz[i], kappa[i], alpha[i], gamma[i], vx[i], pressure[i], out[i])


def empty_outputs(n: int) -> np.ndarray:
    """An output array for ``mf_evaluate_many``."""
    return np.empty((n, N_OUTPUTS))
