"""The soil bed as a kind of ground of the terrain interface (registered as ``"soil"``).

Its queries are the rigid grid's, asked of the bed's current surface
(``SoilSurface.ground``: the undisturbed heights less the rut, bounded by the
undisturbed ones because the soil only sinks), so every contact model reads the soil
through :mod:`tyrelab.road.terrain` as it reads a road. What makes it soil is
:func:`soil_contact`, the ground's answer to a tyre element pressing on it: the
element (a tread block of the ring) and the soil under it in series.

A block of contact ``area`` A, pressed ``penetration`` p into the current surface with
normal force ``fn`` by its own law, is taken as a spring of its secant stiffness
``k_b = fn / p``; the soil under it sinks by a further ``Delta`` where the block and the
soil carry the same force::

    k_b (p - Delta) = sigma(s0 + Delta) A

``s0`` the node's plastic sinkage and ``sigma`` its normal stress (Bekker's law with
elastic unloading and reloading, :func:`~tyrelab.road.soil.scm.node_stress`, with ``b`` the
block's side sqrt(A)); solved by Newton's method in a bracket. Every node under the
block's square footprint is then pressed to the block's sole. In shear the block and the
soil under it are in series too (:func:`soil_shear`, the kind's ``terrain_shear``): the
soil's Janosi & Hanamoto law, reversing by Dahl's, which the rigid and flexible wheels apply
per node, with the block's own shear stiffness, up to the smaller of the soil's Mohr-Coulomb
strength ``A (c + sigma tan phi)`` (Wong 2008, 2.3) and the block's friction.
"""

from __future__ import annotations

import math
from pathlib import Path

import numba as nb
import numpy as np

from ..grid import (grid_block_max, grid_blocks, grid_line_height, grid_lines, grid_range,
                    grid_row, local_zmax, road_height, road_height_gradient, road_penetration)
from ..terrain_registry import TerrainKind, register_terrain
from .field import lay_soil_field
from .params import Soil
from .scm import BED_SPACING, SoilSurface, bekker_modulus, check_bed_memory, mobilized_shear, node_stress

#: the bed's width [m] across the wheel's track (its centre line y = 0)
BED_WIDTH = 2.0
#: the bed reaches this far [m] behind the start and beyond the end of the run
BED_MARGIN = 1.0

#: the series solve stops when the block and the soil agree to this fraction of the force
SERIES_TOLERANCE = 1e-6
#: at most this many Newton or bisection steps
SERIES_ITERATIONS = 50


@nb.njit(cache=True)
def soil_height(bed, x, y):
    return road_height(bed.ground, x, y)


@nb.njit(cache=True, inline="always")
def soil_height_gradient(bed, x, y):
    return road_height_gradient(bed.ground, x, y)


@nb.njit(cache=True, inline="always")
def soil_penetration(bed, x, y, z):
    return road_penetration(bed.ground, x, y, z)


@nb.njit(cache=True, inline="always")
def soil_zmax(bed, x0, x1):
    return local_zmax(bed.ground, x0, x1)


@nb.njit(cache=True, inline="always")
def soil_range(bed):
    return grid_range(bed.ground)


@nb.njit(cache=True, inline="always")
def soil_lines(bed):
    return grid_lines(bed.ground)


@nb.njit(cache=True, inline="always")
def soil_row(bed, y):
    return grid_row(bed.ground, y)


@nb.njit(cache=True, inline="always")
def soil_line_height(bed, row, weight, k):
    return grid_line_height(bed.ground, row, weight, k)


@nb.njit(cache=True, inline="always")
def soil_blocks(bed):
    return grid_blocks(bed.ground)


@nb.njit(cache=True, inline="always")
def soil_block_max(bed, i):
    return grid_block_max(bed.ground, i)


@nb.njit(cache=True)
def _nearest(bed, x, y):
    """The node nearest to (x, y), clamped to the bed."""
    nx, ny = bed.h0.shape
    i = min(max(int(round((x - bed.x0) / bed.dx)), 0), nx - 1)
    k = min(max(int(round((y - bed.y0) / bed.dy)), 0), ny - 1)
    return i, k


@nb.njit(cache=True)
def soil_contact(bed, x, y, penetration, area, v1, v2, fn, f1, f2, dt):
    """The forces the soil carries from a tyre element (module docstring); the nodes under
    it sink. ``area`` 0 (a point contact) takes one node's cell."""
    if fn <= 0.0 or penetration <= 0.0:
        return 0.0, 0.0, 0.0
    soil = bed.soil
    a = area if area > 0.0 else bed.dx * bed.dy
    side = math.sqrt(a)
    i, k = _nearest(bed, x, y)
    s0 = bed.h0[i, k] - bed.ground.z[i, k]
    kb = fn / penetration
    modulus = bekker_modulus(soil, side)
    lo, hi = 0.0, penetration
    delta = 0.5 * penetration
    for _ in range(SERIES_ITERATIONS):
        sigma, _, slope = node_stress(soil, modulus, s0 + delta, s0)
        g = kb * (penetration - delta) - sigma * a
        if abs(g) <= SERIES_TOLERANCE * fn:
            break
        if g > 0.0:
            lo = delta
        else:
            hi = delta
        nxt = delta + g / (kb + slope * a)
        delta = nxt if lo < nxt < hi else 0.5 * (lo + hi)
    sigma, _, _ = node_stress(soil, modulus, s0 + delta, s0)
    carried = sigma * a
    # the block's sole, Delta below the surface where it presses; the nodes under it follow
    sole = soil_height(bed, x, y) - delta
    nx, ny = bed.h0.shape
    ri = int(math.ceil(0.5 * side / bed.dx))
    rk = int(math.ceil(0.5 * side / bed.dy))
    for ii in range(max(0, i - ri), min(nx - 1, i + ri) + 1):
        if abs(bed.x0 + ii * bed.dx - x) > 0.5 * side + 0.5 * bed.dx:
            continue
        for kk in range(max(0, k - rk), min(ny - 1, k + rk) + 1):
            if abs(bed.y0 + kk * bed.dy - y) > 0.5 * side + 0.5 * bed.dy:
                continue
            if bed.ground.z[ii, kk] > sole:
                s_i = bed.h0[ii, kk] - sole
                sig_i, sp_i, _ = node_stress(soil, modulus, s_i, bed.h0[ii, kk] - bed.ground.z[ii, kk])
                bed.ground.z[ii, kk] = bed.h0[ii, kk] - sp_i
                bed.sigma[ii, kk] = sig_i
    # Mohr-Coulomb: the soil shears off beyond its strength under the carried stress
    strength = a * (soil.cohesion + sigma * math.tan(soil.friction_angle))
    ft = math.sqrt(f1 * f1 + f2 * f2)
    scale = strength / ft if ft > strength else 1.0
    return carried, f1 * scale, f2 * scale


@nb.njit(cache=True)
def soil_shear(bed, x, y, fn, area, m1, m2, d1, d2, element_stiffness, limit):
    """A tread element's shear on the soil (:func:`~tyrelab.road.terrain.terrain_shear`):
    the element and the soil under it in series, one Dahl element.

    The soil shears by Janosi & Hanamoto's law, reversing by Dahl's
    (:func:`~tyrelab.road.soil.scm.mobilized_shear`), as under the wheels; the element
    (a tread block) in series with it by its own shear stiffness ``k`` [Pa/m]. Their
    strength is the smaller of the soil's, ``A (c + sigma tan phi)`` with ``sigma = fn / A``,
    and the element's friction ``limit``; the mobilized shear ``m`` of the two moves by
    Dahl's law with the modulus that gives their series stiffness at the start of
    shearing, ``strength (K / (A tau_max) + 1 / (A k))`` (the soil's ``K / tau_max`` and
    the block's ``1 / k`` per area, added). The force on the element is
    ``-strength m``, against the sliding that mobilized it. Sliding one way with a block
    far stiffer than the soil it is Janosi & Hanamoto's curve over the distance slid.
    """
    soil = bed.soil
    a = area if area > 0.0 else bed.dx * bed.dy
    tau_max = soil.cohesion + fn / a * math.tan(soil.friction_angle)
    strength = min(a * tau_max, limit)
    if not strength > 0.0:
        return True, 0.0, 0.0, 0.0, 0.0
    compliance = soil.janosi_k / (a * tau_max)
    if element_stiffness > 0.0:
        compliance += 1.0 / (a * element_stiffness)
    m1, m2 = mobilized_shear(m1, m2, d1, d2, strength * compliance)
    return True, -strength * m1, -strength * m2, m1, m2


def resolve_soil(value):
    """``(Soil, label)`` when ``value`` names a soil (a :class:`Soil`, a built-in soil's name, a
    ``.toml`` file), else None (:attr:`TerrainKind.resolve`); a malformed soil file is an
    InputError naming its line."""
    from . import load_soil, soil_names
    if isinstance(value, Soil) or (isinstance(value, (str, Path)) and (
            str(value) in soil_names() or str(value).lower().endswith(".toml"))):
        return load_soil(value)
    return None


def lay_soil(soil: Soil, road, x0: float, x1: float, level_at: float | None = None,
             width: float = BED_WIDTH, spacing: float = BED_SPACING, moving: bool = True):
    """The soil from ``x0`` to ``x1`` [m] (plus :data:`BED_MARGIN` each end), ``width`` [m]
    across y = 0, nodes every ``spacing`` [m], over ``road``'s heights (less its height at
    ``(level_at, 0)`` when given): a :class:`~tyrelab.road.soil.patch.SoilPatch` holding at
    most :data:`~tyrelab.road.soil.patch.PATCH_LENGTH` of it at once, the whole of it when not
    ``moving`` (a run that comes back over its rut); refused above the memory allowed
    (:data:`~tyrelab.resources.MAX_MEMORY`). :attr:`TerrainKind.lay` of the soil."""
    from .patch import PATCH_LENGTH, SoilPatch
    x0, x1 = x0 - BED_MARGIN, x1 + BED_MARGIN
    n_run = int(np.ceil((x1 - x0) / spacing)) + 1
    ny = int(np.ceil(width / spacing)) + 1
    rows = min(n_run, int(np.ceil(PATCH_LENGTH / spacing)) + 1) if moving else n_run
    check_bed_memory(rows * ny, f"a soil bed {(rows - 1) * spacing:.6g} m long and {width:g} m "
                                f"wide at {spacing:g} m",
                     "a shorter run or a coarser bed" if not moving else "a coarser bed",
                     "duration" if not moving else "spacing")
    level = float(road.height(level_at, 0.0)) if level_at is not None else 0.0
    return SoilPatch(soil, road, x0, n_run, -0.5 * width, ny, spacing, level, rows)


register_terrain(TerrainKind(
    "soil", SoilSurface, height=soil_height, height_gradient=soil_height_gradient,
    penetration=soil_penetration, zmax=soil_zmax, range=soil_range, lines=soil_lines,
    row=soil_row, line_height=soil_line_height, blocks=soil_blocks, block_max=soil_block_max,
    contact=soil_contact, shear=soil_shear, rigid=False, resolve=resolve_soil, lay=lay_soil,
    lay_around=lay_soil_field,
    hint="a soil, NAME (tyrelab soil list) or FILE.toml",
    description="deformable soil (SCM class): Bekker-Wong pressure-sinkage, Mohr-Coulomb and "
                "Janosi shear, a rut that stays (--terrain NAME|FILE.toml)"))
