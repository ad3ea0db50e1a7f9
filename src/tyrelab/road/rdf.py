"""Adams road data files (``.rdf``, TeimOrbit syntax): read any as a :class:`Road`, write any road.

Syntax (Adams/Tire road documentation): ``$`` and ``!`` start a comment
(outside quotes), ``[BLOCK]`` opens a block, ``(SUBBLOCK)`` a sub-block
inside it, ``{a b c}`` names a table's columns; ``KEY = value`` holds a
number or a quoted string; other lines are rows of numbers. Numbers are
converted to SI by the ``[UNITS]`` block: LENGTH (meter, mm, cm, km, inch,
foot and their spellings) and ANGLE (degree, radian); without a ``[UNITS]``
block lengths are metres and angles degrees (``DIRECTION = 45 $ deg`` in
the documentation's examples). FORCE, MASS and TIME play no part in a road.

What is read
------------
* ``METHOD = '2D'`` (``[MODEL]``), with ``ROAD_TYPE`` one of flat, plank,
  poly_line, pot_hole, ramp, roof, sine, sine_sweep; parameters in
  ``[PARAMETERS]`` (or in ``[MODEL]``, as some examples write them). The
  exact geometry of each type is stated in :mod:`tyrelab.road.rdf_profiles`.
  drum, stochastic_uneven and the rest are input errors.
* ``METHOD = '3D'`` shell roads, or any file with ``[NODES]`` and
  ``[ELEMENTS]``: nodes ``{id x y z}`` and triangles ``{n1 n2 n3 mu}`` naming
  nodes by their id (any distinct integers: 0-based as ENVE writes, 1-based
  as Adams does), the friction column optional (then ``MU``, default 1). A
  :class:`~tyrelab.road.mesh.MeshRoad`, queried exactly on its triangles.
* ``OFFSET`` (raises the road) and ``ROTATION_ANGLE_XY_PLANE`` (the direction
  of the file's x axis in the road frame) where present; ``MU``.

Every bad input -- a missing block or key, a non-numeric, NaN or infinite
value, a row of the wrong width, a node id that does not exist, a
degenerate triangle, an unknown ROAD_TYPE or unit -- is an
:class:`~tyrelab.errors.InputError` naming the file and line.

Writing (:func:`write_rdf`) and what "reads back identically" means
------------------------------------------------------------------
* ``method="2D"``: a ``poly_line`` through the x nodes of the road's grid,
  the right track the road's exact height along y = 0, the left track along
  y = :data:`~tyrelab.road.rdf_profiles.LEFT_TRACK_Y` (the same numbers for a
  road that does not vary in y). Read back, the heights at the written x are
  the written ones bit for bit (17 significant digits), linear between: for
  a 2D road that is its compiled grid exactly.
* ``method="3D"``: a shell. A :class:`MeshRoad` is written as its own
  triangles (reads back the same mesh); any other road as its grid, each
  cell split into two triangles along the diagonal from node (i, j) to
  (i+1, j+1). The nodes read back bit for bit (the height queried at a node
  to the last digit: barycentric rounding), linear on each triangle between
  them (the grid itself is bilinear; the two differ inside a cell by at
  most a quarter of ``|z00 - z10 - z01 + z11|``, zero for a road that does
  not vary in y).
Files are written to a temporary name beside the target and renamed.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError
from . import rdf_profiles as P
from .base import Road
from .mesh import MeshRoad
from .rdf_write import write_rdf

__all__ = ["ANGLE_UNITS", "LENGTH_UNITS", "ROAD_TYPES", "parse_rdf", "read_rdf", "write_rdf"]

#: factor to metres of each LENGTH unit word
LENGTH_UNITS = {"meter": 1.0, "meters": 1.0, "metre": 1.0, "m": 1.0, "millimeter": 1e-3, "millimeters": 1e-3,
                "millimetre": 1e-3, "mm": 1e-3, "centimeter": 1e-2, "centimetre": 1e-2, "cm": 1e-2,
                "kilometer": 1e3, "kilometre": 1e3, "km": 1e3, "inch": 0.0254, "inches": 0.0254,
                "in": 0.0254, "foot": 0.3048, "feet": 0.3048, "ft": 0.3048}
#: factor to radians of each ANGLE unit word
ANGLE_UNITS = {"degree": math.pi / 180, "degrees": math.pi / 180, "deg": math.pi / 180,
               "radian": 1.0, "radians": 1.0, "rad": 1.0}
ROAD_TYPES = ("flat", "plank", "poly_line", "pot_hole", "ramp", "roof", "sine", "sine_sweep")

_KEY = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(.*)$")
_HEAD = re.compile(r"^([\[(])\s*([A-Za-z0-9_]+)\s*([\])])$")


@dataclass
class _Block:
    """One ``[BLOCK]`` or ``(SUBBLOCK)``: its keys, its rows of numbers (as text) and sub-blocks."""

    name: str
    line: int
    keys: dict = field(default_factory=dict)   # KEY -> (value, line)
    rows: list = field(default_factory=list)   # token lists
    row_lines: list = field(default_factory=list)
    subs: dict = field(default_factory=dict)


def _strip(text: str) -> str:
    """The line without its ``$``/``!`` comment (outside quotes)."""
    if "'" not in text and '"' not in text:
        cut = min((i for i in (text.find("$"), text.find("!")) if i >= 0), default=len(text))
        return text[:cut].strip()
    quote = None
    for i, ch in enumerate(text):
        if quote:
            quote = None if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch in "$!":
            return text[:i].strip()
    return text.strip()


def parse_rdf(text: str, source: str = "<string>") -> dict[str, _Block]:
    """The blocks of an ``.rdf`` text by upper-case name (values still text)."""
    blocks: dict[str, _Block] = {}
    block = sub = None
    for n, raw in enumerate(text.splitlines(), start=1):
        body = _strip(raw)
        if not body:
            continue
        if body[0] in "[(":
            m = _HEAD.match(body)
            if not m or "[(".index(m.group(1)) != "])".index(m.group(3)):
                raise InputError(f"malformed block header '{body}', expected [NAME] or (NAME)",
                                 source=source, line=n)
            name = m.group(2).upper()
            if m.group(1) == "[":
                block, sub = _Block(name, n), None
                blocks[name] = block
            elif block is None:
                raise InputError(f"sub-block ({name}) before any [BLOCK]", source=source, line=n)
            else:
                sub = block.subs[name] = _Block(name, n)
            continue
        if block is None:
            raise InputError(f"'{body}' before the first [BLOCK]", source=source, line=n)
        target = sub or block
        if body[0] == "{":
            if not body.endswith("}"):
                raise InputError(f"unterminated table header '{body}'", source=source, line=n)
            continue
        m = _KEY.match(body)
        if m:
            target.keys[m.group(1).upper()] = (m.group(2).strip(), n)
        else:
            target.rows.append(body.split())
            target.row_lines.append(n)
    return blocks


def _value(raw: str, source, line, key):
    """A quoted string's text, or the number; anything else is an error."""
    if raw[:1] in "'\"":
        if len(raw) < 2 or raw[-1] != raw[0]:
            raise InputError(f"unterminated string {raw}", source=source, line=line, field=key)
        return raw[1:-1].strip()
    try:
        return float(raw.replace("D", "E").replace("d", "e"))
    except ValueError:
        if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", raw):
            return raw  # a bare word (METHOD = 2D in some writers)
        raise InputError(f"expected a number or a quoted string, found '{raw}'", source=source,
                         line=line, field=key) from None


class _File:
    """A parsed file with its units: typed access that reports the line of every bad value."""

    def __init__(self, path: Path):
        self.source = str(path)
        try:
            text = path.read_text(encoding="utf-8", errors="replace")
        except OSError as exc:
            raise InputError(f"cannot read the file: {exc}", source=self.source) from exc
        self.blocks = parse_rdf(text, self.source)
        units = self.blocks.get("UNITS")
        self.length, self.angle = 1.0, ANGLE_UNITS["degree"]
        if units is not None:
            for key, table in (("LENGTH", LENGTH_UNITS), ("ANGLE", ANGLE_UNITS)):
                if key in units.keys:
                    raw, line = units.keys[key]
                    word = str(_value(raw, self.source, line, key)).lower()
                    if word not in table:
                        raise InputError(f"unknown {key.lower()} unit '{word}'; expected one of "
                                         f"{', '.join(table)}", source=self.source, line=line, field=key)
                    setattr(self, key.lower(), table[word])

    def string(self, block: _Block, key: str, default=None) -> str | None:
        if key not in block.keys:
            return default
        raw, line = block.keys[key]
        return str(_value(raw, self.source, line, key))

    def number(self, params: dict, key: str, unit: float = 1.0, default=None, where: _Block | None = None):
        """``params[key]`` as a finite number times ``unit``; ``default`` if absent (None: required)."""
        if key not in params:
            if default is None:
                raise InputError(f"missing {key} (expected 'KEY = number')", source=self.source,
                                 line=where.line if where else None, field=key)
            return default
        raw, line = params[key]
        value = _value(raw, self.source, line, key)
        if isinstance(value, str) or not math.isfinite(value):
            raise InputError(f"{key} must be a finite number, found '{raw}'", source=self.source,
                             line=line, field=key)
        return value * unit

    def table(self, block: _Block, widths: tuple[int, ...], what: str) -> np.ndarray:
        """The rows of ``block`` as a float array, each row ``widths`` wide; bad rows name their line."""
        if not block.rows:
            raise InputError(f"{what} has no rows of numbers", source=self.source, line=block.line)
        width = len(block.rows[0])
        try:
            if any(len(r) != width for r in block.rows):
                raise ValueError
            a = np.array(block.rows, dtype=float)
        except ValueError:
            a = None
        if a is None or width not in widths or not np.all(np.isfinite(a)):
            for r, line in zip(block.rows, block.row_lines):
                if len(r) not in widths or len(r) != width:
                    raise InputError(f"{what}: row has {len(r)} values, expected "
                                     f"{' or '.join(map(str, widths))} like the first row",
                                     source=self.source, line=line)
                for tok in r:
                    try:
                        x = float(tok)
                    except ValueError:
                        raise InputError(f"{what}: '{tok}' is not a number", source=self.source,
                                         line=line) from None
                    if not math.isfinite(x):
                        raise InputError(f"{what}: {tok} is not a finite number", source=self.source,
                                         line=line)
        if a is None:  # pragma: no cover - every failure above names its row
            raise InputError(f"{what}: unreadable rows", source=self.source, line=block.line)
        return a


def read_rdf(path, y_offset: float = 0.0) -> Road:
    """An Adams road data file as a :class:`Road` (see the module docstring).

    ``height(x, y)`` is the file's height at ``(x, y + y_offset)`` (the
    trailer's path at the file's lateral position ``y_offset`` [m]).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("no such road data file", source=str(path))
    f = _File(path)
    model = f.blocks.get("MODEL")
    params: dict = {}
    for name in ("MODEL", "PARAMETERS"):
        if name in f.blocks:
            b = f.blocks[name]
            if b.rows:
                raise InputError(f"a row of numbers in the key-value block [{name}]", source=f.source,
                                 line=b.row_lines[0])
            params.update(b.keys)
    method = (f.string(model, "METHOD", "") if model else "").upper()
    shell = "NODES" in f.blocks or "ELEMENTS" in f.blocks
    if method not in ("", "2D", "3D"):
        raise InputError(f"METHOD '{method}' is not read by tyrelab; expected '2D' or a '3D' shell road "
                         "([NODES] and [ELEMENTS])", source=f.source, line=model.keys["METHOD"][1],
                         field="METHOD")
    place = dict(offset=f.number(params, "OFFSET", f.length, 0.0),
                 rotation=f.number(params, "ROTATION_ANGLE_XY_PLANE", f.angle, 0.0),
                 mu=f.number(params, "MU", 1.0, 1.0))
    if shell or method == "3D":
        road = _read_shell(f, place, y_offset)
    else:
        if model is None:
            raise InputError("no [MODEL] block (and no [NODES]/[ELEMENTS] of a shell road)", source=f.source)
        try:
            road = _read_2d(f, model, params).place(y_offset=y_offset, **place)
        except InputError as exc:  # a size the obstacle itself refuses (tyrelab's limits)
            if exc.source is not None:
                raise
            block = f.blocks.get("PARAMETERS", model)
            raise InputError(exc.reason, source=f.source, line=block.line, field=exc.field) from exc
        road.name = f"Adams road {path.name} ({road.name})"
    if y_offset:
        road.name += f" at y = {y_offset:g} m"
    return road


def _read_2d(f: _File, model: _Block, params: dict) -> P.RdfRoad:
    """The 2D road type of the file, sizes in SI (see :mod:`.rdf_profiles`)."""
    if "ROAD_TYPE" not in model.keys and "ROAD_TYPE" not in params:
        raise InputError("missing ROAD_TYPE in [MODEL]", source=f.source, line=model.line, field="ROAD_TYPE")
    raw, line = params["ROAD_TYPE"]
    kind = str(_value(raw, f.source, line, "ROAD_TYPE")).lower()
    where = f.blocks.get("PARAMETERS", model)
    L, A = f.length, f.angle

    def num(key, unit=L, default=None):
        return f.number(params, key, unit, default, where)

    def check(ok, key, msg):
        if not ok:
            raise InputError(msg, source=f.source, line=params.get(key, (None, where.line))[1], field=key)

    if kind == "flat":
        return P.FlatRdf()
    if kind == "plank":
        check(f.number(params, "EDGE_ROUNDED", 1.0, 0.0) == 0, "EDGE_ROUNDED",
              "rounded plank edges (EDGE_ROUNDED = 1) are not supported; use a bevel")
        h, length = num("HEIGHT"), num("LENGTH")
        bevel, d = num("BEVEL_EDGE_LENGTH", L, 0.0), num("DIRECTION", A, 0.0)
        check(h != 0, "HEIGHT", "HEIGHT must not be zero")
        check(length > 0, "LENGTH", f"LENGTH must be positive, got {length} m")
        check(abs(math.degrees(d)) <= 80, "DIRECTION", "DIRECTION must be between -80 and 80 degrees")
        check(0 <= bevel <= length / 2 and bevel * math.cos(d) <= abs(h) * (1 + 1e-12), "BEVEL_EDGE_LENGTH",
              "BEVEL_EDGE_LENGTH must be between 0 and half the LENGTH, its height within HEIGHT")
        return P.Plank(h, num("START"), length, bevel, d)
    if kind == "pot_hole":
        length, d = num("LENGTH"), num("DIRECTION", A, 0.0)
        check(length > 0, "LENGTH", f"LENGTH must be positive, got {length} m")
        check(abs(math.degrees(d)) <= 80, "DIRECTION", "DIRECTION must be between -80 and 80 degrees")
        return P.PotHole(num("DEPTH"), num("START"), length, d)
    if kind == "ramp":
        slope = num("SLOPE", 1.0)
        check(slope > 0, "SLOPE", f"SLOPE must be positive (rise per run), got {slope}")
        return P.Ramp(num("HEIGHT"), num("START"), slope)
    if kind == "roof":
        length = num("LENGTH")
        check(length > 0, "LENGTH", f"LENGTH must be positive, got {length} m")
        return P.Roof(num("HEIGHT"), num("START"), length)
    if kind == "sine":
        wl, length = num("WAVE_LENGTH"), num("LENGTH", L, math.inf)
        check(wl > 0, "WAVE_LENGTH", f"WAVE_LENGTH must be positive, got {wl} m")
        check(length > 0, "LENGTH", f"LENGTH must be positive, got {length} m")
        return P.Sine(num("AMPLITUDE"), wl, num("START"), None if math.isinf(length) else length)
    if kind == "sine_sweep":
        start, end = num("START"), num("END")
        l0, l1 = num("WAVE_LENGTH_AT_START"), num("WAVE_LENGTH_AT_END")
        a0 = num("AMPLITUDE_AT_START")
        sweep = num("SWEEP_TYPE", 1.0, 0.0)
        check(end > start, "END", "END must lie beyond START")
        check(0 < l1 <= l0, "WAVE_LENGTH_AT_END",
              "wave lengths must be positive, WAVE_LENGTH_AT_END <= WAVE_LENGTH_AT_START")
        check(sweep in (0, 1), "SWEEP_TYPE", "SWEEP_TYPE must be 0 (linear) or 1 (logarithmic)")
        return P.SineSweep(start, end, a0, num("AMPLITUDE_AT_END", L, a0), l0, l1, log=sweep == 1)
    if kind == "poly_line":
        data = where.subs.get("XZ_DATA") or model.subs.get("XZ_DATA")
        if data is None:
            raise InputError("poly_line road without an (XZ_DATA) sub-block", source=f.source,
                             line=where.line, field="XZ_DATA")
        t = f.table(data, (3,), "(XZ_DATA)") * L
        if len(t) < 2:
            raise InputError("(XZ_DATA) needs at least 2 rows", source=f.source, line=data.line)
        bad = np.flatnonzero(np.diff(t[:, 0]) <= 0)
        if bad.size:
            raise InputError(f"x must increase from row to row, found {t[bad[0], 0]:g} then "
                             f"{t[bad[0] + 1, 0]:g} m", source=f.source, line=data.row_lines[bad[0] + 1])
        return P.PolyLine(t[:, 0], t[:, 1], t[:, 2])
    raise InputError(f"unknown ROAD_TYPE '{kind}'; expected one of {', '.join(ROAD_TYPES)}",
                     source=f.source, line=line, field="ROAD_TYPE")


def _read_shell(f: _File, place: dict, y_offset: float) -> MeshRoad:
    """A 3D shell road: [NODES] {id x y z} and [ELEMENTS] {n1 n2 n3 [mu]}."""
    for name in ("NODES", "ELEMENTS"):
        if name not in f.blocks:
            raise InputError(f"a 3D shell road needs a [{name}] block", source=f.source)
    nb, eb = f.blocks["NODES"], f.blocks["ELEMENTS"]
    nodes = f.table(nb, (4,), "[NODES]")
    elems = f.table(eb, (3, 4), "[ELEMENTS]")
    for block, count, key in ((nb, len(nodes), "NUMBER_OF_NODES"), (eb, len(elems), "NUMBER_OF_ELEMENTS")):
        if key in block.keys and f.number(block.keys, key) != count:
            raise InputError(f"{key} says {f.number(block.keys, key):g}, the block has {count} rows",
                             source=f.source, line=block.keys[key][1], field=key)
    for arr, block, cols in ((nodes, nb, [0]), (elems, eb, [0, 1, 2])):
        frac = np.flatnonzero((arr[:, cols] != np.round(arr[:, cols])).any(axis=1))
        if frac.size:
            raise InputError("node ids must be integers", source=f.source, line=block.row_lines[frac[0]])
    ids = nodes[:, 0].astype(np.int64)
    order = np.argsort(ids, kind="stable")
    dup = np.flatnonzero(np.diff(ids[order]) == 0)
    if dup.size:
        raise InputError(f"node id {ids[order[dup[0]]]} appears twice", source=f.source,
                         line=nb.row_lines[order[dup[0] + 1]])
    refs = elems[:, :3].astype(np.int64)
    pos = np.clip(np.searchsorted(ids[order], refs), 0, len(ids) - 1)
    missing = np.flatnonzero((ids[order][pos] != refs).any(axis=1))
    if missing.size:
        k = missing[0]
        raise InputError(f"element refers to node {refs[k][ids[order][pos[k]] != refs[k]][0]}, which "
                         "is not in [NODES]", source=f.source, line=eb.row_lines[k])
    mu = elems[:, 3] if elems.shape[1] == 4 else place["mu"]
    u, v = nodes[:, 1] * f.length, nodes[:, 2] * f.length
    c, s = P.rotation_cos_sin(place["rotation"])
    xyz = np.column_stack([c * u - s * v, s * u + c * v - y_offset, nodes[:, 3] * f.length + place["offset"]])
    road = MeshRoad(xyz, order[pos], mu, name=f"Adams shell road {Path(f.source).name}", source=f.source,
                    element_lines=eb.row_lines)
    return road
