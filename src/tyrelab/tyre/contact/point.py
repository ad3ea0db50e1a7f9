"""One-point (roller) contact: a rigid disc on a 3D road (thesis 2.3.1, 4.2).

The tyre is a disc of radius R0 in the wheel plane. The contact point is the
point of the road's section by the wheel plane that lies nearest the wheel
centre -- equivalently, where the wheel plane meets the road tangent plane
nearest the centre -- so it is not tied to the point straight below the
centre, and a rigid disc rolls over a step along the exact circular path
about the step's corner. The deflection is ``R0 - distance``; the force acts
along the road normal at the contact point (so a pothole edge, whose
supporting "plane" is tilted, pushes the wheel along that plane's normal and
nothing else).

The model reads the road only along its own section (a 2D road, like the
roller model it is): the normal lies in the wheel plane, pointing from the
contact point to the centre -- the supporting line of the section, well
defined at a corner too. A road feature therefore gives no lateral force
and no overturning moment about the contact point (an oblique cleat does
not steer a rigid disc); the volume and enveloping models, which see the
road across the tyre's width, do. On a banked road the contact point is the
plane's, but the force stays in the wheel plane.
"""

from __future__ import annotations

import math

import numba as nb

from ...core.vec3 import unit, wheel_axes
from ...road.grid import grid_height

#: geometry output layout written by every contact model
GEO_RHO, GEO_PX, GEO_PY, GEO_PZ, GEO_NX, GEO_NY, GEO_NZ = range(7)
GEO_SIZE = 8


@nb.njit(cache=True)
def local_zmax(zinfo, x0, x1):
    """Highest road point over road x in [x0, x1], from the block maxima.

    ``zinfo`` = ``[zmin, zmax, block_x0, block_dx, nblocks, max_0, max_1, ...]``
    (see :func:`tyrelab.tyre.kernel.road_info`).
    """
    nb_ = int(zinfo[4])
    if nb_ == 0:
        return zinfo[1]
    i0 = int(math.floor((x0 - zinfo[2]) / zinfo[3]))
    i1 = int(math.floor((x1 - zinfo[2]) / zinfo[3]))
    if i0 < 0:
        i0 = 0
    if i1 > nb_ - 1:
        i1 = nb_ - 1
    if i1 < i0:  # beyond the grid: the edge blocks continue
        i0 = i1 = 0 if x1 < zinfo[2] else nb_ - 1
    m = -1e300
    for i in range(i0, i1 + 1):
        if zinfo[5 + i] > m:
            m = zinfo[5 + i]
    return m


@nb.njit(cache=True, inline="always")
def _segment_nearest(s0, q0, s1, q1):
    """Nearest point to the origin on the segment (s0,q0)-(s1,q1) and its squared distance."""
    es = s1 - s0
    eq = q1 - q0
    t = -(s0 * es + q0 * eq) / (es * es + eq * eq)
    if t < 0.0:
        t = 0.0
    elif t > 1.0:
        t = 1.0
    ps = s0 + t * es
    pq = q0 + t * eq
    return ps, pq, ps * ps + pq * pq


@nb.njit(cache=True, inline="always")
def _nearer(s0, q0, s1, q1, bs, bq, best):
    """The segment's nearest point if it beats the best (squared distance) so far."""
    ps, pq, d2 = _segment_nearest(s0, q0, s1, q1)
    if d2 < best:
        return ps, pq, d2
    return bs, bq, best


@nb.njit(cache=True, inline="always")
def _depth(gp, z, cx, cy, cz, fx, fy, dz, hx, hy, base_q, s):
    """Depth below the centre, along the in-plane down vector, of the section at s."""
    return base_q + (grid_height(gp, z, cx + s * fx + hx, cy + s * fy + hy) - cz) * dz


@nb.njit(cache=True)
def _scan(gp, z, cx, cy, cz, fx, fy, dz, hx, hy, base_q, sa, sb, step, bs, bq, best):
    """Nearest point to the centre on the section between s = sa and sb.

    When the wheel heads along x (the rigs drive along x) the section is
    sampled exactly where it crosses the grid's x nodes: between them the
    bilinear road is linear along the section, so the piecewise-linear
    section is exact and a sharp edge stays a sharp corner. Otherwise the
    section is sampled every ``step``.
    """
    s0 = sa
    q0 = _depth(gp, z, cx, cy, cz, fx, fy, dz, hx, hy, base_q, s0)
    if abs(fx) > 0.9:
        # node coordinates of the two ends, walked in the direction of s
        u0 = (cx + sa * fx - gp[0]) * gp[4]
        u1 = (cx + sb * fx - gp[0]) * gp[4]
        k_first = int(math.floor(u0)) + 1 if u1 > u0 else int(math.ceil(u0)) - 1
        k_last = int(math.ceil(u1)) - 1 if u1 > u0 else int(math.floor(u1)) + 1
        direction = 1 if u1 > u0 else -1
        count = (k_last - k_first) * direction + 1
        for j in range(count + 1):
            if j < count:
                xk = gp[0] + (k_first + j * direction) * gp[2]
                s1 = (xk - cx) / fx
            else:
                s1 = sb
            if s1 <= s0:
                continue
            q1 = _depth(gp, z, cx, cy, cz, fx, fy, dz, hx, hy, base_q, s1)
            bs, bq, best = _nearer(s0, q0, s1, q1, bs, bq, best)
            s0 = s1
            q0 = q1
        return bs, bq, best
    n = int(math.ceil((sb - sa) / step)) + 1
    if n < 2:
        n = 2
    ds = (sb - sa) / (n - 1)
    for i in range(1, n):
        s1 = sa + i * ds
        q1 = _depth(gp, z, cx, cy, cz, fx, fy, dz, hx, hy, base_q, s1)
        bs, bq, best = _nearer(s0, q0, s1, q1, bs, bq, best)
        s0 = s1
        q0 = q1
    return bs, bq, best


@nb.njit(cache=True)
def point_contact(r0, step, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
    """Contact geometry of a rigid disc on a gridded road.

    Parameters
    ----------
    r0 : float
        Unloaded radius [m].
    step : float
        Sampling step along the road section [m] (the road grid spacing).
    gp, z : arrays
        Road grid (see :mod:`tyrelab.road.grid`).
    zinfo : float64 array
        Road height bounds (see :func:`local_zmax`); they bound the part of
        the section that can touch.
    cx, cy, cz : float
        Wheel centre [m].
    ax, ay, az : float
        Unit spin axis.
    geo : float64 array
        Output: deflection, contact point (3), unit road normal (3).
        Deflection <= 0 means no contact.
    """
    fx, fy, fz, dx, dy, dz = wheel_axes(ax, ay, az)
    cosg = -dz  # cosine of the wheel plane's tilt from vertical
    reach = r0 * abs(fx) + 1e-9
    zmax = local_zmax(zinfo, cx - reach, cx + reach)
    q_top = (cz - zmax) * cosg
    if q_top >= r0:  # even the highest road point is out of reach
        geo[GEO_RHO] = r0 - q_top
        geo[GEO_PX] = cx
        geo[GEO_PY] = cy
        geo[GEO_PZ] = cz - r0
        geo[GEO_NX] = 0.0
        geo[GEO_NY] = 0.0
        geo[GEO_NZ] = 1.0
        return
    half = math.sqrt(r0 * r0 - q_top * q_top)
    # lateral shift of the section's ground trace for a cambered wheel
    lever = (cz - grid_height(gp, z, cx, cy)) / cosg
    hx = dx * lever
    hy = dy * lever
    base_q = lever * (dx * dx + dy * dy)
    # Scan the section block by block (blocks of the road's block maxima),
    # nearest blocks first; a block is skipped when even its highest point,
    # placed at its nearest s, is farther from the centre than the best
    # point found so far. The section is sampled at grid resolution and
    # treated as piecewise linear, which it is for a bilinear road driven
    # along a grid axis.
    best = 1e300
    bs = 0.0
    bq = 0.0
    nblk = int(zinfo[4])
    if nblk == 0 or abs(fx) < 0.9:
        bs, bq, best = _scan(gp, z, cx, cy, cz, fx, fy, dz, hx, hy, base_q, -half, half, step,
                             bs, bq, best)
    else:
        bx0 = zinfo[2]
        bdx = zinfo[3]
        sgn = 1.0 if fx > 0.0 else -1.0
        # the block holding the centre, then alternately outwards
        ic = int(math.floor((cx - bx0) / bdx))
        kmax = int(math.ceil(half / bdx)) + 1
        for k in range(2 * kmax + 1):
            off = (k + 1) // 2 if (k % 2) == 1 else -(k // 2)
            ib = ic + off
            xb0 = bx0 + ib * bdx
            xb1 = xb0 + bdx
            # the block's span of s (s grows with x when heading +x)
            sa = (xb0 - cx) * sgn
            sb = (xb1 - cx) * sgn
            if sa > sb:
                sa, sb = sb, sa
            if sb < -half or sa > half:
                continue
            if sa < -half:
                sa = -half
            if sb > half:
                sb = half
            jb = ib if ib >= 0 else 0
            if jb > nblk - 1:
                jb = nblk - 1
            q_lo = (cz - zinfo[5 + jb]) * cosg
            s_lo = 0.0 if sa <= 0.0 <= sb else min(abs(sa), abs(sb))
            lb = s_lo * s_lo + (q_lo * q_lo if q_lo > 0.0 else 0.0)
            if lb >= best:
                continue
            bs, bq, best = _scan(gp, z, cx, cy, cz, fx, fy, dz, hx, hy, base_q, sa, sb, step,
                                 bs, bq, best)
    dist = math.sqrt(best)
    px = cx + bs * fx + bq * dx
    py = cy + bs * fy + bq * dy
    pz = cz + bs * fz + bq * dz
    # the normal lies in the wheel plane: from the contact point to the
    # centre (the supporting line of the section; well defined at a corner)
    ux, uy, uz = unit(cx - px, cy - py, cz - pz)
    geo[GEO_RHO] = r0 - dist
    geo[GEO_PX] = px
    geo[GEO_PY] = py
    geo[GEO_PZ] = pz
    geo[GEO_NX] = ux
    geo[GEO_NY] = uy
    geo[GEO_NZ] = uz
