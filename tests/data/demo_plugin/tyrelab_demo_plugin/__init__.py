"""A demonstration tyrelab plugin: a contact model, a rig and a road file format.

* ``preloaded-point``: the one-point contact whose tyre is compressed by ``preload``
  [m] (option, default 10 mm) before it touches the road -- it carries a load at a
  deflection ``preload`` smaller than the point model's, so its axle rides that
  much higher.
* ``raised-rolling``: the rolling rig with the axle :data:`RAISE` above the height
  at which the model carries the load.
* ``.xz``: a longitudinal road profile, one ``x z`` pair [m] per line, the same
  across the road.
"""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numba as nb
import numpy as np
from tyrelab.registry import (ContactModel, Rig, RoadFormat, register_contact, register_rig,
                              register_road_format)
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


def register() -> None:
    register_contact(ContactModel("preloaded-point", PreloadedPoint, build, geometry=geometry,
                                  equilibrium=equilibrium, options={"preload": float}, cost=0.002,
                                  summary="point contact, the tyre preloaded by 'preload' [m] (demo plugin)"))
    register_rig(Rig("raised-rolling", _raised_rolling, "the rolling rig, the axle 5 mm up (demo plugin)",
                     channels="tyrelab.rig.rolling:CHANNELS"))
    register_road_format(RoadFormat(".xz", "x-z profile", _read_xz,
                                    summary="longitudinal profile, 'x z' per line [m] (demo plugin)"))


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
