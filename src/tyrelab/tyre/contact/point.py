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
from typing import NamedTuple

import numba as nb

from ...core.vec3 import unit, wheel_axes
from ...road.terrain import (terrain_block_max, terrain_blocks, terrain_height, terrain_lines,
                             terrain_zmax)
from ..model import TyreModel, contact_geometry_table
from ..registry import ContactModel, register_contact
from ..wheel import ContactGeometry


class PointParams(NamedTuple):
    """Parameters of the one-point contact model.

    ``unloaded_radius`` R0 [m]; ``step`` [m] the sampling step along road
    sections that do not run along x (the ground's finest spacing).
    """

    unloaded_radius: float
    step: float


def point_params(tyre, grid, **options) -> PointParams:
    """The point model's record for ``tyre`` on road ``grid`` (it takes no options)."""
    from ...errors import InputError
    if options:
        raise InputError(f"unknown point-model option(s) {', '.join(sorted(options))}; "
                         "the point model takes none", field="options")
    return PointParams(float(tyre.unloaded_radius), max(grid.sampling_step(), 1e-4))


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
def _depth(road, cx, cy, cz, fx, fy, dz, hx, hy, base_q, s):
    """Depth below the centre, along the in-plane down vector, of the section at s."""
    return base_q + (terrain_height(road, cx + s * fx + hx, cy + s * fy + hy) - cz) * dz


@nb.njit(cache=True)
def _scan(road, cx, cy, cz, fx, fy, dz, hx, hy, base_q, sa, sb, step, bs, bq, best):
    """Nearest point to the centre on the section between s = sa and sb.

    When the wheel heads along x (the rigs drive along x) the section is
    sampled exactly where it crosses the ground's break lines
    (:func:`~tyrelab.road.terrain.terrain_lines`, the grid's x nodes): between
    them the ground is linear along the section, so the piecewise-linear
    section is exact and a sharp edge stays a sharp corner. Otherwise the
    section is sampled every ``step``.
    """
    s0 = sa
    q0 = _depth(road, cx, cy, cz, fx, fy, dz, hx, hy, base_q, s0)
    if abs(fx) > 0.9:
        # line coordinates of the two ends, walked in the direction of s
        line0, spacing, inv_spacing, _ = terrain_lines(road)
        u0 = (cx + sa * fx - line0) * inv_spacing
        u1 = (cx + sb * fx - line0) * inv_spacing
        k_first = int(math.floor(u0)) + 1 if u1 > u0 else int(math.ceil(u0)) - 1
        k_last = int(math.ceil(u1)) - 1 if u1 > u0 else int(math.floor(u1)) + 1
        direction = 1 if u1 > u0 else -1
        count = (k_last - k_first) * direction + 1
        for j in range(count + 1):
            if j < count:
                xk = line0 + (k_first + j * direction) * spacing
                s1 = (xk - cx) / fx
            else:
                s1 = sb
            if s1 <= s0:
                continue
            q1 = _depth(road, cx, cy, cz, fx, fy, dz, hx, hy, base_q, s1)
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
        q1 = _depth(road, cx, cy, cz, fx, fy, dz, hx, hy, base_q, s1)
        bs, bq, best = _nearer(s0, q0, s1, q1, bs, bq, best)
        s0 = s1
        q0 = q1
    return bs, bq, best


@nb.njit(cache=True)
def point_contact(params, road, pose):
    """Contact geometry of a rigid disc on the ground.

    Parameters
    ----------
    params : PointParams
    road : a terrain record (:mod:`tyrelab.road.terrain`; the grid's RoadSurface)
    pose : WheelPose
        Only the centre and the spin axis are used.

    Returns
    -------
    ContactGeometry
        Deflection ``R0 - distance`` (<= 0: no contact), the nearest point
        of the section and the unit normal from it to the centre.
    """
    r0 = params.unloaded_radius
    step = params.step
    cx, cy, cz = pose.cx, pose.cy, pose.cz
    fx, fy, fz, dx, dy, dz = wheel_axes(pose.ax, pose.ay, pose.az)
    cosg = -dz  # cosine of the wheel plane's tilt from vertical
    reach = r0 * abs(fx) + 1e-9
    zmax = terrain_zmax(road, cx - reach, cx + reach)
    q_top = (cz - zmax) * cosg
    if q_top >= r0:  # even the highest road point is out of reach
        return ContactGeometry(r0 - q_top, cx, cy, cz - r0, 0.0, 0.0, 1.0, 0.0)
    half = math.sqrt(r0 * r0 - q_top * q_top)
    # lateral shift of the section's ground trace for a cambered wheel
    lever = (cz - terrain_height(road, cx, cy)) / cosg
    hx = dx * lever
    hy = dy * lever
    base_q = lever * (dx * dx + dy * dy)
    # Scan the section block by block (the ground's bound blocks,
    # terrain_blocks), nearest blocks first; a block is skipped when even its
    # highest point, placed at its nearest s, is farther from the centre than
    # the best point found so far. The section is sampled at the ground's
    # break lines and treated as piecewise linear, which it is for a ground
    # driven along x.
    best = 1e300
    bs = 0.0
    bq = 0.0
    bx0, bdx, nblk = terrain_blocks(road)
    if nblk == 0 or abs(fx) < 0.9:
        bs, bq, best = _scan(road, cx, cy, cz, fx, fy, dz, hx, hy, base_q, -half, half, step,
                             bs, bq, best)
    else:
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
            q_lo = (cz - terrain_block_max(road, ib)) * cosg
            s_lo = 0.0 if sa <= 0.0 <= sb else min(abs(sa), abs(sb))
            lb = s_lo * s_lo + (q_lo * q_lo if q_lo > 0.0 else 0.0)
            if lb >= best:
                continue
            bs, bq, best = _scan(road, cx, cy, cz, fx, fy, dz, hx, hy, base_q, sa, sb, step,
                                 bs, bq, best)
    dist = math.sqrt(best)
    px = cx + bs * fx + bq * dx
    py = cy + bs * fy + bq * dy
    pz = cz + bs * fz + bq * dz
    # the normal lies in the wheel plane: from the contact point to the
    # centre (the supporting line of the section; well defined at a corner)
    ux, uy, uz = unit(cx - px, cy - py, cz - pz)
    return ContactGeometry(r0 - dist, px, py, pz, ux, uy, uz, 0.0)


def point_geometry(tyre, road, x, y=0.0, z=None, axis=(0.0, 1.0, 0.0)):
    """Deflection, contact point and normal of the point model at wheel centres ``(x, y, z)``.

    See :func:`tyrelab.tyre.model.contact_geometry_table` for the arguments
    and the returned table.
    """
    return contact_geometry_table(TyreModel(tyre, "point"), road, x, y, z, axis)


register_contact(ContactModel("point", PointParams, point_params, geometry=point_contact,
                              summary="one-point (roller) contact, thesis 2.3.1", cost=0.003,
                              parameterization="load-deflection curve (static press on a flat plate)",
                              terrains=("rigid", "soil"), fit_steps=("vertical", "damping")))
