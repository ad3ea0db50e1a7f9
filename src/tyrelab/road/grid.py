"""The compiled form of every road: heights on a regular grid, bilinear.

Every road produces a :class:`RoadGrid`; the contact models query it through
the compiled functions here and never call Python road objects inside a time
step. Grid node ``(i, j)`` sits at ``x0 + i*dx, y0 + j*dy``; between nodes
the height is bilinear. Outside the grid the road continues with the height
of the nearest edge node (a flat run-in and run-out), so a tyre never falls
off the end of a road.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba as nb
import numpy as np


@dataclass(frozen=True)
class RoadGrid:
    """Road heights on a regular grid.

    Attributes
    ----------
    x0, y0 : float
        Position of node (0, 0) [m].
    dx, dy : float
        Node spacing [m].
    z : ndarray, shape (nx, ny)
        Heights [m]; finite everywhere (readers fill empty cells first).
    """

    x0: float
    y0: float
    dx: float
    dy: float
    z: np.ndarray

    def __post_init__(self):
        z = np.ascontiguousarray(self.z, dtype=np.float64)
        if z.ndim != 2 or z.shape[0] < 2 or z.shape[1] < 2:
            raise ValueError("a road grid needs at least 2 x 2 nodes")
        if not np.all(np.isfinite(z)):
            raise ValueError("a road grid must be finite; fill empty cells first")
        if not (self.dx > 0 and self.dy > 0):
            raise ValueError("grid spacing must be positive")
        object.__setattr__(self, "z", z)

    @property
    def params(self) -> np.ndarray:
        """``[x0, y0, dx, dy, 1/dx, 1/dy]`` as the compiled kernels take it."""
        return np.array([self.x0, self.y0, self.dx, self.dy, 1.0 / self.dx, 1.0 / self.dy],
                        dtype=np.float64)

    @property
    def nbytes(self) -> int:
        return self.z.nbytes

    def height(self, x, y) -> np.ndarray:
        """Bilinear height at points ``(x, y)`` (arrays broadcast)."""
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        out = np.empty(x.shape)
        grid_heights(self.params, self.z, x.ravel(), y.ravel(), out.reshape(-1))
        return out


@nb.njit(cache=True, inline="always")
def _locate(u, n):
    """Cell index and fraction for node coordinate ``u`` in a line of ``n`` nodes."""
    if u <= 0.0:
        return 0, 0.0
    if u >= n - 1:
        return n - 2, 1.0
    i = int(u)
    if i > n - 2:
        i = n - 2
    return i, u - i


@nb.njit(cache=True)
def grid_height(gp, z, x, y):
    """Bilinear road height at (x, y). ``gp`` is :attr:`RoadGrid.params`."""
    i, fx = _locate((x - gp[0]) * gp[4], z.shape[0])
    j, fy = _locate((y - gp[1]) * gp[5], z.shape[1])
    z00 = z[i, j]
    z10 = z[i + 1, j]
    z01 = z[i, j + 1]
    z11 = z[i + 1, j + 1]
    return (z00 * (1.0 - fx) + z10 * fx) * (1.0 - fy) + (z01 * (1.0 - fx) + z11 * fx) * fy


@nb.njit(cache=True)
def grid_height_gradient(gp, z, x, y):
    """Height and its gradient ``(h, dh/dx, dh/dy)`` of the bilinear surface.

    Outside the grid the surface is flat (edge extension), so the gradient
    across an edge is zero.
    """
    ux = (x - gp[0]) * gp[4]
    uy = (y - gp[1]) * gp[5]
    nx = z.shape[0]
    ny = z.shape[1]
    i, fx = _locate(ux, nx)
    j, fy = _locate(uy, ny)
    z00 = z[i, j]
    z10 = z[i + 1, j]
    z01 = z[i, j + 1]
    z11 = z[i + 1, j + 1]
    h = (z00 * (1.0 - fx) + z10 * fx) * (1.0 - fy) + (z01 * (1.0 - fx) + z11 * fx) * fy
    gx = ((z10 - z00) * (1.0 - fy) + (z11 - z01) * fy) * gp[4]
    gy = ((z01 - z00) * (1.0 - fx) + (z11 - z10) * fx) * gp[5]
    if ux <= 0.0 or ux >= nx - 1:
        gx = 0.0
    if uy <= 0.0 or uy >= ny - 1:
        gy = 0.0
    return h, gx, gy


@nb.njit(cache=True)
def grid_heights(gp, z, xs, ys, out):
    """Vectorised :func:`grid_height` over arrays of points."""
    for k in range(xs.shape[0]):
        out[k] = grid_height(gp, z, xs[k], ys[k])
