"""The compiled form of every road: heights on a regular grid, bilinear.

Every road produces a :class:`RoadGrid`; its :meth:`RoadGrid.surface` is the
record the compiled contact models take (:class:`RoadSurface`: the grid, its
height bounds and block maxima). Grid node ``(i, j)`` sits at ``x0 + i*dx,
y0 + j*dy``; between nodes the height is bilinear. Outside the grid the road
continues with the height of the nearest edge node (a flat run-in and
run-out), so a tyre never falls off the end of a road.

The grid is the rigid kind of ground of the terrain interface
(:mod:`tyrelab.road.terrain`, registered as ``"rigid"`` at the bottom): the
contact models reach the functions here only through that interface, never
by name, so another kind of ground takes every model. In its terms the
grid's break lines are its x node lines (the bilinear surface is linear in x
between them on any line of constant y), a row handle ``(j, wy)`` is the
line between node rows j and j+1 at weight wy, and its blocks are the
:data:`BLOCK_LENGTH` blocks of ``RoadSurface.block_max``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numba as nb
import numpy as np

from ..errors import InputError
from .terrain_registry import TerrainKind, block_maxima, profile_breaks, register_terrain

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

    # --- the Python side of the terrain interface (terrain.Ground): what a model's
    # build may precompute from the ground

    def sampling_step(self) -> float:
        """The finest node spacing [m] (along y only when the grid varies across)."""
        return min(self.dx, self.dy if self.z.shape[1] > 2 else self.dx)

    def uniform_across(self) -> bool:
        """True when every node row is alike (a 2D profile)."""
        return bool(np.all(self.z == self.z[:, :1]))

    def profile_breaks(self) -> np.ndarray | None:
        """Per x node, the next node where a profile's slope changes; None when the grid
        varies across (:func:`~tyrelab.road.terrain.profile_breaks`)."""
        return profile_breaks(self.z)

    def row_maxima(self, length: float):
        """``(per, maxima)``: the road's maxima over blocks of ``per`` x cells (about
        ``length`` [m]) for each pair of node rows, shape ``(blocks, ny - 1)``
        (:func:`~tyrelab.road.terrain.block_maxima`); no blocks for a grid of two x nodes."""
        z = self.z
        per = max(1, int(round(length / self.dx)))
        if z.shape[0] > 2:
            return per, block_maxima(z, per)
        return per, np.zeros((0, z.shape[1] - 1))

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


# --- the grid's side of the terrain interface (tyrelab.road.terrain) -----------------------

@nb.njit(cache=True, inline="always")
def grid_range(road):
    """Lowest and highest node of the grid."""
    return road.zmin, road.zmax


@nb.njit(cache=True, inline="always")
def grid_lines(road):
    """The x node lines: first, spacing, its inverse, count."""
    return road.x0, road.dx, road.inv_dx, road.z.shape[0]


@nb.njit(cache=True, inline="always")
def grid_row(road, y):
    """``(j, wy)``: the road at y lies between node rows j and j+1, weight wy (clamped)."""
    jf = (y - road.y0) * road.inv_dy
    ny = road.z.shape[1]
    if jf >= ny - 1:
        return ny - 2, 1.0
    if jf > 0.0:
        j = min(int(jf), ny - 2)
        return j, jf - j
    return 0, 0.0


@nb.njit(cache=True, inline="always")
def grid_line_height(road, row, weight, k):
    """Height at x node k on the line between node rows ``row``, ``row + 1``."""
    z = road.z
    return z[k, row] * (1.0 - weight) + z[k, row + 1] * weight


@nb.njit(cache=True, inline="always")
def grid_blocks(road):
    """The blocks of ``road.block_max``: first x, length, count."""
    return road.block_x0, road.block_dx, road.block_max.shape[0]


@nb.njit(cache=True, inline="always")
def grid_block_max(road, i):
    """``road.block_max`` of block i, the end blocks beyond the ends."""
    n = road.block_max.shape[0]
    k = i if i >= 0 else 0
    if k > n - 1:
        k = n - 1
    return road.block_max[k]


register_terrain(TerrainKind(
    "rigid", RoadSurface, height=road_height, height_gradient=road_height_gradient,
    penetration=road_penetration, zmax=local_zmax, range=grid_range, lines=grid_lines,
    row=grid_row, line_height=grid_line_height,
    blocks=grid_blocks, block_max=grid_block_max,
    description="rigid road: heights on a regular grid, bilinear between nodes"))
