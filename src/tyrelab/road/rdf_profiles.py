"""The 2D road types of Adams road data files (``METHOD = '2D'``), as exact height fields.

Each type is a profile along the road's own axis u (its x, "travel
distance"), placed in the road frame by :class:`RdfRoad` (``OFFSET``,
``ROTATION_ANGLE_XY_PLANE``, a lateral offset). Parameters come from the
Adams/Tire 2D road documentation and the COSIN/road TeimOrbit road-type
tables (Altair MotionView help); where those give a parameter's meaning but
not the formula, the geometry below is the one chosen here, stated exactly.
All lengths in metres, angles in radians (:mod:`tyrelab.road.rdf` converts
``[UNITS]``). With ``s = u - START``:

* ``flat``: ``z = 0``.
* ``plank``: a rectangular plank ``HEIGHT`` high (negative: a depression)
  whose edges run at ``DIRECTION`` to the road's y axis (positive: the left
  side, y > 0, is met first). Its extent along u at any v is ``LENGTH`` and
  its top edges carry 45-degree bevels (in the plank's own section) whose
  extent along u is ``BEVEL_EDGE_LENGTH``: exactly tyrelab's
  :class:`~tyrelab.road.obstacles.Cleat` of width ``LENGTH cos(DIRECTION)``,
  bevel ``BEVEL_EDGE_LENGTH cos(DIRECTION)``, at ``START`` (``cleat:WxH``
  for a perpendicular plank); a negative HEIGHT mirrors it (a trench of the
  same section, the bevels at its bottom). ``EDGE_ROUNDED = 1`` is not
  supported.
* ``pot_hole``: ``z = -DEPTH`` for ``0 < s' < LENGTH cos(DIRECTION)`` with the
  across coordinate ``s' = s cos(DIRECTION) + v sin(DIRECTION)``, else 0; the
  rim stays at road level (as :class:`~tyrelab.road.obstacles.Pothole`). A
  positive DEPTH is a hole (COSIN: "depth of pot-hole"); a negative one a
  raised block. (Altair's help adds that a positive value "acts as a bump";
  that contradicts its own example, and is not followed.)
* ``ramp``: ``z = sign(HEIGHT) min(|HEIGHT|, SLOPE s)`` for s >= 0, else 0;
  ``SLOPE`` is the dimensionless rise per run (1 = 45 degrees), > 0; a
  negative HEIGHT is a falling ramp.
* ``roof``: the symmetric triangle ``z = HEIGHT (1 - |2 s / LENGTH - 1|)`` for
  ``0 <= s <= LENGTH``, else 0 (apex at mid-length).
* ``sine``: ``z = AMPLITUDE sin(2 pi s / WAVE_LENGTH)`` for ``0 <= s <= LENGTH``
  (``s >= 0`` without LENGTH), else 0.
* ``sine_sweep``: over ``0 <= s <= L = END - START`` (else 0),
  ``z = A(s) sin(phi(s))`` with the amplitude linear from
  ``AMPLITUDE_AT_START`` to ``AMPLITUDE_AT_END``. ``SWEEP_TYPE = 0`` (linear,
  the default): the spatial frequency rises linearly from ``1/l0`` to
  ``1/l1`` (``l0, l1 = WAVE_LENGTH_AT_START, _AT_END``, ``l1 <= l0``):
  ``phi = 2 pi s (1/l0 + (1/l1 - 1/l0) s / (2 L))``. ``SWEEP_TYPE = 1``
  (logarithmic): the wave length falls linearly, ``l(s) = l0 (1 - s/s_inf)``
  with ``s_inf = l0 L / (l0 - l1)`` (infinite frequency at s_inf, COSIN's
  definition), so each cycle is shorter than the last by a constant factor:
  ``phi = -(2 pi s_inf / l0) ln(1 - s / s_inf)``. (The 0/1 assignment follows
  the order in which COSIN lists the two.)
* ``poly_line``: ``(XZ_DATA)`` rows ``x z_left z_right``, x strictly
  increasing; each track linear between rows and constant beyond the first
  and last. Adams gives each tyre its side's track; here the right track is
  the line y = 0, where tyrelab's test wheel runs (the trailer's right
  wheel), the left track the line y = :data:`LEFT_TRACK_Y` (the trailer's
  track, where its left wheel runs), linear in y between them and constant
  outside. Equal tracks make a road that does not vary in y.

Compiled grids put every edge of a profile on a node (perpendicular types),
so they are exact for the piecewise-linear types (plank, pot_hole, ramp,
roof, poly_line on a lattice of rows); a sine is sampled every <= 5 mm and
1/50 of its shortest wave length (error below ``A (pi dx / l)^2 / 2``).
"""

from __future__ import annotations

import math
from abc import abstractmethod

import numpy as np

from ..errors import InputError
from ..limits import MAX_ROAD_HEIGHT
from .base import Road
from .mesh import RUN_IN, fit_budget, lattice_spacing
from .obstacles import EDGE_SPACING, HALF_WIDTH, RUN_OUT, Cleat

#: lateral position [m] of the left track of a poly_line road (tyrelab's trailer track)
LEFT_TRACK_Y = 2.4
#: length [m] of an endless sine covered by the compiled grid (a run ends there)
SINE_GRID_LENGTH = 100.0


def _before(start: float, dx: float, distance: float = 1.0) -> float:
    """A grid origin ``distance`` or a little more before ``start``, ``start`` on a node."""
    return start - dx * math.ceil(distance / dx - 1e-9)


def rotation_cos_sin(rotation: float) -> tuple[float, float]:
    """``cos, sin`` of an angle [rad], exact for quarter turns (180 degrees mirrors cleanly)."""
    deg = math.degrees(rotation) % 360.0
    quarter = round(deg / 90.0)
    if abs(deg - 90.0 * quarter) < 1e-9:
        return [(1, 0), (0, 1), (-1, 0), (0, -1), (1, 0)][quarter]
    return math.cos(rotation), math.sin(rotation)


class RdfRoad(Road):
    """A 2D Adams road type: a local profile placed in the road frame.

    The file's frame is the road frame rotated by ``rotation`` [rad] about z
    (``ROTATION_ANGLE_XY_PLANE``: the direction of the file's x axis) and
    raised by ``offset`` [m] (``OFFSET``); tyrelab's path runs at the file's
    y = ``y_offset``. So ``height(x, y) = h(u, v) + offset`` with
    ``(u, v) = R(-rotation) (x, y + y_offset)``. Subclasses give the profile
    ``local_height(u, v)`` and, in file coordinates, ``_extent`` (region the
    grid covers, the profile constant beyond it), ``_feature`` (u range where
    the profile changes), ``_spacing`` and ``_varies``.
    """

    _extent: tuple[float, float, float, float]
    _feature: tuple[float, float]
    _spacing: tuple[float, float] = (1.0, 1.0)
    _varies: bool = False

    def place(self, offset=0.0, rotation=0.0, y_offset=0.0, mu=1.0):
        """Set the placement (see the class docstring) and friction ``mu``; returns self."""
        self.offset, self.y_offset, self.mu = float(offset), float(y_offset), float(mu)
        self._cos, self._sin = rotation_cos_sin(rotation)
        self.rotation = float(rotation)
        return self

    offset = y_offset = rotation = 0.0
    mu = 1.0
    _cos, _sin = 1, 0

    @abstractmethod
    def local_height(self, u, v) -> np.ndarray:
        """Profile height [m] at file coordinates (u, v), before OFFSET."""

    def _to_file(self, x, y):
        X, Y = np.asarray(x, float), np.asarray(y, float) + self.y_offset
        return self._cos * X + self._sin * Y, -self._sin * X + self._cos * Y

    def _to_road(self, u, v):
        u, v = np.asarray(u, float), np.asarray(v, float)
        return self._cos * u - self._sin * v, self._sin * u + self._cos * v - self.y_offset

    def height(self, x, y) -> np.ndarray:
        u, v = self._to_file(x, y)
        u, v = np.broadcast_arrays(u, v)
        return self.local_height(u, v) + self.offset

    def friction(self, x, y) -> np.ndarray:
        """The file's MU everywhere."""
        return np.full(np.broadcast(np.asarray(x), np.asarray(y)).shape, self.mu)

    def _square(self) -> bool:
        return self._sin == 0

    def extent(self):
        u0, u1, v0, v1 = self._extent
        if self._square() and self._cos < 0:  # mirrored: keep the nodes on the profile's lattice
            du, _ = self._spacing
            u1 = u0 + du * math.ceil((u1 - u0) / du - 1e-9)
        x, y = self._to_road(np.array([u0, u1, u0, u1]), np.array([v0, v0, v1, v1]))
        return (float(x.min()), float(x.max()), float(y.min()), float(y.max()))

    def varies_in_y(self) -> bool:
        if isinstance(self, FlatRdf):
            return False
        return self._varies if self._square() else True

    @property
    def default_spacing(self):
        spacing = self._spacing if self._square() else (EDGE_SPACING, EDGE_SPACING)
        return fit_budget(self.extent(), spacing, two_rows=not self.varies_in_y())

    @property
    def run_start(self) -> float:
        """``RUN_IN`` before the first point of the road (x) where the profile changes."""
        u0, u1 = self._feature
        _, _, v0, v1 = self._extent
        x, _ = self._to_road(np.array([u0, u1, u0, u1]), np.array([v0, v0, v1, v1]))
        return float(x.min()) - RUN_IN if not isinstance(self, FlatRdf) else 0.0


class FlatRdf(RdfRoad):
    """``flat``: z = 0."""

    name = "flat"
    _extent = (0.0, 1.0, -HALF_WIDTH, HALF_WIDTH)
    _feature = (0.0, 0.0)

    def local_height(self, u, v):
        return np.zeros(np.shape(u))


class Plank(RdfRoad):
    """``plank``: tyrelab's :class:`Cleat` with the file's sizes (see the module docstring)."""

    def __init__(self, height, start, length, bevel=0.0, direction=0.0):
        c = math.cos(direction)
        self.sign = 1.0 if height > 0 else -1.0
        self.cleat = Cleat(width=length * c, height=abs(height), angle=math.degrees(direction),
                           bevel=bevel * c, start=start)
        reach = HALF_WIDTH * abs(math.tan(direction))
        self._feature = (start - reach, start + length + reach)
        self._extent = self.cleat.extent()
        self._spacing = self.cleat.default_spacing
        self._varies = self.cleat.varies_in_y()
        self.name = f"plank {height * 1e3:g} x {length * 1e3:g} mm at {math.degrees(direction):g} deg"

    def local_height(self, u, v):
        return self.sign * self.cleat.height(u, v)


class PotHole(RdfRoad):
    """``pot_hole``: a rectangular hole DEPTH deep across the road (see the module docstring)."""

    def __init__(self, depth, start, length, direction=0.0):
        self.depth, self.start, self.direction = depth, start, direction
        self.width = length * math.cos(direction)
        reach = HALF_WIDTH * abs(math.tan(direction))
        self._feature = (start - reach, start + length + reach)
        if direction == 0.0:
            dx, _ = lattice_spacing([0.0, length], EDGE_SPACING)
            self._spacing, self._varies = (dx, 1.0), False
        else:
            dx = EDGE_SPACING
            self._spacing, self._varies = (dx, dx), True
        self._extent = (_before(start - reach, dx), start + length + reach + RUN_OUT, -HALF_WIDTH, HALF_WIDTH)
        self.name = f"pot hole {depth * 1e3:g} mm deep, {length * 1e3:g} mm long"

    def local_height(self, u, v):
        s = (u - self.start) * math.cos(self.direction) + v * math.sin(self.direction)
        return np.where((s > 0) & (s < self.width), -self.depth, 0.0)


class _Profile(RdfRoad):
    """A profile along u only, with the u positions of its corners (grid nodes)."""

    def _setup(self, start, edges, end, target=EDGE_SPACING):
        dx, _ = lattice_spacing(edges, target)
        self._spacing = (dx, 1.0)
        self._feature = (start, edges[-1])
        self._extent = (_before(start, dx), end, -HALF_WIDTH, HALF_WIDTH)


class Ramp(_Profile):
    """``ramp``: ``z = sign(H) min(|H|, SLOPE s)`` for s >= 0."""

    def __init__(self, height, start, slope):
        self.h, self.start, self.slope = height, start, slope
        top = start + abs(height) / slope
        self._setup(start, [start, top], top + RUN_OUT)
        self.name = f"ramp {height * 1e3:g} mm, slope {slope:g}"

    def local_height(self, u, v):
        return math.copysign(1.0, self.h) * np.clip(self.slope * (u - self.start), 0.0, abs(self.h))


class Roof(_Profile):
    """``roof``: a symmetric triangle HEIGHT high over LENGTH."""

    def __init__(self, height, start, length):
        self.h, self.start, self.length = height, start, length
        self._setup(start, [start, start + length / 2, start + length], start + length + RUN_OUT)
        self.name = f"roof {height * 1e3:g} mm high, {length * 1e3:g} mm long"

    def local_height(self, u, v):
        s = (u - self.start) / self.length
        return self.h * np.clip(1.0 - np.abs(2.0 * s - 1.0), 0.0, None)


class Sine(_Profile):
    """``sine``: ``A sin(2 pi s / WAVE_LENGTH)`` over ``0 <= s <= LENGTH``."""

    def __init__(self, amplitude, wave_length, start, length=None):
        self.a, self.wl, self.start, self.length = amplitude, wave_length, start, length
        end = start + (length if length is not None else SINE_GRID_LENGTH)
        self._setup(start, [start, end], end + (RUN_OUT if length is not None else 0.0),
                    min(EDGE_SPACING, wave_length / 50))
        self.name = f"sine {amplitude * 1e3:g} mm, wave length {wave_length:g} m"

    def local_height(self, u, v):
        s = u - self.start
        on = (s >= 0) & ((s <= self.length) if self.length is not None else True)
        return np.where(on, self.a * np.sin(2 * np.pi * s / self.wl), 0.0)


class SineSweep(_Profile):
    """``sine_sweep``: a swept sine from START to END (see the module docstring)."""

    def __init__(self, start, end, a0, a1, l0, l1, log=False):
        self.start, self.L, self.log = start, end - start, log
        self.a0, self.a1, self.l0, self.l1 = a0, a1, l0, l1
        self._setup(start, [start, end], end + RUN_OUT, min(EDGE_SPACING, l1 / 50))
        self.name = (f"{'logarithmic' if log else 'linear'} sine sweep {l0:g} to {l1:g} m wave length")

    def phase(self, s):
        """Phase [rad] at travel ``s`` [m] after START."""
        if not self.log:
            return 2 * np.pi * s * (1 / self.l0 + (1 / self.l1 - 1 / self.l0) * s / (2 * self.L))
        if self.l1 == self.l0:
            return 2 * np.pi * s / self.l0
        s_inf = self.l0 * self.L / (self.l0 - self.l1)
        return -(2 * np.pi * s_inf / self.l0) * np.log1p(-np.clip(s, 0.0, self.L) / s_inf)

    def local_height(self, u, v):
        s = u - self.start
        on = (s >= 0) & (s <= self.L)
        sc = np.clip(s, 0.0, self.L)
        amp = self.a0 + (self.a1 - self.a0) * sc / self.L
        return np.where(on, amp * np.sin(self.phase(sc)), 0.0)


class PolyLine(RdfRoad):
    """``poly_line``: left and right tracks, linear between rows (see the module docstring)."""

    def __init__(self, x, z_left, z_right):
        self.x, self.zl, self.zr = (np.asarray(a, float) for a in (x, z_left, z_right))
        top = max(np.abs(self.zl).max(), np.abs(self.zr).max())
        if top > MAX_ROAD_HEIGHT:
            raise InputError(f"a track height of {top:.3g} m; road heights are at most "
                             f"{MAX_ROAD_HEIGHT:g} m", field="XZ_DATA")
        self.same = bool(np.array_equal(self.zl, self.zr))
        changes = np.flatnonzero((np.diff(self.zl) != 0) | (np.diff(self.zr) != 0))
        u0, u1 = (self.x[changes[0]], self.x[changes[-1] + 1]) if changes.size else (self.x[0], self.x[0])
        knots = self.x[(self.x >= u0) & (self.x <= u1)]
        dx, self.exact = lattice_spacing(knots, EDGE_SPACING)
        self._feature = (float(u0), float(u1))
        x0 = _before(u0, dx)
        x1 = u1 + RUN_OUT
        if self.same:
            self._extent, self._spacing, self._varies = (x0, x1, -HALF_WIDTH, HALF_WIDTH), (dx, 1.0), False
        else:  # rows at -w/2, 0 (right track), w/2, w (left track), 3w/2: bilinear is exact
            w = LEFT_TRACK_Y
            self._extent, self._spacing, self._varies = (x0, x1, -w / 2, 1.5 * w), (dx, w / 2), True
        self.name = f"poly_line of {len(self.x)} rows"

    def local_height(self, u, v):
        right = np.interp(u, self.x, self.zr)
        if self.same:
            return right
        w = np.clip(v / LEFT_TRACK_Y, 0.0, 1.0)
        return right + w * (np.interp(u, self.x, self.zl) - right)
