"""OpenCRG road files: read any ``.crg`` as a :class:`Road`, write any road as ``.crg``.

Reading goes through :mod:`pycrg`, the Python binding of the ASAM OpenCRG
reference C library (ASAM OpenCRG 1.2.0), so the file formats (KRBI, KDBI,
LRFI, LDFI), straight and curved reference lines, slope, banking and the
minimalist header are interpreted exactly as the reference does (the
pure-Python ``pyopencrg`` serves as the independent second reader in the tests).
The C loader is lenient about headers (it loads a misspelt ``$ROAD_CRG`` block
or an unknown ``#:`` format), so the header is checked here first.

Conventions
-----------
* **No modifiers.** The data is used as stored in the file: the C library is
  opened with ``apply_modifiers=False``, so neither OpenCRG's default
  modifiers (which move the reference line start to z = 0) nor a file's own
  ``$ROAD_CRG_MODS`` are applied. Heights are absolute as in the file.
* **Road coordinates.** ``x = u`` (along the reference line) and
  ``y = v - v_offset`` (lateral, positive left). The reference line's
  curvature is not represented: the road is straightened along u, which is
  what a trailer following the reference line sees.
* **Height.** ``z(u, v) = z_grid(u, v) + z_ref(u) + bank(u) * v``, bilinear
  between the nodes (OpenCRG's ``crgEvaluv2z``); the elevation is stored
  on the file's own (u, v) nodes so the compiled grid reproduces the C library.
  Long sections at uneven v (explicit ``D:long section at v = ...``) are
  refined to the greatest common step of their spacings, a grid holding every
  original node, which is exact under bilinear interpolation.
* **Minimalist headers** (only ``LONG_SECTION_V_INCREMENT`` given): v runs
  from 0 to the width, as in the C library (the MATLAB tools centre it).
* **Empty cells** (``NaN``, ``*missing*``): each cross section (fixed u) is
  filled along v: a border cell takes the last valid value towards the
  inside (OpenCRG's default ``GRID_NAN_KEEP_LAST``), a cell between valid
  cells is interpolated linearly between them. A cross section with no valid
  value at all is an input error. So the grid is always finite.
"""

from __future__ import annotations

import os
from math import gcd
from pathlib import Path

import numpy as np

from ..errors import InputError
from .base import GriddedRoad, Road
from .grid import RoadGrid

#: the four OpenCRG data formats: K/L = binary/text, R/D = single/double
CRG_FORMATS = ("KRBI", "KDBI", "LRFI", "LDFI")


def _header(path: Path):
    """Parse and check the header; :class:`InputError` naming the file if it is bad."""
    import pycrg

    try:
        header = pycrg.read_header(path)
    except Exception as exc:  # pycrg raises OSError / ValueError on unreadable headers
        raise InputError(f"cannot read the OpenCRG header: {exc}", source=str(path)) from exc
    if not header.road:
        raise InputError("bad OpenCRG header: no $ROAD_CRG block with road parameters",
                         source=str(path))
    fmt = (header.data_format or "").upper()
    if fmt not in CRG_FORMATS:
        raise InputError(f"bad OpenCRG header: data format '#:{header.data_format}' is not one of "
                         f"{', '.join(CRG_FORMATS)}", source=str(path), field="$KD_DEFINITION")
    inc = header.road.get("reference_line_increment")
    if not isinstance(inc, float) or not inc > 0:
        raise InputError("bad OpenCRG header: REFERENCE_LINE_INCREMENT must be a positive number",
                         source=str(path), field="reference_line_increment")
    if header.long_section_count < 2:
        raise InputError("bad OpenCRG header: at least 2 long sections ('D:long section ...') needed, "
                         f"found {header.long_section_count}", source=str(path), field="$KD_DEFINITION")
    return header


def _data_offset(path: Path) -> int | None:
    """Byte offset of the data section: after the ``$$$$...`` separator line."""
    offset = 0
    with open(path, "rb") as fh:
        for raw in fh:
            offset += len(raw)
            line = raw.strip()
            if len(line) >= 4 and set(line) == {ord("$")}:
                return offset
    return None


def _check_binary_length(path: Path, header) -> None:
    """A binary data section must hold a whole number of 80-byte IPLOS blocks of values.

    A few white-space bytes after the data (a final newline) are tolerated, as
    by the C library.
    """
    fmt = header.data_format.upper()
    if fmt[0] != "K":
        return
    offset = _data_offset(path)
    if offset is None:
        raise InputError("bad OpenCRG file: no '$$$$' line separating header and binary data",
                         source=str(path))
    nbytes = path.stat().st_size - offset
    extra = nbytes % 80
    if extra and extra < 8:
        with open(path, "rb") as fh:
            fh.seek(offset + nbytes - extra)
            if not fh.read(extra).strip():
                nbytes -= extra
    itemsize = 4 if fmt == "KRBI" else 8
    nchan = len(header.channels)
    if nbytes <= 0 or nbytes % 80 or nbytes % itemsize:
        raise InputError(f"truncated or corrupted OpenCRG file: {nbytes} bytes of {fmt} data is not a "
                         f"whole number of 80-byte records of {itemsize}-byte values", source=str(path))
    if nchan and nbytes // itemsize < 2 * nchan:
        raise InputError(f"truncated OpenCRG file: {nbytes} bytes of data hold fewer than 2 cross "
                         f"sections of {nchan} channels", source=str(path))


def _load_grid(path: Path):
    """The file's arrays as the C library reads them (no modifiers), and its u increment."""
    import pycrg

    try:
        with pycrg.DataSet.open(path, apply_modifiers=False) as ds:
            return ds.grid(), float(ds.increments()[0])
    except pycrg.OpenCRGError as exc:
        reasons = [text.strip() for level, text in getattr(exc, "messages", ()) if level <= 2]
        why = "; ".join(reasons) or str(exc)
        raise InputError(f"OpenCRG cannot load the file: {why}", source=str(path)) from exc


def fill_empty_cells(z: np.ndarray, source: str = "OpenCRG data") -> np.ndarray:
    """Fill NaN cells along each cross section (row) by the stated policy.

    Border cells keep the last valid value (OpenCRG ``GRID_NAN_KEEP_LAST``);
    interior cells are linear between their valid neighbours.
    """
    z = np.array(z, dtype=np.float64)
    bad = ~np.isfinite(z)
    if not bad.any():
        return z
    cols = np.arange(z.shape[1])
    for i in np.flatnonzero(bad.any(axis=1)):
        ok = ~bad[i]
        if not ok.any():
            raise InputError(f"cross section {i} (row {i + 1} of the data) has no valid height",
                             source=source)
        z[i] = np.interp(cols, cols[ok], z[i, ok])  # np.interp holds the end values
    return z


def _regular_v(v: np.ndarray, max_nodes: int = 100_000) -> tuple[float, np.ndarray]:
    """A regular v-step whose nodes include every long section (exact refinement).

    Uses the greatest common divisor of the steps in micrometres; when that
    would give more than ``max_nodes`` nodes, the smallest step (resampled).
    """
    steps_um = np.rint(np.diff(v) * 1e6).astype(np.int64)
    dv_um = 0
    for s in steps_um:
        dv_um = gcd(dv_um, int(s))
    dv = dv_um * 1e-6
    nodes = v[0] + dv * np.arange(int(round((v[-1] - v[0]) / dv)) + 1) if dv > 0 else v
    if dv <= 0 or len(nodes) > max_nodes or np.max(np.abs(np.interp(v, nodes, nodes) - v)) > 1e-9:
        dv = float(np.min(np.diff(v)))
        nodes = v[0] + dv * np.arange(int(np.floor((v[-1] - v[0]) / dv + 1e-9)) + 1)
    return dv, nodes


class CrgRoad(GriddedRoad):
    """An OpenCRG road file as a :class:`Road` (see the module docstring).

    Parameters
    ----------
    path : str or Path
        The ``.crg`` file.
    v_offset : float
        Lateral offset [m] of the trailer's path from the reference line:
        ``height(x, y)`` is the file's height at ``u = x, v = y + v_offset``.
    """

    def __init__(self, path, v_offset: float = 0.0):
        self.path = Path(path)
        if not self.path.is_file():
            raise InputError("no such OpenCRG file", source=str(self.path))
        self.v_offset = float(v_offset)
        self.header = _header(self.path)
        _check_binary_length(self.path, self.header)
        g, du = _load_grid(self.path)
        z = fill_empty_cells(g.z, source=str(self.path))
        elevation = z + g.ref_z[:, None] + g.bank[:, None] * g.v[None, :]
        dv, v_nodes = _regular_v(g.v)
        if len(v_nodes) != len(g.v) or np.any(np.abs(v_nodes - g.v) > 1e-12):
            elevation = np.stack([np.interp(v_nodes, g.v, row) for row in elevation])
        self.u = g.u
        self.v = v_nodes
        self._grid = RoadGrid(float(g.u[0]), float(v_nodes[0]) - self.v_offset, du, dv, elevation)
        self.default_spacing = (du, dv)
        # a run starts at the file's first cross section (measured files often
        # start far from u = 0); rigs level the road to its height there
        self.run_start = float(g.u[0])
        self._varies_in_y = not bool(np.all(elevation == elevation[:, :1]))
        at = f" at v = {self.v_offset:g} m" if self.v_offset else ""
        self.name = f"OpenCRG {self.path.name}{at}"

    # height (u = x, v = y + v_offset, bilinear on the file's nodes as OpenCRG),
    # extent and grid come from GriddedRoad


def write_crg(road: Road, path, spacing: tuple[float, float] | None = None, fmt: str = "KDBI",
              comment: str | None = None) -> Path:
    """Write any road to an OpenCRG file (straight reference line along x).

    ``road`` is a :class:`Road`; for a road name, pass
    ``tyrelab.road.spec.road_from_spec(name)`` (name parsing lives in
    :mod:`.spec` only, which imports this module). The road is sampled on its
    grid (``road.grid(spacing)``), u = x and v = y, with an empty
    ``$ROAD_CRG_MODS`` section so readers keep the data where it is. ``fmt`` is
    one of :data:`CRG_FORMATS`; the default KDBI (binary double) keeps heights
    exact. The file appears only when complete.
    """
    import pycrg

    if not isinstance(road, Road):
        raise InputError(f"write_crg needs a Road, not {type(road).__name__} {road!r}; "
                         "make one from a name with tyrelab.road.spec.road_from_spec", field="road")
    fmt = str(fmt).upper()
    if fmt not in CRG_FORMATS:
        raise InputError(f"unknown OpenCRG format '{fmt}'; expected one of {', '.join(CRG_FORMATS)}",
                         field="fmt")
    g = road.grid(spacing)
    nx, ny = g.z.shape
    v = g.y0 + g.dy * np.arange(ny)
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.part")
    text = comment or f"{road.name}; written by tyrelab"
    try:
        pycrg.write(tmp, g.z, g.dx, v, 0.0, u0=g.x0, fmt=fmt, mods={}, comment=text)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    return path
