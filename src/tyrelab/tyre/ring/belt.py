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


@nb.njit(cache=True)
def foundation_forces(params, state):
    """Rim-to-belt springs and dampers; sets (not adds) the force arrays of ``state``.

    Returns nothing; the rim receives the opposite forces (see the kernel).
    """
    n = params.n_segments
    kr, kt, ky, kb = (params.radial_stiffness, params.tangential_stiffness,
                      params.lateral_stiffness, params.torsion_stiffness)
    cr, ct, cy, cb = (params.radial_damping, params.tangential_damping, params.lateral_damping,
                      params.torsion_damping)
    rb = params.belt_radius
    cos_t = params.cos_theta
    sin_t = params.sin_theta
    p1s, p2s, v1s, v2s = state.p1, state.p2, state.v1, state.v2
    f1, f2, fy, fb = state.f1, state.f2, state.fy, state.fb
    for i in range(n):
        c = cos_t[i]
        s = sin_t[i]
        p1 = p1s[i]
        p2 = p2s[i]
        v1 = v1s[i]
        v2 = v2s[i]
        ur = p1 * c + p2 * s - rb
        ut = -p1 * s + p2 * c
        vr = v1 * c + v2 * s
        vt = -v1 * s + v2 * c
        fr = -kr * ur - cr * vr
        ft = -kt * ut - ct * vt
        f1[i] = fr * c - ft * s
        f2[i] = fr * s + ft * c
        fy[i] = -ky * state.y[i] - cy * state.vy[i]
        fb[i] = -kb * state.beta[i] - cb * state.vbeta[i]


@nb.njit(cache=True)
def membrane_forces(params, state):
    """Add chord tension (pre-tension + extension + its damping) and pressure.

    Also keeps each chord's direction and extension rate (``state.chord_1,
    chord_2, chord_rate``), which the implicit step of :mod:`.implicit` needs.
    """
    n = params.n_segments
    t0, ea, cea, l0, pb = (params.pretension, params.extension_stiffness,
                           params.extension_damping, params.chord_length, params.pressure_load)
    p1, p2, v1, v2 = state.p1, state.p2, state.v1, state.v2
    f1, f2 = state.f1, state.f2
    c1, c2, c_rate = state.chord_1, state.chord_2, state.chord_rate
    for i in range(n):
        j = i + 1 if i + 1 < n else 0
        d1 = p1[j] - p1[i]
        d2 = p2[j] - p2[i]
        w1 = v1[j] - v1[i]
        w2 = v2[j] - v2[i]
        length = math.sqrt(d1 * d1 + d2 * d2)
        u1 = d1 / length
        u2 = d2 / length
        rate = u1 * w1 + u2 * w2
        c1[i] = u1
        c2[i] = u2
        c_rate[i] = rate
        t = t0 + (ea * (length - l0) + cea * rate) / l0
        g1 = t * u1
        g2 = t * u2
        f1[i] += g1
        f2[i] += g2
        f1[j] -= g1
        f2[j] -= g2
        # pressure on the edge i-j: half to each end, along the outward normal
        f1[i] += 0.5 * pb * d2
        f2[i] -= 0.5 * pb * d1
        f1[j] += 0.5 * pb * d2
        f2[j] -= 0.5 * pb * d1


@nb.njit(cache=True, inline="always")
def _turn_beyond(cross, dot, cd, sd, dth):
    """``atan2(cross, dot) - dth`` (the turning angle beyond the nominal one).

    The difference is the angle of ``(dot cos dth + cross sin dth,
    cross cos dth - dot sin dth)``; where it is small (|tan| < 1/4, every
    belt short of a fold) its arctangent series to the 15th power is exact
    to 4e-12 rad and costs a third of ``atan2``.
    """
    u = cross * cd - dot * sd
    v = dot * cd + cross * sd
    if v > 0.0 and abs(u) < 0.25 * v:
        t = u / v
        t2 = t * t
        return t * (1.0 + t2 * (-1.0 / 3.0 + t2 * (0.2 + t2 * (-1.0 / 7.0 + t2 * (
            1.0 / 9.0 + t2 * (-1.0 / 11.0 + t2 * (1.0 / 13.0 - t2 / 15.0)))))))
    return math.atan2(cross, dot) - dth


@nb.njit(cache=True)
def bending_forces(params, state):
    """Add the in-plane bending springs ``M = EI/L0 (phi_i - dth)`` at every node."""
    n = params.n_segments
    k = params.bending_stiffness / params.chord_length
    if k == 0.0:
        return
    dth = params.segment_angle
    cd = math.cos(dth)
    sd = math.sin(dth)
    p1, p2 = state.p1, state.p2
    f1, f2 = state.f1, state.f2
    for i in range(n):
        h = i - 1 if i > 0 else n - 1
        j = i + 1 if i + 1 < n else 0
        a1 = p1[i] - p1[h]
        a2 = p2[i] - p2[h]
        b1 = p1[j] - p1[i]
        b2 = p2[j] - p2[i]
        cross = a1 * b2 - a2 * b1
        dot = a1 * b1 + a2 * b2
        m = -k * _turn_beyond(cross, dot, cd, sd, dth)
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
def out_of_plane_forces(params, state):
    """Add lateral bending, torsion and pre-tension string forces (linear)."""
    n = params.n_segments
    rb = params.belt_radius
    dth = params.segment_angle
    l0 = params.chord_length
    eio = params.lateral_bending_stiffness
    gj = params.belt_torsion_stiffness
    ks = params.pretension / l0
    y = state.y
    b = state.beta
    fy, fb = state.fy, state.fb
    for i in range(n):
        h = i - 1 if i > 0 else n - 1
        j = i + 1 if i + 1 < n else 0
        # bending at node i: kappa = (y'' + Rb beta) / Rb^2
        kap = ((y[j] - 2.0 * y[i] + y[h]) / (dth * dth) + rb * b[i]) / (rb * rb)
        m = eio * kap * l0
        dk_dy = 1.0 / (dth * dth * rb * rb)
        fy[j] -= m * dk_dy
        fy[h] -= m * dk_dy
        fy[i] += 2.0 * m * dk_dy
        fb[i] -= m / rb
        # torsion between i and j: tau = ((b_j - b_i) - (y_j - y_i)/Rb) / (Rb dth)
        tau = ((b[j] - b[i]) - (y[j] - y[i]) / rb) / (rb * dth)
        q = gj * tau * l0 / (rb * dth)
        fb[j] -= q
        fb[i] += q
        fy[j] += q / rb
        fy[i] -= q / rb
        # string stiffness of the pre-tension
        s = ks * (y[j] - y[i])
        fy[i] += s
        fy[j] -= s


@nb.njit(cache=True)
def belt_forces(params, state):
    """All structural forces on the segments (foundation included), into ``state.f1 .. fb``."""
    foundation_forces(params, state)
    membrane_forces(params, state)
    bending_forces(params, state)
    out_of_plane_forces(params, state)


@nb.njit(cache=True)
def belt_potential(params, state):
    """Elastic + pressure potential energy of the belt [J] (dampers excluded).

    ``V = sum 1/2 k u^2 (foundation) + sum [T0 (L - L0) + EA (L - L0)^2 / (2 L0)]
    - p b A + sum EI/(2 L0) (phi - dth)^2 + out-of-plane terms``, A the
    polygon area. Its negative gradient is :func:`belt_forces` without dampers.
    """
    n = params.n_segments
    rb = params.belt_radius
    dth = params.segment_angle
    l0 = params.chord_length
    e = 0.0
    area = 0.0
    ps1, ps2, ys, bs = state.p1, state.p2, state.y, state.beta
    for i in range(n):
        h = i - 1 if i > 0 else n - 1
        j = i + 1 if i + 1 < n else 0
        c = params.cos_theta[i]
        s = params.sin_theta[i]
        p1 = ps1[i]
        p2 = ps2[i]
        ur = p1 * c + p2 * s - rb
        ut = -p1 * s + p2 * c
        y = ys[i]
        b = bs[i]
        e += 0.5 * (params.radial_stiffness * ur * ur + params.tangential_stiffness * ut * ut
                    + params.lateral_stiffness * y * y + params.torsion_stiffness * b * b)
        q1 = ps1[j]
        q2 = ps2[j]
        length = math.sqrt((q1 - p1) ** 2 + (q2 - p2) ** 2)
        e += params.pretension * (length - l0) + 0.5 * params.extension_stiffness * (
            length - l0) ** 2 / l0
        area += 0.5 * (p1 * q2 - p2 * q1)
        a1 = p1 - ps1[h]
        a2 = p2 - ps2[h]
        phi = math.atan2(a1 * (q2 - p2) - a2 * (q1 - p1), a1 * (q1 - p1) + a2 * (q2 - p2))
        e += 0.5 * params.bending_stiffness / l0 * (phi - dth) ** 2
        yh = ys[h]
        yj = ys[j]
        bj = bs[j]
        kap = ((yj - 2.0 * y + yh) / (dth * dth) + rb * b) / (rb * rb)
        tau = ((bj - b) - (yj - y) / rb) / (rb * dth)
        e += 0.5 * (params.lateral_bending_stiffness * kap * kap
                    + params.belt_torsion_stiffness * tau * tau) * l0
        e += 0.5 * params.pretension / l0 * (yj - y) ** 2
    return e - params.pressure_load * area
