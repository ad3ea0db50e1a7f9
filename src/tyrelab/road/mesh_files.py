"""Triangle-mesh files: Wavefront ``.obj`` read (through :mod:`trimesh`) and written, grids as triangles.

OBJ has no units and no up axis: coordinates are taken as metres in the
road frame (x along the road, y to the left, z up); a y-up file must be
turned first. Polygons are split into triangles (fans). Writers put the
file in place only when it is complete (:func:`tyrelab.io_atomic.atomic_write_text`).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..io_atomic import atomic_write_text
from .base import Road
from .grid import RoadGrid
from .mesh import MeshRoad


def _obj_lines(path: Path):
    """Line number of each vertex and of each triangle (polygons fan out to n - 2 triangles)."""
    v_lines, f_lines = [], []
    with open(path, encoding="utf-8", errors="replace") as fh:
        for n, raw in enumerate(fh, start=1):
            parts = raw.split("#", 1)[0].split()
            if not parts:
                continue
            if parts[0] == "v":
                if len(parts) < 4:
                    raise InputError("a vertex needs x, y, z", source=str(path), line=n)
                try:
                    xyz = [float(p) for p in parts[1:4]]
                except ValueError:
                    raise InputError(f"non-numeric vertex coordinate in '{raw.strip()}'",
                                     source=str(path), line=n) from None
                if not all(math.isfinite(c) for c in xyz):
                    raise InputError("non-finite vertex coordinate", source=str(path), line=n)
                v_lines.append(n)
            elif parts[0] == "f":
                idx = []
                for p in parts[1:]:
                    try:
                        i = int(p.split("/")[0])
                    except ValueError:
                        raise InputError(f"bad face index '{p}'", source=str(path), line=n) from None
                    i = i if i > 0 else len(v_lines) + 1 + i
                    if not 1 <= i <= len(v_lines):
                        raise InputError(f"face refers to vertex {p}, only {len(v_lines)} defined "
                                         "above it", source=str(path), line=n)
                    idx.append(i)
                if len(idx) < 3:
                    raise InputError("a face needs at least 3 vertices", source=str(path), line=n)
                f_lines += [n] * (len(idx) - 2)
    return v_lines, f_lines


def read_obj(path, friction: float = 1.0, y_offset: float = 0.0) -> MeshRoad:
    """A :class:`MeshRoad` from a Wavefront ``.obj`` file (read by :mod:`trimesh`).

    Coordinates are taken as metres in the road frame (z up; OBJ has no
    units). Polygons are split into triangles, all with ``friction``.
    ``height(x, y)`` is the file's height at ``(x, y + y_offset)``. The file is
    first scanned line by line, so bad vertices and faces are reported with
    their line.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("no such OBJ file", source=str(path))
    _, f_lines = _obj_lines(path)
    try:
        import trimesh
    except ImportError as exc:  # pragma: no cover - a declared dependency
        raise InputError("reading .obj needs the trimesh package (pip install trimesh)",
                         source=str(path)) from exc
    try:
        mesh = trimesh.load(path, file_type="obj", force="mesh", process=False)
    except Exception as exc:  # trimesh raises ValueError / IndexError on broken files
        raise InputError(f"cannot read the OBJ mesh: {exc}", source=str(path)) from exc
    faces = np.asarray(getattr(mesh, "faces", np.empty((0, 3))), dtype=np.int64)
    if faces.size == 0:
        raise InputError("no faces in the OBJ file", source=str(path))
    v = np.array(mesh.vertices, dtype=np.float64)
    v[:, 1] -= y_offset
    lines = f_lines if len(f_lines) == len(faces) else None
    road = MeshRoad(v, faces, friction, name=f"mesh {path.name}", source=str(path), element_lines=lines)
    if y_offset:
        road.name += f" at y = {y_offset:g} m"
    return road


def write_obj(road: Road, path, spacing: tuple[float, float] | None = None) -> Path:
    """Write a road as a Wavefront ``.obj`` triangle mesh; returns the path.

    A :class:`MeshRoad` is written as its own triangles; any other road as
    its grid (``road.grid(spacing)``), each cell split into two triangles
    along the diagonal from node (i, j) to (i+1, j+1). Numbers are written
    with 17 significant digits, so nodes read back bit for bit. The file
    appears only when complete.
    """
    if isinstance(road, MeshRoad):
        v, t = road.vertices, road.triangles
    else:
        v, t = grid_triangles(road.grid(spacing))
    path = Path(path)
    body = [f"# {road.name}; written by tyrelab (metres, z up)"]
    body += ["v %.17g %.17g %.17g" % tuple(p) for p in v.tolist()]
    body += ["f %d %d %d" % tuple(f) for f in (t + 1).tolist()]
    atomic_write_text(path, "\n".join(body) + "\n")
    return path


def grid_triangles(grid: RoadGrid):
    """Nodes (n, 3) and triangles (m, 3) of a grid, two per cell, split from (i, j) to (i+1, j+1)."""
    nx, ny = grid.z.shape
    X, Y = np.meshgrid(grid.x0 + grid.dx * np.arange(nx), grid.y0 + grid.dy * np.arange(ny), indexing="ij")
    v = np.column_stack([X.ravel(), Y.ravel(), grid.z.ravel()])
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1), indexing="ij")
    n00 = (i * ny + j).ravel()
    n10, n01, n11 = n00 + ny, n00 + 1, n00 + ny + 1
    t = np.concatenate([np.column_stack([n00, n10, n11]), np.column_stack([n00, n11, n01])])
    return v, t
