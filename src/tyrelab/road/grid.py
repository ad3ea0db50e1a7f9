"""The compiled form of every road: heights on a regular grid, bilinear.

Every road produces a :class:`RoadGrid`; its :meth:`RoadGrid.surface` is the
record the compiled contact models take (:class:`RoadSurface`: the grid, its
height bounds and block maxima), and they query it only through the compiled
functions here, never through Python road objects inside a time step. Grid
node ``(i, j)`` sits at ``x0 + i*dx, y0 + j*dy``; between nodes the height is
bilinear. Outside the grid the road continues with the height
of the nearest edge node (a flat run-in and run-out), so a tyre never falls
off the end of a road.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numba as nb
import numpy as np

from ..errors import InputError

#: length along x of the road blocks whose maximum height bounds a contact search [m]
BLOCK_LENGTH = 0.04


class RoadSurface(NamedTuple):
    """The compiled form of a road: a regular grid with its height bounds.

    Node ``(i, j)`` sits at ``(x0 + i dx, y0 + j dy)``; heights are bilinear
    between nodes and continue flat beyond the edges. ``block_max[k]`` is the
    highest road point over all y for x in ``[block_x0 + k block_dx,
    block_x0 + (k + 1) block_dx]``; contact models use it to skip road no
    tyre part can reach (:func:`local_zmax`).
    """

    x0: float
    y0: float
    dx: float
    dy: float
    inv_dx: float
    inv_dy: float
    z: np.ndarray
    zmin: float
    zmax: float
    block_x0: float
    block_dx: float
    block_max: np.ndarray


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
            raise InputError("a road grid needs at least 2 x 2 nodes", field="road")
        if not np.all(np.isfinite(z)):
            raise InputError("a road grid must be finite; fill empty cells first", field="road")
        if not (math.isfinite(self.dx) and math.isfinite(self.dy) and self.dx > 0 and self.dy > 0):
            raise InputError(f"grid spacing must be positive and finite, got {self.dx}, {self.dy}",
                             field="road")
        if not (math.isfinite(self.x0) and math.isfinite(self.y0)):
            raise InputError(f"grid origin must be finite, got {self.x0}, {self.y0}", field="road")
        object.__setattr__(self, "z", z)

    def surface(self) -> RoadSurface:
        """The record the compiled kernels take (built once per grid)."""
        cached = self.__dict__.get("_surface")
        if cached is None:
            cached = _surface(self)
            object.__setattr__(self, "_surface", cached)
        return cached

    @property
    def nbytes(self) -> int:
        return self.z.nbytes

    def height(self, x, y) -> np.ndarray:
        """Bilinear height at points ``(x, y)`` (arrays broadcast)."""
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        out = np.empty(x.shape)
        road_heights(self.surface(), x.ravel(), y.ravel(), out.reshape(-1))
        return out


def _surface(grid: RoadGrid) -> RoadSurface:
    # one array type for every road (writeable, C order), so a rig loop compiles once per model
    z = grid.z if grid.z.flags.writeable else grid.z.copy()
    per = max(1, int(round(BLOCK_LENGTH / grid.dx)))
    nblocks = -(-z.shape[0] // per)
    col = z.max(axis=1)
    # a block's maximum includes its right edge node (bilinear cells span nodes)
    ends = np.minimum(np.arange(1, nblocks + 1) * per + 1, z.shape[0])
    maxima = np.maximum.reduceat(col, np.arange(nblocks) * per)
    maxima = np.maximum(maxima, col[ends - 1])
    return RoadSurface(float(grid.x0), float(grid.y0), float(grid.dx), float(grid.dy),
                       1.0 / grid.dx, 1.0 / grid.dy, z, float(z.min()), float(z.max()),
                       float(grid.x0), per * grid.dx, np.ascontiguousarray(maxima, np.float64))


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
def road_height(road, x, y):
    """Bilinear height [m] of :class:`RoadSurface` ``road`` at (x, y)."""
    z = road.z
    i, fx = _locate((x - road.x0) * road.inv_dx, z.shape[0])
    j, fy = _locate((y - road.y0) * road.inv_dy, z.shape[1])
    z00 = z[i, j]
    z10 = z[i + 1, j]
    z01 = z[i, j + 1]
    z11 = z[i + 1, j + 1]
    return (z00 * (1.0 - fx) + z10 * fx) * (1.0 - fy) + (z01 * (1.0 - fx) + z11 * fx) * fy


# inlined, as road_penetration: no call (and no reference counting) per query in
# the ring's compiled contact loops
@nb.njit(cache=True, inline="always")
def road_height_gradient(road, x, y):
    """Height and its gradient ``(h, dh/dx, dh/dy)`` of the bilinear surface.

    Outside the grid the surface is flat (edge extension), so the gradient
    across an edge is zero. (:func:`road_penetration` below a point no road reaches.)
    """
    _, h, gx, gy = road_penetration(road, x, y, -math.inf)
    return h, gx, gy


@nb.njit(cache=True, inline="always")
def road_penetration(road, x, y, zq):
    """``(h - zq, h, dh/dx, dh/dy)`` at (x, y), the gradient only where ``h > zq``.

    The same height and gradient as :func:`road_height_gradient` (the same
    arithmetic); where the point at height ``zq`` is above the road
    (``h <= zq``) the gradient is not computed and returned as 0.
    """
    z = road.z
    ux = (x - road.x0) * road.inv_dx
    uy = (y - road.y0) * road.inv_dy
    nx = z.shape[0]
    ny = z.shape[1]
    i, fx = _locate(ux, nx)
    j, fy = _locate(uy, ny)
    z00 = z[i, j]
    z10 = z[i + 1, j]
    z01 = z[i, j + 1]
    z11 = z[i + 1, j + 1]
    h = (z00 * (1.0 - fx) + z10 * fx) * (1.0 - fy) + (z01 * (1.0 - fx) + z11 * fx) * fy
    p = h - zq
    if p <= 0.0:
        return p, h, 0.0, 0.0
    gx = ((z10 - z00) * (1.0 - fy) + (z11 - z01) * fy) * road.inv_dx
    gy = ((z01 - z00) * (1.0 - fx) + (z11 - z10) * fx) * road.inv_dy
    if ux <= 0.0 or ux >= nx - 1:
        gx = 0.0
    if uy <= 0.0 or uy >= ny - 1:
        gy = 0.0
    return p, h, gx, gy


@nb.njit(cache=True)
def road_heights(road, xs, ys, out):
    """Vectorised :func:`road_height` over arrays of points."""
    for k in range(xs.shape[0]):
        out[k] = road_height(road, xs[k], ys[k])


@nb.njit(cache=True, inline="always")
def local_zmax(road, x0, x1):
    """Highest road point [m] over road x in [x0, x1], from the block maxima."""
    blocks = road.block_max
    nb_ = blocks.shape[0]
    i0 = int(math.floor((x0 - road.block_x0) / road.block_dx))
    i1 = int(math.floor((x1 - road.block_x0) / road.block_dx))
    if i0 < 0:
        i0 = 0
    if i1 > nb_ - 1:
        i1 = nb_ - 1
    if i1 < i0:  # beyond the grid: the edge blocks continue
        i0 = i1 = 0 if x1 < road.block_x0 else nb_ - 1
    m = -1e300
    for i in range(i0, i1 + 1):
        if blocks[i] > m:
            m = blocks[i]
    return m
