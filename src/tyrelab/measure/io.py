"""One entry point for reading a run, simulated or measured, by file suffix."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from ..errors import InputError
from ..signal import read_signal
from .columns import read_column_map, read_mapped_csv
from .tydex import read_tydex


def read_run(path, column_map=None) -> pd.DataFrame:
    """Read a run as a signal table in SI.

    ``.tdx`` -> :func:`read_tydex`; ``.csv`` with ``column_map`` (a dict or
    the path of a column map file) -> :func:`read_mapped_csv`; ``.csv`` or
    ``.parquet`` without a map -> :func:`tyrelab.signal.read_signal` (files
    this project wrote).
    """
    path = Path(path)
    df = _read(path, column_map)
    df.attrs["path"] = str(path)  # what a later message about this run names
    return df


def _read(path: Path, column_map) -> pd.DataFrame:
    suffix = path.suffix.lower()
    if suffix == ".tdx":
        return read_tydex(path)
    if column_map is not None:
        if suffix != ".csv":
            raise InputError("a column map applies to .csv files only", source=str(path))
        if not isinstance(column_map, dict):
            column_map = read_column_map(column_map)
        return read_mapped_csv(path, column_map)
    if suffix in (".csv", ".parquet"):
        return read_signal(path)
    raise InputError(f"unknown run format '{path.suffix}', expected .tdx, .csv or .parquet",
                     source=str(path))
