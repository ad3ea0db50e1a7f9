"""Triangle-mesh roads: heights queried exactly on the triangles, friction per triangle.

A :class:`MeshRoad` is a set of triangles in the road frame (x along the
road, y to the left, z up; metres), each with its own friction coefficient.
It comes from an Adams 3D shell road (:func:`tyrelab.road.rdf.read_rdf`), a
Wavefront ``.obj`` file (:func:`tyrelab.road.mesh_files.read_obj`, read
through :mod:`trimesh`) or any arrays of nodes and triangles.

Conventions
-----------
* **Height.** ``h(x, y)`` is the height of the triangle whose projection on
  the xy plane contains (x, y), linear on it (barycentric interpolation of
  its three nodes). Where several triangles contain the point (a shared
  edge, a wall's top edge, overlapping layers such as a bridge over a road)
  the *highest* is taken. A point on an edge counts as inside within a
  barycentric tolerance of 1e-10 of the triangle's size.
* **Walls.** Triangles whose projection has no area (vertical faces: the
  sides of a cleat, a kerb) carry no height of their own: the surfaces on
  either side meet along the wall's line, where the highest wins, so a
  wall is a step.
* **Outside the mesh** (beyond its outline, or in a hole) the height is the
  one of the nearest point of the mesh's boundary edges (edges used by one
  upward-facing triangle only): the surface continues flat outwards from its
  rim. For a mesh whose outline is its bounding rectangle this is exactly
  what the compiled grid does beyond its edges (the nearest edge node).
* **Run start.** A run starts :data:`RUN_IN` before the first crease (see
  below), as the obstacle roads start 5 m before their obstacle; a single
  plane starts at its first node.
* **Friction.** ``friction(x, y)`` is the coefficient of the triangle that
  gives the height (outside: of the triangle owning the nearest boundary edge).
* **Search.** A uniform bucket grid over the xy bounding box lists the
  triangles overlapping each bucket (built with numpy, bucket size about
  one triangle); a query tests only its bucket's triangles.
* **Compiled grid.** :meth:`MeshRoad.grid` samples the exact heights at the
  nodes of a regular grid, which the kernels interpolate bilinearly -- it is
  a cache, not the road (kept per spacing). It is exact at its nodes and in
  every cell lying within one triangle (a plane is its own bilinear
  interpolant). In a cell that triangle edges cross, on a continuous mesh,
  the error is at most twice the largest difference between the slopes of
  the triangles there times the cell diagonal; next to a wall it reaches
  the wall's height within one cell. The grid is aligned to the mesh's
  *creases* (nodes on walls and on edges where the slope changes): when
  their x (y) lie on a lattice, all of them are grid lines, so walls across
  x or y stay sharp; the lattice is refined to at most :data:`MESH_SPACING`
  and coarsened only to keep the grid within :data:`MAX_GRID_NODES`.
  :meth:`MeshRoad.grid_error` measures the error. Measured: 0.1 mm on a
  Delaunay mesh of a 50 mm undulation (bound 4.2 mm), 1.2 mm on the ASAM
  belgian block triangulated (the triangles against their own 5 mm grid).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..limits import MAX_ROAD_HEIGHT
from .base import Road
from .grid import RoadGrid

#: why a mesh of walls or of heights of many metres is usually a Y-up export
Y_UP_HINT = ("is it exported Y-up, as Blender and glTF do? tyrelab reads x along the road, "
             "y across and z up")

#: finest grid spacing [m] the compiled grid of a mesh is refined to (sharp edges)
MESH_SPACING = 0.005
#: largest number of nodes of a compiled grid chosen by default (32 MB)
MAX_GRID_NODES = 4_000_000
#: barycentric tolerance of the point-in-triangle test
BARY_TOL = 1e-10
#: distance [m] a run starts before a road's first feature (as the obstacle roads: 5 m)
RUN_IN = 5.0
#: candidate (point, triangle) pairs handled at once (memory bound of a query)
_PAIRS = 2_000_000


def lattice_spacing(coords, target: float = MESH_SPACING) -> tuple[float, bool]:
    """A spacing <= ``target`` putting every coordinate on a node, and whether one exists.

    The coarsest lattice holding all coordinates (relative to the smallest)
    is sought as the smallest gap between them divided by 1 to 12, else as
    the greatest common divisor of the coordinates in nanometres; it is then
    refined to ``d / ceil(d / target)``. When no lattice of at least
    ``target / 4`` holds them (to 1e-6 of a cell), returns ``(target, False)``:
    the grid then only samples the road.
    """
    c = np.unique(np.asarray(coords, float))
    if c.size < 2:
        return float(target), True
    rel = c - c[0]
    found = None
    for k in range(1, 13):
        d = float(np.min(np.diff(c))) / k
        if d < target / 4:
            break
        snapped = round(d * 1e9) / 1e9  # a gap of 0.04999999999999982 is 50 mm
        for d in (snapped, d) if abs(snapped - d) < 1e-12 else (d,):
            u = rel / d
            if np.max(np.abs(u - np.rint(u))) < 1e-6:
                found = d
                break
        if found is not None:
            break
    if found is None and rel[-1] < 1e9:
        ticks = np.rint(rel * 1e9)
        if np.max(np.abs(rel * 1e9 - ticks)) < 1e-3:
            found = int(np.gcd.reduce(ticks.astype(np.int64))) / 1e9
    if found is None or found < target / 4:
        return float(target), False
    return found / math.ceil(found / target - 1e-9), True


def fit_budget(extent, spacing, max_nodes: int = MAX_GRID_NODES, two_rows: bool = False):
    """``spacing`` coarsened by a whole factor until the grid over ``extent`` has <= ``max_nodes``."""
    xmin, xmax, ymin, ymax = extent
    dx, dy = spacing
    k = 1
    while True:
        nx = (xmax - xmin) / (k * dx) + 1
        ny = 2 if two_rows else (ymax - ymin) / (k * dy) + 1
        if nx * ny <= max_nodes:
            return (k * dx, k * dy)
        k += 1


class _Buckets:
    """Uniform bucket grid over the xy bounding box: the triangles overlapping each bucket."""

    def __init__(self, x0, y0, x1, y1):
        self.lo = np.array([x0.min(), y0.min()])
        span = np.maximum(np.array([x1.max(), y1.max()]) - self.lo, 1e-9)
        n = len(x0)
        h = math.sqrt(span[0] * span[1] / n)
        while True:  # coarser buckets while long triangles would be listed too often
            self.h = np.maximum(h, span / 4000.0)
            self.nb = np.floor(span / self.h).astype(np.int64) + 1
            i0, i1 = self._cell(x0, 0), self._cell(x1, 0)
            j0, j1 = self._cell(y0, 1), self._cell(y1, 1)
            counts = (i1 - i0 + 1) * (j1 - j0 + 1)
            if counts.sum() <= 8 * n + 1_000_000:
                break
            h *= 2.0
        tri = np.repeat(np.arange(n), counts)
        k = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        w = (i1 - i0 + 1)[tri]
        cell = (i0[tri] + k % w) * self.nb[1] + (j0[tri] + k // w)
        order = np.argsort(cell, kind="stable")
        self.tris = tri[order]
        self.start = np.searchsorted(cell[order], np.arange(self.nb[0] * self.nb[1] + 1))
        #: mean number of triangles listed per bucket
        self.load = self.tris.size / (self.nb[0] * self.nb[1])

    def _cell(self, u, axis):
        return np.clip(np.floor((u - self.lo[axis]) / self.h[axis]).astype(np.int64), 0, self.nb[axis] - 1)

    def pairs(self, px, py):
        """(point index, triangle index) of every triangle listed in each point's bucket."""
        hi = self.lo + self.nb * self.h
        inside = ((px >= self.lo[0] - 1e-9 * self.h[0]) & (py >= self.lo[1] - 1e-9 * self.h[1])
                  & (px <= hi[0]) & (py <= hi[1]))
        pts = np.flatnonzero(inside)
        cell = self._cell(px[pts], 0) * self.nb[1] + self._cell(py[pts], 1)
        first, counts = self.start[cell], self.start[cell + 1] - self.start[cell]
        p = np.repeat(pts, counts)
        k = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        return p, self.tris[np.repeat(first, counts) + k]


class MeshRoad(Road):
    """A road made of triangles, queried exactly (see the module docstring).

    Parameters
    ----------
    vertices : array (n, 3)
        Node coordinates x, y, z [m] in the road frame.
    triangles : int array (m, 3)
        Node indices (0-based) of each triangle.
    friction : float or array (m,)
        Friction coefficient of each triangle (>= 0).
    name : str
        Description.
    source : str, optional
        File the mesh came from, and ``element_lines`` the line of each
        triangle in it: bad triangles are reported there.
    """

    def __init__(self, vertices, triangles, friction=1.0, name: str = "triangle mesh",
                 source: str | None = None, element_lines=None):
        v = np.ascontiguousarray(vertices, dtype=np.float64)
        t = np.asarray(triangles)
        self.name, self.source = name, source

        def bad(msg, k=None):
            line = None if k is None or element_lines is None else int(element_lines[k])
            return InputError(msg, source=source, line=line, field=None if line else "mesh")

        if v.ndim != 2 or v.shape[1] != 3 or len(v) < 3:
            raise bad(f"a mesh needs at least 3 nodes of x, y, z; got an array of shape {v.shape}")
        if not np.all(np.isfinite(v)):
            raise bad(f"node {int(np.flatnonzero(~np.isfinite(v).all(axis=1))[0]) + 1} has a "
                      "non-finite coordinate")
        if np.abs(v[:, 2]).max() > MAX_ROAD_HEIGHT:
            raise bad(f"node {int(np.argmax(np.abs(v[:, 2]))) + 1} is {np.abs(v[:, 2]).max():.3g} m "
                      f"from z = 0; road heights are at most {MAX_ROAD_HEIGHT:g} m ({Y_UP_HINT})")
        if t.ndim != 2 or t.shape[1] != 3 or len(t) < 1 or not np.issubdtype(t.dtype, np.integer):
            raise bad(f"a mesh needs at least one triangle of 3 integer node indices; got {t.shape}")
        out = np.flatnonzero(((t < 0) | (t >= len(v))).any(axis=1))
        if out.size:
            raise bad(f"triangle {out[0] + 1} refers to a node that does not exist "
                      f"(indices {t[out[0]].tolist()}, {len(v)} nodes)", out[0])
        mu = np.broadcast_to(np.asarray(friction, float), (len(t),)).copy()
        if not np.all(np.isfinite(mu) & (mu >= 0)):
            k = int(np.flatnonzero(~(np.isfinite(mu) & (mu >= 0)))[0])
            raise bad(f"triangle {k + 1} has friction {mu[k]}; expected a finite number >= 0", k)
        a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
        scale2 = np.maximum.reduce([((b - a) ** 2).sum(1), ((c - b) ** 2).sum(1), ((a - c) ** 2).sum(1)])
        area2 = np.linalg.norm(np.cross(b - a, c - a), axis=1)
        degenerate = np.flatnonzero(~(area2 > 1e-12 * scale2))
        if degenerate.size:
            k = int(degenerate[0])
            raise bad(f"triangle {k + 1} is degenerate: its nodes {t[k].tolist()} are repeated or "
                      "collinear (no area)", k)
        self.vertices, self.triangles, self.mu = v, t.astype(np.int64), mu
        # upward or downward facing triangles carry heights; vertical ones (walls) do not
        det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
        face = np.abs(det) > 1e-12 * scale2
        if not face.any():
            raise bad("no triangle faces up: every triangle is vertical, the mesh has no surface "
                      f"({Y_UP_HINT})")
        self._face = np.flatnonzero(face)
        a, b, c, det = a[face], b[face], c[face], det[face]
        self._a = a
        # barycentric (l1, l2) = inv(T) (p - a), T = [[bx-ax, cx-ax], [by-ay, cy-ay]]
        self._inv = np.stack([np.stack([c[:, 1] - a[:, 1], a[:, 0] - c[:, 0]], 1),
                              np.stack([a[:, 1] - b[:, 1], b[:, 0] - a[:, 0]], 1)], 1) / det[:, None, None]
        self._dz = np.stack([b[:, 2] - a[:, 2], c[:, 2] - a[:, 2]], 1)
        xs, ys = np.stack([a[:, 0], b[:, 0], c[:, 0]]), np.stack([a[:, 1], b[:, 1], c[:, 1]])
        self._buckets = _Buckets(xs.min(0), ys.min(0), xs.max(0), ys.max(0))
        self._boundary = self._boundary_edges()
        fv = v[t[self._face]].reshape(-1, 3)
        self._bbox = (float(fv[:, 0].min()), float(fv[:, 0].max()),
                      float(fv[:, 1].min()), float(fv[:, 1].max()))
        self._grids: dict = {}
        self._varies: bool | None = None
        nodes, bends = self._crease_nodes(face)
        crease = v[nodes]
        self._lattice = (lattice_spacing(crease[:, 0])[0], lattice_spacing(crease[:, 1])[0])
        self._anchor = (float(crease[:, 0].min()), float(crease[:, 1].min()))
        #: x [m] where a run starts: RUN_IN before the first crease (a plane: its first node)
        self.run_start = self._anchor[0] - RUN_IN if bends else self._bbox[0]

    def _crease_nodes(self, face):
        """Nodes where the surface bends: on walls and on edges between triangles of different planes.

        The compiled grid is aligned to them (all of them on grid lines when they lie on a lattice);
        a mesh without any (one plane) uses all its nodes. Returns the nodes and whether any bends.
        """
        g = np.einsum("ki,kij->kj", self._dz, self._inv)  # (dz/dx, dz/dy) of each upward triangle
        t = self.triangles[self._face]
        e = np.sort(np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
        key = e[:, 0] * len(self.vertices) + e[:, 1]
        owner = np.tile(np.arange(len(t)), 3)
        order = np.argsort(key, kind="stable")
        ks, os_ = key[order], owner[order]
        pair = np.flatnonzero(ks[1:] == ks[:-1])
        g1, g2 = g[os_[pair]], g[os_[pair + 1]]
        bend = np.abs(g1 - g2).max(axis=1) > 1e-9 * (1 + np.abs(g1).max(axis=1))
        nodes = [e[order[pair[bend]]].ravel(), self.triangles[~face].ravel()]
        nodes = np.unique(np.concatenate(nodes))
        return (nodes, True) if nodes.size else (np.unique(t), False)

    # --- exact queries ------------------------------------------------------

    def _boundary_edges(self):
        """Edges used by one upward-facing triangle only: (node a, node b, owning triangle)."""
        t = self.triangles[self._face]
        e = np.sort(np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
        owner = np.tile(self._face, 3)
        _, first, counts = np.unique(e[:, 0] * len(self.vertices) + e[:, 1], return_index=True,
                                     return_counts=True)
        once = first[counts == 1]
        return e[once, 0], e[once, 1], owner[once]

    def locate(self, x, y):
        """Height [m] and index of the highest triangle containing each point (-1: outside)."""
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        px, py = x.ravel(), y.ravel()
        z = np.full(px.size, -np.inf)
        tri = np.full(px.size, -1, dtype=np.int64)
        step = max(4096, int(_PAIRS / max(1.0, 2.0 * self._buckets.load)))
        for s in range(0, px.size, step):
            sl = slice(s, s + step)
            p, k = self._buckets.pairs(px[sl], py[sl])
            dx = px[sl][p] - self._a[k, 0]
            dy = py[sl][p] - self._a[k, 1]
            l1 = self._inv[k, 0, 0] * dx + self._inv[k, 0, 1] * dy
            l2 = self._inv[k, 1, 0] * dx + self._inv[k, 1, 1] * dy
            ok = (l1 >= -BARY_TOL) & (l2 >= -BARY_TOL) & (l1 + l2 <= 1 + BARY_TOL)
            p, k = p[ok], k[ok]
            zk = self._a[k, 2] + l1[ok] * self._dz[k, 0] + l2[ok] * self._dz[k, 1]
            zs = z[sl]
            np.maximum.at(zs, p, zk)
            top = zk == zs[p]
            tri[sl][p[top]] = self._face[k[top]]
            z[sl] = zs
        return z.reshape(x.shape), tri.reshape(x.shape)

    def _nearest_edge(self, px, py):
        """Height and owning triangle of the nearest boundary-edge point of each (outside) point."""
        ea, eb, owner = self._boundary
        A, B = self.vertices[ea], self.vertices[eb]
        d = B - A
        L2 = np.maximum((d[:, :2] ** 2).sum(1), 1e-300)
        z = np.empty(px.size)
        tri = np.empty(px.size, dtype=np.int64)
        step = max(1, _PAIRS // max(1, len(ea)))
        for s in range(0, px.size, step):
            qx, qy = px[s:s + step, None], py[s:s + step, None]
            t = np.clip(((qx - A[:, 0]) * d[:, 0] + (qy - A[:, 1]) * d[:, 1]) / L2, 0.0, 1.0)
            dist = (A[:, 0] + t * d[:, 0] - qx) ** 2 + (A[:, 1] + t * d[:, 1] - qy) ** 2
            j = np.argmin(dist, axis=1)
            rows = np.arange(j.size)
            z[s:s + step] = A[j, 2] + t[rows, j] * d[j, 2]
            tri[s:s + step] = owner[j]
        return z, tri

    def _query(self, x, y):
        z, tri = self.locate(x, y)
        out = tri < 0
        if out.any():
            x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
            z[out], tri[out] = self._nearest_edge(x[out], y[out])
        return z, tri

    def height(self, x, y) -> np.ndarray:
        """Exact height [m]: the highest triangle over (x, y); outside, the nearest rim point."""
        return self._query(x, y)[0]

    def friction(self, x, y) -> np.ndarray:
        """Friction coefficient of the triangle giving the height at (x, y)."""
        return self.mu[self._query(x, y)[1]]

    # --- the compiled grid (a cache) ----------------------------------------

    def extent(self) -> tuple[float, float, float, float]:
        """The xy bounding box of the upward-facing triangles, widened to the grid's aligned nodes."""
        return self._aligned(*self.default_spacing)

    def _aligned(self, dx, dy):
        """The bounding box widened so the first crease node lies on the grid."""
        xmin, xmax, ymin, ymax = self._bbox
        x0 = self._anchor[0] - dx * math.ceil((self._anchor[0] - xmin) / dx - 1e-9)
        if not self.varies_in_y():
            return (x0, xmax, ymin, ymax)
        y0 = self._anchor[1] - dy * math.ceil((self._anchor[1] - ymin) / dy - 1e-9)
        return (x0, xmax, y0, ymax)

    @property
    def default_spacing(self) -> tuple[float, float]:
        """The nodes' lattice refined to <= :data:`MESH_SPACING`, within :data:`MAX_GRID_NODES`."""
        return fit_budget(self._bbox, self._lattice, two_rows=not self.varies_in_y())

    def varies_in_y(self) -> bool:
        """False when no triangle slopes across y and every cross section is the same."""
        if self._varies is None:
            grad_y = self._dz[:, 0] * self._inv[:, 0, 1] + self._dz[:, 1] * self._inv[:, 1, 1]
            two_d = bool(np.all(np.abs(grad_y) <= 1e-12))
            if two_d:
                xmin, xmax, ymin, ymax = self._bbox
                xs = np.linspace(xmin, xmax, int(min(2e5, (xmax - xmin) / self._lattice[0] + 1)))
                rows = self.height(xs[None, :], np.linspace(ymin, ymax, 7)[:, None])
                two_d = bool(np.all(np.abs(rows - rows[:1]) <= 1e-12 * max(1.0, np.abs(rows).max())))
            self._varies = not two_d
        return self._varies

    def grid(self, spacing: tuple[float, float] | None = None) -> RoadGrid:
        """The exact heights sampled on a regular grid (cached per spacing).

        The grid covers the mesh with its origin placed so that the first
        crease node (see the module docstring) is a node.
        """
        key = tuple(float(s) for s in (spacing or self.default_spacing))
        if key not in self._grids:
            dx, dy = key
            x0, x1, y0, y1 = self._aligned(dx, dy)
            xs = x0 + dx * np.arange(int(math.ceil((x1 - x0) / dx - 1e-9)) + 1)
            if self.varies_in_y():
                ys = y0 + dy * np.arange(int(math.ceil((y1 - y0) / dy - 1e-9)) + 1)
            else:
                ys, dy = np.array([y0, y1]), y1 - y0
            X, Y = np.meshgrid(xs, ys, indexing="ij")
            self._grids[key] = RoadGrid(x0, y0, dx, dy, self.height(X, Y))
        return self._grids[key]

    def grid_error(self, spacing: tuple[float, float] | None = None, samples: int = 200_000,
                   seed: int = 0) -> float:
        """Largest |grid - exact| height [m] at ``samples`` random points inside the extent."""
        g = self.grid(spacing)
        xmin, xmax, ymin, ymax = self.extent()
        rng = np.random.default_rng(seed)
        x, y = rng.uniform(xmin, xmax, samples), rng.uniform(ymin, ymax, samples)
        return float(np.max(np.abs(g.height(x, y) - self.height(x, y))))
