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
