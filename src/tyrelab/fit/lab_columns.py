"""Finding and reading the columns of a campaign's test files (CSV or TYDEX), in SI.

A column is found by the manifest's ``columns`` (quantity -> header) or by its name: the
quantity or an alias (:data:`QUANTITIES`), with the unit after an underscore or in
brackets; ``units`` in the manifest overrides; without any unit the column is SI. A TYDEX
file's channel is the manifest's or :data:`TYDEX_CHANNELS`'. :mod:`.lab_files` reads each
kind of test with these.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..measure.columns import _number, _table
from ..measure.units import is_known_unit, si_unit, to_si

#: quantity -> (its SI unit, names it goes by in a file header, lower case)
QUANTITIES = {
    "deflection": ("m", ("deflection", "defl", "rho", "pen", "deflect", "penetration")),
    "load": ("N", ("load", "force", "fz", "fzw")),
    "time": ("s", ("time", "t", "runtime")),
    "displacement": ("m", ("displacement", "z", "z_wc", "height", "position")),
    "length": ("m", ("length", "contact_length")),
    "width": ("m", ("width", "contact_width")),
    "y": ("m", ("y", "lateral", "offset")),
    "radius": ("m", ("radius", "r")),
    "drop": ("m", ("drop", "depth")),
}
#: TYDEX channel of each quantity when the manifest names none
TYDEX_CHANNELS = {"deflection": ("DEFLECT",), "load": ("FZW", "FZ"), "time": ("RUNTIME",),
                  "displacement": ("Z_WC",)}


def _tokens(header: str) -> list[str]:
    text = re.sub(r"[\[\]()]", " ", header)
    return [t for t in re.split(r"[\s_]+", text.strip()) if t]


def _unit_in(header: str, quantity: str) -> str | None:
    """The unit a header names for ``quantity`` (``load_N_300kPa`` -> ``N``), if any."""
    want = QUANTITIES[quantity][0]
    for tok in _tokens(header)[1:]:
        if is_known_unit(tok) and si_unit(tok) == want:
            return tok
    return None


def _find(header: list[str], quantity: str, source=None, line=None) -> str | None:
    """The one header that names ``quantity`` (None if none; an error if several do)."""
    names = QUANTITIES[quantity][1]
    found = []
    for h in header:
        low = h.strip().lower()
        toks = _tokens(low)
        if low in names or (toks and toks[0] in names and (len(toks) == 1 or _unit_in(h, quantity))) \
                or (len(toks) > 2 and "_".join(toks[:2]) in names):
            found.append(h)
    if len(found) > 1:
        raise InputError(f"columns {', '.join(found)} could each be the {quantity}: name one in the "
                         f"manifest's columns (campaign.toml)", source=source, line=line, field=quantity)
    return found[0] if found else None


#: a unit each SI unit's quantities are often written in, for the example of a message
_EXAMPLE_UNIT = {"m": "mm", "N": "kN", "s": "ms"}


def _unit_not_known(header: list[str], quantity: str, source, line) -> None:
    """Raise when a header names ``quantity`` with a unit that is not one of its units
    (``deflection_furlong``, ``load_mm``): the column is there, its unit is what is wrong."""
    si = QUANTITIES[quantity][0]
    for h in header:
        toks = _tokens(h.strip())
        if len(toks) > 1 and toks[0].lower() in QUANTITIES[quantity][1] and _unit_in(h, quantity) is None:
            raise InputError(f"column '{h}': '{' '.join(toks[1:])}' is not a unit of {quantity} "
                             f"({si}); name it like {toks[0]}_{si} or {toks[0]}_{_EXAMPLE_UNIT[si]}",
                             source=source, line=line, field=quantity)


def read_columns(path, required, optional=(), columns=None, units=None) -> tuple[dict, np.ndarray]:
    """Columns of a CSV file in SI: ``({quantity: array}, line of each row)``.

    ``columns`` maps a quantity to its header (else found by name), ``units`` a quantity to the
    unit its column is written in (else the header's, else SI). A cell that is not a finite
    number is an error naming its line; an empty cell is NaN.
    """
    path = Path(path)
    columns, units = dict(columns or {}), dict(units or {})
    header, header_line, rows = _table(path, ",")
    if not rows:
        raise InputError("no data rows below the header", source=str(path), line=header_line)
    out, found = {}, {}
    for q in (*required, *optional):
        name = columns.get(q) or _find(header, q, str(path), header_line)
        if name is None or name not in header:
            if q in required or q in columns:
                if q not in columns:
                    _unit_not_known(header, q, str(path), header_line)
                what = f"column '{name}'" if name else \
                    f"a '{q}' column ({', '.join(QUANTITIES[q][1][:3])} ..., unit after '_')"
                raise InputError(f"{what} is not in the header ({', '.join(header)})",
                                 source=str(path), line=header_line, field=q)
            continue
        found[q] = name
    lines = np.array([ln for ln, _ in rows], int)
    for q, name in found.items():
        i = header.index(name)
        raw = np.empty(len(rows))
        for r, (ln, row) in enumerate(rows):
            if i >= len(row):
                raise InputError(f"row has {len(row)} fields, the header {len(header)}",
                                 source=str(path), line=ln)
            raw[r] = _number(row[i], path, ln, name)
        unit = units.get(q) or _unit_in(name, q) or QUANTITIES[q][0]
        if si_unit(unit, source=str(path), line=header_line, field=name) != QUANTITIES[q][0]:
            raise InputError(f"unit '{unit}' is not a unit of {q} ({QUANTITIES[q][0]})",
                             source=str(path), line=header_line, field=name)
        out[q] = to_si(raw, unit)
    return out, lines


def _tydex_columns(path, required, optional=(), columns=None):
    from ..measure.io import read_run
    run = read_run(path)
    out = {}
    for q in (*required, *optional):
        names = [columns[q]] if columns and q in columns else TYDEX_CHANNELS.get(q, ())
        name = next((n for n in names if n in run.columns), None)
        if name is None:
            if q in required:
                raise InputError(f"no channel {' or '.join(names) or q} for the {q}; name it in the "
                                 f"manifest's columns", source=str(path), field=q)
            continue
        out[q] = run[name].to_numpy(float)
    # a record's line is not kept by the TYDEX reader: rows are named by their record number
    return out, np.arange(1, len(run) + 1), run


def read_test_columns(path, required, optional=(), columns=None, units=None):
    path = Path(path)
    if not path.is_file():
        raise InputError("no such file", source=str(path))
    if path.suffix.lower() in (".tdx", ".parquet"):
        data, lines, _ = _tydex_columns(path, required, optional, columns)
        return data, lines, "record"
    if path.suffix.lower() != ".csv":
        raise InputError(f"expected a .csv or .tdx file, got '{path.suffix}'", source=str(path))
    data, lines = read_columns(path, required, optional, columns, units)
    return data, lines, "line"


def check_rows(path, lines, kind, values, ok, message, field_name):
    """Raise naming the first row whose value fails ``ok``."""
    bad = np.flatnonzero(~ok)
    if bad.size:
        k = int(bad[0])
        where = {"line": lines[k]} if kind == "line" else {}
        text = message.format(value=values[k]) + ("" if kind == "line" else f" (record {lines[k]})")
        raise InputError(text, source=str(path), field=field_name, **where)


def check_finite(path, lines, kind, data, names):
    for q in names:
        if q in data:
            check_rows(path, lines, kind, data[q], np.isfinite(data[q]),
                   "missing value (every row needs a " + q + ")", q)
