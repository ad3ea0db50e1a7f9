"""Discrete obstacles and the flat road (thesis 3.4.2, 3.4.3).

Each obstacle is a height field that is zero away from it. ``start`` is the
x where the obstacle begins at the road centreline (y = 0). Sizes in metres.
Grids place the obstacle's edges on grid nodes where the geometry allows it
(perpendicular obstacles), so a sharp edge stays sharp under bilinear
interpolation.

Sizes are bounded (:mod:`tyrelab.limits`): heights and depths up to
:data:`~tyrelab.limits.MAX_OBSTACLE_HEIGHT`, lengths along the road from
:data:`~tyrelab.limits.MIN_OBSTACLE_SIZE` to
:data:`~tyrelab.limits.MAX_OBSTACLE_LENGTH`, widths across it up to the
road's width; a size outside is an :class:`InputError` naming it, before
any grid is built.
"""

from __future__ import annotations

import contextvars
from contextlib import contextmanager
import math

import numpy as np

from .. import limits
from ..errors import InputError
from .base import Road

#: length of flat road after an obstacle [m], enough for the response to die out
RUN_OUT = 15.0
#: half width of obstacle roads [m] (the thesis tracks are 4 m wide)
HALF_WIDTH = 2.0
#: target grid spacing along the road for sharp-edged obstacles [m]
EDGE_SPACING = 0.005


#: the unit a message quotes a size in, as (unit, factor from metres): metres, the
#: constructors' unit, or millimetres while a road is built from its name or a static
#: test's (their grammar is in mm: road.spec, rig.static_press), so that a user reads back
#: the number typed
_QUOTED_UNIT = contextvars.ContextVar("obstacle_size_unit", default=("m", 1.0))


@contextmanager
def sizes_quoted_in_mm():
    """Within this block, a size refused by an obstacle is quoted in millimetres."""
    token = _QUOTED_UNIT.set(("mm", 1e3))
    try:
        yield
    finally:
        _QUOTED_UNIT.reset(token)


def _size(value, name, low, high, low_open=False):
    """A size [m] within ``[low, high]``, refused in the quoted unit."""
    unit, scale = _QUOTED_UNIT.get()
    return limits.check_number(value, "road", low, high, unit, low_open=low_open, what=name,
                               scale=scale)


def _height(value, name):
    """An obstacle height or depth [m]: positive, at most MAX_OBSTACLE_HEIGHT."""
    return _size(value, name, 0.0, limits.MAX_OBSTACLE_HEIGHT, low_open=True)


def _length(value, name, high=limits.MAX_OBSTACLE_LENGTH):
    """An obstacle size [m] along or across the road: MIN_OBSTACLE_SIZE to ``high``."""
    return _size(value, name, limits.MIN_OBSTACLE_SIZE, high)


def _start(value):
    return limits.check_number(value, "road", -limits.MAX_ROAD_LENGTH, limits.MAX_ROAD_LENGTH, "m",
                               what="obstacle start")


def _spacing_through(edges, target=EDGE_SPACING):
    """A spacing <= target that puts every edge (relative to the first) on a node."""
    edges = np.asarray(edges, float) - edges[0]
    length = max(edges[-1], target)
    n = max(1, int(math.ceil(length / target)))
    # try spacings length/n, length/(n+1), ... until all edges fall on nodes
    for k in range(n, 50 * n):
        d = length / k
        if np.all(np.abs(edges / d - np.round(edges / d)) < 1e-6):
            return d
    return target


class Flat(Road):
    """A level road at height zero."""

    name = "flat"
    default_spacing = (1.0, 1.0)

    def height(self, x, y):
        return np.zeros(np.broadcast(np.asarray(x), np.asarray(y)).shape)

    def extent(self):
        return (0.0, 1.0, -HALF_WIDTH, HALF_WIDTH)

    def varies_in_y(self):
        return False


class Cleat(Road):
    """A square (rectangular-section) cleat across the road.

    On the grid the top corners are exact nodes and the side faces lean out
    over one grid cell, so a rolling wheel meets the true corners.

    Parameters
    ----------
    width, height : float
        Cleat section [m] (thesis: 38 x 38 to 100 x 100 mm).
    angle : float
        Angle to the direction of travel [deg]: 0 = perpendicular, 45 = oblique.
        Positive angles make the cleat reach the left side (y > 0) first.
    bevel : float
        Size of a 45-degree chamfer on both top edges [m] (0 = sharp).
    start : float
        x of the leading edge at y = 0 [m].
    """

    def __init__(self, width, height, angle=0.0, bevel=0.0, start=5.0):
        self.width = _length(width, "cleat width")
        self.cleat_height = _height(height, "cleat height")
        self.angle = limits.check_number(angle, "road", -80.0, 80.0, "deg", what="cleat angle")
        # a chamfer of both top edges: at most half the width, at most the height
        self.bevel = _size(bevel, "cleat bevel", 0.0, min(self.width / 2, self.cleat_height))
        self.start = _start(start)
        self.name = (f"cleat {self.width * 1e3:g} x {self.cleat_height * 1e3:g} mm "
                     f"at {self.angle:g} deg")
        if self.angle == 0.0:
            self.default_spacing = (_spacing_through([0.0, self.width]), 1.0)
        else:
            self.default_spacing = (EDGE_SPACING, EDGE_SPACING)

    def across(self, x, y):
        """Coordinate across the cleat, 0 at the leading edge [m]."""
        a = math.radians(self.angle)
        return (np.asarray(x, float) - self.start) * math.cos(a) + np.asarray(y, float) * math.sin(a)

    def height(self, x, y):
        s = self.across(x, y)
        w, h, b = self.width, self.cleat_height, self.bevel
        # a relative tolerance keeps both top corners (up to rounding of the
        # grid's node positions) on the cleat
        eps = 1e-9 * max(1.0, abs(self.start))
        inside = (s >= -eps) & (s <= w + eps)
        top = np.minimum(h, np.minimum(h - b + s, h - b + (w - s))) if b > 0 else np.full(s.shape, h)
        return np.where(inside, top, 0.0)

    def extent(self):
        a = math.radians(self.angle)
        reach = HALF_WIDTH * abs(math.tan(a))
        span = self.width / math.cos(a)
        x0 = self.start - reach - 1.0
        # start the grid exactly at the leading edge minus whole cells so edges sit on nodes
        dx = self.default_spacing[0]
        x0 = self.start - dx * math.ceil((self.start - x0) / dx)
        return (x0, self.start + span + reach + RUN_OUT, -HALF_WIDTH, HALF_WIDTH)

    def varies_in_y(self):
        return self.angle != 0.0


class TrapezoidalBump(Road):
    """A trapezoidal bump across the road (the APG bump of thesis Figure 3-22).

    Parameters
    ----------
    height : float
        Bump height [m].
    ramp_length, top_length : float, optional
        Horizontal length of each ramp and of the flat top [m]. The thesis
        gives these only in a figure; the defaults (ramps 4 x height, top
        0.5 m) are assumptions stated in ARCHITECTURE.md.
    """

    def __init__(self, height, ramp_length=None, top_length=None, start=5.0):
        self.bump_height = _height(height, "bump height")
        self.ramp_length = _length(ramp_length if ramp_length is not None else 4.0 * self.bump_height,
                                   "bump ramp length")
        self.top_length = (_size(top_length, "bump top length", 0.0, limits.MAX_OBSTACLE_LENGTH)
                           if top_length is not None else 0.5)
        if self.top_length > 0:
            _length(self.top_length, "bump top length")
        self.start = _start(start)
        self.name = (f"trapezoidal bump {self.bump_height * 1e3:g} mm, ramps "
                     f"{self.ramp_length * 1e3:g} mm, top {self.top_length * 1e3:g} mm")
        self.default_spacing = (_spacing_through(self._edges()), 1.0)

    def _edges(self):
        r, t = self.ramp_length, self.top_length
        return [0.0, r, r + t, 2 * r + t]

    def height(self, x, y):
        s = np.asarray(x, float) - self.start
        s = np.broadcast_to(s, np.broadcast(s, np.asarray(y)).shape)
        return np.interp(s, self._edges(), [0.0, self.bump_height, self.bump_height, 0.0],
                         left=0.0, right=0.0)

    def extent(self):
        dx = self.default_spacing[0]
        x0 = self.start - dx * math.ceil(1.0 / dx)
        return (x0, self.start + self._edges()[-1] + RUN_OUT, -HALF_WIDTH, HALF_WIDTH)

    def varies_in_y(self):
        return False


class Step(Road):
    """A step of ``height`` (negative: down) at x = ``start``."""

    def __init__(self, height, start=5.0, spacing=EDGE_SPACING):
        self.step_height = _size(height, "step height", -limits.MAX_OBSTACLE_HEIGHT,
                                 limits.MAX_OBSTACLE_HEIGHT)
        if self.step_height == 0.0:
            raise InputError("step height must not be 0 (negative: a step down)", field="road")
        self.start = _start(start)
        self.default_spacing = (limits.check_number(spacing, "road", limits.MIN_GRID_SPACING,
                                                    limits.MAX_GRID_SPACING, "m",
                                                    what="step grid spacing"), 1.0)
        self.name = f"step {self.step_height * 1e3:g} mm"

    def height(self, x, y):
        x = np.asarray(x, float)
        shape = np.broadcast(x, np.asarray(y)).shape
        # the edge itself belongs to the upper level: that corner is what a
        # wheel rolls over, and on the grid it must be a node
        after = x >= self.start if self.step_height > 0 else x > self.start
        return np.broadcast_to(np.where(after, self.step_height, 0.0), shape)

    def extent(self):
        dx = self.default_spacing[0]
        x0 = self.start - dx * math.ceil(1.0 / dx)
        return (x0, self.start + RUN_OUT, -HALF_WIDTH, HALF_WIDTH)

    def varies_in_y(self):
        return False


class Pothole(Road):
    """A rectangular pothole ``depth`` deep, ``length`` long and ``width`` wide.

    ``width=None`` makes it span the whole road (a trench). Centred on y = 0.
    """

    def __init__(self, depth, length, width=None, start=5.0):
        self.depth = _height(depth, "pothole depth")
        self.length = _length(length, "pothole length")
        self.width = None if width is None else _length(width, "pothole width", limits.MAX_OBSTACLE_WIDTH)
        self.start = _start(start)
        self.name = (f"pothole {self.depth * 1e3:g} mm deep, {self.length * 1e3:g} mm long"
                     + ("" if self.width is None else f", {self.width * 1e3:g} mm wide"))
        dx = _spacing_through([0.0, self.length])
        if self.width is None:
            self.default_spacing = (dx, 1.0)
        else:
            self.default_spacing = (dx, _spacing_through([0.0, self.width]))

    def height(self, x, y):
        x = np.asarray(x, float)
        y = np.asarray(y, float)
        # strict inequalities: the rim of the hole stays at road level on the
        # grid nodes, so the edges a wheel rolls over are exact corners
        inside = (x > self.start) & (x < self.start + self.length)
        if self.width is not None:
            inside = inside & (np.abs(y) < self.width / 2)
        return np.where(inside, -self.depth, 0.0)

    def extent(self):
        dx = self.default_spacing[0]
        x0 = self.start - dx * math.ceil(1.0 / dx)
        if self.width is None:
            return (x0, self.start + self.length + RUN_OUT, -HALF_WIDTH, HALF_WIDTH)
        dy = self.default_spacing[1]
        ny = math.ceil(HALF_WIDTH / dy)
        y0 = -self.width / 2 - dy * ny
        return (x0, self.start + self.length + RUN_OUT, y0, -y0)

    def varies_in_y(self):
        return self.width is not None


class Ridge(Road):
    """A square cleat running *along* the road (a longitudinal cleat), centred on y = 0.

    The static lab press of thesis 3.3.4 puts cleats under the tyre both
    across (a :class:`Cleat`) and along the wheel plane (this).
    """

    def __init__(self, width, height, length=2.0, start=-1.0):
        self.width = _length(width, "cleat width", limits.MAX_OBSTACLE_WIDTH)
        self.ridge_height = _height(height, "cleat height")
        self.length = _length(length, "ridge length")
        self.start = _start(start)
        self.name = f"longitudinal cleat {self.width * 1e3:g} x {self.ridge_height * 1e3:g} mm"
        dy = _spacing_through([0.0, self.width])
        self.default_spacing = (0.01, dy)

    def height(self, x, y):
        x = np.asarray(x, float)
        y = np.asarray(y, float)
        # a relative tolerance keeps the edge nodes (y = +-width/2 up to rounding) on the ridge
        half = self.width / 2 * (1 + 1e-9)
        inside = (np.abs(y) <= half) & (x >= self.start) & (x <= self.start + self.length)
        return np.where(inside, self.ridge_height, 0.0)

    def extent(self):
        dy = self.default_spacing[1]
        y0 = -self.width / 2 - dy * math.ceil(0.5 / dy)
        return (self.start - 0.5, self.start + self.length + 0.5, y0, -y0)
