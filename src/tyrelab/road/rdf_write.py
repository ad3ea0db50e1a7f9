"""Writing Adams road data files: any road as a 2D poly_line road or a 3D shell road.

See :mod:`tyrelab.road.rdf` (which re-exports :func:`write_rdf`) for what is
written and in what sense it reads back identically.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..errors import InputError
from . import rdf_profiles as P
from .base import Road
from .mesh import MeshRoad
from ..io_atomic import atomic_write_text
from .mesh_files import grid_triangles


def _rows(a: np.ndarray) -> str:
    return "\n".join(" ".join("%.17g" % x for x in r) for r in a.tolist())


_HEADER = """$---------------------------------------------------------------------UNITS
[UNITS]
LENGTH = 'meter'
FORCE = 'newton'
ANGLE = 'degree'
MASS = 'kg'
TIME = 'sec'
$---------------------------------------------------------------------MODEL
[MODEL]
METHOD = '{method}'
"""


def write_rdf(road: Road, path, method: str = "2D", spacing: tuple[float, float] | None = None,
              mu: float = 1.0, comment: str | None = None) -> Path:
    """Write any road as an Adams road data file; returns the path (see the module docstring).

    ``method`` is ``"2D"`` (a poly_line road) or ``"3D"`` (a shell road);
    ``spacing`` the grid spacing [m] sampled (default: the road's own);
    ``mu`` the friction written (a :class:`MeshRoad` keeps its own per
    triangle). Units are metres and degrees.
    """
    if not isinstance(road, Road):
        raise InputError(f"write_rdf needs a Road, not {type(road).__name__}; make one from a name with "
                         "tyrelab.road.spec.road_from_spec", field="road")
    method = str(method).upper()
    if method not in ("2D", "3D"):
        raise InputError(f"unknown method '{method}', expected '2D' or '3D'", field="method")
    if not (math.isfinite(mu) and mu >= 0):
        raise InputError(f"mu must be a finite number >= 0, got {mu}", field="mu")
    text = "".join(f"$ {line}\n" for line in (comment or f"{road.name}; written by tyrelab").splitlines())
    text += _HEADER.format(method=method)
    if method == "2D":
        g = road.grid(spacing)
        x = g.x0 + g.dx * np.arange(g.z.shape[0])
        right = road.height(x, 0.0)
        left = road.height(x, P.LEFT_TRACK_Y) if road.varies_in_y() else right
        text += ("ROAD_TYPE = 'poly_line'\n$----------------------------------------------------------------"
                 f"PARAMETERS\n[PARAMETERS]\nMU = {float(mu)!r}\nOFFSET = 0\nROTATION_ANGLE_XY_PLANE = 0\n"
                 f"$ right track along y = 0, left track along y = {P.LEFT_TRACK_Y:g} m\n(XZ_DATA)\n"
                 "{ x z_left z_right }\n" + _rows(np.column_stack([x, left, right])) + "\n")
    else:
        if isinstance(road, MeshRoad):
            v, t, m = road.vertices, road.triangles, road.mu
        else:
            v, t = grid_triangles(road.grid(spacing))
            m = np.full(len(t), float(mu))
        ids = np.arange(1, len(v) + 1)
        text += ("$---------------------------------------------------------PARAMETERS\n[PARAMETERS]\n"
                 f"MU = {float(mu)!r}\nOFFSET = 0\nROTATION_ANGLE_XY_PLANE = 0\n"
                 f"[NODES]\nNUMBER_OF_NODES = {len(v)}\n{{ node x_value y_value z_value }}\n"
                 + _rows(np.column_stack([ids, v])) + f"\n[ELEMENTS]\nNUMBER_OF_ELEMENTS = {len(t)}\n"
                 "{ node_1 node_2 node_3 mu }\n" + _rows(np.column_stack([t + 1, m])) + "\n")
    path = Path(path)
    atomic_write_text(path, text)
    return path
