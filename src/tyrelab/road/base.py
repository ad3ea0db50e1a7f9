"""What every road is: a height field ``h(x, y)`` and its compiled grid form.

Axes: x along the road (direction of travel), y to the left, z up; SI.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np

from .grid import RoadGrid


class Road(ABC):
    """A road surface.

    Subclasses implement :meth:`height` (vectorised, exact) and say how fine
    their compiled grid must be (:attr:`default_spacing`) and where the
    surface differs from its surroundings (:meth:`extent`).
    """

    #: human-readable description, e.g. "cleat 50 x 50 mm at 0 deg"
    name: str = "road"
    #: grid spacing (dx, dy) [m] that resolves the road's features
    default_spacing: tuple[float, float] = (0.01, 0.01)
    #: x [m] where a run starts by default (the test wheel's first position)
    run_start: float = 0.0

    @abstractmethod
    def height(self, x, y) -> np.ndarray:
        """Road height [m] at points (x, y) [m]; arrays broadcast."""

    @abstractmethod
    def extent(self) -> tuple[float, float, float, float]:
        """``(xmin, xmax, ymin, ymax)`` [m] of the region the grid must cover.

        Outside it the grid continues the edge heights.
        """

    def varies_in_y(self) -> bool:
        """False when the height does not depend on y (a 2D profile road)."""
        return True

    def grid(self, spacing: tuple[float, float] | None = None) -> RoadGrid:
        """Sample the road on a regular grid (the form the kernels query).

        Roads whose height does not depend on y get a two-row grid spanning
        their width, which is exact under bilinear interpolation.
        """
        dx, dy = spacing or self.default_spacing
        xmin, xmax, ymin, ymax = self.extent()
        nx = int(np.ceil((xmax - xmin) / dx - 1e-9)) + 1
        xs = xmin + dx * np.arange(nx)
        if not self.varies_in_y():
            ys = np.array([ymin, ymax])
            dy = ymax - ymin
        else:
            ny = int(np.ceil((ymax - ymin) / dy - 1e-9)) + 1
            ys = ymin + dy * np.arange(ny)
        X, Y = np.meshgrid(xs, ys, indexing="ij")
        return RoadGrid(xmin, ymin, dx, dy, self.height(X, Y))

    def __repr__(self) -> str:
        return f"<{type(self).__name__}: {self.name}>"


class GriddedRoad(Road):
    """A road defined by heights on its own regular grid (files, synthesised roads).

    Subclasses set ``self._grid`` (a :class:`RoadGrid`) and
    ``self._varies_in_y``; heights between nodes are bilinear, exactly as the
    compiled kernels see them.
    """

    _grid: RoadGrid
    _varies_in_y: bool = True

    def height(self, x, y) -> np.ndarray:
        return self._grid.height(x, y)

    def extent(self) -> tuple[float, float, float, float]:
        g = self._grid
        return (g.x0, g.x0 + g.dx * (g.z.shape[0] - 1), g.y0, g.y0 + g.dy * (g.z.shape[1] - 1))

    def varies_in_y(self) -> bool:
        return self._varies_in_y

    def grid(self, spacing: tuple[float, float] | None = None) -> RoadGrid:
        """The road's own grid (exact) unless another spacing is asked for."""
        if spacing is None or np.allclose(spacing, (self._grid.dx, self._grid.dy), rtol=1e-12, atol=0):
            return self._grid
        return super().grid(spacing)
