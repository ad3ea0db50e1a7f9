"""Longitudinal and lateral forces, pure and combined slip (scalar, compiled).

Equation numbers are those of Pacejka, *Tire and Vehicle Dynamics*, 3rd ed.
(2012), section 4.3.2 ("4.E.."), as implemented in MFeval 4.3.1, including
MFeval's MF 5.2 variants (marked "MF5.2") from the MF-Tyre equation manual.
All functions take the packed coefficient vector ``c`` (see
:mod:`.coefficients`) and scalars; ISO-W axes, forces of road on tyre.
"""

from __future__ import annotations

import math

import numba

from . import coefficient_index as C

EPS = 1e-6  # singularity guard epsilon_x,y,k (4.E6a)


@numba.njit(cache=True, error_model="numpy")
def sign(x):
    """sign(x) with sign(0) = 0."""
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)


@numba.njit(cache=True, error_model="numpy")
def sign1(x):
    """sign(x) with sign(0) = 1 (denominator guards, page 177)."""
    return -1.0 if x < 0.0 else 1.0


@numba.njit(cache=True, error_model="numpy")
def cos_atan(x):
    """cos(atan(x)) = 1 / sqrt(1 + x^2), without the two trigonometric calls."""
    return 1.0 / math.sqrt(1.0 + x * x)


@numba.njit(cache=True, error_model="numpy")
def magic(b, cc, d, e, x):
    """The Magic Formula sine version D sin(C atan(B x - E (B x - atan(B x))))."""
    bx = b * x
    return d * math.sin(cc * math.atan(bx - e * (bx - math.atan(bx))))


@numba.njit(cache=True, error_model="numpy")
def weight(b, cc, e, x):
    """Combined-slip weighting cos(C atan(B x - E (B x - atan(B x)))) (4.E51, 4.E59)."""
    bx = b * x
    return math.cos(cc * math.atan(bx - e * (bx - math.atan(bx))))


@numba.njit(cache=True, error_model="numpy")
def clip_curvature(e, check, flags):
    """Curvature factor limited to <= 1 when limit checks are on (MFeval)."""
    if check and e > 1.0:
        return 1.0, flags | 2048
    return e, flags


@numba.njit(cache=True, error_model="numpy")
def pure_fx(c, fz, kappa, gamma, dfz, dpi, vx, smooth, check, flags):
    """Pure longitudinal force Fx0 (4.E9-4.E18).

    Returns (Fx0, mux, Kxk, SHx, SVx, flags); Kxk is the slip stiffness (4.E15).
    Shifts SHx, SVx are scaled by ``smooth`` below VXLOW; Fx0 changes sign
    for Vx < 0.
    """
    cx = c[C.PCX1] * c[C.LCX]  # (4.E11)
    mux = ((c[C.PDX1] + c[C.PDX2] * dfz) * (1.0 + c[C.PPX3] * dpi + c[C.PPX4] * dpi * dpi)
           * (1.0 - c[C.PDX3] * gamma * gamma) * c[C.LMUX])  # (4.E13)
    if fz == 0.0:
        mux = 0.0
    dx = mux * fz  # (4.E12)
    kxk = (fz * (c[C.PKX1] + c[C.PKX2] * dfz) * math.exp(c[C.PKX3] * dfz)
           * (1.0 + c[C.PPX1] * dpi + c[C.PPX2] * dpi * dpi) * c[C.LKX])  # (4.E15)
    bx = kxk / (cx * dx + EPS * sign1(dx))  # (4.E16)
    shx = (c[C.PHX1] + c[C.PHX2] * dfz) * c[C.LHX] * smooth  # (4.E17)
    svx = fz * (c[C.PVX1] + c[C.PVX2] * dfz) * c[C.LVX] * c[C.LMUX] * smooth  # (4.E18)
    kx = kappa + shx  # (4.E10)
    ex = ((c[C.PEX1] + c[C.PEX2] * dfz + c[C.PEX3] * dfz * dfz)
          * (1.0 - c[C.PEX4] * sign(kx)) * c[C.LEX])  # (4.E14)
    ex, flags = clip_curvature(ex, check, flags)
    fx0 = magic(bx, cx, dx, ex, kx) + svx  # (4.E9)
    if vx < 0.0:
        fx0 = -fx0
    return fx0, mux, kxk, shx, svx, flags


@numba.njit(cache=True, error_model="numpy")
def cornering_stiffness(c, fz, gamma_s, dpi):
    """Cornering stiffness Kya = dFy0/dalpha at alpha = 0 (4.E25)."""
    fz0p = c[C.FNOMIN] * c[C.LFZO]
    return (c[C.PKY1] * fz0p * (1.0 + c[C.PPY1] * dpi) * (1.0 - c[C.PKY3] * abs(gamma_s))
            * math.sin(c[C.PKY4] * math.atan((fz / fz0p)
                                              / ((c[C.PKY2] + c[C.PKY5] * gamma_s * gamma_s)
                                                 * (1.0 + c[C.PPY2] * dpi))))
            * c[C.LKY])


@numba.njit(cache=True, error_model="numpy")
def pure_fy(c, fz, alpha_s, gamma_s, dfz, dpi, vx, smooth, star, check, flags):
    """Pure lateral force Fy0 (4.E19-4.E30; MF5.2 SHy from the MF-Tyre manual).

    Returns (Fy0, muy, Kya, SHy, SVy, By, Cy, flags). Shifts are scaled by
    ``smooth`` below VXLOW. With alpha* (``star``) Fy0 changes sign for Vx < 0.
    """
    kya = cornering_stiffness(c, fz, gamma_s, dpi)
    svyg = fz * (c[C.PVY3] + c[C.PVY4] * dfz) * gamma_s * c[C.LKYC] * c[C.LMUY]  # (4.E28)
    if c[C.VERSION] == 52.0:
        shy = (c[C.PHY1] + c[C.PHY2] * dfz) * c[C.LHY] + c[C.PHY3] * gamma_s * c[C.LKYC]  # MF5.2
    else:
        kyg0 = fz * (c[C.PKY6] + c[C.PKY7] * dfz) * (1.0 + c[C.PPY5] * dpi) * c[C.LKYC]  # (4.E30)
        shy = ((c[C.PHY1] + c[C.PHY2] * dfz) * c[C.LHY]
               + (kyg0 * gamma_s - svyg) / (kya + EPS * sign1(kya)))  # (4.E27)
    svy = fz * (c[C.PVY1] + c[C.PVY2] * dfz) * c[C.LVY] * c[C.LMUY] + svyg  # (4.E29)
    shy *= smooth
    svy *= smooth
    ay = alpha_s + shy  # (4.E20)
    cy = c[C.PCY1] * c[C.LCY]  # (4.E21)
    muy = ((c[C.PDY1] + c[C.PDY2] * dfz) * (1.0 + c[C.PPY3] * dpi + c[C.PPY4] * dpi * dpi)
           * (1.0 - c[C.PDY3] * gamma_s * gamma_s) * c[C.LMUY])  # (4.E23)
    dy = muy * fz  # (4.E22)
    ey = ((c[C.PEY1] + c[C.PEY2] * dfz)
          * (1.0 + c[C.PEY5] * gamma_s * gamma_s - (c[C.PEY3] + c[C.PEY4] * gamma_s) * sign1(ay))
          * c[C.LEY])  # (4.E24)
    ey, flags = clip_curvature(ey, check, flags)
    by = kya / (cy * dy + EPS * sign1(dy))  # (4.E26)
    fy0 = magic(by, cy, dy, ey, ay) + svy  # (4.E19)
    if star and vx < 0.0:
        fy0 = -fy0
    if fz == 0.0:
        muy = 0.0
    return fy0, muy, kya, shy, svy, by, cy, flags


@numba.njit(cache=True, error_model="numpy")
def combined_fx_weight(c, kappa, alpha_s, gamma_s, dfz, check, flags):
    """Weighting function Gxa of Fx for combined slip (4.E51-4.E57)."""
    exa, flags = clip_curvature(c[C.REX1] + c[C.REX2] * dfz, check, flags)  # (4.E56)
    shxa = c[C.RHX1]  # (4.E57)
    bxa = ((c[C.RBX1] + c[C.RBX3] * gamma_s * gamma_s) * cos_atan(c[C.RBX2] * kappa)
           * c[C.LXAL])  # (4.E54)
    g0 = weight(bxa, c[C.RCX1], exa, shxa)  # (4.E52)
    return weight(bxa, c[C.RCX1], exa, alpha_s + shxa) / g0, flags  # (4.E51, 4.E53)


@numba.njit(cache=True, error_model="numpy")
def combined_fy_weight(c, kappa, alpha_s, gamma_s, dfz, check, flags):
    """Weighting function Gyk of Fy for combined slip (4.E59-4.E65)."""
    eyk, flags = clip_curvature(c[C.REY1] + c[C.REY2] * dfz, check, flags)  # (4.E64)
    shyk = c[C.RHY1] + c[C.RHY2] * dfz  # (4.E65)
    byk = ((c[C.RBY1] + c[C.RBY4] * gamma_s * gamma_s)
           * cos_atan(c[C.RBY2] * (alpha_s - c[C.RBY3])) * c[C.LYKA])  # (4.E62)
    g0 = weight(byk, c[C.RCY1], eyk, shyk)  # (4.E60)
    return weight(byk, c[C.RCY1], eyk, kappa + shyk) / g0, flags  # (4.E59, 4.E61)


@numba.njit(cache=True, error_model="numpy")
def kappa_induced_fy(c, fz, muy, kappa, alpha_s, gamma_s, dfz, smooth):
    """'Ply-steer' like side force SVyk induced by longitudinal slip (4.E66-4.E67)."""
    dvyk = (muy * fz * (c[C.RVY1] + c[C.RVY2] * dfz + c[C.RVY3] * gamma_s)
            * cos_atan(c[C.RVY4] * alpha_s))  # (4.E67)
    return dvyk * math.sin(c[C.RVY5] * math.atan(c[C.RVY6] * kappa)) * c[C.LVYKA] * smooth  # (4.E66)


@numba.njit(cache=True, error_model="numpy")
def friction_ellipse_weights(fz, kappa, alpha_s, vx, star, fx0, fy0, mux, muy, kxk, kya, shx, svx,
                             shy, svy):
    """Weights ``(Gx, Gy)`` of the friction ellipse, the combined slip of a file with
    ``FE_METHOD = 'YES'`` (in place of Pacejka's Gxa, Gyk, 4.E51 and 4.E59; no SVyk).

    The slips measured from the pure curves' zero-force points, ``kc = kappa + SHx +
    SVx / Kxk`` and ``ac = sin(alpha + SHy + SVy / Kya)``, give the direction
    ``tan(beta) = |ac| / |kc|``; each force keeps its own pure-slip friction in its own
    direction and meets the other's peak on the ellipse (Project Chrono's ``ChPac02Tire``,
    ``CalcFxyMz``, use mode 4, "combining without Pacejka coefficients"):

        mu_x = 1 / sqrt(1 / mu_x0^2 + tan(beta)^2 / mu_y,max^2)
        mu_y = tan(beta) / sqrt(1 / mu_x,max^2 + tan(beta)^2 / mu_y0^2)

    with ``mu_x0 = |Fx0 - SVx| / Fz``, ``mu_y0 = |Fy0 - SVy| / Fz`` and the peaks
    ``mu_max = |D| / Fz`` (the shifts and stiffnesses those of :func:`pure_fx` and
    :func:`pure_fy`). Written here without the angle, so that it holds at zero slip:
    ``Gx = |kc| Dy / sqrt((kc Dy)^2 + ((Fx0 - SVx) ac)^2)``,
    ``Gy = |ac| Dx / sqrt(((Fy0 - SVy) kc)^2 + (ac Dx)^2)``; a pure slip (``ac = 0`` or
    ``kc = 0``) leaves its own force whole (weight 1) and takes the other's away.
    """
    kc = kappa + shx + (svx / kxk if kxk != 0.0 else 0.0)
    ac = math.sin(alpha_s + shy + (svy / kya if kya != 0.0 else 0.0))
    fx_own = (-fx0 if vx < 0.0 else fx0) - svx  # the curve's own part, before 4.E9's sign turn
    fy_own = (-fy0 if star and vx < 0.0 else fy0) - svy
    dx = abs(mux * fz)
    dy = abs(muy * fz)
    gx_den = math.sqrt((kc * dy) ** 2 + (fx_own * ac) ** 2)
    gy_den = math.sqrt((fy_own * kc) ** 2 + (ac * dx) ** 2)
    gx = abs(kc) * dy / gx_den if gx_den > 0.0 else 1.0
    gy = abs(ac) * dx / gy_den if gy_den > 0.0 else 1.0
    return gx, gy
