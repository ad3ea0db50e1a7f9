"""Compiled tread-block contact: massless blocks with stick/slip friction.

Each belt segment carries NB massless tread blocks spread across the width
(and, with a tread pattern, along the segment). Block j of segment i stands
on the belt at lateral offset ``y_j`` and circumferential offset ``s_j`` and
reaches ``h_j`` out along the belt normal ``n_i`` (``h_j`` follows the
carcass contour of [SHAPE]: the tread thickness at the centre, less where the
shoulder drops). Its base follows the segment's lateral displacement and
twist: ``B = P_i + (y_i + y_j) a + s_j t_i - y_j beta_i n_i``.

Normal law (thesis 2.3.4: nonlinear radial stiffness and damping), with the
compression ``d`` of the block tip measured along the road normal N::

    Fn = max(0, k A d (1 + q d / h0) + c A d'),   d' = -v_B . N

``A`` the block's share of the footprint area. Tangential law: the tip sticks
to the road; its elastic deflection ``s`` (2 components in the road plane,
kept in the state) grows with the base's sliding velocity, ``s += v_t dt``,
and the shear force is ``Ft = -k_s A s - c_s A v_t``; when ``|Ft| > mu Fn``
the block slides: ``s`` is cut back so that ``|Ft| = mu Fn`` (a brush model
with Coulomb friction, as in FTire's tread blocks). Out of contact ``s = 0``.
On a ground with a shear law of its own (the soil:
:func:`~tyrelab.road.terrain.terrain_shear`) the block and the ground shear in series
by that law instead, and the state kept is theirs (the soil's: the mobilized shear of
the two).

A block stands for a strip of tread one segment pitch long. Where the road
near the strip has relief that can reach the tip (its bound,
:func:`~tyrelab.road.terrain.terrain_zmax`, is above the road's lowest point
and the tip), the
strip is sampled every 10 mm and the
block presses with the mean penetration of the samples (its area shared
among them) at their penetration-weighted mean point, so obstacles
narrower than the block pitch (a 25 mm cleat under 40 mm segments) are
neither stepped over nor felt by the whole block. On flat ground this
costs nothing; on a rough road every block in contact samples its strip.
With the option ``lateral_samples`` > 1 the strip is also sampled across
the block's width (for obstacles narrower than the block column pitch
running along the wheel, as a longitudinal cleat; a static build sets it
when the road varies across, see :func:`~.model.ring_params`).

The ground is read through the terrain interface only (:mod:`tyrelab.road.terrain`):
its friction scale multiplies ``mu``, and a ground that is not rigid answers
each block's forces (:func:`~tyrelab.road.terrain.terrain_contact`: it may
sink and carry less); on the rigid road that branch is compiled out.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb

from ...road.terrain import (terrain_contact, terrain_friction, terrain_height_gradient,
                             terrain_is_rigid, terrain_penetration, terrain_range, terrain_shear,
                             terrain_zmax)

#: contact-patch sums of a step (``RingState.patch``, world frame): force of the
#: road on the blocks, normal-force-weighted contact point and normal, total
#: normal force, and the largest deflection of a contact point
ACC_FX, ACC_FY, ACC_FZ, ACC_PX, ACC_PY, ACC_PZ, ACC_NX, ACC_NY, ACC_NZ, ACC_W, ACC_DEFL = range(11)
ACC_SIZE = 11
#: sampling step along a block's strip where the road is uneven under it [m]
STRIP_STEP = 0.01


class SegmentFrame(NamedTuple):
    """A belt segment in the world: centre ``p``, belt normal ``n`` and
    tangent ``t`` (unit vectors), twist ``beta`` [rad]."""

    px: float
    py: float
    pz: float
    nx: float
    ny: float
    nz: float
    tx: float
    ty: float
    tz: float
    beta: float


class SegmentMotion(NamedTuple):
    """Velocity of a segment's block bases: ``ub + u s_j + w y_j`` [m/s].

    ``ub`` the rigid velocity of the segment centre, ``u`` its change per
    unit offset along the tangent, ``w`` per unit offset along the spin axis.
    """

    ubx: float
    uby: float
    ubz: float
    ux: float
    uy: float
    uz: float
    wx: float
    wy: float
    wz: float


@nb.njit(cache=True, inline="always")
def segment_can_touch(params, road, px, py, pz, az, beta):
    """False when no block of a segment at world point P can reach the road.

    The lowest any block tip can be is ``pz - h_max - W/2 (|a_z| + |beta|)``;
    the ground's bound (:func:`~tyrelab.road.terrain.terrain_zmax`) bounds the road under it.
    """
    reach = params.tread_half_width * (abs(az) + abs(beta)) + params.max_block_height + 0.002
    zmax = terrain_zmax(road, px - reach - 0.05, px + reach + 0.05)
    return pz - reach <= zmax


# inlined into the step: a call passing the three records costs about 15 % of a step
@nb.njit(cache=True, inline="always")
def segment_contact(params, road, state, i, seg, motion, pose, fwx, fwy, fwz, h):
    """Forces of the road on the blocks of segment i: ``(Fx, Fy, Fz, twist moment)``.

    ``seg`` the segment's :class:`SegmentFrame`, ``motion`` its
    :class:`SegmentMotion`, ``pose`` the wheel (centre ``c`` at this
    internal step, spin axis ``a``), ``fw`` the wheel's forward direction,
    ``h`` the time step. Updates the blocks' tangential deflections
    ``state.s1, s2`` and normal forces ``state.block_force``, and adds the
    contact-patch sums into ``state.patch``.
    """
    nbk = params.n_blocks
    o = i * nbk
    block_y = params.block_y
    block_s = params.block_s
    block_h = params.block_h
    block_area = params.block_area
    sblk1 = state.s1
    sblk2 = state.s2
    force = state.block_force
    acc = state.patch
    px, py, pz = seg.px, seg.py, seg.pz
    nx, ny, nz = seg.nx, seg.ny, seg.nz
    tx, ty, tz = seg.tx, seg.ty, seg.tz
    beta = seg.beta
    ax, ay, az = pose.ax, pose.ay, pose.az
    cx, cy, cz = pose.cx, pose.cy, pose.cz
    ubx, uby, ubz = motion.ubx, motion.uby, motion.ubz
    ux, uy, uz = motion.ux, motion.uy, motion.uz
    wx, wy, wz = motion.wx, motion.wy, motion.wz
    k_n = params.tread_stiffness
    q_n = params.tread_progression
    c_n = params.tread_damping
    k_s = params.tread_shear_stiffness
    c_s = params.tread_shear_damping
    mu = params.friction
    r0 = params.unloaded_radius
    half_l = 0.5 * params.chord_length
    n_strip = int(math.ceil(2.0 * half_l / STRIP_STEP))
    n_lat = params.lateral_samples if params.lateral_samples >= 1 else 1
    cell_w = 2.0 * params.tread_half_width / nbk
    zmin, _ = terrain_range(road)
    fx_sum = 0.0
    fy_sum = 0.0
    fz_sum = 0.0
    m_twist = 0.0
    for j in range(nbk):
        area = block_area[o + j]
        if area <= 0.0:
            continue
        yj = block_y[o + j]
        sj = block_s[o + j]
        hj = block_h[o + j]
        lat = yj
        bx = px + lat * ax + sj * tx - yj * beta * nx
        by = py + lat * ay + sj * ty - yj * beta * ny
        bz = pz + lat * az + sj * tz - yj * beta * nz
        tipx = bx + hj * nx
        tipy = by + hj * ny
        tipz = bz + hj * nz
        # a block stands for a strip of tread one segment long: where the
        # road under that strip rises above the height at the tip (a cleat
        # narrower than the block pitch), the strip is sampled every <= 10 mm
        # and the deepest point is the block's contact point; else the tip
        # alone is queried
        lz = terrain_zmax(road, tipx - half_l, tipx + half_l)
        strip = lz > zmin + 1e-4 and lz > tipz
        if not strip:
            g, gx, gy = terrain_height_gradient(road, tipx, tipy)
            pen = g - tipz
        else:
            # distributed strip: the block's area is shared by the samples;
            # it presses with the mean penetration, at the penetration-
            # weighted mean point and road gradient
            g = gx = gy = 0.0
            bx0 = tipx
            by0 = tipy
            bz0 = tipz
            sw = 0.0
            sx = 0.0
            sy = 0.0
            sg = 0.0
            sgx = 0.0
            sgy = 0.0
            for q in range(n_strip):
                u = -half_l + (q + 0.5) * (2.0 * half_l / n_strip)
                for r in range(n_lat):
                    w = ((r + 0.5) / n_lat - 0.5) * cell_w
                    qx = bx0 + u * tx + w * ax
                    qy = by0 + u * ty + w * ay
                    qz = bz0 + u * tz + w * az
                    # the gradient only where the sample is below the road
                    pq, gq, gxq, gyq = terrain_penetration(road, qx, qy, qz)
                    if pq > 0.0:
                        sw += pq
                        sx += pq * qx
                        sy += pq * qy
                        sg += pq * gq
                        sgx += pq * gxq
                        sgy += pq * gyq
            if sw > 0.0:
                pen = sw / (n_strip * n_lat)
                tipx = sx / sw
                tipy = sy / sw
                g = sg / sw
                tipz = g - pen
                gx = sgx / sw
                gy = sgy / sw
            else:
                pen = -1.0
        k = o + j
        if pen <= 0.0:
            sblk1[k] = 0.0
            sblk2[k] = 0.0
            force[k] = 0.0
            continue
        inv = 1.0 / math.sqrt(1.0 + gx * gx + gy * gy)
        nnx = -gx * inv
        nny = -gy * inv
        nnz = inv
        d = pen * inv
        vbx = ubx + sj * ux + yj * wx
        vby = uby + sj * uy + yj * wy
        vbz = ubz + sj * uz + yj * wz
        vn = vbx * nnx + vby * nny + vbz * nnz
        fn = area * (k_n * d * (1.0 + q_n * d / hj) - c_n * vn)
        if fn < 0.0:
            fn = 0.0
        # road tangent axes: t1 along the wheel's heading, t2 = N x t1
        dn = fwx * nnx + fwy * nny + fwz * nnz
        t1x = fwx - dn * nnx
        t1y = fwy - dn * nny
        t1z = fwz - dn * nnz
        tl = math.sqrt(t1x * t1x + t1y * t1y + t1z * t1z)
        t1x /= tl
        t1y /= tl
        t1z /= tl
        t2x = nny * t1z - nnz * t1y
        t2y = nnz * t1x - nnx * t1z
        t2z = nnx * t1y - nny * t1x
        v1 = vbx * t1x + vby * t1y + vbz * t1z
        v2 = vbx * t2x + vby * t2y + vbz * t2z
        kept1 = sblk1[k]
        kept2 = sblk2[k]
        s1 = kept1 + v1 * h
        s2 = kept2 + v2 * h
        f1 = -area * (k_s * s1 + c_s * v1)
        f2 = -area * (k_s * s2 + c_s * v2)
        fmag = math.sqrt(f1 * f1 + f2 * f2)
        mu_here = mu * terrain_friction(road, tipx, tipy)
        lim = mu_here * fn
        if fmag > lim:
            # sliding: the force is capped at mu Fn; the elastic deflection
            # is what the capped force would hold
            scale = lim / fmag
            f1 *= scale
            f2 *= scale
            s1 = -f1 / (area * k_s)
            s2 = -f2 / (area * k_s)
        if not terrain_is_rigid(road):  # a deformable ground answers (compiled out on rigid)
            fn, f1, f2 = terrain_contact(road, tipx, tipy, pen, area, v1, v2, fn, f1, f2, h)
            # a ground with its own shear law (the soil) shears in series with the block:
            # the block's state is then theirs (terrain_shear), not its deflection
            own, g1, g2, m1, m2 = terrain_shear(road, tipx, tipy, fn, area, kept1, kept2, v1 * h,
                                                v2 * h, k_s, mu_here * fn)
            if own:
                f1, f2, s1, s2 = g1, g2, m1, m2
        sblk1[k] = s1
        sblk2[k] = s2
        fbx = fn * nnx + f1 * t1x + f2 * t2x
        fby = fn * nny + f1 * t1y + f2 * t2y
        fbz = fn * nnz + f1 * t1z + f2 * t2z
        fx_sum += fbx
        fy_sum += fby
        fz_sum += fbz
        # generalized force on the twist: dB/dbeta = -y_j n
        m_twist -= yj * (fbx * nx + fby * ny + fbz * nz)
        # contact-patch bookkeeping
        acc[ACC_FX] += fbx
        acc[ACC_FY] += fby
        acc[ACC_FZ] += fbz
        acc[ACC_PX] += fn * tipx
        acc[ACC_PY] += fn * tipy
        acc[ACC_PZ] += fn * g
        acc[ACC_NX] += fn * nnx
        acc[ACC_NY] += fn * nny
        acc[ACC_NZ] += fn * nnz
        acc[ACC_W] += fn
        dist = math.sqrt((tipx - cx) ** 2 + (tipy - cy) ** 2 + (g - cz) ** 2)
        if r0 - dist > acc[ACC_DEFL]:
            acc[ACC_DEFL] = r0 - dist
        force[k] = fn
    return fx_sum, fy_sum, fz_sum, m_twist


@nb.njit(cache=True, inline="always")
def clear_segment(params, state, i):
    """Segment i out of reach: zero its blocks' tangential deflections and normal forces."""
    nbk = params.n_blocks
    for j in range(nbk):
        k = i * nbk + j
        state.s1[k] = 0.0
        state.s2[k] = 0.0
        state.block_force[k] = 0.0
