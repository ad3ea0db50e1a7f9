"""The soil under a run: a bed that holds at most :data:`PATCH_LENGTH` of it and moves with the
wheel (the active patch), so a run of any length needs the memory of a few metres.

A run's soil is laid from its start; while the wheel stays inside the first
:data:`PATCH_LENGTH` of it nothing moves. Before a chunk of the run that would take the wheel
past the bed's far end, the rig asks the patch to cover the part the chunk drives
(:meth:`SoilPatch.follow`): the rows more than the rig's margin behind the wheel are dropped
(their rut is forgotten: no wheel of the run comes back to them), the rows kept move to the
front with their state (rut, mobilized shear, stress) unchanged, and the new rows ahead
are laid fresh from the road's heights. Node ``i`` of the bed always lies at
``x_first + (offset + i) dx``, the node the whole run's bed would have there (up to the
rounding of its position). Project Chrono's SCM keeps memory bounded differently (a hash map
of the nodes a wheel has touched, which grows with the rut); a rig on a straight run never
looks back, so a moving window is enough and keeps the arrays the compiled code reads.
"""

from __future__ import annotations

import numpy as np

from ..grid import RoadGrid
from .params import Soil
from .scm import bed_record, no_shear, soil_bed

#: the longest stretch of soil held at once [m] (a run's first chunk and its margins fit)
PATCH_LENGTH = 30.0


class SoilPatch:
    """The Python ground of a soil laid over a run (:class:`~tyrelab.road.terrain.Ground`).

    ``soil`` laid over ``road``'s heights less ``level`` [m], from ``x_first`` [m] over
    ``n_run`` rows along x and ``ny`` across from ``y0``, nodes every ``spacing`` [m]; at
    most ``rows`` of them held at once (all when ``rows >= n_run``). Every other method of
    the terrain interface's Python side is the :class:`~tyrelab.road.soil.scm.SoilSurface`'s
    of the part held now (``bed``): ``surface()`` its record, ``fresh_copy()`` a copy of its
    state, ``row_maxima`` its bounds (a model that kept them for a whole run would read
    them for that stretch only; no model on soil keeps them).
    """

    def __init__(self, soil: Soil, road, x_first: float, n_run: int, y0: float, ny: int,
                 spacing: float, level: float, rows: int):
        self.soil, self.road, self.level = soil, road, float(level)
        self.x_first, self.n_run, self.spacing = float(x_first), int(n_run), float(spacing)
        self.ys = y0 + spacing * np.arange(ny)
        self.offset = 0                              # the run's row of the bed's first row
        nx = min(int(rows), self.n_run)
        self.bed = soil_bed(soil, RoadGrid(self.x_first, float(y0), spacing, spacing,
                                           self._heights(0, nx)))

    def _heights(self, first: int, count: int) -> np.ndarray:
        """The undisturbed heights of the run's rows ``first`` to ``first + count - 1``."""
        xs = self.x_first + self.spacing * np.arange(first, first + count)
        z = np.asarray(self.road.height(xs[:, None], self.ys[None, :]), dtype=np.float64)
        return z - self.level if self.level else z

    def undisturbed(self, x, y) -> np.ndarray:
        """The surface as laid [m] at ``(x, y)`` [m] (arrays broadcast): the road's height less
        ``level``, which the nodes' undisturbed heights sample (:attr:`SoilSurface.h0` before
        any wheel; here exact between them)."""
        z = np.asarray(self.road.height(np.asarray(x, dtype=float), np.asarray(y, dtype=float)),
                       dtype=np.float64)
        return z - self.level

    def held(self) -> tuple[float, float]:
        """The stretch of the run held now: the first and last rows' x [m]."""
        nx = self.bed.h0.shape[0]
        return (self.x_first + self.offset * self.spacing,
                self.x_first + (self.offset + nx - 1) * self.spacing)

    def follow(self, x_behind: float, x_ahead: float):
        """The bed's record once it covers ``x_behind`` to ``x_ahead`` [m]: moved forward, the rows
        before ``x_behind`` dropped and new ones laid up to ``x_ahead`` (as far as the run goes),
        when ``x_ahead`` lies past the rows held; None when they cover it already. The bed holds
        as many rows as it did, or more when the stretch asked for is longer."""
        start, end = self.held()
        b = self.bed
        nx = b.h0.shape[0]
        if x_ahead <= end or self.offset + nx >= self.n_run:
            return None
        drop = max(0, min(int(np.floor((x_behind - start) / self.spacing)), nx))
        reach = int(np.ceil((x_ahead - start) / self.spacing)) + 1     # rows from the first held
        rows = min(max(nx, reach - drop), self.n_run - self.offset - drop)
        fresh = self._heights(self.offset + nx, rows - (nx - drop))
        zeros = np.zeros_like(fresh)
        base = np.concatenate([b.base[drop:], fresh])
        h0 = np.concatenate([b.h0[drop:], fresh]) if b.h0 is not b.base else base
        z = np.concatenate([b.ground.z[drop:], fresh])
        shear = np.concatenate([b.shear[drop:], no_shear(fresh.shape)])
        sigma = np.concatenate([b.sigma[drop:], zeros])
        self.offset += drop
        self.bed = bed_record(self.soil, self.x_first + self.offset * self.spacing, b.y0, b.dx,
                              b.dy, base, h0, z, shear, sigma)
        return self.bed

    def __getattr__(self, name):
        # the rest of the terrain interface's Python side (surface, fresh_copy, sampling_step,
        # row_maxima, ...) is the bed's held now
        if name == "bed":               # not set yet (a copy being built): no recursion
            raise AttributeError(name)
        return getattr(self.bed, name)
