"""Compiled structural forces of the belt: foundation, membrane, bending, torsion.

The belt is a ring of N rigid segments (thesis 2.3.4, Gipser 1999). The
state is kept relative to the rim, in rim-fixed axes that spin with it:
in-plane segment centre ``p_i = (p1, p2)`` in the rotating wheel-plane axes
(E1, E2), lateral displacement ``y_i`` along the spin axis and twist
``beta_i`` about the belt tangent. Nominal position ``Rb (cos th_i,
sin th_i)``, ``th_i = 2 pi i / N``.

Forces on segment i (per segment; "per length" stiffnesses times L0 = Rb dth):

* foundation (sidewall) springs and dampers to the rim, in the nominal radial
  and tangential directions, laterally and in torsion:
  ``F = -k u - c u'``, with ``k_r = (k_r0 + k_rp p) L0`` (stiffer with
  inflation pressure p),
* membrane: chords between neighbours carry ``T = T0 + EA (L - L0)/L0`` with
  the pressure pre-tension ``T0 = p b Rb cos(dth/2)`` (exact equilibrium of
  the discrete ring), and the inflation pressure acts on the polygon as the
  follower load ``F_i = (p b / 2) rot(p_{i+1} - p_{i-1})`` (gradient of the
  enclosed area, so it is conservative),
* in-plane bending: a rotational spring ``EI / L0`` on the turning angle
  between neighbouring chords,
* out-of-plane bending and torsion of the curved belt (Love's ring strains,
  both zero for rigid motions of the ring):
  ``kappa_i = (y''_i + Rb beta_i) / Rb^2``, ``tau = (beta' - y'/Rb) / Rb``
  (primes: differences over dth), energy ``sum 1/2 (EI_o kappa^2 + GJ tau^2) L0``,
  plus the string stiffness of the pre-tension ``T0 (y_{i+1} - y_i)^2 / (2 L0)``.

The continuum limit of the in-plane part is the classical pre-tensioned ring
on an elastic foundation; :func:`tyrelab.tyre.ring.modal.ring_frequencies_analytic`
gives its natural frequencies.
"""

from __future__ import annotations

import math

import numba as nb

from .layout import (CP_CB, CP_CEA, CP_CR, CP_CT, CP_CY, CP_DTH, CP_EA, CP_EI, CP_EIO, CP_GJ,
                     CP_KB, CP_KR, CP_KT, CP_KY, CP_L0, CP_N, CP_OFF_COS, CP_OFF_SIN, CP_PB,
                     CP_RB, CP_T0, S_B, S_P1, S_P2, S_V1, S_V2, S_VB, S_VY, S_Y, TS_HEADER)


@nb.njit(cache=True)
def foundation_forces(cp, ts, f1, f2, fy, fb):
    """Rim-to-belt springs and dampers; sets (not adds) the force arrays.

    Returns nothing; the rim receives the opposite forces (see the kernel).
    """
    n = int(cp[CP_N])
    o = TS_HEADER
    kr, kt, ky, kb = cp[CP_KR], cp[CP_KT], cp[CP_KY], cp[CP_KB]
    cr, ct, cy, cb = cp[CP_CR], cp[CP_CT], cp[CP_CY], cp[CP_CB]
    rb = cp[CP_RB]
    oc = int(cp[CP_OFF_COS])
    os_ = int(cp[CP_OFF_SIN])
    for i in range(n):
        c = cp[oc + i]
        s = cp[os_ + i]
        p1 = ts[o + S_P1 * n + i]
        p2 = ts[o + S_P2 * n + i]
        v1 = ts[o + S_V1 * n + i]
        v2 = ts[o + S_V2 * n + i]
        ur = p1 * c + p2 * s - rb
        ut = -p1 * s + p2 * c
        vr = v1 * c + v2 * s
        vt = -v1 * s + v2 * c
        fr = -kr * ur - cr * vr
        ft = -kt * ut - ct * vt
        f1[i] = fr * c - ft * s
        f2[i] = fr * s + ft * c
        fy[i] = -ky * ts[o + S_Y * n + i] - cy * ts[o + S_VY * n + i]
        fb[i] = -kb * ts[o + S_B * n + i] - cb * ts[o + S_VB * n + i]


@nb.njit(cache=True)
def membrane_forces(cp, ts, f1, f2):
    """Add chord tension (pre-tension + extension + its damping) and pressure."""
    n = int(cp[CP_N])
    o = TS_HEADER
    t0, ea, cea, l0, pb = cp[CP_T0], cp[CP_EA], cp[CP_CEA], cp[CP_L0], cp[CP_PB]
    for i in range(n):
        j = i + 1 if i + 1 < n else 0
        d1 = ts[o + S_P1 * n + j] - ts[o + S_P1 * n + i]
        d2 = ts[o + S_P2 * n + j] - ts[o + S_P2 * n + i]
        w1 = ts[o + S_V1 * n + j] - ts[o + S_V1 * n + i]
        w2 = ts[o + S_V2 * n + j] - ts[o + S_V2 * n + i]
        length = math.sqrt(d1 * d1 + d2 * d2)
        rate = (d1 * w1 + d2 * w2) / length
        t = t0 + ea * (length - l0) / l0 + cea * rate / l0
        g1 = t * d1 / length
        g2 = t * d2 / length
        f1[i] += g1
        f2[i] += g2
        f1[j] -= g1
        f2[j] -= g2
        # pressure on the edge i-j: half to each end, along the outward normal
        f1[i] += 0.5 * pb * d2
        f2[i] -= 0.5 * pb * d1
        f1[j] += 0.5 * pb * d2
        f2[j] -= 0.5 * pb * d1


@nb.njit(cache=True)
def bending_forces(cp, ts, f1, f2):
    """Add the in-plane bending springs ``M = EI/L0 (phi_i - dth)`` at every node."""
    n = int(cp[CP_N])
    o = TS_HEADER
    k = cp[CP_EI] / cp[CP_L0]
    if k == 0.0:
        return
    dth = cp[CP_DTH]
    for i in range(n):
        h = i - 1 if i > 0 else n - 1
        j = i + 1 if i + 1 < n else 0
        a1 = ts[o + S_P1 * n + i] - ts[o + S_P1 * n + h]
        a2 = ts[o + S_P2 * n + i] - ts[o + S_P2 * n + h]
        b1 = ts[o + S_P1 * n + j] - ts[o + S_P1 * n + i]
        b2 = ts[o + S_P2 * n + j] - ts[o + S_P2 * n + i]
        phi = math.atan2(a1 * b2 - a2 * b1, a1 * b1 + a2 * b2)
        m = -k * (phi - dth)
        la = a1 * a1 + a2 * a2
        lb = b1 * b1 + b2 * b2
        # dphi/db = perp(b)/|b|^2, dphi/da = -perp(a)/|a|^2, perp(x) = (-x2, x1)
        gb1 = -b2 / lb
        gb2 = b1 / lb
        ga1 = a2 / la
        ga2 = -a1 / la
        f1[j] += m * gb1
        f2[j] += m * gb2
        f1[i] += m * (ga1 - gb1)
        f2[i] += m * (ga2 - gb2)
        f1[h] -= m * ga1
        f2[h] -= m * ga2


@nb.njit(cache=True)
def out_of_plane_forces(cp, ts, fy, fb):
    """Add lateral bending, torsion and pre-tension string forces (linear)."""
    n = int(cp[CP_N])
    o = TS_HEADER
    rb = cp[CP_RB]
    dth = cp[CP_DTH]
    l0 = cp[CP_L0]
    eio = cp[CP_EIO]
    gj = cp[CP_GJ]
    ks = cp[CP_T0] / l0
    yo = o + S_Y * n
    bo = o + S_B * n
    for i in range(n):
        h = i - 1 if i > 0 else n - 1
        j = i + 1 if i + 1 < n else 0
        # bending at node i: kappa = (y'' + Rb beta) / Rb^2
        kap = ((ts[yo + j] - 2.0 * ts[yo + i] + ts[yo + h]) / (dth * dth) + rb * ts[bo + i]) / (rb * rb)
        m = eio * kap * l0
        dk_dy = 1.0 / (dth * dth * rb * rb)
        fy[j] -= m * dk_dy
        fy[h] -= m * dk_dy
        fy[i] += 2.0 * m * dk_dy
        fb[i] -= m / rb
        # torsion between i and j: tau = ((b_j - b_i) - (y_j - y_i)/Rb) / (Rb dth)
        tau = ((ts[bo + j] - ts[bo + i]) - (ts[yo + j] - ts[yo + i]) / rb) / (rb * dth)
        q = gj * tau * l0 / (rb * dth)
        fb[j] -= q
        fb[i] += q
        fy[j] += q / rb
        fy[i] -= q / rb
        # string stiffness of the pre-tension
        s = ks * (ts[yo + j] - ts[yo + i])
        fy[i] += s
        fy[j] -= s


@nb.njit(cache=True)
def belt_forces(cp, ts, f1, f2, fy, fb):
    """All structural forces on the segments (foundation included)."""
    foundation_forces(cp, ts, f1, f2, fy, fb)
    membrane_forces(cp, ts, f1, f2)
    bending_forces(cp, ts, f1, f2)
    out_of_plane_forces(cp, ts, fy, fb)


@nb.njit(cache=True)
def belt_potential(cp, ts):
    """Elastic + pressure potential energy of the belt [J] (dampers excluded).

    ``V = sum 1/2 k u^2 (foundation) + sum [T0 (L - L0) + EA (L - L0)^2 / (2 L0)]
    - p b A + sum EI/(2 L0) (phi - dth)^2 + out-of-plane terms``, A the
    polygon area. Its negative gradient is :func:`belt_forces` without dampers.
    """
    n = int(cp[CP_N])
    o = TS_HEADER
    rb = cp[CP_RB]
    dth = cp[CP_DTH]
    l0 = cp[CP_L0]
    oc = int(cp[CP_OFF_COS])
    os_ = int(cp[CP_OFF_SIN])
    e = 0.0
    area = 0.0
    for i in range(n):
        h = i - 1 if i > 0 else n - 1
        j = i + 1 if i + 1 < n else 0
        c = cp[oc + i]
        s = cp[os_ + i]
        p1 = ts[o + S_P1 * n + i]
        p2 = ts[o + S_P2 * n + i]
        ur = p1 * c + p2 * s - rb
        ut = -p1 * s + p2 * c
        y = ts[o + S_Y * n + i]
        b = ts[o + S_B * n + i]
        e += 0.5 * (cp[CP_KR] * ur * ur + cp[CP_KT] * ut * ut + cp[CP_KY] * y * y + cp[CP_KB] * b * b)
        q1 = ts[o + S_P1 * n + j]
        q2 = ts[o + S_P2 * n + j]
        length = math.sqrt((q1 - p1) ** 2 + (q2 - p2) ** 2)
        e += cp[CP_T0] * (length - l0) + 0.5 * cp[CP_EA] * (length - l0) ** 2 / l0
        area += 0.5 * (p1 * q2 - p2 * q1)
        a1 = p1 - ts[o + S_P1 * n + h]
        a2 = p2 - ts[o + S_P2 * n + h]
        phi = math.atan2(a1 * (q2 - p2) - a2 * (q1 - p1), a1 * (q1 - p1) + a2 * (q2 - p2))
        e += 0.5 * cp[CP_EI] / l0 * (phi - dth) ** 2
        yh = ts[o + S_Y * n + h]
        yj = ts[o + S_Y * n + j]
        bj = ts[o + S_B * n + j]
        kap = ((yj - 2.0 * y + yh) / (dth * dth) + rb * b) / (rb * rb)
        tau = ((bj - b) - (yj - y) / rb) / (rb * dth)
        e += 0.5 * (cp[CP_EIO] * kap * kap + cp[CP_GJ] * tau * tau) * l0
        e += 0.5 * cp[CP_T0] / l0 * (yj - y) ** 2
    return e - cp[CP_PB] * area
