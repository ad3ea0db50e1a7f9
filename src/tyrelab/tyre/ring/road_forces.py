"""The road's forces on the ring's belt in one internal step (:mod:`.kernel`).

:func:`tread_contact`: every segment within reach of the road, its tread
blocks' forces (:func:`~.tread.segment_contact`) added to the belt's; the
others passed over without a road query. :func:`patch_hysteresis`: the
contact patch's Maxwell element between the road and the rim (docs/ring.md,
"Damping at the trailer's frequencies"). Both are inlined into
:func:`~.kernel.ring_kick`, so they are compiled without reference counting
with it.
"""

from __future__ import annotations

import math

import numba as nb

from ...road.terrain import terrain_zmax
from .tread import (SegmentFrame, SegmentMotion, clear_segment, segment_can_touch,
                    segment_contact)


# inlined into ring_kick, so compiled without reference counting
@nb.njit(cache=True, inline="always")
def tread_contact(params, state, road, pose, e1x, e1y, e1z, e2x, e2y, e2z, fwx, fwy, fwz, h):
    """The road's forces on the blocks of every segment within its reach, added to the belt.

    ``e1, e2`` the rotating in-plane axes, ``fw`` the wheel's forward
    direction, ``h`` the step. Adds each segment's contact force to
    ``state.f1, f2, fy`` and twist moment to ``state.fb``, updates the
    blocks (:func:`~.tread.segment_contact`) and ``state.in_reach``, and adds
    the contact-patch sums into ``state.patch``.
    """
    n = params.n_segments
    p1s, p2s, v1s, v2s = state.p1, state.p2, state.v1, state.v2
    ys, vys, bs, vbs = state.y, state.vy, state.beta, state.vbeta
    f1, f2, fy, fb = state.f1, state.f2, state.fy, state.fb
    in_reach = state.in_reach
    cx, cy, cz = pose.cx, pose.cy, pose.cz
    ax, ay, az = pose.ax, pose.ay, pose.az
    vx, vy, vz = pose.vx, pose.vy, pose.vz
    omega = pose.omega
    # the highest road under the whole wheel (every window segment_can_touch
    # looks at for a twist up to 1 rad): segments above it, most of the belt,
    # are passed over without a road query of their own
    span = (params.unloaded_radius + params.tread_half_width * (abs(az) + 1.0)
            + params.max_block_height + 0.06)
    road_top = terrain_zmax(road, cx - span, cx + span) + params.max_block_height + 0.01
    for i in range(n):
        p1 = p1s[i]
        p2 = p2s[i]
        yi = ys[i]
        beta = bs[i]
        pz = cz + p1 * e1z + p2 * e2z + yi * az
        px = cx + p1 * e1x + p2 * e2x + yi * ax
        py = cy + p1 * e1y + p2 * e2y + yi * ay
        if ((abs(beta) <= 1.0 and pz - params.tread_half_width * (abs(az) + abs(beta)) > road_top)
                or not segment_can_touch(params, road, px, py, pz, az, beta)):
            if in_reach[i]:  # else its blocks are clear already
                clear_segment(params, state, i)
                in_reach[i] = False
            continue
        in_reach[i] = True
        hh = i - 1 if i > 0 else n - 1
        j = i + 1 if i + 1 < n else 0
        d1 = p1s[j] - p1s[hh]
        d2 = p2s[j] - p2s[hh]
        dl = math.sqrt(d1 * d1 + d2 * d2)
        n1 = d2 / dl
        n2 = -d1 / dl
        nx = n1 * e1x + n2 * e2x
        ny = n1 * e1y + n2 * e2y
        nz = n1 * e1z + n2 * e2z
        tx = -n2 * e1x + n1 * e2x
        ty = -n2 * e1y + n1 * e2y
        tz = -n2 * e1z + n1 * e2z
        v1 = v1s[i]
        v2 = v2s[i]
        vyy = vys[i]
        vb = vbs[i]
        # absolute velocity of the segment centre: v + omega a x p + p'
        q1 = v1 + omega * p2
        q2 = v2 - omega * p1
        ubx = vx + q1 * e1x + q2 * e2x + vyy * ax
        uby = vy + q1 * e1y + q2 * e2y + vyy * ay
        ubz = vz + q1 * e1z + q2 * e2z + vyy * az
        # per unit offset along t: omega a x t; per unit offset along a: -beta' n
        ux = omega * (ay * tz - az * ty)
        uy = omega * (az * tx - ax * tz)
        uz = omega * (ax * ty - ay * tx)
        bfx, bfy, bfz, btw = segment_contact(
            params, road, state, i, SegmentFrame(px, py, pz, nx, ny, nz, tx, ty, tz, beta),
            SegmentMotion(ubx, uby, ubz, ux, uy, uz, -vb * nx, -vb * ny, -vb * nz),
            pose, fwx, fwy, fwz, h)
        f1[i] += bfx * e1x + bfy * e1y + bfz * e1z
        f2[i] += bfx * e2x + bfy * e2y + bfz * e2z
        fy[i] += bfx * ax + bfy * ay + bfz * az
        fb[i] += btw


@nb.njit(cache=True, inline="always")
def patch_hysteresis(params, state, fn, decay):
    """The force [N] of the contact patch's Maxwell element over one internal step.

    The element stands between the road and the rim, in parallel with the
    whole tyre, and is driven by the patch's normal force ``Fn`` (``fn``,
    this step's sum over the blocks): its force is ``g (Fn - r)`` with
    ``r' = (Fn - r) / tau``, relaxed exactly here (``decay = 1 - exp(-h /
    tau)``). Below ``1/(2 pi tau)`` that is the damper ``g tau Fn'``, which
    for a tyre of vertical stiffness ``k`` (``Fn = k rho``) is the damper
    ``c = g tau k`` on the deflection rate (eq. 2.2's ``c rho'``); above it,
    a stiffening by ``g``. It lives where the tyre meets the road, not on
    material points of the belt, so rolling does not relax it: a steady patch
    leaves it unloaded at any speed, an oscillating one is damped. It never
    pulls: the force is held at ``>= -Fn`` so the contact force stays
    ``>= 0``, and is 0 off the road.
    """
    gain = params.patch_hysteresis_gain
    if gain == 0.0:
        return 0.0
    r = state.patch_relaxed[0]
    state.patch_relaxed[0] = r + (fn - r) * decay
    if fn <= 0.0:
        return 0.0
    force = gain * (fn - r)
    if force < -fn:
        force = -fn
    return force
