"""The signal table: one form for simulated and measured runs.

A run is a :class:`pandas.DataFrame` with one row per time sample and SI
columns. Column names follow TYDEX where TYDEX has a name for the quantity;
the others are this project's and are listed here once.

Sign convention (written down once, used everywhere)
----------------------------------------------------
Forces and moments are those of the road on the tyre (equivalently, at the
hub, of the tyre on the rim), expressed in the TYDEX C-axis system of the
wheel: origin in the wheel centre, x forward in the wheel plane and parallel
to the ground, y along the spin axis pointing to the left of the direction of
travel, z upward, turning with the inclination angle (TYDEX manual; SAE J2047
C-axis). A tyre pressed onto the ground therefore shows a *positive* FZ.
Contact-patch quantities (suffix ``W``) use the TYDEX W-axis system: origin
in the contact point, z along the (effective) road normal, x the intersection
of the wheel plane with the road plane.

Positions and velocities are in the road (inertial) frame: x along the road,
y to the left, z up. Time is in seconds.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from .errors import InputError
from . import io_atomic
from .io_atomic import atomic_output  # noqa: F401 - the one atomic writer, re-exported here

#: column name -> (unit, description). Order is the order in files.
CHANNELS: dict[str, tuple[str, str]] = {
    "RUNTIME": ("s", "time since the start of the run"),
    "DISTANCE": ("m", "distance travelled by the wheel centre along the road"),
    # wheel-centre forces and moments, C-axis (TYDEX names)
    "FX": ("N", "longitudinal force at the wheel centre, C-axis"),
    "FY": ("N", "lateral force at the wheel centre, C-axis"),
    "FZ": ("N", "vertical force at the wheel centre, C-axis"),
    "MX": ("N m", "overturning moment at the wheel centre, C-axis"),
    "MY": ("N m", "rolling-resistance moment at the wheel centre, C-axis"),
    "MZ": ("N m", "aligning moment at the wheel centre, C-axis"),
    # contact-patch forces, W-axis (TYDEX names)
    "FXW": ("N", "longitudinal force in the contact point, W-axis"),
    "FYW": ("N", "lateral force in the contact point, W-axis"),
    "FZW": ("N", "normal force in the contact point, W-axis"),
    # wheel state (project names)
    "X_WC": ("m", "wheel-centre x, road frame"),
    "Y_WC": ("m", "wheel-centre y, road frame"),
    "Z_WC": ("m", "wheel-centre z, road frame"),
    "VX_WC": ("m/s", "wheel-centre velocity x, road frame"),
    "VY_WC": ("m/s", "wheel-centre velocity y, road frame"),
    "VZ_WC": ("m/s", "wheel-centre velocity z, road frame"),
    "ROTSPEED": ("rad/s", "wheel spin rate about its axis, positive rolling forward"),
    "INCLANGL": ("rad", "inclination (camber) angle of the wheel plane to the road frame's z axis "
                           "(the normal of a level road), positive when the wheel's top leans to its right"),
    "DEFLECT": ("m", "tyre radial deflection (positive in compression)"),
    "LONGSLIP": ("-", "longitudinal slip kappa (ISO/TYDEX W, > 0 driving)"),
    "SLIPANGL": ("rad", "slip angle alpha (ISO/TYDEX W)"),
    "LONGVEL": ("m/s", "longitudinal speed of the wheel centre"),
    "X_CP": ("m", "contact point x, road frame"),
    "Y_CP": ("m", "contact point y, road frame"),
    "Z_CP": ("m", "contact point z, road frame"),
    # rig channels (project names)
    "FX_HUB": ("N", "load-cell force at the hub, C-axis x (tyre force less wheel inertia)"),
    "FY_HUB": ("N", "load-cell force at the hub, C-axis y"),
    "FZ_HUB": ("N", "load-cell force at the hub, C-axis z"),
    "FZ_LEFT": ("N", "normal force of the trailer's left (non-test) wheel"),
    "PITCH": ("rad", "trailer pitch about the hitch (positive: rear up)"),
    "ROLL": ("rad", "trailer roll about its longitudinal axis"),
    "Z_BODY": ("m", "quarter vehicle: sprung-mass height"),
    "VZ_BODY": ("m/s", "quarter vehicle: sprung-mass vertical velocity"),
    "F_SUSP": ("N", "quarter vehicle: suspension force (compression positive)"),
    "SINKAGE": ("m", "soil: depth of the tyre's contact point below the surface as laid"),
    "TORQUE": ("N m", "single-wheel tester: driving torque the axle applies (positive driving)"),
}

#: Channels that a force signal must never carry as NaN or negative.
NORMAL_FORCE_CHANNELS = ("FZW",)


def units(columns) -> dict[str, str]:
    """Unit of each known column (unknown columns get '')."""
    return {c: CHANNELS.get(c, ("", ""))[0] for c in columns}


def _described(df: pd.DataFrame, metadata: dict | None) -> pd.DataFrame:
    """Attach the units of the columns and the run metadata to a table."""
    df.attrs["units"] = units(df.columns)
    df.attrs["metadata"] = dict(metadata or {})
    return df


def signal_from_array(data: np.ndarray, channels, metadata: dict | None = None) -> pd.DataFrame:
    """A signal table from a 2D array whose columns are ``channels`` (no copy)."""
    return _described(pd.DataFrame(np.asarray(data, dtype=float), columns=list(channels), copy=False),
                      metadata)


def make_signal(data: dict[str, np.ndarray], metadata: dict | None = None) -> pd.DataFrame:
    """Build a signal table from arrays, in the standard column order.

    Known channels come first in :data:`CHANNELS` order, then any extra
    columns in the order given. ``metadata`` (run description: tyre, model,
    road, speed ...) and the units go to ``DataFrame.attrs``.
    """
    known = [c for c in CHANNELS if c in data]
    extra = [c for c in data if c not in CHANNELS]
    return _described(pd.DataFrame({c: np.asarray(data[c], dtype=float) for c in known + extra}),
                      metadata)


#: Parquet compressions of :func:`write_signal`: ``"snappy"`` is pyarrow's default (dictionary
#: encoding, snappy: every file tyrelab wrote before the compact study store, and still
#: ``tyrelab simulate -o``'s),
#: ``"zstd"`` is zstd at :data:`ZSTD_LEVEL` with the float columns byte-stream split and no
#: dictionary: lossless too, and 45 % smaller on the thesis campaign's runs
#: (``benchmarks/store_format.py``)
PARQUET_COMPRESSIONS = ("snappy", "zstd")
ZSTD_LEVEL = 3
#: the largest relative change of a value stored as float32 (round to nearest: half its ulp)
FLOAT32_RELATIVE_ERROR = 2.0 ** -24
_FLOAT32_MAX = float(np.finfo(np.float32).max)


def _narrowed(df: pd.DataFrame, float32) -> tuple[pd.DataFrame, list[str]]:
    """``df`` with the float64 columns of ``float32`` rounded to float32 (those whose finite
    values all fit; a larger one stays float64), and the names of the rounded columns."""
    wanted = set(float32)
    narrow = []
    for col in df.columns:
        if col in wanted and df[col].dtype == np.float64:
            values = df[col].to_numpy()
            finite = values[np.isfinite(values)]
            if finite.size == 0 or np.abs(finite).max() <= _FLOAT32_MAX:
                narrow.append(col)
    if not narrow:
        return df, []
    return df.astype({c: np.float32 for c in narrow}), narrow


def write_signal(df: pd.DataFrame, path, *, compression: str = "snappy", float32=(),
                 storage: dict | None = None) -> None:
    """Write a signal table as Parquet (``.parquet``) or CSV (``.csv``).

    Units and run metadata go into the Parquet schema metadata, or into
    ``#`` comment lines at the top of a CSV. The file appears only when it is
    complete (written to a temporary name, then renamed: :mod:`tyrelab.io_atomic`),
    so an interrupted run never leaves a file that looks finished. A missing
    folder, a folder as ``path`` or a table with no rows is an
    :class:`InputError` before anything is written.

    Parquet only (a CSV is written as before, and these must keep their defaults):
    ``compression`` one of :data:`PARQUET_COMPRESSIONS` (default ``"snappy"``, the
    form of every earlier file); ``float32`` the columns to store rounded to float32
    (each value within :data:`FLOAT32_RELATIVE_ERROR` of the original, relative;
    a column with a finite value beyond float32's range stays float64);
    ``storage`` a JSON-able description of the form, kept in the file with
    the rounded columns' names (``"storage"`` of the schema metadata, read back
    into ``attrs["storage"]``). :func:`read_signal` returns float64 columns
    whatever was stored.
    """

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".parquet", ".csv"):
        raise InputError(f"unknown output format '{path.suffix}', expected .parquet or .csv",
                         source=str(path))
    if compression not in PARQUET_COMPRESSIONS:
        raise ValueError(f"compression {compression!r}: expected one of {PARQUET_COMPRESSIONS}")
    if suffix == ".csv" and (compression != "snappy" or list(float32) or storage):
        raise ValueError("compression, float32 and storage apply to Parquet files only")
    if len(df) == 0:
        raise InputError("refusing to write a signal table with no rows", source=str(path))
    meta = {"units": df.attrs.get("units", units(df.columns)),
            "metadata": df.attrs.get("metadata", {})}
    with io_atomic.atomic_output(path) as tmp:
        if suffix == ".parquet":
            import pyarrow as pa
            import pyarrow.parquet as pq
            data, narrow = _narrowed(df, float32)
            if storage is not None or narrow:
                meta["storage"] = {**(storage or {}), "float32": narrow}
            table = pa.Table.from_pandas(data, preserve_index=False)
            old = table.schema.metadata or {}
            table = table.replace_schema_metadata({**old, b"tyrelab": json.dumps(meta).encode()})
            if compression == "snappy":
                pq.write_table(table, tmp)  # pyarrow's defaults: the form of every earlier file
            else:
                floats = [f.name for f in table.schema if pa.types.is_floating(f.type)]
                pq.write_table(table, tmp, compression="zstd", compression_level=ZSTD_LEVEL,
                               use_dictionary=False, use_byte_stream_split=floats or False)
        else:
            with open(tmp, "w", encoding="utf-8", newline="") as fh:
                fh.write("# tyrelab " + json.dumps(meta) + "\n")
                df.to_csv(fh, index=False, float_format="%.9g")


def read_signal(path, columns=None) -> pd.DataFrame:
    """Read a signal table written by :func:`write_signal`; ``columns``: only these
    channels (a Parquet file reads only them from the disk; an absent one is an error)."""

    path = Path(path)
    if not path.is_file():
        raise InputError("no such file", source=str(path))
    suffix = path.suffix.lower()
    meta = {}
    try:
        if suffix == ".parquet":
            import pyarrow.parquet as pq
            table = pq.read_table(path, columns=None if columns is None else list(columns))
            raw = (table.schema.metadata or {}).get(b"tyrelab")
            meta = json.loads(raw) if raw else {}
            df = table.to_pandas()
            narrow = {c: np.float64 for c in df.columns if df[c].dtype == np.float32}
            if narrow:  # stored as float32 (a compact study store): read as every other table
                df = df.astype(narrow)
        elif suffix == ".csv":
            with open(path, encoding="utf-8") as fh:
                first = fh.readline()
            if first.startswith("# tyrelab "):
                meta = json.loads(first[len("# tyrelab "):])
            df = pd.read_csv(path, comment="#", usecols=None if columns is None else list(columns))
        else:
            raise InputError(f"unknown signal format '{path.suffix}', expected .parquet or .csv",
                             source=str(path))
    except InputError:
        raise
    except Exception as exc:  # pyarrow / pandas parse errors
        raise InputError(f"not a readable signal table ({exc})", source=str(path)) from None
    for col in df.columns:  # NaN marks a missing sample; an infinite one is a damaged file
        values = df[col].to_numpy()
        if values.dtype.kind == "f" and np.isinf(values).any():
            row = int(np.flatnonzero(np.isinf(values))[0])
            raise InputError(f"sample {row + 1} is infinite ({values[row]})", source=str(path), field=col)
    df.attrs["units"] = {c: u for c, u in meta.get("units", units(df.columns)).items()
                         if c in df.columns}
    df.attrs["metadata"] = meta.get("metadata", {})
    if "storage" in meta:  # how a compact store kept it (write_signal)
        df.attrs["storage"] = meta["storage"]
    return df
