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
* **Checked before use** (:mod:`tyrelab.limits`): header numbers finite, the
  u and v increments positive and within the grid-spacing bounds, u and v
  strictly increasing, no infinite height and no height beyond
  :data:`~tyrelab.limits.MAX_ROAD_HEIGHT` (an error names the cross and the
  long section), the lateral offset inside the road, and the grid's memory
  estimated from the header before the data are loaded.
"""

from __future__ import annotations

import logging
import math
import textwrap
import warnings
from contextlib import contextmanager
from math import gcd
from pathlib import Path

import numpy as np

from .. import limits, resources
from ..errors import InputError
from ..io_atomic import atomic_write
from .base import GriddedRoad, Road
from .grid import RoadGrid

#: the four OpenCRG data formats: K/L = binary/text, R/D = single/double
CRG_FORMATS = ("KRBI", "KDBI", "LRFI", "LDFI")


class _Collect(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.messages: list[str] = []

    def emit(self, record):
        self.messages.append(" ".join(record.getMessage().split()))


@contextmanager
def _pycrg_messages(path: Path):
    """Keep the C library's messages off stderr: a failure carries them in its exception, and
    warnings of a load that succeeds become one warning line naming the file."""
    logger = logging.getLogger("pycrg")
    handler = _Collect()
    propagate = logger.propagate
    logger.addHandler(handler)
    logger.propagate = False
    try:
        yield handler.messages
    finally:
        logger.removeHandler(handler)
        logger.propagate = propagate
    if handler.messages:
        more = f" (and {len(handler.messages) - 1} more)" if len(handler.messages) > 1 else ""
        warnings.warn(f"{path}: OpenCRG: {handler.messages[0][:200]}{more}", stacklevel=3)


def _header(path: Path):
    """Parse and check the header; :class:`InputError` naming the file if it is bad."""
    import pycrg

    try:
        with _pycrg_messages(path):
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
    for key, value in header.road.items():
        if isinstance(value, float) and not math.isfinite(value):
            raise InputError(f"bad OpenCRG header: {key.upper()} is {value}; expected a finite number",
                             source=str(path), field=key)
    inc = header.road.get("reference_line_increment")
    if not isinstance(inc, float) or not inc > 0:
        raise InputError("bad OpenCRG header: REFERENCE_LINE_INCREMENT must be a positive number",
                         source=str(path), field="reference_line_increment")
    if not limits.MIN_GRID_SPACING <= inc <= limits.MAX_GRID_SPACING:
        raise InputError(f"bad OpenCRG header: REFERENCE_LINE_INCREMENT {inc:g} m is out of range; "
                         f"allowed: {limits.MIN_GRID_SPACING:g} to {limits.MAX_GRID_SPACING:g} m",
                         source=str(path), field="reference_line_increment")
    vinc = header.road.get("long_section_v_increment")
    if vinc is not None and not (isinstance(vinc, float) and vinc >= limits.MIN_GRID_SPACING):
        raise InputError(f"bad OpenCRG header: LONG_SECTION_V_INCREMENT is {vinc}; expected at least "
                         f"{limits.MIN_GRID_SPACING:g} m", source=str(path),
                         field="long_section_v_increment")
    u0, u1 = header.road.get("reference_line_start_u"), header.road.get("reference_line_end_u")
    if isinstance(u0, float) and isinstance(u1, float) and not u1 > u0:
        raise InputError(f"bad OpenCRG header: REFERENCE_LINE_END_U {u1:g} is not after "
                         f"REFERENCE_LINE_START_U {u0:g}", source=str(path), field="reference_line_end_u")
    vr, vl = header.road.get("long_section_v_right"), header.road.get("long_section_v_left")
    if isinstance(vr, float) and isinstance(vl, float) and not vl > vr:
        raise InputError(f"bad OpenCRG header: LONG_SECTION_V_LEFT {vl:g} is not left of "
                         f"LONG_SECTION_V_RIGHT {vr:g}", source=str(path), field="long_section_v_left")
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
        with _pycrg_messages(path), pycrg.DataSet.open(path, apply_modifiers=False) as ds:
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


def _estimated_bytes(path: Path, header) -> float:
    """Memory [bytes] the loaded grid will take (a few copies of u x v doubles), from the header."""
    road = header.road
    inc = road["reference_line_increment"]
    u0, u1 = road.get("reference_line_start_u"), road.get("reference_line_end_u")
    nv = max(int(header.long_section_count), 2)
    vinc = road.get("long_section_v_increment")
    vr, vl = road.get("long_section_v_right"), road.get("long_section_v_left")
    if isinstance(vinc, float) and isinstance(vr, float) and isinstance(vl, float):
        nv = max(nv, int((vl - vr) / vinc) + 1)
    if isinstance(u0, float) and isinstance(u1, float):
        nu = (u1 - u0) / inc + 1
    else:  # no end given: as many cross sections as the data can hold
        nu = path.stat().st_size / (4.0 * max(len(header.channels), 1))
    return 8.0 * 4 * nu * nv


def _check_data(g, source: str) -> None:
    """Finite, strictly increasing u and v; no infinite or absurd height (NaN is an empty cell)."""
    for name, axis in (("u (reference line)", g.u), ("v (long sections)", g.v)):
        axis = np.asarray(axis, float)
        if not np.all(np.isfinite(axis)):
            raise InputError(f"non-finite {name} positions", source=source)
        if axis.size < 2 or np.any(np.diff(axis) <= 0):
            raise InputError(f"{name} positions must increase strictly", source=source)
    z = np.asarray(g.z, float)
    bad = np.isinf(z) | (np.abs(np.nan_to_num(z, nan=0.0)) > limits.MAX_ROAD_HEIGHT)
    if bad.any():
        i, j = (int(k) for k in np.argwhere(bad)[0])
        raise InputError(f"height {z[i, j]:g} m in cross section {i + 1} (u = {g.u[i]:g} m), long "
                         f"section {j + 1} (v = {g.v[j]:g} m) is not a road height; allowed: finite, "
                         f"|z| <= {limits.MAX_ROAD_HEIGHT:g} m (NaN marks an empty cell)", source=source)
    for name, values in (("reference line height", g.ref_z), ("banking", g.bank)):
        values = np.asarray(values, float)
        if not np.all(np.isfinite(values)) or np.any(np.abs(values) > limits.MAX_ROAD_HEIGHT):
            k = int(np.argmax(~np.isfinite(values) | (np.abs(np.nan_to_num(values, nan=np.inf))
                                                        > limits.MAX_ROAD_HEIGHT)))
            raise InputError(f"{name} {values[k]:g} in cross section {k + 1} is not finite or beyond "
                             f"{limits.MAX_ROAD_HEIGHT:g}", source=source)


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

    def __init__(self, path, v_offset: float = 0.0, force: bool = False):
        self.path = Path(path)
        if not self.path.is_file():
            raise InputError("no such OpenCRG file", source=str(self.path))
        self.v_offset = limits.check_number(v_offset, "road", -limits.MAX_ROAD_WIDTH,
                                            limits.MAX_ROAD_WIDTH, "m", what="lateral offset")
        self.header = _header(self.path)
        _check_binary_length(self.path, self.header)
        src = str(self.path)
        resources.check_resources(f"the OpenCRG file {self.path.name}", memory=_estimated_bytes(self.path,
                               self.header), force=force, field="road")
        g, du = _load_grid(self.path)
        _check_data(g, src)
        z = fill_empty_cells(g.z, source=src)
        elevation = z + g.ref_z[:, None] + g.bank[:, None] * g.v[None, :]
        if not np.all(np.isfinite(elevation)):
            raise InputError("heights overflow when the reference line's height and banking are added",
                             source=src)
        if not g.v[0] - 1e-9 <= self.v_offset <= g.v[-1] + 1e-9:
            raise InputError(f"lateral offset {self.v_offset:g} m is outside the road, whose long "
                             f"sections run from v = {g.v[0]:g} to {g.v[-1]:g} m", source=src, field="road")
        dv, v_nodes = _regular_v(g.v)
        resources.check_resources(f"the OpenCRG file {self.path.name} on a regular v grid",
                               memory=8.0 * 3 * len(v_nodes) * len(g.u), force=force, field="road")
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
              comment: str | None = None, force: bool = False) -> Path:
    """Write any road to an OpenCRG file (straight reference line along x).

    ``road`` is a :class:`Road`; for a road name, pass
    ``tyrelab.road.spec.road_from_spec(name)`` (name parsing lives in
    :mod:`.spec` only, which imports this module). The road is sampled on its
    grid (``road.grid(spacing)``), u = x and v = y, with an empty
    ``$ROAD_CRG_MODS`` section so readers keep the data where it is. ``fmt`` is
    one of :data:`CRG_FORMATS`; the default KDBI (binary double) keeps heights
    exact. The file appears only when complete. ``spacing`` is bounded
    (:data:`tyrelab.limits.MIN_GRID_SPACING` to ``MAX_GRID_SPACING``) and a
    grid above :data:`tyrelab.resources.MAX_MEMORY` is refused unless ``force``.
    """
    import pycrg

    if not isinstance(road, Road):
        raise InputError(f"write_crg needs a Road, not {type(road).__name__} {road!r}; "
                         "make one from a name with tyrelab.road.spec.road_from_spec", field="road")
    fmt = str(fmt).upper()
    if fmt not in CRG_FORMATS:
        raise InputError(f"unknown OpenCRG format '{fmt}'; expected one of {', '.join(CRG_FORMATS)}",
                         field="fmt")
    if spacing is not None:
        try:
            dx, dy = spacing
        except (TypeError, ValueError):
            raise InputError(f"spacing must be two numbers (dx, dy), got {spacing!r}",
                             field="spacing") from None
        spacing = tuple(limits.check_number(d, "spacing", limits.MIN_GRID_SPACING,
                                            limits.MAX_GRID_SPACING, "m", what="grid spacing")
                        for d in (dx, dy))
    cells = resources.grid_cells(road, spacing)
    resources.check_resources(f"the grid of {road.name} at this spacing ({cells:.3g} nodes)",
                           memory=8.0 * 3 * cells, force=force, field="spacing",
                           hint="use a coarser spacing")
    g = road.grid(spacing)
    nx, ny = g.z.shape
    v = g.y0 + g.dy * np.arange(ny)
    # the OpenCRG header holds lines of at most 72 characters
    text = "\n".join(textwrap.fill(line, 72) or "" for line in
                     (comment or f"{road.name}; written by tyrelab").splitlines())
    return atomic_write(Path(path), lambda tmp: pycrg.write(tmp, g.z, g.dx, v, 0.0, u0=g.x0, fmt=fmt,
                                                            mods={}, comment=text))
