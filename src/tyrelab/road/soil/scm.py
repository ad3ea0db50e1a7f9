"""Soil as a terrain of the SCM class: a node grid with plastic sinkage memory (compiled).

After Krenn & Hirzinger's Soil Contact Model (2009) as Project Chrono's SCMTerrain
implements it, with one deliberate difference. Each grid node (spacing ``dx``,
``dy``) keeps its undisturbed height ``h0``, its plastic sinkage ``sp`` (the rut
left behind) and its mobilized shear ``m``. Where a wheel's surface
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

      tau = (c + sigma tan(phi)) m,   dm = (dj - m |dj|) / K,   dj = v_t dt

  ``v_t`` the wheel surface's sliding velocity over the node, tangent to the
  surface, while the node stays in contact; ``m`` the fraction of its strength the
  shear has reached (two components: along the tread's circumferential tangent and
  the axis; :func:`mobilized_shear`). Sliding one way, ``|m| = 1 - exp(-j / K)`` with
  ``j`` the distance slid: Janosi & Hanamoto's curve, and Wong & Reece's (1967)
  ``j(theta)`` for a rigid wheel in steady state. Sliding back, the shear reverses
  after a short way (Dahl 1968), as soil, whose shear displacement is plastic, does.

Each node's stresses act on the wheel surface element above it, whose area is the
node's cell ``dx dy`` divided by the cosine of the surface's slope: the normal
stress along the wheel surface's normal, the shear along its tangent against ``m``
-- as in Wong & Reece's analysis, so the horizontal part of the
normal stress is the compaction resistance in the drawbar pull. (Chrono's SCM
applies the normal stress along the undisturbed terrain normal and the shear
horizontally, which drops that resistance.) A wheel's pass over the nodes:
:mod:`tyrelab.road.soil.wheel`. Bulldozing (soil pushed beside and
ahead of the rut), optional: :mod:`tyrelab.road.soil.bulldozing`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from ..grid import RoadSurface
from .params import Soil

#: the soil bed's node spacing [m]: halving it moves the pull of the XZL's rigid wheel on LETE
#: sand at s = 0.2 by 0.15 % and its sinkage by 1.8 %, and costs four times the time
BED_SPACING = 0.02
#: memory of a soil node: undisturbed height, surface, mobilized shear (two components),
#: stress
BYTES_PER_NODE = 5 * 8


def check_bed_memory(nodes: int, bed: str, remedy: str, field: str) -> None:
    """One InputError on ``field`` when a bed of ``nodes`` nodes (``bed``: what it is, in words)
    needs more than the memory one request may take (:data:`~tyrelab.resources.MAX_MEMORY`)."""
    from ...errors import InputError
    from ...resources import MAX_MEMORY
    if nodes * BYTES_PER_NODE > MAX_MEMORY:
        raise InputError(f"{bed} needs {nodes * BYTES_PER_NODE / 1024 ** 3:.3g} GiB, above the "
                         f"{MAX_MEMORY / 1024 ** 3:g} GiB allowed; {remedy}", field=field)


class SoilSurface(NamedTuple):
    """A soil bed: its parameters and the state of every node (arrays ``(nx, ny)``).

    Node ``(i, k)`` sits at ``(x0 + i dx, y0 + k dy)``. ``h0`` the undisturbed height
    [m] (from which its sinkage counts); ``ground`` the surface as it is now, a rigid-road
    record (:class:`~tyrelab.road.grid.RoadSurface`) whose heights ``ground.z`` are ``h0``
    less each node's plastic sinkage (the rut) and whose bounds are those of ``h0`` (the
    soil only sinks) -- of ``base`` plus :data:`PILE_LIMIT` on a soil that bulldozes; ``shear``
    (``(nx, ny, 2)``) the mobilized shear of the current contact (:func:`mobilized_shear`):
    along the wheel's circumferential tangent ``a x n`` and along its axis ``a``
    (:mod:`tyrelab.road.soil.wheel`); ``sigma`` the last
    normal stress [Pa] (> 0: in contact at the last step); ``zmax`` the highest of those
    bounds [m] (bounds the nodes a wheel can reach); ``base`` the surface as laid [m] (the
    same array as ``h0``, unless the soil bulldozes: soil pushed onto a node raises its
    ``h0`` and its surface alike, as in Chrono's SCM, while ``base`` stays).

    It is also the Python ground a model's ``build`` receives
    (:class:`~tyrelab.road.terrain.Ground`): its record is itself.
    """

    soil: Soil
    x0: float
    y0: float
    dx: float
    dy: float
    h0: np.ndarray
    shear: np.ndarray
    sigma: np.ndarray
    zmax: float
    ground: RoadSurface
    base: np.ndarray

    @property
    def rut(self) -> np.ndarray:
        """Each node's plastic sinkage [m]: how far the surface lies below ``h0``."""
        return self.h0 - self.ground.z

    def fresh_copy(self) -> "SoilSurface":
        """The bed with its own copy of every node's state (a trial that leaves no rut)."""
        h0 = self.h0.copy() if self.soil.bulldozing else self.h0
        return self._replace(h0=h0, shear=self.shear.copy(), sigma=self.sigma.copy(),
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
            return per, block_maxima(self.base + pile_limit(self.soil), per)
        return per, np.zeros((0, self.h0.shape[1] - 1))


#: how deep [m] the soil's surface may sink below its lowest undisturbed node, for the lower
#: bound of its heights (terrain_range): far below any wheel's reach
SINK_BOUND = 10.0


#: on a soil that bulldozes, the highest [m] soil may pile above the surface as laid (the
#: bounds the contact models' searches take); a node is raised no further
PILE_LIMIT = 0.15


def pile_limit(soil: Soil) -> float:
    """How far [m] the soil may rise above the surface as laid: :data:`PILE_LIMIT` on a soil
    that bulldozes, else 0."""
    return PILE_LIMIT if soil.bulldozing else 0.0


def bed_record(soil: Soil, x0: float, y0: float, dx: float, dy: float, base: np.ndarray,
               h0: np.ndarray, z: np.ndarray, shear: np.ndarray, sigma: np.ndarray) -> SoilSurface:
    """The record of a bed over nodes from ``(x0, y0)`` every ``dx``, ``dy`` [m] laid on heights
    ``base``, in the state ``h0``, ``z`` (its surface), ``shear``, ``sigma``; its bounds those
    of ``base`` (plus :func:`pile_limit`)."""
    from ..grid import RoadGrid
    top = base + pile_limit(soil) if soil.bulldozing else base
    ground = RoadGrid(x0, y0, dx, dy, top).surface()
    ground = ground._replace(z=z, zmin=float(base.min()) - SINK_BOUND)
    return SoilSurface(soil, float(x0), float(y0), float(dx), float(dy), h0, shear, sigma,
                       float(top.max()), ground, base)


def soil_bed(soil: Soil, road_grid) -> SoilSurface:
    """A fresh soil bed over a road's grid (its heights the undisturbed surface)."""
    base = np.ascontiguousarray(road_grid.z, dtype=np.float64).copy()
    h0 = base.copy() if soil.bulldozing else base
    return bed_record(soil, road_grid.x0, road_grid.y0, road_grid.dx, road_grid.dy, base, h0,
                      base.copy(), no_shear(base.shape), np.zeros_like(base))


def no_shear(shape: tuple[int, int]) -> np.ndarray:
    """The mobilized shear of ``shape`` fresh nodes: none (both components zero)."""
    return np.zeros(tuple(shape) + (2,))


@nb.njit(cache=True)
def undisturbed_height(bed, x, y):
    """The bed's surface as laid [m] at (x, y): bilinear between its nodes (clamped to the bed)."""
    nx, ny = bed.base.shape
    u = min(max((x - bed.x0) / bed.dx, 0.0), nx - 1.0)
    v = min(max((y - bed.y0) / bed.dy, 0.0), ny - 1.0)
    i = min(int(u), nx - 2)
    k = min(int(v), ny - 2)
    a, b = u - i, v - k
    return ((bed.base[i, k] * (1.0 - b) + bed.base[i, k + 1] * b) * (1.0 - a)
            + (bed.base[i + 1, k] * (1.0 - b) + bed.base[i + 1, k + 1] * b) * a)


@nb.njit(cache=True)
def bekker_modulus(soil, b):
    """Bekker's modulus ``k_c / b + k_phi`` [N/m^(n+2)] of a contact whose smaller dimension is
    ``b`` [m] (Bekker 1969)."""
    return soil.kc / b + soil.kphi


@nb.njit(cache=True)
def node_stress(soil, modulus, s, sp):
    """Normal stress [Pa] of a node pressed to total sinkage ``s`` with plastic sinkage ``sp``
    (``modulus`` the contact's :func:`bekker_modulus`), its plastic sinkage after, and the
    stress's slope with ``s`` [Pa/m] (see the module docstring)."""
    if s <= 0.0:
        return 0.0, sp, 0.0
    elastic = soil.elastic_stiffness * (s - sp)
    if elastic <= 0.0:
        return 0.0, sp, 0.0
    bekker = modulus * s ** soil.n
    if elastic < bekker:
        return elastic, sp, soil.elastic_stiffness
    return bekker, s - bekker / soil.elastic_stiffness, soil.n * bekker / s


@nb.njit(cache=True)
def mobilized_shear(mc, ma, dc, da, k):
    """The mobilized shear ``m`` of a node after the wheel slid ``(dc, da)`` [m] over it
    (along the tread's circumferential tangent and the axis), from ``(mc, ma)``: the fraction
    of the node's strength ``c + sigma tan(phi)`` its shear stress has reached, a vector,
    ``|m| < 1``. ``k`` Janosi's shear deformation modulus ``K`` [m].

    Dahl's (1968) solid-friction law with exponent 1, in the plane::

        dm = (dj - m |dj|) / K

    solved exactly over the step (the sliding's direction ``e = dj / |dj|`` held)::

        m' = e + (m - e) exp(-|dj| / K)

    Sliding one way from rest it is Janosi & Hanamoto's (1961) curve,
    ``|m| = 1 - exp(-j / K)``, to rounding. Where the sliding turns back, the shear falls
    at ``(1 + |m|)`` times the fresh soil's stiffness ``tau_max / K`` and reverses after
    ``K ln(1 + |m|)`` of sliding (at most 0.69 K): soil keeps the shear displacement it was
    given (it is plastic, Wong, Theory of Ground Vehicles, on terrain under repetitive
    shear), so the work of shearing it is spent, not stored to be given back.
    """
    d = math.sqrt(dc * dc + da * da)
    if d == 0.0:
        return mc, ma
    e = math.exp(-d / k)
    ec, ea = dc / d, da / d
    return ec + (mc - ec) * e, ea + (ma - ea) * e

