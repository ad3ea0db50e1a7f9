"""Radii, deflection, contact patch and relaxation lengths (scalar, compiled).

Equations of Besselink, Schmeitz & Pacejka, "An improved Magic Formula /
Swift tyre model that can handle inflation pressure changes", VSD 48 (2010)
("Paper eq."), the MF-Tyre 5.2 / 6.2 equation manuals and MFeval 4.3.1.
"""

from __future__ import annotations

import math

import numba

from . import coefficient_index as C


@numba.njit(cache=True, error_model="numpy")
def free_radius(c, omega):
    """Free-spinning radius with centrifugal growth, R_omega (Paper eq. 1)."""
    r0 = c[C.UNLOADED_RADIUS]
    return r0 * (c[C.Q_RE0] + c[C.Q_V1] * (omega * r0 / c[C.LONGVL]) ** 2)


@numba.njit(cache=True, error_model="numpy")
def radius_drop(c, fz_u, dpi):
    """How far the effective rolling radius lies below the free one under the load ``fz_u``
    (Paper eq. 7): ``(Fz0 / Cz) (DREFF atan(BREFF Fz / Fz0) + FREFF Fz / Fz0)``, Cz =
    VERTICAL_STIFFNESS (1 + PFZ1 dpi) (Paper eq. 5)."""
    fz0 = c[C.FNOMIN]
    cz = c[C.VERTICAL_STIFFNESS] * (1.0 + c[C.PFZ1] * dpi)
    return (fz0 / cz) * (c[C.DREFF] * math.atan(c[C.BREFF] * fz_u / fz0) + c[C.FREFF] * fz_u / fz0)


@numba.njit(cache=True, error_model="numpy")
def effective_rolling_radius(c, fz_u, kappa_u, vx, dpi):
    """Effective rolling radius Re and wheel speed omega (Paper eq. 7, Pacejka eq. 2.5).

    omega = (1 + kappa) Vx / Re is not an input, so Re and omega are found
    by fixed-point iteration from Re = 0.965 R0, as MFeval does (to 1e-12 m
    here). Returns (Re, R_omega, omega).
    """
    load = radius_drop(c, fz_u, dpi)
    re = 0.965 * c[C.UNLOADED_RADIUS]
    omega = 0.0
    r_omega = free_radius(c, 0.0)
    for _ in range(100):
        omega = (kappa_u * vx + vx) / re
        r_omega = free_radius(c, omega)
        new = r_omega - load
        done = abs(new - re) <= 1e-12
        re = new
        if done:
            break
    return re, r_omega, omega


@numba.njit(cache=True, error_model="numpy")
def deflection_61(c, fz, fx, fy, omega, r_omega, dpi):
    """Deflection rho and loaded radius Rl for MF 5.2/6.1 (Pacejka eq. A3.3).

    The load-deflection law Fz = (Q_FZ1 x + Q_FZ2 x^2) f(V, Fx, Fy, p) Fz0
    (x = rho/R0) is solved for x. Returns (rho, Rl, Cz).
    """
    r0 = c[C.UNLOADED_RADIUS]
    fz0 = c[C.FNOMIN]
    stiffening = (1.0 + c[C.Q_V2] * (r0 / c[C.LONGVL]) * abs(omega)
                  - (c[C.Q_FCX] * fx / fz0) ** 2 - (c[C.Q_FCY] * fy / fz0) ** 2)
    # far outside the file's force range the law would give a non-positive
    # stiffness; it is held at a tenth of the nominal one instead
    ext = max(stiffening, 0.1) * max(1.0 + c[C.PFZ1] * dpi, 0.1) * fz0
    a, b = c[C.Q_FZ2], c[C.Q_FZ1]
    q = fz / ext
    disc = b * b + 4.0 * a * q
    root = b + math.sqrt(disc) if disc > 0.0 else b
    x = 2.0 * q / root if root > 0.0 else 0.0  # positive root, cancellation-free form
    rho = max(x * r0, 0.0)
    rl = max(r_omega - rho, 0.0)
    if fz == 0.0:
        rho = 1e-6
    return rho, rl, fz / rho


@numba.njit(cache=True, error_model="numpy")
def load_62(c, rl, gamma, omega, r_omega, dpi, fx, fy):
    """Vertical load of MF 6.2 for a given loaded radius (MF-Tyre 6.2 manual).

    Includes the camber and lateral-force effects on vertical stiffness.
    Returns (Fz, rho).
    """
    r0 = c[C.UNLOADED_RADIUS]
    fz0 = c[C.FNOMIN]
    ratio = rl / r_omega
    sfyg = (c[C.Q_FYS1] + c[C.Q_FYS2] * ratio + c[C.Q_FYS3] * ratio * ratio) * gamma
    rho_fr = max(r_omega - rl, 0.0)
    rtw = (1.075 - 0.5 * c[C.ASPECT_RATIO]) * c[C.WIDTH]
    q1, q2 = c[C.Q_CAM1], c[C.Q_CAM2]
    den = ((q1 * r_omega + q2 * r_omega * r_omega) * gamma) ** 2
    rho_g = 0.0
    if den != 0.0:
        rho_g = ((q1 * rl + q2 * rl * rl) * gamma) ** 2 * (rtw / 8.0) * abs(math.tan(gamma)) / den
    rho_g -= c[C.Q_CAM3] * rho_fr * abs(gamma)
    rho = max(rho_fr + rho_g, 1e-12)
    fcorr = ((1.0 + c[C.Q_V2] * (r0 / c[C.LONGVL]) * abs(omega) - (c[C.Q_FCX] * fx / fz0) ** 2
              - ((rho / r0) ** c[C.Q_FCY2] * (c[C.Q_FCY] * (fy - sfyg) / fz0)) ** 2)
             * (1.0 + c[C.PFZ1] * dpi))
    x = rho / r0
    return fcorr * (c[C.Q_FZ1] * x + c[C.Q_FZ2] * x * x) * fz0, rho


@numba.njit(cache=True, error_model="numpy")
def deflection_62(c, fz_u, fz, gamma, fx, fy, omega, r_omega, dpi):
    """Loaded radius of MF 6.2 by the secant method on ``load_62`` (MFeval).

    Starts from 0.95 R0 and R0, stops when the load error is below
    FNOMIN 1e-6 or after 18 steps. Returns (rho, Rl, Cz).
    """
    r0 = c[C.UNLOADED_RADIUS]
    tol = c[C.FNOMIN] * 1e-6
    x0, x1 = 0.95 * r0, r0
    y0 = load_62(c, x0, gamma, omega, r_omega, dpi, fx, fy)[0] - fz_u
    y1 = load_62(c, x1, gamma, omega, r_omega, dpi, fx, fy)[0] - fz_u
    x = x1
    for _ in range(18):
        if y1 == y0:
            break
        x = x1 - (x1 - x0) / (y1 - y0) * y1
        y = load_62(c, x, gamma, omega, r_omega, dpi, fx, fy)[0] - fz_u
        if abs(y) <= tol:
            break
        if abs(y1) < abs(y0):
            x0, y0 = x1, y1
        x1, y1 = x, y
    rho = load_62(c, x, gamma, omega, r_omega, dpi, fx, fy)[1]
    if fz == 0.0:
        rho = 1e-6
    return rho, x, fz / rho


@numba.njit(cache=True, error_model="numpy")
def contact_patch(c, fz_u, dpi):
    """Contact patch half length a and half width b (Paper eqs. 9, 10; MF5.2 manual).

    When the approximate loaded radius reaches the rim plus BOTTOM_OFFST the
    load is held at the bottoming load (MFeval). Returns (a, b).
    """
    r0 = c[C.UNLOADED_RADIUS]
    ncz = c[C.VERTICAL_STIFFNESS] * (1.0 + c[C.PFZ1] * dpi)
    floor = c[C.RIM_RADIUS] + c[C.BOTTOM_OFFST]
    if r0 - fz_u / ncz < floor:
        fz_u = (r0 - floor) * ncz
    fz_u = max(fz_u, 0.0)
    if c[C.VERSION] == 52.0:
        z = fz_u / c[C.FNOMIN]
        return r0 * (c[C.QA2_EFF] * z + c[C.QA1_EFF] * math.sqrt(z)), 0.5 * c[C.WIDTH]
    z = fz_u / (ncz * r0)
    a = r0 * (c[C.Q_RA2] * z + c[C.Q_RA1] * math.sqrt(z))
    b = c[C.WIDTH] * (c[C.Q_RB2] * z + c[C.Q_RB1] * z ** (1.0 / 3.0))
    return a, b


@numba.njit(cache=True, error_model="numpy")
def relaxation(c, fz, gamma, dpi, kxk, kya):
    """Overall stiffnesses Cx, Cy and relaxation lengths (Paper eqs. 17-19; MF5.2 manual).

    Returns (Cx, Cy, sigma_x, sigma_y).
    """
    fz0 = c[C.FNOMIN]
    fz0p = fz0 * c[C.LFZO]
    dfz = (fz - fz0p) / fz0p
    cx = (c[C.LONGITUDINAL_STIFFNESS] * (1.0 + c[C.PCFX1] * dfz + c[C.PCFX2] * dfz * dfz)
          * (1.0 + c[C.PCFX3] * dpi))
    cy = (c[C.LATERAL_STIFFNESS] * (1.0 + c[C.PCFY1] * dfz + c[C.PCFY2] * dfz * dfz)
          * (1.0 + c[C.PCFY3] * dpi))
    r0 = c[C.UNLOADED_RADIUS]
    if c[C.VERSION] == 52.0:
        sx = ((c[C.PTX1] + c[C.PTX2] * dfz) * math.exp(-c[C.PTX3] * dfz) * c[C.LSGKP] * r0 * fz / fz0)
        pty = c[C.PTY2] * fz0p
        arg = fz / pty if pty != 0.0 else (math.inf if fz > 0.0 else 0.0)
        sy = (c[C.PTY1] * math.sin(2.0 * math.atan(arg)) * (1.0 - c[C.PKY3] * abs(gamma))
              * r0 * c[C.LFZO] * c[C.LSGAL])
    else:
        sx = abs(kxk / cx) if cx != 0.0 else 0.0
        sy = abs(kya / cy) if cy != 0.0 else 0.0
    return cx, cy, sx, sy
