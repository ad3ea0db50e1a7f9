"""Soil as a terrain of the SCM class: a node grid with plastic sinkage memory (compiled).

After Krenn & Hirzinger's Soil Contact Model (2009) as Project Chrono's SCMTerrain
implements it, with one deliberate difference. Each grid node (spacing ``dx``,
``dy``) keeps its undisturbed height ``h0``, its plastic sinkage ``sp`` (the rut
left behind) and its accumulated shear displacement ``j``. Where a wheel's surface
lies below a node's current surface the node is in contact, at total sinkage
``s = h0 - w`` (``w`` the wheel surface's height above the node), and carries:

* a normal stress (Bekker 1969; elastic unloading and reloading after Krenn &
  Hirzinger 2009)::

      sigma = min(K_e (s - sp), (k_c / b + k_phi) s^n)

  the first term the elastic reloading line of slope ``K_e``
  (``elastic_stiffness``), the second Bekker's pressure-sinkage law, which bounds
  it: where it is reached the soil yields and ``sp = s - sigma / K_e`` (the node
  stays down by the plastic part when the wheel leaves). ``b`` is the contact's
  smaller dimension, here the wheel's width;
* a shear stress (Mohr-Coulomb strength, Janosi & Hanamoto 1961)::

      tau = (c + sigma tan(phi)) (1 - exp(-j / K)),   j = integral of |v_t| dt

  ``v_t`` the wheel surface's sliding velocity over the node, tangent to the
  surface, accumulated while the node stays in contact (Wong & Reece 1967's
  ``j(theta)`` for a rigid wheel in steady state).

Each node's stresses act on the wheel surface element above it, whose area is the
node's cell ``dx dy`` divided by the cosine of the surface's slope: the normal
stress along the wheel surface's normal, the shear along its tangent against the
sliding velocity -- as in Wong & Reece's analysis, so the horizontal part of the
normal stress is the compaction resistance in the drawbar pull. (Chrono's SCM
applies the normal stress along the undisturbed terrain normal and the shear
horizontally, which drops that resistance.) Bulldozing (soil pushed beside and
ahead of the rut) is not modelled.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from ...core.vec3 import cross, unit, wheel_axes
from ..grid import RoadSurface
from .params import Soil

#: the wheel surface's slope beyond which a node's cell is not scaled further: cos >= this
MIN_COS = 0.2


class SoilSurface(NamedTuple):
    """A soil bed: its parameters and the state of every node (arrays ``(nx, ny)``).

    Node ``(i, j)`` sits at ``(x0 + i dx, y0 + j dy)``. ``h0`` the undisturbed height
    [m]; ``ground`` the surface as it is now, a rigid-road record
    (:class:`~tyrelab.road.grid.RoadSurface`) whose heights ``ground.z`` are ``h0`` less
    each node's plastic sinkage (the rut) and whose bounds are those of ``h0`` (the soil
    only sinks); ``j`` the shear displacement [m] accumulated in the current contact,
    ``sigma`` the last normal stress [Pa] (for plots of the patch); ``zmax`` the highest
    undisturbed height [m] (bounds the nodes a wheel can reach).

    It is also the Python ground a model's ``build`` receives
    (:class:`~tyrelab.road.terrain.Ground`): its record is itself.
    """

    soil: Soil
    x0: float
    y0: float
    dx: float
    dy: float
    h0: np.ndarray
    j: np.ndarray
    sigma: np.ndarray
    zmax: float
    ground: RoadSurface

    @property
    def rut(self) -> np.ndarray:
        """Each node's plastic sinkage [m]: how far the surface lies below ``h0``."""
        return self.h0 - self.ground.z

    def fresh_copy(self) -> "SoilSurface":
        """The bed with its own copy of every node's state (a trial that leaves no rut)."""
        return self._replace(j=self.j.copy(), sigma=self.sigma.copy(),
                             ground=self.ground._replace(z=self.ground.z.copy()))

    # the Python side of the terrain interface (tyrelab.road.terrain.Ground)
    def surface(self) -> "SoilSurface":
        return self

    def sampling_step(self) -> float:
        return min(self.dx, self.dy)

    def uniform_across(self) -> bool:
        return False        # a wheel's rut makes it vary across

    def profile_breaks(self):
        return None

    def row_maxima(self, length: float):
        """Bounds from the undisturbed heights, valid for the whole run (the soil only sinks)."""
        from ..terrain_registry import block_maxima
        per = max(1, int(round(length / self.dx)))
        if self.h0.shape[0] > 2:
            return per, block_maxima(self.h0, per)
        return per, np.zeros((0, self.h0.shape[1] - 1))


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


#: how deep [m] the soil's surface may sink below its lowest undisturbed node, for the lower
#: bound of its heights (terrain_range): far below any wheel's reach
SINK_BOUND = 10.0


def soil_bed(soil: Soil, road_grid) -> SoilSurface:
    """A fresh soil bed over a road's grid (its heights the undisturbed surface)."""
    from ..grid import RoadGrid
    h0 = np.ascontiguousarray(road_grid.z, dtype=np.float64).copy()
    ground = RoadGrid(road_grid.x0, road_grid.y0, road_grid.dx, road_grid.dy, h0.copy()).surface()
    ground = ground._replace(zmin=float(h0.min()) - SINK_BOUND)
    zeros = np.zeros_like(h0)
    return SoilSurface(soil, float(road_grid.x0), float(road_grid.y0), float(road_grid.dx),
                       float(road_grid.dy), h0, zeros, zeros.copy(), float(h0.max()), ground)


@nb.njit(cache=True)
def undisturbed_height(bed, x, y):
    """The bed's undisturbed surface [m] at (x, y): bilinear between its nodes (clamped to the bed)."""
    nx, ny = bed.h0.shape
    u = min(max((x - bed.x0) / bed.dx, 0.0), nx - 1.0)
    v = min(max((y - bed.y0) / bed.dy, 0.0), ny - 1.0)
    i = min(int(u), nx - 2)
    k = min(int(v), ny - 2)
    a, b = u - i, v - k
    return ((bed.h0[i, k] * (1.0 - b) + bed.h0[i, k + 1] * b) * (1.0 - a)
            + (bed.h0[i + 1, k] * (1.0 - b) + bed.h0[i + 1, k + 1] * b) * a)


@nb.njit(cache=True)
def node_stress(soil, s, sp, width):
    """Normal stress [Pa] of a node pressed to total sinkage ``s`` with plastic sinkage ``sp``,
    its plastic sinkage after, and the stress's slope with ``s`` [Pa/m] (see the module
    docstring)."""
    if s <= 0.0:
        return 0.0, sp, 0.0
    elastic = soil.elastic_stiffness * (s - sp)
    if elastic <= 0.0:
        return 0.0, sp, 0.0
    k = soil.kc / width + soil.kphi
    bekker = k * s ** soil.n
    if elastic < bekker:
        return elastic, sp, soil.elastic_stiffness
    return bekker, s - bekker / soil.elastic_stiffness, soil.n * bekker / s


@nb.njit(cache=True)
def wheel_loads(bed, cx, cy, cz, ax, ay, az, vx, vy, vz, omega, radius, width, flat, dt, update):
    """Loads of the soil on a wheel over one step ``dt`` [s]: a cylinder (centre ``c``, unit
    axis ``a``, centre velocity ``v``, spin ``omega`` about ``a``; ``radius``, ``width`` [m])
    cut flat at ``flat`` [m] from the axis along its in-plane downward direction ``d`` (a
    flexible tyre's footprint, Wong 2008 sec. 2.4; ``flat >= radius``: the whole cylinder,
    the rigid wheel).

    Every node under the wheel's footprint is visited: the wheel's lower surface above it
    (the flat, or the lower root of ``|q|^2 = R^2``, ``q`` the node's offset from the axis)
    gives its total sinkage; the node's stresses act on the surface element above it. The
    wheel's surface moves with it as a rigid body (``v + omega a x p``); on the flat, the
    tread moves along it at ``omega flat``, the speed of the flat's middle (the kinematics of
    the analytic models on a rigid road, whose contact point turns at the loaded radius). With
    ``update`` the nodes' plastic sinkage and shear displacement advance (a step of the run);
    without, the bed is only read (an equilibrium search).
    """
    soil = bed.soil
    nx, ny = bed.h0.shape
    tanphi = math.tan(soil.friction_angle)
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
    # m = e_z - a_z a: how the offset from the axis changes with the height below the centre
    mx_, my_, mzz = -az * ax, -az * ay, 1.0 - az * az
    mm = mx_ * mx_ + my_ * my_ + mzz * mzz
    # the flat's plane: (p - c) . d = flat, tilted no further than MIN_COS from level
    _, _, _, dx_, dy_, dz_ = wheel_axes(ax, ay, az)
    has_flat = flat < radius and -dz_ >= MIN_COS
    # the tread on the flat slides with v + omega flat (a x d)
    rx_, ry_, rz_ = cross(ax, ay, az, dx_, dy_, dz_)
    fx = fy = fz = mx = my = mz = 0.0
    normal = dnormal = 0.0
    area = 0.0
    for i in range(i0, i1 + 1):
        x = bed.x0 + i * bed.dx
        for k in range(k0, k1 + 1):
            y = bed.y0 + k * bed.dy
            # offset from the axis in the horizontal plane through the centre
            d0x, d0y = x - cx, y - cy
            la = d0x * ax + d0y * ay
            q0x, q0y, q0z = d0x - la * ax, d0y - la * ay, -la * az
            qm = q0x * mx_ + q0y * my_ + q0z * mzz
            qq = q0x * q0x + q0y * q0y + q0z * q0z
            disc = qm * qm - mm * (qq - radius * radius)
            inside = False
            on_flat = False
            zr = 0.0
            if disc > 0.0 and mm > 0.0:
                zr = (-qm - math.sqrt(disc)) / mm          # the lower surface, below the axis
                if has_flat:
                    zf = (flat - d0x * dx_ - d0y * dy_) / dz_
                    if zf > zr and zf < (-qm + math.sqrt(disc)) / mm:
                        zr = zf                            # the flat cuts the cylinder here
                        on_flat = True
                lateral = la + zr * az
                inside = abs(lateral) <= 0.5 * width
            surface = bed.ground.z[i, k]
            if not inside or cz + zr >= surface:
                if update:
                    bed.j[i, k] = 0.0                        # a new contact starts afresh
                    bed.sigma[i, k] = 0.0
                continue
            w = cz + zr
            s = bed.h0[i, k] - w
            sigma, sp_new, slope = node_stress(soil, s, bed.h0[i, k] - surface, width)
            px, py, pz = d0x, d0y, zr                        # the surface point, from the centre
            if on_flat:
                nxw, nyw, nzw = dx_, dy_, dz_
                ux = vx + omega * flat * rx_
                uy = vy + omega * flat * ry_
                uz = vz + omega * flat * rz_
            else:
                # the outward normal (from the axis); the velocity v + omega a x p
                nxw, nyw, nzw = unit(q0x + zr * mx_, q0y + zr * my_, q0z + zr * mzz)
                wx, wy, wz = cross(ax, ay, az, px, py, pz)
                ux, uy, uz = vx + omega * wx, vy + omega * wy, vz + omega * wz
            un = ux * nxw + uy * nyw + uz * nzw
            tx, ty, tz = ux - un * nxw, uy - un * nyw, uz - un * nzw
            speed = math.sqrt(tx * tx + ty * ty + tz * tz)
            sigma += soil.damping * max(0.0, un) if sigma > 0.0 else 0.0  # compressing: un > 0
            jn = bed.j[i, k] + speed * dt
            tau = (soil.cohesion + sigma * tanphi) * (1.0 - math.exp(-jn / soil.janosi_k)) \
                if sigma > 0.0 else 0.0
            a_s = cell / max(abs(nzw), MIN_COS)              # the surface element above the cell
            gx, gy, gz = -sigma * a_s * nxw, -sigma * a_s * nyw, -sigma * a_s * nzw
            if speed > 0.0:
                gx -= tau * a_s * tx / speed
                gy -= tau * a_s * ty / speed
                gz -= tau * a_s * tz / speed
            fx += gx
            fy += gy
            fz += gz
            normal -= gx * dx_ + gy * dy_ + gz * dz_
            if on_flat:
                # the flat rising by d(delta) lifts the node's surface by d(delta) / -d_z
                dnormal += slope * a_s / dz_
            qx, qy, qz = cross(px, py, pz, gx, gy, gz)       # the moment about the centre
            mx += qx
            my += qy
            mz += qz
            if sigma > 0.0:
                area += cell
            if update:
                bed.ground.z[i, k] = bed.h0[i, k] - sp_new
                bed.j[i, k] = jn
                bed.sigma[i, k] = sigma
    return SoilLoads(fx, fy, fz, mx, my, mz, area, normal, dnormal)
