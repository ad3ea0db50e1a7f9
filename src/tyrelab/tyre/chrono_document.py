"""Project Chrono tyre JSON files as a document, and the property file built from one.

:class:`_Document` reads a Chrono JSON file (``//`` and ``/* */`` comments
blanked so lines and columns stay), finds keys with their line numbers and
checks their kinds; :class:`_Builder` assembles a :class:`~.tir.TirFile`
from it with the sections ADAMS reads. The template mappings that use them
are in :mod:`.chrono_json`; every error is an :class:`InputError` naming
the file, the line and the key.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np

from ..errors import InputError
from .tir import TirFile, TirSection

#: contact-patch keys assumed for tyres read from JSON values (as tyre/data/hmmwv-pac89.tir)
ASSUMED_CONTACT_PATCH = {"PA1": 0.15, "PA2": 7.06, "PAE": 0.72, "PBE": 1.0, "PCE": 2.0, "PLS": 0.9,
                         "N_WIDTH": 6, "N_LENGTH": 5}
#: assumed half contact width as a fraction of the section width, at every deflection
ASSUMED_HALF_WIDTH = 0.4
#: deflections [m] of the two rows of the assumed [CONTACT_WIDTH_CURVE]
_WIDTH_CURVE_DEFLECTIONS = (0.0, 0.1)

_SECTION_NAME = re.compile(r"[A-Z][A-Z0-9_]*")
_COMMENT = re.compile(r'"(?:\\.|[^"\\])*"|//[^\n]*|/\*.*?\*/', re.S)


# --- the JSON document ------------------------------------------------------

def _blank(match: re.Match) -> str:
    """A comment replaced by spaces (newlines kept): lines and columns stay where they were."""
    text = match.group(0)
    if text.startswith('"'):
        return text
    return re.sub(r"[^\n]", " ", text)


def _where(keys) -> str:
    return " > ".join(str(k) if not isinstance(k, int) else f"row {k + 1}" for k in keys)


class _Document:
    """A parsed Chrono JSON file with the helpers that read it and name what is wrong."""

    def __init__(self, path: Path):
        self.path = path
        self.source = str(path)
        if not path.is_file():
            raise InputError("no such Chrono tyre file", source=self.source)
        try:
            raw = path.read_text(encoding="utf-8")
        except UnicodeDecodeError as exc:
            raise InputError(f"not UTF-8 text ({exc.reason} at byte {exc.start})",
                             source=self.source) from None
        self.text = _COMMENT.sub(_blank, raw)
        try:
            self.data = json.loads(self.text)
        except json.JSONDecodeError as exc:
            raise InputError(f"malformed JSON: {exc.msg} (column {exc.colno})", source=self.source,
                             line=exc.lineno) from None
        if not isinstance(self.data, dict):
            raise InputError("expected a JSON object ({ ... }) at the top level", source=self.source,
                             line=1)

    # -- where -------------------------------------------------------------
    def line(self, keys) -> int | None:
        """Line of the last key of ``keys`` found in the text (each searched after its parent)."""
        pos, line = 0, None
        for key in keys:
            if isinstance(key, int):
                break
            pattern = '"' + re.escape(json.dumps(key, ensure_ascii=False)[1:-1]) + r'"\s*:'
            m = re.compile(pattern).search(self.text, pos)
            if m is None:
                break
            pos = m.end()
            line = self.text.count("\n", 0, m.start()) + 1
        return line

    def error(self, message: str, keys) -> InputError:
        return InputError(message, source=self.source, line=self.line(keys), field=_where(keys) or None)

    # -- what --------------------------------------------------------------
    def has(self, *keys) -> bool:
        node = self.data
        for key in keys:
            if isinstance(node, dict) and not isinstance(key, int) and key in node:
                node = node[key]
            elif isinstance(node, list) and isinstance(key, int) and 0 <= key < len(node):
                node = node[key]
            else:
                return False
        return True

    def value(self, *keys):
        """The value at ``keys``; a missing key names itself and the object that lacks it."""
        node = self.data
        for i, key in enumerate(keys):
            if not isinstance(node, dict):
                raise self.error(f"expected an object holding '{key}', found {_kind(node)}", keys[:i])
            if key not in node:
                where = f" in '{_where(keys[:i])}'" if i else ""
                raise self.error(f"missing key '{key}'{where}", keys[:i + 1])
            node = node[key]
        return node

    def number(self, *keys, minimum: float | None = None, positive: bool = False) -> float:
        """The finite number at ``keys`` (``minimum``, ``positive``: its range)."""
        return self.check_number(self.value(*keys), keys, minimum, positive)

    def check_number(self, value, keys, minimum: float | None = None, positive: bool = False) -> float:
        """``value`` (found at ``keys``) as a finite float in range, or an error naming ``keys``."""
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(f"expected a number, found {_kind(value)}", keys)
        x = float(value)
        if not math.isfinite(x):
            raise self.error(f"expected a finite number, found {value!r}", keys)
        if positive and not x > 0:
            raise self.error(f"expected a positive number, found {value!r}", keys)
        if minimum is not None and not x >= minimum:
            raise self.error(f"expected a number >= {minimum:g}, found {value!r}", keys)
        return x

    def string(self, *keys) -> str:
        value = self.value(*keys)
        if not isinstance(value, str) or not value.strip():
            raise self.error(f"expected a non-empty string, found {_kind(value)}", keys)
        return value

    def vector(self, *keys, size: int) -> list[float]:
        value = self.value(*keys)
        if not isinstance(value, list) or len(value) != size:
            raise self.error(f"expected a list of {size} numbers, found {_kind(value)}", keys)
        return [self.check_number(v, keys, minimum=0.0) for v in value]

    def curve(self, *keys) -> np.ndarray:
        """A load-deflection curve: 2-100 rows of (deflection [m], load [N]), deflection increasing."""
        value = self.value(*keys)
        if not isinstance(value, list) or not 2 <= len(value) <= 100:
            raise self.error(f"expected a list of 2 to 100 [deflection, load] rows, found {_kind(value)}",
                             keys)
        rows = []
        for i, row in enumerate(value):
            if not isinstance(row, list) or len(row) != 2:
                raise self.error(f"expected a [deflection, load] pair, found {_kind(row)}", keys + (i,))
            rows.append([self.check_number(v, keys + (i,), minimum=0.0) for v in row])
        table = np.array(rows, dtype=float)
        if np.any(np.diff(table[:, 0]) <= 0):
            raise self.error("deflections must increase strictly down the curve", keys)
        return table


def _kind(value) -> str:
    if isinstance(value, bool):
        return f"'{str(value).lower()}'"
    if isinstance(value, (dict, list)):
        return "an object" if isinstance(value, dict) else f"a list of {len(value)}"
    if value is None:
        return "null"
    return repr(value)


# --- the property file --------------------------------------------------------

class _Builder:
    """A :class:`TirFile` in SI filled key by key, each key remembering its JSON line."""

    def __init__(self, doc: _Document, template: str, header=(), tir: TirFile | None = None):
        self.doc = doc
        if tir is not None:  # add to a property file read from elsewhere
            self.tir = tir
            return
        self.tir = TirFile(source=doc.source, header=[
            "$" + "-" * 74,
            f"$ Project Chrono {template} read from {doc.path.name} by tyrelab.tyre.chrono_json",
            *header])
        self.put("MDI_HEADER", "FILE_TYPE", "tir")
        self.put("MDI_HEADER", "FILE_VERSION", 3.0)
        self.put("MDI_HEADER", "FILE_FORMAT", "ASCII")
        for key, word in (("LENGTH", "meter"), ("FORCE", "newton"), ("ANGLE", "radians"),
                          ("MASS", "kg"), ("TIME", "second")):
            self.put("UNITS", key, word)

    def section(self, name: str, keys=()) -> TirSection:
        sec = self.tir.sections.get(name)
        if sec is None:
            sec = TirSection(name, self.doc.line(keys) or 0)
            self.tir.sections[name] = sec
        return sec

    def put(self, section: str, key: str, value, keys=()) -> None:
        sec = self.section(section, keys)
        sec.entries[key] = value
        line = self.doc.line(keys) if keys else None
        if line is not None:
            sec.lines[key] = line

    def table(self, section: str, table, columns, keys=()) -> None:
        sec = self.section(section, keys)
        sec.table = np.asarray(table, dtype=float)
        sec.columns = list(columns)

    def assumed_contact_patch(self, width: float) -> None:
        self.tir.header += [
            "$ ASSUMED (the JSON has no contact-patch data): [CONTACT_PATCH] length and cam",
            "$ shape are the thesis's dimensionless XZL values (section 4.4), cam counts",
            "$ Schmeitz's passenger-car optimum (5 along, 6 across); [CONTACT_WIDTH_CURVE]",
            f"$ a half contact width of {ASSUMED_HALF_WIDTH:g} x the section width at every deflection.",
        ]
        for key, value in ASSUMED_CONTACT_PATCH.items():
            self.put("CONTACT_PATCH", key, value)
        b = ASSUMED_HALF_WIDTH * width
        self.table("CONTACT_WIDTH_CURVE", [[d, b] for d in _WIDTH_CURVE_DEFLECTIONS],
                   ["deflection", "half_width"])

    def mass_and_inertia(self, mass_keys=("Mass",), inertia_keys=("Inertia",)) -> None:
        doc = self.doc
        self.put("INERTIA", "MASS", doc.number(*mass_keys, minimum=0.0), mass_keys)
        self.put("INERTIA", "IYY", doc.vector(*inertia_keys, size=3)[1], inertia_keys)

    def vertical(self, stiffness_keys, damping_keys, curve_keys=None) -> None:
        """Linear stiffness (optional when a curve is given), damping, curve."""
        doc = self.doc
        has_curve = curve_keys is not None and doc.has(*curve_keys)
        if not has_curve or doc.has(*stiffness_keys):
            self.put("VERTICAL", "VERTICAL_STIFFNESS", doc.number(*stiffness_keys, positive=True),
                     stiffness_keys)
        self.put("VERTICAL", "VERTICAL_DAMPING", doc.number(*damping_keys, minimum=0.0), damping_keys)
        if has_curve:
            self.table("DEFLECTION_LOAD_CURVE", doc.curve(*curve_keys), ["pen", "fz"], curve_keys)

    def dimensions(self, radius_keys, width: float | None = None, width_keys=None,
                   rim_keys=None) -> tuple[float, float]:
        doc = self.doc
        r0 = doc.number(*radius_keys, positive=True)
        self.put("DIMENSION", "UNLOADED_RADIUS", r0, radius_keys)
        if width is None:
            width = doc.number(*width_keys, positive=True)
        self.put("DIMENSION", "WIDTH", width, width_keys or ())
        if rim_keys is not None:
            rim = doc.number(*rim_keys, positive=True)
            if not rim < r0:
                raise doc.error(f"the rim radius {rim:g} m must be below the unloaded radius {r0:g} m",
                                rim_keys)
            self.put("DIMENSION", "RIM_RADIUS", rim, rim_keys)
        return r0, width


def _comment(doc: _Document, label: str, *keys) -> list[str]:
    """A header line recording a value tyrelab does not use (nothing when absent)."""
    if not doc.has(*keys):
        return []
    return [f"$ {label}: {json.dumps(doc.value(*keys))} (not used by tyrelab)"]
