"""The soil under a wheel a host drives anywhere: a square window of the soil that moves with
the wheel in x and y (co-simulation: a vehicle model turns, reverses and puts its wheels away
from y = 0).

The rigs drive straight along x, so their soil is a strip that moves forward only
(:mod:`.patch`). A host's wheel may go any way, so :class:`SoilField` holds a window of
``size`` x ``size`` metres of a soil laid over the whole plane, on one lattice of nodes
``(x_anchor + i dx, y_anchor + k dy)`` (``i``, ``k`` any integers). When the wheel needs soil
outside the window (:meth:`SoilField.cover`), the window moves: the nodes it still holds keep
their state (rut, mobilized shear, stress), the nodes it newly holds are laid fresh from the
road's heights, and the nodes it leaves are forgotten (a wheel coming back there finds fresh
soil). Node ``(i, k)`` is always at the same place, so a node's undisturbed height does not
change when the window moves. Project Chrono's SCM keeps every node a wheel has touched (a hash
map, which grows with the rut); a bounded window keeps the arrays the compiled code reads, at
the cost of the rut it leaves behind.
"""

from __future__ import annotations

import math
import weakref

import numpy as np

from ...errors import InputError
from .params import Soil
from .scm import BED_SPACING, bed_record, check_bed_memory, no_shear

#: side of the square of soil held at once [m]: 601 x 601 nodes at 2 cm (12 MB); the wheel
#: drives about 6 m between moves
FIELD_SIZE = 12.0


class SoilField:
    """The Python ground of a soil laid over the whole plane, a window of it held at a time
    (:class:`~tyrelab.road.terrain.Ground`).

    ``soil`` over ``road``'s heights less ``level`` [m], nodes every ``spacing`` [m] on the
    lattice through ``(x, y)``, the window ``size`` [m] square centred on ``(x, y)`` to begin
    with. The rest of the terrain interface's Python side (``surface()``, ``fresh_copy()``,
    ``row_maxima``, ...) is the :class:`~tyrelab.road.soil.scm.SoilSurface`'s of the window
    held now (``bed``).
    """

    def __init__(self, soil: Soil, road, x: float, y: float, size: float, spacing: float,
                 level: float = 0.0):
        self.soil, self.road, self.level = soil, road, float(level)
        self.spacing = float(spacing)
        self.x_anchor, self.y_anchor = float(x), float(y)
        n = int(math.ceil(size / self.spacing)) + 1
        self.first = (-(n // 2), -(n // 2))              # lattice index of the window's corner
        self.bed = self._fresh(self.first, (n, n))
        self._wheels = weakref.WeakKeyDictionary()        # a wheel on it -> the box it needs

    def _heights(self, first: tuple[int, int], shape: tuple[int, int]) -> np.ndarray:
        """The undisturbed heights of the nodes from lattice index ``first``, ``shape`` of them."""
        xs = self.x_anchor + self.spacing * np.arange(first[0], first[0] + shape[0])
        ys = self.y_anchor + self.spacing * np.arange(first[1], first[1] + shape[1])
        z = np.asarray(self.road.height(xs[:, None], ys[None, :]), dtype=np.float64)
        return np.ascontiguousarray(z - self.level if self.level else z)

    def _fresh(self, first, shape):
        """Fresh soil on the road's heights: the nodes from lattice index ``first``, ``shape``."""
        base = self._heights(first, shape)
        h0 = base.copy() if self.soil.bulldozing else base
        return bed_record(self.soil, self.x_anchor + first[0] * self.spacing,
                          self.y_anchor + first[1] * self.spacing, self.spacing, self.spacing,
                          base, h0, base.copy(), no_shear(base.shape), np.zeros_like(base))

    def held(self) -> tuple[float, float, float, float]:
        """The window held now: ``(x_lo, x_hi, y_lo, y_hi)`` of its outer nodes [m]."""
        nx, ny = self.bed.base.shape
        (i, k), d = self.first, self.spacing
        return (self.x_anchor + i * d, self.x_anchor + (i + nx - 1) * d,
                self.y_anchor + k * d, self.y_anchor + (k + ny - 1) * d)

    def cover(self, x_lo: float, x_hi: float, y_lo: float, y_hi: float,
              toward: tuple[float, float] = (0.0, 0.0), behind: float = 0.0, wheel=None):
        """The bed's record once the window holds the box ``x_lo..x_hi``, ``y_lo..y_hi`` [m], or
        None when it holds it already.

        Moved, the window keeps its size (or grows to the box) and puts the box ``behind``
        [m] from its edge opposite ``toward`` (a horizontal unit vector, the way the wheel
        goes; (0, 0): the box in the middle), so that the wheel drives as far as it can
        before the next move. The nodes held before and after keep their state.

        Several wheels on one field (a vehicle's, each stepped on its own): each names
        itself as ``wheel`` (any object; forgotten once nothing else holds it), the box is
        its own, and the window holds the boxes of every wheel on the field, so that the
        rear wheels run in the front wheels' ruts and no wheel's move drops another's soil."""
        lo_x, hi_x, lo_y, hi_y = self.held()
        inside = lo_x <= x_lo and x_hi <= hi_x and lo_y <= y_lo and y_hi <= hi_y
        if wheel is not None:
            self._wheels[wheel] = (x_lo, x_hi, y_lo, y_hi)
            if not inside:  # (every other wheel's box is inside: each move holds them all)
                boxes = list(self._wheels.values())
                x_lo, x_hi = min(b[0] for b in boxes), max(b[1] for b in boxes)
                y_lo, y_hi = min(b[2] for b in boxes), max(b[3] for b in boxes)
        if inside:
            return None
        d = self.spacing
        old = self.bed
        nx0, ny0 = old.base.shape
        shape = (max(nx0, int(math.ceil((x_hi - x_lo) / d)) + 3),
                 max(ny0, int(math.ceil((y_hi - y_lo) / d)) + 3))
        first = []
        for lo, hi, n, u, anchor in ((x_lo, x_hi, shape[0], toward[0], self.x_anchor),
                                     (y_lo, y_hi, shape[1], toward[1], self.y_anchor)):
            room = max(0.5 * ((n - 1) * d - (hi - lo)) - behind, 0.0)  # slack beyond the margin
            centre = 0.5 * (lo + hi) + u * room
            i = int(round((centre - anchor) / d)) - (n - 1) // 2
            # the box must lie inside whatever the rounding did
            i = min(i, int(math.floor((lo - anchor) / d)))
            first.append(max(i, int(math.ceil((hi - anchor) / d)) - n + 1))
        first = (first[0], first[1])
        check_bed_memory(shape[0] * shape[1], f"the soil the wheels reach in one step ({x_hi - x_lo:.3g} "
                         f"m x {y_hi - y_lo:.3g} m)", "shorter steps", "dt")
        new = self._fresh(first, shape)
        # the nodes both windows hold keep their state
        a = [max(first[0], self.first[0]), max(first[1], self.first[1])]
        b = [min(first[0] + shape[0], self.first[0] + nx0), min(first[1] + shape[1], self.first[1] + ny0)]
        if a[0] < b[0] and a[1] < b[1]:
            dst = (slice(a[0] - first[0], b[0] - first[0]), slice(a[1] - first[1], b[1] - first[1]))
            src = (slice(a[0] - self.first[0], b[0] - self.first[0]),
                   slice(a[1] - self.first[1], b[1] - self.first[1]))
            new.ground.z[dst] = old.ground.z[src]
            new.shear[dst] = old.shear[src]
            new.sigma[dst] = old.sigma[src]
            if self.soil.bulldozing:
                new.h0[dst] = old.h0[src]
        self.first = first
        self.bed = new
        return new

    def __getattr__(self, name):
        # the rest of the terrain interface's Python side is the window's held now
        if name == "bed":               # not set yet (a copy being built): no recursion
            raise AttributeError(name)
        return getattr(self.bed, name)


def lay_soil_field(soil: Soil, road, x: float, y: float, level_at: float | None = None,
                   size: float | None = None, spacing: float | None = None) -> SoilField:
    """The soil laid over ``road``'s heights (less its height at ``(level_at, 0)`` when given)
    everywhere, held ``size`` [m] square at a time around a wheel at ``(x, y)`` [m] and moved
    with it (:class:`SoilField`; default :data:`FIELD_SIZE`); nodes every ``spacing`` [m]
    (default the rigs' bed's).
    :attr:`~tyrelab.road.terrain_registry.TerrainKind.lay_around` of the soil."""
    spacing = BED_SPACING if spacing is None else float(spacing)
    size = FIELD_SIZE if size is None else float(size)
    if not (math.isfinite(size) and math.isfinite(spacing) and 0.0 < spacing and 2 * spacing <= size):
        raise InputError(f"a soil field needs a node spacing > 0 and a side of at least two "
                         f"spacings, got {spacing:g} m and {size:g} m", field="size")
    n = int(math.ceil(size / spacing)) + 1
    check_bed_memory(n * n, f"a soil field {size:g} m square at {spacing:g} m",
                     "a smaller field or a coarser bed", "size")
    level = float(road.height(level_at, 0.0)) if level_at is not None else 0.0
    return SoilField(soil, road, x, y, size, spacing, level)
