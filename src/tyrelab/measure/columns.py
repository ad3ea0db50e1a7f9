"""Measured CSV files with a column map: laboratory exports into the signal table.

Test rigs and data loggers export CSV with their own column names and units
("Time [ms]", "Fz_hub (kN)" ...). A *column map* says, for each column to
keep, which signal channel it is and in which unit it was logged::

    {"Time [ms]": ("RUNTIME", "ms"), "Fz_hub (kN)": ("FZ", "kN")}

or, as a small CSV file read by :func:`read_column_map`, lines
``source,channel,unit`` (a header line ``source,channel,unit`` is optional).
A channel written with a leading minus (``"-FZ"``) is logged with the opposite
sign: a load cell whose axis points the other way from the TYDEX C-axis
system's (z up, the road's force on the tyre), as an ISO W-axis logger's vertical
force does. The column is negated when read.
Values are converted to SI (:mod:`tyrelab.measure.units`); columns not in
the map are ignored. Lines that start with ``#`` and blank lines are
skipped; empty cells read as NaN.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import InputError
from ..signal import make_signal
from .units import si_unit, to_si


def _csv_rows(path: Path, delimiter: str = ","):
    """``(line number, cells)`` of a CSV text file; a file that is not UTF-8 text or not CSV
    (binary bytes, a NUL) is one InputError naming it, never a decoding traceback."""
    try:
        with open(path, encoding="utf-8", newline="") as fh:
            reader = csv.reader(fh, delimiter=delimiter)
            for row in reader:
                yield reader.line_num, row
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte {exc.start}: {exc.reason}); expected a CSV "
                         "text file", source=str(path)) from None
    except csv.Error as exc:
        raise InputError(f"not a CSV text file ({exc})", source=str(path)) from None


def read_column_map(path) -> dict[str, tuple[str, str]]:
    """Read a column map file: ``source,channel,unit`` per line."""
    path = Path(path)
    if not path.is_file():
        raise InputError("no such file", source=str(path))
    mapping: dict[str, tuple[str, str]] = {}
    for lineno, row in _csv_rows(path):
        if not row or not "".join(row).strip() or row[0].lstrip().startswith("#"):
            continue
        cells = [c.strip() for c in row]
        if lineno == 1 and [c.lower() for c in cells[:3]] == ["source", "channel", "unit"]:
            continue
        if len(cells) not in (2, 3):
            raise InputError(f"expected 'source,channel,unit', got {len(cells)} fields",
                             source=str(path), line=lineno)
        column, channel, unit = cells if len(cells) == 3 else (*cells, "")  # unit optional
        si_unit(unit, source=str(path), line=lineno, field=column)
        mapping[column] = (channel, unit)
    if not mapping:
        raise InputError("column map is empty", source=str(path))
    return mapping


def _table(path: Path, delimiter: str):
    """(header cells, header line, [(line number, cells)]) of a CSV file."""
    header, header_line, rows = None, None, []
    for lineno, row in _csv_rows(path, delimiter):
        if not row or not "".join(row).strip() or row[0].lstrip().startswith("#"):
            continue
        if header is None:
            header, header_line = [c.strip() for c in row], lineno
            continue
        rows.append((lineno, row))
    if header is None:
        raise InputError("no header line", source=str(path))
    return header, header_line, rows


def _number(cell: str, path, lineno, field) -> float:
    text = cell.strip()
    if text == "" or text.lower() == "nan":
        return np.nan
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"'{text}' is not a number", source=str(path), line=lineno,
                         field=field) from None
    if not np.isfinite(value):
        raise InputError(f"'{text}' is not a finite number (leave the cell empty for a missing value)",
                         source=str(path), line=lineno, field=field)
    return value


def read_mapped_csv(path, column_map: dict, delimiter: str = ",",
                    metadata: dict | None = None) -> pd.DataFrame:
    """Read a measured CSV file into a signal table in SI.

    Parameters
    ----------
    path : str or Path
        The CSV file (first non-comment line is the header).
    column_map : dict
        Source column -> (channel, unit); see the module docstring.
    delimiter : str
        Field separator (``","``; ``";"`` for many European loggers).
    metadata : dict, optional
        Run description stored in ``attrs["metadata"]``.

    Raises
    ------
    InputError
        A mapped column missing from the header (field = column), a cell that
        is not a number (line, field), a row with too few cells, an unknown
        unit, two source columns mapped to one channel.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("no such file", source=str(path))
    signs = {src: -1.0 if ch.startswith("-") else 1.0 for src, (ch, _) in column_map.items()}
    for src, (ch, _) in column_map.items():
        if ch == "-RUNTIME":
            raise InputError("time cannot be logged with the opposite sign ('-RUNTIME'); "
                             "a minus belongs to a force, moment or position channel",
                             source=str(path), field=src)
    column_map = {src: (ch.removeprefix("-"), unit) for src, (ch, unit) in column_map.items()}
    channels = [ch for ch, _ in column_map.values()]
    if len(set(channels)) != len(channels):
        raise InputError("two source columns map to the same channel", source=str(path))
    header, header_line, rows = _table(path, delimiter)
    index = {}
    for source in column_map:
        if source not in header:
            raise InputError("column not in the file header", source=str(path),
                             line=header_line, field=source)
        index[source] = header.index(source)
    data = {ch: np.empty(len(rows)) for ch in channels}
    for r, (lineno, row) in enumerate(rows):
        for source, (channel, _) in column_map.items():
            i = index[source]
            if i >= len(row):
                raise InputError(f"row has {len(row)} fields, header has {len(header)}",
                                 source=str(path), line=lineno)
            data[channel][r] = _number(row[i], path, lineno, source)
    if not rows:
        raise InputError("no data rows", source=str(path))
    with np.errstate(over="ignore"):
        si = {ch: signs[src] * to_si(data[ch], unit, source=str(path), field=src)
              for src, (ch, unit) in column_map.items()}
    for src, (ch, _) in column_map.items():
        over = np.isinf(si[ch])
        if over.any():
            k = int(np.flatnonzero(over)[0])
            raise InputError(f"value {data[ch][k]!r} overflows when converted to SI", source=str(path),
                             line=rows[k][0], field=src)
    df = make_signal(si, {"source": str(path), **(metadata or {})})
    df.attrs["units"] = {ch: si_unit(unit) for ch, unit in column_map.values()} | {
        c: df.attrs["units"].get(c, "") for c in df.columns if c not in channels}
    df.attrs["units"] = {c: df.attrs["units"][c] for c in df.columns}
    return df
