"""The soil's loads on a wheel: a cylinder, or a cylinder cut flat (compiled).

One pass over the soil bed's nodes under a wheel (:mod:`tyrelab.road.soil.scm` for the
nodes' stresses): each node in contact carries its normal stress along the wheel
surface's normal and its shear along the surface's tangent, on the surface element above
its cell.

The shear follows the sliding (:func:`~tyrelab.road.soil.scm.mobilized_shear`): each step
the sliding velocity's parts along the surface's circumferential tangent ``a x n`` and along
the axis ``a``, times the step, move the node's mobilized shear ``m`` by Dahl's law, and the
shear ``(c + sigma tan phi) m`` acts against it. Sliding one way it is Janosi & Hanamoto's
``1 - exp(-j / K)``; where the sliding reverses (a braked wheel whose rim slides backwards at
entry and forwards below, a towed wheel sunk deep, a wheel whose spin rings) the shear
reverses after ``K ln(1 + |m|)`` of sliding back. Two other readings were tried. Chrono's
SCM accumulates the distance slid, whatever its direction, and turns the shear at once
with the sliding: on dry sand a rigid wheel braked at s = -0.05 pulled -8.7 kN (-1.6 kN
here, and in Wong & Reece's integration with Dahl's reversal), and a towed flexible wheel,
whose flat slides by a hair either way, chattered by +-3.6 kN about its drag. A signed ``j``
read elastically on Janosi's curve (the shear back to zero only where ``j`` is) gives the
soil back all the work of shearing it: a wheel under a constant torque then rang on the
soil's shear without end, its slip swinging by up to +-0.4 on LETE sand and +-1.3 in snow
about a mean off the slip curve's (now +-0.06 at most, the mean on the curve;
``tests/test_soil_rigid_wheel.py``).

The tread moves round the axis as one band at ``omega min(flat, R)``: the rigid wheel's
rim at ``omega R``; a flexible tyre's tread on its arcs as on its flat, at
``omega (R - delta)``, the speed at which its contact point turns on a rigid road (the
analytic models' loaded radius). A rim turning rigidly at ``omega R`` on the arcs would
slide forwards over the soil wherever the flat does not, and the shear would keep that as a
pull at zero slip.

The wheel's surface above a node depends on the node's position along the wheel's
heading and across it. When the wheel's axis lies along the grid's rows (no camber, no
steer: ``a = (0, +-1, 0)``, every rig's wheel rolling straight) everything but the lateral
position is the same for a whole row of nodes, so the surface point, its normal and its
sliding velocity are found once per row (:func:`wheel_loads`); otherwise per node. The
per-row values are the per-node formulas at the row's centre line, where the lateral
offset enters only through terms it multiplies by zero (a wheel yawed by 1e-9 rad, which
takes the per-node path, agrees to rounding: ``tests/test_soil_wheel_pass.py``).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb

from ...core.vec3 import cross, unit, wheel_axes
from .bulldozing import bulldoze
from .scm import bekker_modulus, mobilized_shear, node_stress

#: the wheel surface's slope beyond which a node's cell is not scaled further: cos >= this
MIN_COS = 0.2


class SoilLoads(NamedTuple):
    """Loads of the soil on a wheel, about its centre (road frame) [N], [N m].

    ``area`` the horizontal area in contact [m^2]; ``normal`` the force's component along the wheel's
    in-plane upward direction ``-d`` [N] (what the tyre's vertical law must carry) and
    ``dnormal`` its derivative with the tyre's deflection ``radius - flat`` [N/m] (<= 0:
    the flat rising unloads the soil under it; the flat's nodes only).
    """

    fx: float
    fy: float
    fz: float
    mx: float
    my: float
    mz: float
    area: float
    normal: float
    dnormal: float


class WheelShape(NamedTuple):
    """A wheel's pose and shape for one pass: centre ``c``, unit axis ``a``, centre velocity
    ``v``, spin ``omega`` about ``a``, ``radius``, ``width``, cut flat at ``flat`` from the
    axis along ``d`` (``has_flat``), its in-plane down ``d`` and the flat tread's direction
    of motion ``r = a x d``; ``m = e_z - a_z a`` and ``mm = |m|^2`` (how the offset from the
    axis changes with the height below the centre); ``tread_spin`` the rate [rad/s] at which
    the tread turns round the axis off the flat, ``omega min(flat, R) / R`` (one band at the
    flat's speed; the rigid wheel's rim at ``omega``)."""

    cx: float
    cy: float
    cz: float
    ax: float
    ay: float
    az: float
    vx: float
    vy: float
    vz: float
    omega: float
    radius: float
    width: float
    flat: float
    has_flat: bool
    dx: float
    dy: float
    dz: float
    rx: float
    ry: float
    rz: float
    mx: float
    my: float
    mz: float
    mm: float
    tread_spin: float


class SurfacePoint(NamedTuple):
    """The wheel's lower surface above a node: ``touches`` whether the node lies under the
    cylinder's footprint at all; ``lateral`` its offset along the axis [m]; ``zr`` the
    surface's height below the centre [m]; ``on_flat``; the outward normal ``n`` and the
    surface's velocity there ``u`` [m/s]."""

    touches: bool
    lateral: float
    zr: float
    on_flat: bool
    nx: float
    ny: float
    nz: float
    ux: float
    uy: float
    uz: float


@nb.njit(cache=True)
def surface_point(w, d0x, d0y):
    """The wheel ``w``'s (:class:`WheelShape`) lower surface above the point ``(d0x, d0y)``
    from its centre: the lower root of ``|q|^2 = R^2`` (``q`` the offset from the axis), or the
    flat where it cuts the cylinder there."""
    la = d0x * w.ax + d0y * w.ay
    q0x, q0y, q0z = d0x - la * w.ax, d0y - la * w.ay, -la * w.az
    qm = q0x * w.mx + q0y * w.my + q0z * w.mz
    qq = q0x * q0x + q0y * q0y + q0z * q0z
    disc = qm * qm - w.mm * (qq - w.radius * w.radius)
    if not (disc > 0.0 and w.mm > 0.0):
        return SurfacePoint(False, 0.0, 0.0, False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    zr = (-qm - math.sqrt(disc)) / w.mm                 # the lower surface, below the axis
    on_flat = False
    if w.has_flat:
        zf = (w.flat - d0x * w.dx - d0y * w.dy) / w.dz
        if zf > zr and zf < (-qm + math.sqrt(disc)) / w.mm:
            zr = zf                                     # the flat cuts the cylinder here
            on_flat = True
    if on_flat:
        # the tread on the flat slides with v + omega flat (a x d)
        return SurfacePoint(True, la + zr * w.az, zr, True, w.dx, w.dy, w.dz,
                            w.vx + w.omega * w.flat * w.rx, w.vy + w.omega * w.flat * w.ry,
                            w.vz + w.omega * w.flat * w.rz)
    # the outward normal (from the axis); the tread moves round the axis at the band's speed
    # omega min(flat, R) (a x p is R long): the rigid wheel's rim at omega R, a flexible tyre's
    # tread on its arcs as on its flat, one inextensible band
    nx, ny, nz = unit(q0x + zr * w.mx, q0y + zr * w.my, q0z + zr * w.mz)
    wx, wy, wz = cross(w.ax, w.ay, w.az, d0x, d0y, zr)
    return SurfacePoint(True, la + zr * w.az, zr, False, nx, ny, nz, w.vx + w.tread_spin * wx,
                        w.vy + w.tread_spin * wy, w.vz + w.tread_spin * wz)


@nb.njit(cache=True)
def wheel_loads(bed, cx, cy, cz, ax, ay, az, vx, vy, vz, omega, radius, width, flat, dt, update,
                normal_only=False):
    """Loads of the soil on a wheel over one step ``dt`` [s]: a cylinder (centre ``c``, unit
    axis ``a``, centre velocity ``v``, spin ``omega`` about ``a``; ``radius``, ``width`` [m])
    cut flat at ``flat`` [m] from the axis along its in-plane downward direction ``d`` (a
    flexible tyre's footprint, Wong 2008 sec. 2.4; ``flat >= radius``: the whole cylinder,
    the rigid wheel).

    Every node under the wheel's footprint is visited: the wheel's lower surface above it
    (:func:`surface_point`) gives its total sinkage; the node's stresses act on the surface
    element above it. The wheel's surface moves with it as a rigid body (``v + omega a x p``);
    on the flat, the tread moves along it at ``omega flat``, the speed of the flat's middle
    (the kinematics of the analytic models on a rigid road, whose contact point turns at the
    loaded radius). With ``update`` the nodes' plastic sinkage and shear displacement advance
    (a step of the run; on a soil that bulldozes, the soil pressed down then moves to the
    rut's edge: :mod:`tyrelab.road.soil.bulldozing`); without, the bed is only read (an
    equilibrium search). With
    ``normal_only`` (a trial: only ``normal`` and ``dnormal`` are wanted) the shear on the
    flat, which lies in the flat and so has no part along ``d``, is not computed, and the
    other loads leave it out.
    """
    soil = bed.soil
    nx, ny = bed.h0.shape
    tanphi = math.tan(soil.friction_angle)
    modulus = bekker_modulus(soil, width)
    # the nodes that can touch: within the chord the highest soil cuts from the cylinder along
    # its heading, and its width (plus the tilt of its axis) across
    depth = bed.zmax - (cz - radius)
    if depth <= 0.0:
        return SoilLoads(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    chord = math.sqrt(max(0.0, radius * radius - (radius - min(depth, radius)) ** 2))
    across = 0.5 * width + radius * abs(az)
    reach_x = chord * math.sqrt(max(0.0, 1.0 - ax * ax)) + across * abs(ax) + bed.dx
    reach_y = chord * abs(ax) + across * math.sqrt(max(0.0, 1.0 - ax * ax)) + bed.dy
    i0 = max(0, int(math.floor((cx - reach_x - bed.x0) / bed.dx)))
    i1 = min(nx - 1, int(math.ceil((cx + reach_x - bed.x0) / bed.dx)))
    k0 = max(0, int(math.floor((cy - reach_y - bed.y0) / bed.dy)))
    k1 = min(ny - 1, int(math.ceil((cy + reach_y - bed.y0) / bed.dy)))
    cell = bed.dx * bed.dy
    _, _, _, dx_, dy_, dz_ = wheel_axes(ax, ay, az)
    rx_, ry_, rz_ = cross(ax, ay, az, dx_, dy_, dz_)
    # the flat's plane: (p - c) . d = flat, tilted no further than MIN_COS from level
    mx_, my_, mz_ = -az * ax, -az * ay, 1.0 - az * az
    w = WheelShape(cx, cy, cz, ax, ay, az, vx, vy, vz, omega, radius, width, flat,
                   flat < radius and -dz_ >= MIN_COS, dx_, dy_, dz_, rx_, ry_, rz_,
                   mx_, my_, mz_, mx_ * mx_ + my_ * my_ + mz_ * mz_,
                   omega * min(flat, radius) / radius)
    along_rows = ax == 0.0 and az == 0.0
    fx = fy = fz = mx = my = mz = 0.0
    normal = dnormal = 0.0
    area = 0.0
    bulldozing = update and soil.bulldozing
    pressed = 0.0           # the plastic sinkage the step adds, summed over the nodes [m]
    ci0, ci1, ck0, ck1 = i1 + 1, i0 - 1, k1 + 1, k0 - 1      # the nodes in contact's box
    for i in range(i0, i1 + 1):
        x = bed.x0 + i * bed.dx
        d0x = x - cx
        row = surface_point(w, d0x, 0.0) if along_rows else \
            SurfacePoint(False, 0.0, 0.0, False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        un = tx = ty = tz = vc = va = a_s = 0.0
        if along_rows:
            un, tx, ty, tz, vc, va, a_s = _sliding(row, cell, ax, ay, az)
        # the last node's state and stresses: along the rows a node in the same state as the
        # last one (uniform ground across the wheel, a straight rut) has the same stresses
        seen = False
        h_seen = z_seen = mc_seen = ma_seen = 0.0
        sigma = sp_new = slope = mc = ma = gx = gy = gz = 0.0
        for k in range(k0, k1 + 1):
            d0y = bed.y0 + k * bed.dy - cy
            if along_rows:
                p = row
                lateral = d0y           # the axis is +-e_y: the offset along it is +-d0y
            else:
                p = surface_point(w, d0x, d0y)
                lateral = p.lateral
            surface = bed.ground.z[i, k]
            if not p.touches or abs(lateral) > 0.5 * width or cz + p.zr >= surface:
                if update:
                    bed.shear[i, k, 0] = 0.0                 # a new contact starts afresh
                    bed.shear[i, k, 1] = 0.0
                    bed.sigma[i, k] = 0.0
                seen = False
                continue
            h, m0c, m0a = bed.h0[i, k], bed.shear[i, k, 0], bed.shear[i, k, 1]
            if not (seen and h == h_seen and surface == z_seen and m0c == mc_seen and m0a == ma_seen):
                if not along_rows:
                    un, tx, ty, tz, vc, va, a_s = _sliding(p, cell, ax, ay, az)
                s = h - (cz + p.zr)
                sigma, sp_new, slope = node_stress(soil, modulus, s, h - surface)
                sigma += soil.damping * max(0.0, un) if sigma > 0.0 else 0.0  # compressing: un > 0
                mc, ma = mobilized_shear(m0c, m0a, vc * dt, va * dt, soil.janosi_k)
                strength = (soil.cohesion + sigma * tanphi) \
                    if sigma > 0.0 and not (normal_only and p.on_flat) else 0.0
                gx, gy, gz = -sigma * a_s * p.nx, -sigma * a_s * p.ny, -sigma * a_s * p.nz
                # the shear strength times the mobilized fraction m = mc (a x n) + ma a, against
                # the sliding that mobilized it: the tangents (tx, ty, tz) = a x n and a
                gx -= strength * a_s * (mc * tx + ma * ax)
                gy -= strength * a_s * (mc * ty + ma * ay)
                gz -= strength * a_s * (mc * tz + ma * az)
                seen = along_rows
                h_seen, z_seen, mc_seen, ma_seen = h, surface, m0c, m0a
            fx += gx
            fy += gy
            fz += gz
            normal -= gx * dx_ + gy * dy_ + gz * dz_
            if p.on_flat:
                # the flat rising by d(delta) lifts the node's surface by d(delta) / -d_z
                dnormal += slope * a_s / dz_
            qx, qy, qz = cross(d0x, d0y, p.zr, gx, gy, gz)   # the moment about the centre
            mx += qx
            my += qy
            mz += qz
            if sigma > 0.0:
                area += cell
            if bulldozing and sigma > 0.0:
                pressed += max(0.0, sp_new - (h - surface))
                ci0, ci1, ck0, ck1 = min(ci0, i), max(ci1, i), min(ck0, k), max(ck1, k)
            if update:
                bed.ground.z[i, k] = h - sp_new
                bed.shear[i, k, 0] = mc
                bed.shear[i, k, 1] = ma
                bed.sigma[i, k] = sigma
    if bulldozing and ci1 >= ci0:
        bulldoze(bed, ci0, ci1, ck0, ck1, pressed)
    return SoilLoads(fx, fy, fz, mx, my, mz, area, normal, dnormal)


@nb.njit(cache=True)
def _sliding(p, cell, ax, ay, az):
    """At a surface point (:class:`SurfacePoint`) of a wheel with unit axis ``a``: its velocity
    along the normal ``un`` (> 0 compressing the soil); the surface's circumferential tangent
    ``t = a x n`` (a unit vector: the normal is square to the axis, on the cylinder and on
    the flat); the sliding velocity's parts along ``t`` and along ``a`` [m/s] (the velocity
    less its normal part is ``vc t + va a``); and the area of the surface element above a
    node's ``cell`` [m^2]."""
    un = p.ux * p.nx + p.uy * p.ny + p.uz * p.nz
    tx, ty, tz = cross(ax, ay, az, p.nx, p.ny, p.nz)
    vc = p.ux * tx + p.uy * ty + p.uz * tz
    va = p.ux * ax + p.uy * ay + p.uz * az
    return un, tx, ty, tz, vc, va, cell / max(abs(p.nz), MIN_COS)
