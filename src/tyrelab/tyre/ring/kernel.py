"""Compiled time step of the flexible ring tyre: belt dynamics and hub loads.

``ring_wheel_force(model, cp, ts, gp, z, zinfo, c, a, v, omega, dt, out)``
advances the belt state ``ts`` (relative to the rim, see
:mod:`tyrelab.tyre.ring.layout`) by ``dt`` while the rim centre moves with
velocity ``v`` and spins at ``omega`` about ``a``, and writes the loads on
the rim into ``out`` (layout of :mod:`tyrelab.tyre.kernel`).

Equations of motion of segment i in the rim-fixed axes that spin with the
rim (rotating frame, angular velocity ``Omega = omega a``)::

    m p'' = F_belt + F_tread - m a_rim - m Omega x (Omega x p)
            - 2 m Omega x p' - m Omega' x p
    m y'' = F_y - m a_rim . a,        J beta'' = M_beta

``a_rim`` and ``Omega'`` are estimated from the change of the rim's velocity
and spin between calls. The belt's weight is not applied: the rigs carry the
whole wheel's weight.

Integrator: symplectic (semi-implicit) Euler with a fixed internal step
``h = dt / ceil(dt / h_max)``, ``h_max`` from the stiffest element (see
:func:`tyrelab.tyre.ring.parameters.stable_step`); the Coriolis term is
applied as an exact rotation of the in-plane velocity by ``2 omega h``
between two half kicks (the Boris scheme), so it adds no energy drift. The hub loads written out are the
averages over the internal steps of the foundation forces on the rim
(``-sum F_foundation``) and their moment about the wheel centre.
"""

from __future__ import annotations

import math

import numba as nb

from ...road.grid import grid_height
from .belt import bending_forces, foundation_forces, membrane_forces, out_of_plane_forces
from .layout import (CP_J, CP_M, CP_N, CP_NB, CP_OFF_COS, CP_OFF_SIN, CP_R0, CP_RELAX,
                     CP_DTMAX, N_SCRATCH, N_SEG_ARRAYS, S_B, S_P1, S_P2, S_V1, S_V2, S_VB,
                     S_VY, S_Y, TS_HEADER, TS_INIT, TS_OMEGA, TS_PSI, TS_TIME, TS_VX, TS_VY,
                     TS_VZ)
from .tread import (ACC_DEFL, ACC_FX, ACC_FY, ACC_FZ, ACC_NX, ACC_NY, ACC_NZ, ACC_PX, ACC_PY,
                    ACC_PZ, ACC_SIZE, ACC_W, clear_segment, segment_can_touch, segment_contact)


@nb.njit(cache=True)
def ring_substep(cp, ts, gp, z, zinfo, cx, cy, cz, ax, ay, az, vx, vy, vz, omega, arx, ary,
                 arz, domega, h, rim, acc, pressure_out):
    """One internal step of length h; adds the rim loads (world) into ``rim[0:6]``."""
    n = int(cp[CP_N])
    nbk = int(cp[CP_NB])
    o = TS_HEADER
    m = cp[CP_M]
    jt = cp[CP_J]
    so = TS_HEADER + N_SEG_ARRAYS * n
    o1 = so
    o2 = so + n * nbk
    fo = so + 2 * n * nbk
    f1 = ts[fo:fo + n]
    f2 = ts[fo + n:fo + 2 * n]
    fy = ts[fo + 2 * n:fo + 3 * n]
    fb = ts[fo + 3 * n:fo + 4 * n]
    blk = ts[fo + N_SCRATCH * n + ACC_SIZE:fo + N_SCRATCH * n + ACC_SIZE + 4]
    # rotating axes: E1 = cos(psi) f - sin(psi) up, E2 = sin(psi) f + cos(psi) up,
    # f = a x e_z (forward), up = f x a; a x E1 = -E2, a x E2 = E1
    fl = math.sqrt(ay * ay + ax * ax)
    fwx = ay / fl
    fwy = -ax / fl
    fwz = 0.0
    upx = fwy * az - fwz * ay
    upy = fwz * ax - fwx * az
    upz = fwx * ay - fwy * ax
    psi = ts[TS_PSI]
    cps = math.cos(psi)
    sps = math.sin(psi)
    e1x = cps * fwx - sps * upx
    e1y = cps * fwy - sps * upy
    e1z = cps * fwz - sps * upz
    e2x = sps * fwx + cps * upx
    e2y = sps * fwy + cps * upy
    e2z = sps * fwz + cps * upz
    # foundation: its reaction is the load on the rim
    foundation_forces(cp, ts, f1, f2, fy, fb)
    oc = int(cp[CP_OFF_COS])
    os_ = int(cp[CP_OFF_SIN])
    r1 = 0.0
    r2 = 0.0
    ry = 0.0
    ma = 0.0
    m1 = 0.0
    m2 = 0.0
    for i in range(n):
        p1 = ts[o + S_P1 * n + i]
        p2 = ts[o + S_P2 * n + i]
        g1 = -f1[i]
        g2 = -f2[i]
        gy = -fy[i]
        r1 += g1
        r2 += g2
        ry += gy
        # moment about the centre of the rim force acting at the segment
        # (E1 x E2 = -a, E1 x a = E2, E2 x a = -E1) and the torsion spring
        ma -= p1 * g2 - p2 * g1
        m1 -= gy * p2
        m2 += gy * p1
        m1 += fb[i] * cp[os_ + i]
        m2 -= fb[i] * cp[oc + i]
    rim[0] += r1 * e1x + r2 * e2x + ry * ax
    rim[1] += r1 * e1y + r2 * e2y + ry * ay
    rim[2] += r1 * e1z + r2 * e2z + ry * az
    rim[3] += m1 * e1x + m2 * e2x + ma * ax
    rim[4] += m1 * e1y + m2 * e2y + ma * ay
    rim[5] += m1 * e1z + m2 * e2z + ma * az
    membrane_forces(cp, ts, f1, f2)
    bending_forces(cp, ts, f1, f2)
    out_of_plane_forces(cp, ts, fy, fb)
    # inertial (rotating-frame) forces: centrifugal, rim acceleration, spin acceleration
    a1 = arx * e1x + ary * e1y + arz * e1z
    a2 = arx * e2x + ary * e2y + arz * e2z
    aa = arx * ax + ary * ay + arz * az
    w2 = omega * omega
    for i in range(n):
        p1 = ts[o + S_P1 * n + i]
        p2 = ts[o + S_P2 * n + i]
        f1[i] += m * (w2 * p1 - a1 - domega * p2)
        f2[i] += m * (w2 * p2 - a2 + domega * p1)
        fy[i] -= m * aa
    # tread contact
    acc[ACC_DEFL] = -1.0
    for i in range(n):
        p1 = ts[o + S_P1 * n + i]
        p2 = ts[o + S_P2 * n + i]
        yi = ts[o + S_Y * n + i]
        beta = ts[o + S_B * n + i]
        px = cx + p1 * e1x + p2 * e2x + yi * ax
        py = cy + p1 * e1y + p2 * e2y + yi * ay
        pz = cz + p1 * e1z + p2 * e2z + yi * az
        if not segment_can_touch(cp, zinfo, px, py, pz, az, beta):
            clear_segment(cp, ts, o1, o2, i, pressure_out)
            continue
        hh = i - 1 if i > 0 else n - 1
        j = i + 1 if i + 1 < n else 0
        d1 = ts[o + S_P1 * n + j] - ts[o + S_P1 * n + hh]
        d2 = ts[o + S_P2 * n + j] - ts[o + S_P2 * n + hh]
        dl = math.sqrt(d1 * d1 + d2 * d2)
        n1 = d2 / dl
        n2 = -d1 / dl
        nx = n1 * e1x + n2 * e2x
        ny = n1 * e1y + n2 * e2y
        nz = n1 * e1z + n2 * e2z
        tx = -n2 * e1x + n1 * e2x
        ty = -n2 * e1y + n1 * e2y
        tz = -n2 * e1z + n1 * e2z
        v1 = ts[o + S_V1 * n + i]
        v2 = ts[o + S_V2 * n + i]
        vyy = ts[o + S_VY * n + i]
        vb = ts[o + S_VB * n + i]
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
        segment_contact(cp, gp, z, zinfo, i, px, py, pz, nx, ny, nz, tx, ty, tz, ax, ay, az, beta,
                        ubx, uby, ubz, ux, uy, uz, -vb * nx, -vb * ny, -vb * nz,
                        fwx, fwy, fwz, cx, cy, cz, ts, o1, o2, h, acc, blk, pressure_out)
        f1[i] += blk[0] * e1x + blk[1] * e1y + blk[2] * e1z
        f2[i] += blk[0] * e2x + blk[1] * e2y + blk[2] * e2z
        fy[i] += blk[0] * ax + blk[1] * ay + blk[2] * az
        fb[i] += blk[3]
    # symplectic Euler; Coriolis as an exact rotation of the in-plane velocity
    relax = 1.0 / (1.0 + h * cp[CP_RELAX])
    cr = math.cos(2.0 * omega * h)
    sr = math.sin(2.0 * omega * h)
    hm = h / m
    hj = h / jt
    for i in range(n):
        # Boris splitting: half kick, rotation, half kick (no energy drift)
        v1 = ts[o + S_V1 * n + i] + 0.5 * hm * f1[i]
        v2 = ts[o + S_V2 * n + i] + 0.5 * hm * f2[i]
        w1 = (cr * v1 - sr * v2 + 0.5 * hm * f1[i]) * relax
        w2_ = (sr * v1 + cr * v2 + 0.5 * hm * f2[i]) * relax
        ts[o + S_V1 * n + i] = w1
        ts[o + S_V2 * n + i] = w2_
        ts[o + S_P1 * n + i] += h * w1
        ts[o + S_P2 * n + i] += h * w2_
        vyy = (ts[o + S_VY * n + i] + hm * fy[i]) * relax
        ts[o + S_VY * n + i] = vyy
        ts[o + S_Y * n + i] += h * vyy
        vb = (ts[o + S_VB * n + i] + hj * fb[i]) * relax
        ts[o + S_VB * n + i] = vb
        ts[o + S_B * n + i] += h * vb
    ts[TS_PSI] = psi + omega * h


@nb.njit(cache=True)
def ring_advance(cp, ts, gp, z, zinfo, cx, cy, cz, ax, ay, az, vx, vy, vz, omega, dt, rim, acc,
                 pressure_out):
    """Advance ``ts`` by ``dt`` in internal steps; returns their number.

    ``rim[0:6]`` receives the mean rim force and moment, ``acc`` the summed
    contact-patch quantities (see :mod:`.tread`).
    """
    n_sub = int(math.ceil(dt / cp[CP_DTMAX] - 1e-9))
    if n_sub < 1:
        n_sub = 1
    h = dt / n_sub
    if ts[TS_INIT] > 0.0 and dt > 0.0:
        arx = (vx - ts[TS_VX]) / dt
        ary = (vy - ts[TS_VY]) / dt
        arz = (vz - ts[TS_VZ]) / dt
        dom = (omega - ts[TS_OMEGA]) / dt
    else:
        arx = 0.0
        ary = 0.0
        arz = 0.0
        dom = 0.0
    for k in range(6):
        rim[k] = 0.0
    for k in range(acc.shape[0]):
        acc[k] = 0.0
    defl = -1.0
    for k in range(n_sub):
        t = k * h
        ring_substep(cp, ts, gp, z, zinfo, cx + vx * t, cy + vy * t, cz + vz * t, ax, ay, az,
                     vx, vy, vz, omega, arx, ary, arz, dom, h, rim, acc, pressure_out)
        defl = acc[ACC_DEFL]
    for k in range(6):
        rim[k] /= n_sub
    acc[ACC_DEFL] = defl
    ts[TS_INIT] = 1.0
    ts[TS_VX] = vx
    ts[TS_VY] = vy
    ts[TS_VZ] = vz
    ts[TS_OMEGA] = omega
    ts[TS_TIME] += dt
    return n_sub


@nb.njit(cache=True)
def ring_wheel_force(model, cp, ts, gp, z, zinfo, cx, cy, cz, ax, ay, az,
                     vx, vy, vz, omega, dt, out):
    """Advance the ring by ``dt`` and write the loads on the rim into ``out``.

    ``model`` 3 (evenly spaced blocks) or 4 (tread pattern): the block layout
    is in ``cp``, so both run the same code. Forces are the means over the
    internal steps.
    """
    n = int(cp[CP_N])
    nbk = int(cp[CP_NB])
    fo = TS_HEADER + N_SEG_ARRAYS * n + 2 * n * nbk + N_SCRATCH * n
    acc = ts[fo:fo + ACC_SIZE]
    rim = out[11:17]  # out as scratch, rearranged below
    tmp = ts[fo + ACC_SIZE:fo + ACC_SIZE + 4]
    n_sub = ring_advance(cp, ts, gp, z, zinfo, cx, cy, cz, ax, ay, az, vx, vy, vz, omega, dt,
                         rim, acc, tmp[:1])
    fx, fy, fz = rim[0], rim[1], rim[2]
    mx, my, mz = rim[3], rim[4], rim[5]
    for k in range(out.shape[0]):
        out[k] = 0.0
    out[0] = fx
    out[1] = fy
    out[2] = fz
    out[14] = mx
    out[15] = my
    out[16] = mz
    w = acc[ACC_W]
    r0 = cp[CP_R0]
    if w > 0.0:
        out[3] = acc[ACC_PX] / w
        out[4] = acc[ACC_PY] / w
        out[5] = acc[ACC_PZ] / w
        nl = math.sqrt(acc[ACC_NX] ** 2 + acc[ACC_NY] ** 2 + acc[ACC_NZ] ** 2)
        nx = acc[ACC_NX] / nl
        ny = acc[ACC_NY] / nl
        nz = acc[ACC_NZ] / nl
        rho = acc[ACC_DEFL]
        if rho <= 0.0:
            rho = 1e-9
    else:
        g = grid_height(gp, z, cx, cy)
        out[3] = cx
        out[4] = cy
        out[5] = g
        nx = 0.0
        ny = 0.0
        nz = 1.0
        rho = r0 - (cz - g)
        if rho > -1e-9:
            rho = -1e-9
    out[6] = nx
    out[7] = ny
    out[8] = nz
    out[9] = rho
    out[10] = -(vx * nx + vy * ny + vz * nz)
    # contact-patch resultant in the W-axis: z along the normal, x = a x n
    cfx = acc[ACC_FX] / n_sub
    cfy = acc[ACC_FY] / n_sub
    cfz = acc[ACC_FZ] / n_sub
    wx1 = ay * nz - az * ny
    wx2 = az * nx - ax * nz
    wx3 = ax * ny - ay * nx
    wl = math.sqrt(wx1 * wx1 + wx2 * wx2 + wx3 * wx3)
    if wl > 0.0:
        wx1 /= wl
        wx2 /= wl
        wx3 /= wl
    wy1 = ny * wx3 - nz * wx2
    wy2 = nz * wx1 - nx * wx3
    wy3 = nx * wx2 - ny * wx1
    out[11] = cfx * wx1 + cfy * wx2 + cfz * wx3
    out[12] = cfx * wy1 + cfy * wy2 + cfz * wy3
    fzw = cfx * nx + cfy * ny + cfz * nz
    out[13] = fzw if fzw > 0.0 else 0.0
    for k in range(17):
        if not math.isfinite(out[k]):
            out[k] = 0.0
