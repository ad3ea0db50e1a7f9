"""Reading and writing ADAMS-style tyre property files (``.tir``, TeimOrbit).

A property file is a list of ``[SECTION]`` blocks. A block holds either
``KEY = value $comment`` lines or a numeric table (rows of numbers, optionally
preceded by a ``{col1 col2}`` header). ``$`` and ``!`` start comments.

Units
-----
The ``[UNITS]`` section states the units the file's numbers are written in.
:class:`TirFile` converts every value whose physical dimension it knows
(:data:`~tyrelab.tyre.tir_units.KEY_DIMENSIONS`,
:data:`~tyrelab.tyre.tir_units.TABLE_DIMENSIONS`) to SI when it is read, and
back when it is written. Keys of unknown dimension (Magic Formula
coefficients, which are dimensionless or defined in SI by the MF standard)
are passed through unchanged.

Repeated sections
-----------------
Some real files (for example Project Chrono's FEDA truck tyres) carry a
section twice. The rule here: a later occurrence of a section *replaces*
the earlier one as a whole, and a :class:`RepeatedSectionWarning` names the
section and both line numbers. This is what a reader that fills a dictionary
section by section (MFeval, ADAMS) ends up with, and it keeps a table from
silently growing by concatenation.

Numbers
-------
Every number must be finite and at most :data:`tyrelab.limits.MAX_TIR_MAGNITUDE`
in size, in the file and after conversion to SI (``nan``, ``inf``, ``1e400``
or a value that overflows in its unit are an :class:`InputError` naming the
file, line and key). Each table keeps the line number of every row
(:attr:`TirSection.row_lines`) so later checks can name the line.
"""

from __future__ import annotations

import copy
import math
import re
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..io_atomic import atomic_write_text
from ..limits import MAX_TIR_MAGNITUDE
from .tir_units import KEY_DIMENSIONS, TABLE_DIMENSIONS, units_factor


class RepeatedSectionWarning(UserWarning):
    """A section occurs more than once in a property file."""


# --- data model -----------------------------------------------------------

@dataclass
class TirSection:
    """One ``[SECTION]`` of a property file, values in SI."""

    name: str
    line: int
    entries: dict[str, object] = field(default_factory=dict)
    table: np.ndarray | None = None
    columns: list[str] | None = None
    lines: dict[str, int] = field(default_factory=dict)
    #: line number of each table row (empty when built in memory)
    row_lines: list[int] = field(default_factory=list)


@dataclass
class TirFile:
    """A parsed property file; numbers are SI wherever the dimension is known."""

    sections: dict[str, TirSection] = field(default_factory=dict)
    source: str = "<memory>"
    header: list[str] = field(default_factory=list)

    def has(self, section: str, key: str | None = None) -> bool:
        sec = self.sections.get(section.upper())
        if sec is None:
            return False
        return True if key is None else key.upper() in sec.entries

    def get(self, section: str, key: str, default=None, *, required: bool = False):
        """A value from ``[section]``; ``required`` raises a clear error if absent."""
        sec = self.sections.get(section.upper())
        if sec is not None and key.upper() in sec.entries:
            return sec.entries[key.upper()]
        if required:
            raise InputError(f"missing key {key} in section [{section.upper()}]",
                             source=self.source, field=key.upper())
        return default

    def number(self, section: str, key: str, default=None, *, required: bool = False) -> float:
        value = self.get(section, key, default, required=required)
        if value is None:
            return value
        if not isinstance(value, (int, float)):
            sec = self.sections.get(section.upper())
            line = sec.lines.get(key.upper()) if sec else None
            raise InputError(f"expected a number, found '{value}'", source=self.source,
                             line=line, field=key.upper())
        return float(value)

    def table(self, section: str) -> np.ndarray | None:
        sec = self.sections.get(section.upper())
        return None if sec is None else sec.table

    def line_of(self, section: str, key: str | None = None) -> int | None:
        """Line of ``key`` in ``[section]`` (of the section header without a key), if known."""
        sec = self.sections.get(section.upper())
        if sec is None:
            return None
        if key is None:
            return sec.line or None
        return sec.lines.get(key.upper()) or sec.line or None

    def row_line(self, section: str, row: int) -> int | None:
        """Line of table row ``row`` (0-based) of ``[section]``, if known."""
        sec = self.sections.get(section.upper())
        if sec is None:
            return None
        if 0 <= row < len(sec.row_lines):
            return sec.row_lines[row]
        return sec.line or None

    def set(self, section: str, key: str, value) -> None:
        sec = self.sections.setdefault(section.upper(), TirSection(section.upper(), 0))
        sec.entries[key.upper()] = value

    def set_table(self, section: str, table, columns=None) -> None:
        sec = self.sections.setdefault(section.upper(), TirSection(section.upper(), 0))
        sec.table = np.asarray(table, dtype=float)
        sec.columns = list(columns) if columns else None

    @property
    def units(self) -> dict[str, str]:
        sec = self.sections.get("UNITS")
        return {} if sec is None else {k: str(v) for k, v in sec.entries.items()}


# --- parsing --------------------------------------------------------------

_SECTION_RE = re.compile(r"^\[\s*([A-Za-z0-9_]+)\s*\]\s*$")
_KEY_RE = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(.*)$")


def _strip_comment(text: str) -> str:
    """Remove a trailing ``$`` or ``!`` comment that is outside quotes."""
    out, quote = [], None
    for ch in text:
        if quote:
            out.append(ch)
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
            out.append(ch)
        elif ch in "$!":
            break
        else:
            out.append(ch)
    return "".join(out).strip()


def _parse_value(raw: str, source: str, line: int, key: str):
    raw = raw.strip()
    if not raw:
        raise InputError("missing value after '='", source=source, line=line, field=key)
    if raw[0] in "'\"":
        if len(raw) < 2 or raw[-1] != raw[0]:
            raise InputError(f"unterminated string {raw}", source=source, line=line, field=key)
        return raw[1:-1]
    try:
        number = float(raw.replace("D", "E").replace("d", "e"))
    except ValueError:
        if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_.]*", raw):
            return raw  # bare word, e.g. USE_MODE = YES in some writers
        raise InputError(f"expected a number or a quoted string, found '{raw}'",
                         source=source, line=line, field=key) from None
    _check_finite(number, raw, source, line, key)
    if number.is_integer() and re.fullmatch(r"[+-]?\d+", raw):
        return int(number)
    return number


def _check_finite(number: float, raw: str, source, line, key) -> None:
    if not math.isfinite(number):
        raise InputError(f"'{raw}' is not a finite number", source=source, line=line, field=key)
    if abs(number) > MAX_TIR_MAGNITUDE:
        raise InputError(f"{raw} is beyond the {MAX_TIR_MAGNITUDE:g} any tyre parameter stays within",
                         source=source, line=line, field=key)


def parse_tir(text: str, source: str = "<string>") -> TirFile:
    """Parse the text of a property file; see the module docstring."""
    tir = TirFile(source=source)
    current: TirSection | None = None
    rows: list[list[float]] = []
    row_lines: list[int] = []

    def close():
        if current is not None and rows:
            width = len(rows[0])
            for r, ln in zip(rows, row_lines):
                if len(r) != width:
                    raise InputError(f"table row has {len(r)} values, expected {width} like the first row",
                                     source=source, line=ln, field=current.name)
            current.table = np.array(rows, dtype=float)
            current.row_lines = list(row_lines)

    for lineno, raw_line in enumerate(text.splitlines(), start=1):
        line = raw_line.strip()
        if not line:
            continue
        if line[0] in "$!":
            if current is None:
                tir.header.append(raw_line.rstrip())
            continue
        if line.startswith("["):
            m = _SECTION_RE.match(_strip_comment(line))
            if not m:
                raise InputError(f"malformed section header '{line}', expected [NAME]",
                                 source=source, line=lineno)
            close()
            name = m.group(1).upper()
            if name in tir.sections:
                warnings.warn(f"{source}: section [{name}] appears at line {tir.sections[name].line} "
                              f"and again at line {lineno}; the later one is used",
                              RepeatedSectionWarning, stacklevel=2)
            current = TirSection(name, lineno)
            tir.sections[name] = current
            rows, row_lines = [], []
            continue
        body = _strip_comment(line)
        if not body:
            continue
        if current is None:
            raise InputError(f"'{body}' before the first [SECTION] header", source=source, line=lineno)
        if body.startswith("{"):
            if not body.endswith("}"):
                raise InputError(f"unterminated column header '{body}'", source=source, line=lineno)
            current.columns = body[1:-1].split()
            continue
        m = _KEY_RE.match(body)
        if m:
            if rows:
                raise InputError(f"key '{m.group(1)}' inside the table of [{current.name}]",
                                 source=source, line=lineno)
            key = m.group(1).upper()
            current.entries[key] = _parse_value(m.group(2), source, lineno, key)
            current.lines[key] = lineno
            continue
        try:
            values = [float(tok.replace("D", "E").replace("d", "e")) for tok in body.split()]
        except ValueError:
            raise InputError(f"expected 'KEY = value' or a row of numbers, found '{body}'",
                             source=source, line=lineno, field=current.name) from None
        for tok, v in zip(body.split(), values):
            _check_finite(v, tok, source, lineno, current.name)
        if current.entries:
            raise InputError(f"a row of numbers inside the key-value section [{current.name}]",
                             source=source, line=lineno)
        rows.append(values)
        row_lines.append(lineno)
    close()
    _to_si(tir)
    return tir


def _to_si(tir: TirFile, inverse: bool = False) -> None:
    units = tir.units
    for sec in tir.sections.values():
        if sec.name == "UNITS":
            continue
        for key, value in list(sec.entries.items()):
            dim = KEY_DIMENSIONS.get(key)
            if dim is None or not isinstance(value, (int, float)) or isinstance(value, bool):
                continue
            f = units_factor(units, dim, tir.source, sec.lines.get(key))
            converted = value / f if inverse else value * f
            if not math.isfinite(converted):
                raise InputError(f"{value!r} overflows when converted to SI", source=tir.source,
                                 line=sec.lines.get(key), field=key)
            sec.entries[key] = converted
        dims = TABLE_DIMENSIONS.get(sec.name)
        if dims is not None and sec.table is not None:
            if sec.table.shape[1] != len(dims):
                raise InputError(f"table has {sec.table.shape[1]} columns, expected {len(dims)}",
                                 source=tir.source, line=sec.line, field=sec.name)
            for j, dim in enumerate(dims):
                f = units_factor(units, dim, tir.source, sec.line)
                with np.errstate(over="ignore"):
                    sec.table[:, j] = sec.table[:, j] / f if inverse else sec.table[:, j] * f
                bad = np.flatnonzero(~np.isfinite(sec.table[:, j]))
                if bad.size:
                    k = int(bad[0])
                    line = sec.row_lines[k] if k < len(sec.row_lines) else sec.line
                    raise InputError(f"column {j + 1} overflows when converted to SI", source=tir.source,
                                     line=line, field=sec.name)


def read_tir(path) -> TirFile:
    """Read a property file from disk (values converted to SI)."""
    path = Path(path)
    if not path.is_file():
        raise InputError("no such tyre property file", source=str(path))
    try:
        text = path.read_text(encoding="utf-8", errors="strict")
    except UnicodeDecodeError:
        text = path.read_text(encoding="latin-1")
    return parse_tir(text, source=str(path))


# --- writing --------------------------------------------------------------

def _format_value(value) -> str:
    if isinstance(value, str):
        return f"'{value}'"
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        return str(int(value))
    return repr(float(value))


def format_tir(tir: TirFile, units: dict[str, str] | None = None) -> str:
    """Text of a property file. Values are written in ``units`` (SI by default)."""
    out = copy.deepcopy(tir)
    out.sections.pop("UNITS", None)
    unit_words = {"LENGTH": "meter", "FORCE": "newton", "ANGLE": "radians", "MASS": "kg", "TIME": "second"}
    unit_words.update({k.upper(): v for k, v in (units or {}).items()})
    out.sections = {"UNITS": TirSection("UNITS", 0, dict(unit_words)), **out.sections}
    _to_si(out, inverse=True)
    lines = list(tir.header) or ["$-------- written by tyrelab"]
    for sec in out.sections.values():
        lines.append("$" + "-" * 60 + sec.name.lower())
        lines.append(f"[{sec.name}]")
        width = max([len(k) for k in sec.entries] + [1])
        for key, value in sec.entries.items():
            lines.append(f"{key.ljust(width)} = {_format_value(value)}")
        if sec.table is not None:
            if sec.columns:
                lines.append("{" + " ".join(sec.columns) + "}")
            for row in sec.table:
                lines.append(" ".join(repr(float(v)) for v in row))
    return "\n".join(lines) + "\n"


def write_tir(tir: TirFile, path, units: dict[str, str] | None = None) -> None:
    """Write a property file (atomically: the file appears only when complete)."""
    text = format_tir(tir, units)
    atomic_write_text(Path(path), text)
