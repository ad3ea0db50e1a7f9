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

A block stands for a strip of tread one segment pitch long. Where the road
near the strip has relief that can reach the tip (its block maximum,
:func:`local_zmax`, is above the road's lowest point and the tip), the
strip is sampled every 10 mm and the
block presses with the mean penetration of the samples (its area shared
among them) at their penetration-weighted mean point, so obstacles
narrower than the block pitch (a 25 mm cleat under 40 mm segments) are
neither stepped over nor felt by the whole block. On flat ground this
costs nothing; on a rough road every block in contact samples its strip.
With the option ``lateral_samples`` > 1 the strip is also sampled across
the block's width (for obstacles narrower than the block column pitch
running along the wheel, as a longitudinal cleat; the static press sets it
when the road varies across).
"""

from __future__ import annotations

import math

import numba as nb

from ...road.grid import grid_height_gradient
from ..contact.point import local_zmax
from .layout import (CP_CSH, CP_CTR, CP_HALFW, CP_HMAX, CP_KNL, CP_KSH, CP_KTR, CP_L0, CP_MU, CP_NB,
                     CP_NLAT,
                     CP_OFF_BC, CP_OFF_BH, CP_OFF_BK, CP_OFF_BY, CP_R0)

#: accumulator layout for the contact patch (world frame)
ACC_FX, ACC_FY, ACC_FZ, ACC_PX, ACC_PY, ACC_PZ, ACC_NX, ACC_NY, ACC_NZ, ACC_W, ACC_DEFL, \
    ACC_N = range(12)
ACC_SIZE = 12
#: sampling step along a block's strip where the road is uneven under it [m]
STRIP_STEP = 0.01


@nb.njit(cache=True)
def segment_can_touch(cp, zinfo, px, py, pz, az, beta):
    """False when no block of a segment at world point P can reach the road.

    The lowest any block tip can be is ``pz - h_max - W/2 (|a_z| + |beta|)``;
    the road's block maxima (:func:`local_zmax`) bound the road under it.
    """
    reach = cp[CP_HALFW] * (abs(az) + abs(beta)) + cp[CP_HMAX] + 0.002
    zmax = local_zmax(zinfo, px - reach - 0.05, px + reach + 0.05)
    return pz - reach <= zmax


@nb.njit(cache=True)
def segment_contact(cp, gp, z, zinfo, i, px, py, pz, nx, ny, nz, tx, ty, tz, ax, ay, az, beta,
                    ubx, uby, ubz, ux, uy, uz, wx, wy, wz, fwx, fwy, fwz, cx, cy, cz,
                    sblk, o1, o2, h, acc, out_f, pressure_out):
    """Forces of the road on the blocks of segment i; returns their sum and twist moment.

    ``P`` segment centre, ``n``/``t`` belt normal and tangent, ``a`` spin axis
    (world); the base velocity is ``ub + u s_j + w y_j`` (rigid segment
    velocity, plus the part that varies with the offsets along t and a);
    ``fw`` the wheel's forward direction; ``sblk[o1 + ...]``, ``sblk[o2 + ...]``
    the two components of the block deflections; ``h`` the time step. Adds the contact-patch resultant into
    ``acc``; writes ``(Fx, Fy, Fz)`` and the generalized twist moment into
    ``out_f``; if ``pressure_out`` has more than one entry, writes each
    block's normal force there.
    """
    nbk = int(cp[CP_NB])
    oy = int(cp[CP_OFF_BY]) + i * nbk
    oc = int(cp[CP_OFF_BC]) + i * nbk
    oh = int(cp[CP_OFF_BH]) + i * nbk
    ok = int(cp[CP_OFF_BK]) + i * nbk
    k_n = cp[CP_KTR]
    q_n = cp[CP_KNL]
    c_n = cp[CP_CTR]
    k_s = cp[CP_KSH]
    c_s = cp[CP_CSH]
    mu = cp[CP_MU]
    r0 = cp[CP_R0]
    half_l = 0.5 * cp[CP_L0]
    n_strip = int(math.ceil(2.0 * half_l / STRIP_STEP))
    n_lat = int(cp[CP_NLAT]) if cp[CP_NLAT] >= 1.0 else 1
    cell_w = 2.0 * cp[CP_HALFW] / nbk
    fx_sum = 0.0
    fy_sum = 0.0
    fz_sum = 0.0
    m_twist = 0.0
    for j in range(nbk):
        area = cp[ok + j]
        if area <= 0.0:
            continue
        yj = cp[oy + j]
        sj = cp[oc + j]
        hj = cp[oh + j]
        lat = yj
        bx = px + lat * ax + sj * tx - yj * beta * nx
        by = py + lat * ay + sj * ty - yj * beta * ny
        bz = pz + lat * az + sj * tz - yj * beta * nz
        tipx = bx + hj * nx
        tipy = by + hj * ny
        tipz = bz + hj * nz
        g, gx, gy = grid_height_gradient(gp, z, tipx, tipy)
        pen = g - tipz
        # a block stands for a strip of tread one segment long: where the
        # road under that strip rises above the height at the tip (a cleat
        # narrower than the block pitch), the strip is sampled every <= 10 mm
        # and the deepest point is the block's contact point
        lz = local_zmax(zinfo, tipx - half_l, tipx + half_l)
        if lz > zinfo[0] + 1e-4 and lz > tipz:
            # distributed strip: the block's area is shared by the samples;
            # it presses with the mean penetration, at the penetration-
            # weighted mean point and road gradient
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
                    gq, gxq, gyq = grid_height_gradient(gp, z, qx, qy)
                    pq = gq - qz
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
        ks0 = o1 + i * nbk + j
        ks1 = o2 + i * nbk + j
        if pen <= 0.0:
            sblk[ks0] = 0.0
            sblk[ks1] = 0.0
            if pressure_out.shape[0] > 1:
                pressure_out[i * nbk + j] = 0.0
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
        s1 = sblk[ks0] + v1 * h
        s2 = sblk[ks1] + v2 * h
        f1 = -area * (k_s * s1 + c_s * v1)
        f2 = -area * (k_s * s2 + c_s * v2)
        fmag = math.sqrt(f1 * f1 + f2 * f2)
        lim = mu * fn
        if fmag > lim:
            # sliding: the force is capped at mu Fn; the elastic deflection
            # is what the capped force would hold
            scale = lim / fmag
            f1 *= scale
            f2 *= scale
            s1 = -f1 / (area * k_s)
            s2 = -f2 / (area * k_s)
        sblk[ks0] = s1
        sblk[ks1] = s2
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
        acc[ACC_N] += 1.0
        dist = math.sqrt((tipx - cx) ** 2 + (tipy - cy) ** 2 + (g - cz) ** 2)
        if r0 - dist > acc[ACC_DEFL]:
            acc[ACC_DEFL] = r0 - dist
        if pressure_out.shape[0] > 1:
            pressure_out[i * nbk + j] = fn
    out_f[0] = fx_sum
    out_f[1] = fy_sum
    out_f[2] = fz_sum
    out_f[3] = m_twist


@nb.njit(cache=True)
def clear_segment(cp, sblk, o1, o2, i, pressure_out):
    """Zero the tangential deflections of segment i's blocks (no contact)."""
    nbk = int(cp[CP_NB])
    for j in range(nbk):
        sblk[o1 + i * nbk + j] = 0.0
        sblk[o2 + i * nbk + j] = 0.0
        if pressure_out.shape[0] > 1:
            pressure_out[i * nbk + j] = 0.0
