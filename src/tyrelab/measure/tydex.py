"""TYDEX (``.tdx``) measurement files: read into, and write from, the signal table.

A TYDEX file is plain text in sections that start with ``**``:
``**HEADER`` (file identification: RELEASE, MEASID, DATE ...),
``**COMMENTS`` (free text), ``**CONSTANTS`` (name, description, unit, value),
``**MEASURCHANNELS`` (one line per data column: name, description, unit,
conversion factor and optional offsets), ``**MEASURDATA`` (the numbers, one
record per sample) and ``**END``. Header, constant and channel lines use
fixed columns: name in columns 1-10, description 11-40, unit 41-50, values
from 51 on. Other sections (``**MODELPARAMETERS`` ...) are skipped.

Channel names are the TYDEX names, which the signal table already uses
(RUNTIME, FX, FY, FZ, MX, MY, MZ in the C-axis system, FXW, FYW, FZW in the
W-axis system, INCLANGL, ROTSPEED ...); so the mapping is the identity and
channels the project does not know are kept under their own names. A name
written in lower case (``fz``) is read as the TYDEX channel it spells.

A file without its closing ``**END`` is read, with a warning: it may have been
cut short while it was written or copied.

Values: a stored number ``raw`` of a channel means ``factor * raw + offset``
in the channel's unit, which is then converted to SI
(:mod:`tyrelab.measure.units`). The missing-value word ``NOTAVAIL`` reads as
NaN. A record may be wrapped over several lines; it is complete when it holds
one value per channel. Any other non-finite number (``nan``, ``inf``, a
value that overflows when scaled or converted to SI) is an
:class:`InputError` naming the file, the line and the channel.

References
----------
.. [1] Unrau, H.-J., Zamow, J. (1997). TYDEX-Format: Description and
   Reference Manual, Release 1.3. Universitaet Karlsruhe / Porsche AG.
   (Section and column layout as described there; read from public
   descriptions and readers, not copied.)
"""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import InputError
from ..io_atomic import atomic_write_text
from ..signal import CHANNELS, make_signal
from .units import from_si, si_unit, to_si

SECTIONS = ("**HEADER", "**COMMENTS", "**CONSTANTS", "**MEASURCHANNELS",
            "**MEASURDATA", "**END")
MISSING = "NOTAVAIL"
_META_TAG = "tyrelab-metadata:"
#: SI unit as the signal table writes it -> spelling written in a TYDEX file
_TYDEX_SPELLING = {"N m": "Nm", "": "-"}


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _split_fixed(text: str):
    """(name, description, unit, value text) from a fixed-column line [1]."""
    name = text[:10].strip()
    return name, text[10:40].strip(), text[40:50].strip(), text[50:].strip()


def _split_free(text: str):
    """Whitespace fallback: name, description..., unit, numbers at the end."""
    tokens = text.split()
    k = len(tokens)
    while k > 1 and _is_number(tokens[k - 1]):
        k -= 1
    numbers = tokens[k:]
    unit = tokens[k - 1] if k > 1 else ""
    desc = " ".join(tokens[1:k - 1])
    return tokens[0], desc, unit, " ".join(numbers)


def _parse_entry(text: str, numeric: bool):
    """Split a header/constant/channel line; prefer the fixed columns."""
    fixed = _split_fixed(text)
    if " " not in fixed[0] and fixed[0]:
        values = fixed[3].split()
        if not numeric or (values and all(_is_number(v) for v in values)):
            return fixed
    return _split_free(text)


def _channel(text: str, path, lineno: int) -> dict:
    """One ``**MEASURCHANNELS`` line -> name, description, unit, factor, offset."""
    name, desc, unit, rest = _parse_entry(text, numeric=True)
    if name not in CHANNELS and name.upper() in CHANNELS:
        name = name.upper()  # TYDEX names are upper case; 'fz' is FZ
    numbers = rest.split()
    for tok in numbers:
        if not _is_number(tok):
            raise InputError(f"conversion factor '{tok}' is not a number",
                             source=path, line=lineno, field=name)
    values = [float(v) for v in numbers] or [1.0]
    for v in values:
        if not math.isfinite(v):
            raise InputError(f"conversion factor or offset {v} is not a finite number",
                             source=path, line=lineno, field=name)
    if len(values) > 3:
        raise InputError("expected at most a conversion factor and two offsets",
                         source=path, line=lineno, field=name)
    factor, offset = values[0], (values[1] if len(values) > 1 else 0.0)
    if len(values) == 3 and values[2] != 0.0:
        raise InputError("a second (physical) offset is not supported; use one offset",
                         source=path, line=lineno, field=name)
    if not np.isfinite(factor) or factor == 0.0:
        raise InputError("conversion factor must be finite and non-zero",
                         source=path, line=lineno, field=name)
    si_unit(unit, source=path, line=lineno, field=name)  # raises if unknown
    return {"name": name, "description": desc, "unit": unit,
            "factor": factor, "offset": offset, "line": lineno}


def _read_sections(path: Path):
    """Lines of each section as (line number, text), without blank lines."""
    try:
        text = path.read_text(encoding="utf-8", errors="strict")
    except UnicodeDecodeError as exc:
        raise InputError(f"not a text file ({exc.reason})", source=str(path)) from None
    sections: dict[str, list[tuple[int, str]]] = {}
    current = None
    for lineno, raw in enumerate(text.splitlines(), start=1):
        line = raw.rstrip()
        if line.strip().startswith("**"):
            current = line.strip().upper()
            if current in sections and current in SECTIONS[:-1]:
                raise InputError(f"section {current} appears twice", source=str(path),
                                 line=lineno)
            sections.setdefault(current, [])
            continue
        if current is None:
            if line.strip():
                raise InputError("text before the first '**' section; not a TYDEX file",
                                 source=str(path), line=lineno)
            continue
        if line.strip() and not line.lstrip().startswith("!"):
            sections[current].append((lineno, line))
    return sections


def _records(lines, channels, path):
    """Data records from ``**MEASURDATA`` lines; wrapped records allowed."""
    n = len(channels)
    rows, pending, start, starts = [], [], None, []
    for lineno, text in lines:
        tokens = text.split()
        if not pending:
            start = lineno
        pending.extend((lineno, tok) for tok in tokens)
        if len(pending) > n:
            raise InputError(f"record has {len(pending)} values, expected {n} (one per channel)",
                             source=str(path), line=lineno)
        if len(pending) == n:
            row = []
            for (ln, tok), ch in zip(pending, channels):
                if tok.upper() == MISSING:
                    row.append(np.nan)
                elif _is_number(tok):
                    value = float(tok)
                    if not math.isfinite(value):
                        raise InputError(f"'{tok}' is not a finite number (write {MISSING} for a "
                                         "missing value)", source=str(path), line=ln, field=ch["name"])
                    row.append(value)
                else:
                    raise InputError(f"'{tok}' is not a number", source=str(path), line=ln,
                                     field=ch["name"])
            rows.append(row)
            starts.append(start)
            pending = []
    if pending:
        raise InputError(f"last record has {len(pending)} values, expected {n}",
                         source=str(path), line=start)
    return np.array(rows, dtype=float).reshape(-1, n), starts


def _key_values(lines, path, numeric: bool):
    """Header entries (text) or constants (numbers converted to SI).

    Some writers put a header value in the unit columns 41-50; an entry with
    no text from column 51 on takes its value from there. A constant whose
    value is not a number is kept as text, without unit conversion.
    """
    out = {}
    for lineno, text in lines:
        name, desc, unit, value = _parse_entry(text, numeric=numeric)
        if not value and unit:
            unit, value = "", unit
        entry = {"description": desc, "unit": unit, "value": value}
        if numeric and _is_number(value):
            si = float(to_si(float(value), unit, str(path), lineno, name))
            if not math.isfinite(si):
                raise InputError(f"'{value}' is not a finite number (in SI)", source=str(path),
                                 line=lineno, field=name)
            entry["value"] = si
            entry["unit"] = si_unit(unit)
        out[name] = entry
    return out


def read_tydex(path) -> pd.DataFrame:
    """Read a TYDEX file into a signal table in SI.

    Parameters
    ----------
    path : str or Path
        The ``.tdx`` file.

    Returns
    -------
    pandas.DataFrame
        One column per measurement channel, values in SI; ``attrs["units"]``
        the SI units; ``attrs["metadata"]`` the run metadata written by
        :func:`write_tydex` (if any) plus ``"tydex"``: header entries,
        constants (in SI) and comment lines.

    Raises
    ------
    InputError
        Missing sections, a channel line or data record that does not
        parse, an unknown unit; the message names the file and line.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("no such file", source=str(path))
    sections = _read_sections(path)
    for needed in ("**MEASURCHANNELS", "**MEASURDATA"):
        if needed not in sections:
            raise InputError(f"missing section {needed}", source=str(path))
    channels = [_channel(text, str(path), ln) for ln, text in sections["**MEASURCHANNELS"]]
    if not channels:
        raise InputError("section **MEASURCHANNELS lists no channel", source=str(path))
    seen = {}
    for ch in channels:
        if ch["name"] in seen:
            raise InputError(f"channel listed twice (first on line {seen[ch['name']]})",
                             source=str(path), line=ch["line"], field=ch["name"])
        seen[ch["name"]] = ch["line"]
    raw, record_lines = _records(sections["**MEASURDATA"], channels, path)
    if raw.shape[0] == 0:
        raise InputError("section **MEASURDATA holds no record", source=str(path))
    if "**END" not in sections:
        warnings.warn(f"{path}: no closing **END line: the file may be cut short; read "
                      f"{raw.shape[0]} records, the last on line {record_lines[-1]}", stacklevel=2)
    data = {}
    with np.errstate(over="ignore", invalid="ignore"):
        for i, ch in enumerate(channels):
            data[ch["name"]] = to_si(ch["factor"] * raw[:, i] + ch["offset"], ch["unit"])
            overflow = np.isnan(data[ch["name"]]) != np.isnan(raw[:, i])
            overflow |= np.isinf(data[ch["name"]])
            if overflow.any():
                k = int(np.flatnonzero(overflow)[0])
                raise InputError(f"value {raw[k, i]!r} overflows when scaled by the channel's factor and "
                                 "converted to SI", source=str(path), line=record_lines[k],
                                 field=ch["name"])
    comments = [text for _, text in sections.get("**COMMENTS", [])]
    metadata = {}
    for line in comments:
        if line.strip().startswith(_META_TAG):
            try:
                metadata = json.loads(line.strip()[len(_META_TAG):])
            except json.JSONDecodeError:
                metadata = {}
    metadata["tydex"] = {
        "header": {k: v["value"] for k, v in
                   _key_values(sections.get("**HEADER", []), path, numeric=False).items()},
        "constants": _key_values(sections.get("**CONSTANTS", []), path, numeric=True),
        "comments": [c for c in comments if not c.strip().startswith(_META_TAG)],
    }
    df = make_signal(data, metadata)
    df = df[[ch["name"] for ch in channels]]  # keep the file's channel order
    df.attrs["units"] = {ch["name"]: si_unit(ch["unit"]) for ch in channels}
    df.attrs["metadata"] = metadata
    return df


def _fixed_line(name: str, desc: str, unit: str, value: str) -> str:
    if len(name) > 10 or " " in name:
        raise InputError("TYDEX names have at most 10 characters and no blanks", field=name)
    return f"{name:<10}{desc[:29]:<30}{unit[:10]:<10}{value}".rstrip()


def _format(values) -> list[str]:
    return [MISSING if not np.isfinite(v) else repr(float(v)) for v in values]


def tydex_text(df: pd.DataFrame, units: dict | None = None, header: dict | None = None,
               constants: dict | None = None) -> str:
    """The text of a TYDEX file for a signal table (see :func:`write_tydex`)."""
    units = dict(units or {})
    si_units = df.attrs.get("units", {})
    lines = ["**HEADER"]
    head = {"RELEASE": "1.3", "MEASID": str(df.attrs.get("metadata", {}).get("name", "tyrelab")),
            "SUPPLIER": "tyrelab"}
    head.update(header or {})
    for key, value in head.items():
        lines.append(_fixed_line(key, key.lower(), "", str(value)))
    lines += ["**COMMENTS", "written by tyrelab; values in the units of each channel line",
              _META_TAG + " " + json.dumps(_plain_metadata(df.attrs.get("metadata", {})))]
    lines.append("**CONSTANTS")
    for key, (value, unit) in (constants or {}).items():
        lines.append(_fixed_line(key, key.lower(), unit, repr(float(value))))
    lines.append("**MEASURCHANNELS")
    columns = []
    for col in df.columns:
        own = si_units.get(col, CHANNELS.get(col, ("", ""))[0])
        unit = units.get(col) or _TYDEX_SPELLING.get(own, own)
        if si_unit(unit, field=col) != si_unit(own, field=col):
            raise InputError(f"unit '{unit}' does not measure the same quantity as '{own}'",
                             field=col)
        desc = CHANNELS.get(col, ("", col))[1]
        lines.append(_fixed_line(col, desc, unit, "1"))
        columns.append(from_si(df[col].to_numpy(dtype=float), unit))
    lines.append("**MEASURDATA")
    matrix = np.column_stack(columns) if columns else np.empty((0, 0))
    lines += [" ".join(_format(row)) for row in matrix]
    lines.append("**END")
    return "\n".join(lines) + "\n"


def _plain_metadata(meta: dict) -> dict:
    """Metadata without the ``tydex`` block a reader added (it is rewritten)."""
    return {k: v for k, v in meta.items() if k != "tydex"}


def write_tydex(df: pd.DataFrame, path, units: dict | None = None,
                header: dict | None = None, constants: dict | None = None) -> None:
    """Write a signal table as a TYDEX file.

    Parameters
    ----------
    df : pandas.DataFrame
        Signal table in SI (:func:`tyrelab.signal.make_signal`).
    path : str or Path
        Output file; it appears only when complete (temporary name, rename).
    units : dict, optional
        Channel -> unit to write it in (e.g. ``{"FZ": "kN"}``); default SI.
    header : dict, optional
        Extra ``**HEADER`` entries (name -> text), e.g. ``{"DATE": "..."}``.
    constants : dict, optional
        ``**CONSTANTS``: name -> (value, unit).

    Notes
    -----
    Numbers are written with ``repr`` (shortest round-trip form), so an SI
    table written and read back is identical. One record per line.
    """
    text = tydex_text(df, units=units, header=header, constants=constants)
    atomic_write_text(Path(path), text, newline="\n")
