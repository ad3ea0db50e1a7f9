"""Overturning, rolling resistance and aligning moments (scalar, compiled).

Equation numbers: Pacejka (2012) "4.E..", Besselink et al. (2010) "A..",
and the MF-Tyre equation manual for MF 5.2, as chosen by MFeval 4.3.1.
"""

from __future__ import annotations

import math

import numba

from . import coefficient_index as C
from .forces import EPS, cos_atan, sign, sign1

HALF_PI = 0.5 * math.pi


@numba.njit(cache=True, error_model="numpy")
def overturning_moment(c, fz, fy, gamma, dpi):
    """Overturning moment Mx (4.E69 with QSX12..QSX14 of the TNO manual).

    Below FZMIN the load is replaced by Fz (Fz/FZMIN)^2 (MFeval).
    """
    fzmin = c[C.FZMIN]
    if fz < fzmin:
        fz = fz * (fz / fzmin) ** 2
    fz0 = c[C.FNOMIN]
    r0 = c[C.UNLOADED_RADIUS]
    lmx = c[C.LMX]
    bracket = (c[C.QSX1] * c[C.LVMX] - c[C.QSX2] * gamma * (1.0 + c[C.PPMX1] * dpi)
               + c[C.QSX3] * (fy / fz0)
               + c[C.QSX4] * math.cos(c[C.QSX5] * math.atan((c[C.QSX6] * (fz / fz0)) ** 2))
               * math.sin(c[C.QSX7] * gamma + c[C.QSX8] * math.atan(c[C.QSX9] * (fy / fz0)))
               + c[C.QSX10] * math.atan(c[C.QSX11] * (fz / fz0)) * gamma)
    return (r0 * fz * lmx * bracket
            + r0 * lmx * (fy * (c[C.QSX13] + c[C.QSX14] * abs(gamma))
                          - fz * c[C.QSX12] * gamma * abs(gamma)))


@numba.njit(cache=True, error_model="numpy")
def rolling_resistance(c, fz_u, fx, kappa_u, gamma, vx, p):
    """Rolling resistance moment My (A48; MF5.2: MF-Tyre manual), negative when rolling forward.

    ``fz_u`` and ``kappa_u`` are the unclipped load and slip ratio. Below
    FZMIN the load becomes Fz^2/FZMIN; near kappa = -1 (wheel spinning
    backwards relative to travel) and at standstill MFeval's low-speed
    corrections apply. No load, no rolling resistance.
    """
    if vx == 0.0 or fz_u <= 0.0:
        return 0.0
    fzmin = c[C.FZMIN]
    if fz_u < fzmin:
        fz_u = fz_u * (fz_u / fzmin)
    fz0 = c[C.FNOMIN]
    r0 = c[C.UNLOADED_RADIUS]
    v = vx / c[C.LONGVL]
    base = c[C.QSY1] + c[C.QSY2] * (fx / fz0) + c[C.QSY3] * abs(v) + c[C.QSY4] * v ** 4
    if c[C.VERSION] == 52.0:
        my = -r0 * fz_u * c[C.LMY] * base
    else:
        my = (-r0 * fz0 * c[C.LMY]
              * (base + (c[C.QSY5] + c[C.QSY6] * (fz_u / fz0)) * gamma * gamma)
              * ((fz_u / fz0) ** c[C.QSY7] * (p / c[C.NOMPRES]) ** c[C.QSY8]))
    if vx < 0.0:
        my = -my
    high = c[C.VXLOW] / abs(vx) - 1.0
    low = -1.0 - c[C.VXLOW] - high
    if low <= kappa_u <= high:
        my *= math.sin(HALF_PI * (kappa_u + 1.0) / (high + 1.0))  # linear ramp 0..pi/2
    elif kappa_u < low:
        my = -my
    return my


@numba.njit(cache=True, error_model="numpy")
def trail_and_residual(c, fz, fz_low, check, alpha_s, gamma, gamma_s, dfz, dpi, vx,
                       kya, shy, svy, by, cy, flags):
    """Pneumatic-trail and residual-torque factors of Mz (4.E34-4.E47, A58, A60).

    Returns (alphar, alphat, Dt, Bt, Ct, Et, Dr, Br, Kya_prime, flags).
    With limit checks the residual and trail peaks use the load raised to
    FZMIN (``fz_low``), as MFeval does.
    """
    f = fz_low if check else fz
    if fz <= 0.0:
        f = 0.0
    r0 = c[C.UNLOADED_RADIUS]
    fz0p = c[C.FNOMIN] * c[C.LFZO]
    lmuy = c[C.LMUY]
    kya_p = kya + EPS * sign1(kya)  # (4.E39)
    alphar = alpha_s + shy + svy / kya_p  # (4.E37, 4.E38)
    sht = c[C.QHZ1] + c[C.QHZ2] * dfz + (c[C.QHZ3] + c[C.QHZ4] * dfz) * gamma_s  # (4.E35)
    alphat = alpha_s + sht  # (4.E34)
    dt = ((c[C.QDZ1] + c[C.QDZ2] * dfz) * (1.0 - c[C.PPZ1] * dpi)
          * (1.0 + c[C.QDZ3] * gamma + c[C.QDZ4] * gamma * gamma)
          * f * (r0 / fz0p) * c[C.LTR])  # (A60)
    bt = ((c[C.QBZ1] + c[C.QBZ2] * dfz + c[C.QBZ3] * dfz * dfz)
          * (1.0 + c[C.QBZ4] * gamma + c[C.QBZ5] * abs(gamma)) * c[C.LKY] / lmuy)  # (A58)
    ct = c[C.QCZ1]  # (4.E41)
    et = ((c[C.QEZ1] + c[C.QEZ2] * dfz + c[C.QEZ3] * dfz * dfz)
          * (1.0 + (c[C.QEZ4] + c[C.QEZ5] * gamma_s) * (2.0 / math.pi)
             * math.atan(bt * ct * alphat)))  # (4.E44)
    if check and et > 1.0:
        et = 1.0
        flags |= 2048
    dr = (f * r0 * ((c[C.QDZ6] + c[C.QDZ7] * dfz) * c[C.LRES]
                    + ((c[C.QDZ8] + c[C.QDZ9] * dfz) * (1.0 + c[C.PPZ2] * dpi)
                       + (c[C.QDZ10] + c[C.QDZ11] * dfz) * abs(gamma_s)) * gamma_s * c[C.LKZC])
          * lmuy * sign(vx) * math.cos(alpha_s))  # (4.E47)
    br = c[C.QBZ9] * c[C.LKY] / lmuy + c[C.QBZ10] * by * cy  # (4.E45)
    return alphar, alphat, dt, bt, ct, et, dr, br, kya_p, flags


@numba.njit(cache=True, error_model="numpy")
def equivalent_slip(alpha, kxk, kya_p, kappa):
    """Equivalent slip angle for combined slip (A54, A55)."""
    r = kxk / kya_p * kappa
    return math.atan(math.sqrt(math.tan(alpha) ** 2 + r * r)) * sign(alpha)


@numba.njit(cache=True, error_model="numpy")
def aligning_moment(c, kappa, gamma, dfz, cos_alpha_prime, smooth, alphar, alphat, kxk, kya_p,
                    dt, bt, ct, et, dr, br, fx, fy, fy_prime, svyk):
    """Aligning moment Mz for combined slip (4.E71-4.E76, A54-A56; MF5.2 manual).

    ``fy_prime`` is Gyk Fy0(gamma = 0) (4.E74); ``cos_alpha_prime`` is
    Vx / (Vc + epsilon) = cos(alpha') (4.E6). Returns (Mz, t, Mzr).
    """
    r0 = c[C.UNLOADED_RADIUS]
    ar_eq = equivalent_slip(alphar, kxk, kya_p, kappa)
    at_eq = equivalent_slip(alphat, kxk, kya_p, kappa)
    s = r0 * (c[C.SSZ1] + c[C.SSZ2] * (fy / c[C.FNOMIN])
              + (c[C.SSZ3] + c[C.SSZ4] * dfz) * gamma) * c[C.LS]  # (A56)
    mzr = dr * cos_atan(br * ar_eq) * smooth  # (4.E75), Cr = 1 without turn slip
    bx = bt * at_eq
    t = (dt * math.cos(ct * math.atan(bx - et * (bx - math.atan(bx)))) * cos_alpha_prime
         * c[C.LFZO] * smooth)  # (4.E73), LFZO as in TNO's dteval (MFeval)
    if c[C.VERSION] == 52.0:
        mz = -t * (fy - svyk) + mzr + s * fx  # MF5.2
    else:
        mz = -t * fy_prime + mzr + s * fx  # (4.E71, 4.E72)
    return mz, t, mzr
