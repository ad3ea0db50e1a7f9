"""A demonstration tyrelab plugin: a contact model, a rig, a road file format and a terrain.

* ``preloaded-point``: the one-point contact whose tyre is compressed by ``preload``
  [m] (option, default 10 mm) before it touches the road -- it carries a load at a
  deflection ``preload`` smaller than the point model's, so its axle rides that
  much higher.
* ``raised-rolling``: the rolling rig with the axle :data:`RAISE` above the height
  at which the model carries the load.
* ``.xz``: a longitudinal road profile, one ``x z`` pair [m] per line, the same
  across the road.
* ``slick``: the rigid road with its friction scaled (``--terrain slick:0.5``): every
  query is the road grid's, :func:`~tyrelab.road.terrain.terrain_friction` the scale.
"""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numba as nb
import numpy as np
from tyrelab.registry import (ContactModel, Rig, RoadFormat, register_contact, register_rig,
                              register_road_format)
from tyrelab.road import grid as G
from tyrelab.road.terrain import TerrainKind, register_terrain
from tyrelab.tyre.contact.point import PointParams, point_contact, point_params
from tyrelab.tyre.wheel import ContactGeometry

#: how far the raised rolling rig lifts the axle above its equilibrium height [m]
RAISE = 0.005


class PreloadedPoint(NamedTuple):
    """The point model's record and the preload [m]."""

    unloaded_radius: float
    step: float
    preload: float


def build(tyre, grid, preload=0.01):
    base = point_params(tyre, grid)
    return PreloadedPoint(base.unloaded_radius, base.step, float(preload))


@nb.njit
def geometry(params, road, pose):
    """The point model's contact, the tyre ``preload`` deeper in."""
    g = point_contact(PointParams(params.unloaded_radius, params.step), road, pose)
    return ContactGeometry(g.deflection + params.preload, g.px, g.py, g.pz, g.nx, g.ny, g.nz,
                           g.curvature)


def equilibrium(tyre, load, speed, params, preload=0.01):
    """It carries ``load`` at the vertical law's deflection less the preload."""
    deflection = tyre.static_deflection(load) - params.preload
    return deflection, speed / (tyre.unloaded_radius - deflection), np.zeros(0)


class Slick(NamedTuple):
    """The road grid's record and the friction scale."""

    road: G.RoadSurface
    friction: float


@nb.njit
def _height(t, x, y):
    return G.road_height(t.road, x, y)


@nb.njit
def _gradient(t, x, y):
    return G.road_height_gradient(t.road, x, y)


@nb.njit
def _penetration(t, x, y, z):
    return G.road_penetration(t.road, x, y, z)


@nb.njit
def _zmax(t, x0, x1):
    return G.local_zmax(t.road, x0, x1)


@nb.njit
def _range(t):
    return G.grid_range(t.road)


@nb.njit
def _lines(t):
    return G.grid_lines(t.road)


@nb.njit
def _row(t, y):
    return G.grid_row(t.road, y)


@nb.njit
def _line_height(t, row, weight, k):
    return G.grid_line_height(t.road, row, weight, k)


@nb.njit
def _blocks(t):
    return G.grid_blocks(t.road)


@nb.njit
def _block_max(t, i):
    return G.grid_block_max(t.road, i)


@nb.njit
def _friction(t, x, y):
    return t.friction


class SlickGround:
    """The Python ground (tyrelab.road.terrain.Ground): the road grid's answers."""

    def __init__(self, grid, friction):
        self.grid, self.record = grid, Slick(grid.surface(), float(friction))

    def surface(self):
        return self.record

    def __getattr__(self, name):       # sampling_step, uniform_across, profile_breaks, row_maxima
        return getattr(self.grid, name)


def _resolve(value):
    """``slick:MU``: the friction scale MU >= 0 (None for anything else)."""
    from tyrelab.errors import InputError
    if not (isinstance(value, str) and value.startswith("slick:")):
        return None
    try:
        mu = float(value[len("slick:"):])
    except ValueError:
        mu = -1.0
    if not (np.isfinite(mu) and mu >= 0.0):
        raise InputError(f"slick: expected a friction scale >= 0 after 'slick:', got {value!r}",
                         field="terrain")
    return mu, f"slick road, friction x {mu:g}"


def _lay(mu, road, x0, x1, level_at=None, **options):
    from tyrelab.rig.simulation import levelled_grid
    return SlickGround(levelled_grid(road, level_at) if level_at is not None else road.grid(), mu)


def register() -> None:
    register_contact(ContactModel("preloaded-point", PreloadedPoint, build, geometry=geometry,
                                  equilibrium=equilibrium, options={"preload": float}, cost=0.002,
                                  summary="point contact, the tyre preloaded by 'preload' [m] (demo plugin)"))
    register_rig(Rig("raised-rolling", _raised_rolling, "the rolling rig, the axle 5 mm up (demo plugin)",
                     channels="tyrelab.rig.rolling:CHANNELS"))
    register_road_format(RoadFormat(".xz", "x-z profile", _read_xz,
                                    summary="longitudinal profile, 'x z' per line [m] (demo plugin)"))
    register_terrain(TerrainKind(
        "slick", Slick, height=_height, height_gradient=_gradient, penetration=_penetration,
        zmax=_zmax, range=_range, lines=_lines, row=_row, line_height=_line_height,
        blocks=_blocks, block_max=_block_max, friction=_friction, resolve=_resolve, lay=_lay,
        hint="slick:MU", description="the rigid road, its friction scaled by MU (demo plugin)"))


def _raised_rolling(request):
    from tyrelab.rig.rolling import roll
    model = request.model
    eq = model.equilibrium(request.wheel_load, request.speed)
    height = model.tyre.unloaded_radius - eq.deflection + RAISE
    return roll(model, request.road, request.speed, height=height, load=request.load,
                duration=request.duration, dt=request.dt, output_rate=request.output_rate,
                progress=request.progress)


def _read_xz(path, offset, force):
    from tyrelab.errors import InputError
    from tyrelab.road.base import Road

    xs, zs = [], []
    for n, line in enumerate(Path(path).read_text().splitlines(), start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        try:
            x, z = (float(v) for v in line.split())
        except ValueError:
            raise InputError("expected two numbers 'x z' in metres", source=str(path), line=n) from None
        if xs and x <= xs[-1]:
            raise InputError("x must increase from line to line", source=str(path), line=n)
        xs.append(x)
        zs.append(z)
    if len(xs) < 2:
        raise InputError("expected at least two 'x z' lines", source=str(path))
    xs, zs = np.array(xs), np.array(zs)

    class Profile(Road):
        name = f"profile {Path(path).name}"
        default_spacing = (0.01, 4.0)

        def height(self, x, y):
            return np.interp(np.asarray(x, float), xs, zs) + 0.0 * np.asarray(y, float)

        def extent(self):
            return float(xs[0]), float(xs[-1]), -2.0, 2.0

        def varies_in_y(self):
            return False

    return Profile()
