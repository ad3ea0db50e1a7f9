"""Measured data: TYDEX files, mapped CSV files, units (all into the SI signal table)."""

from .columns import read_column_map, read_mapped_csv
from .io import read_run
from .tydex import read_tydex, tydex_text, write_tydex
from .units import from_si, si_unit, to_si

__all__ = ["read_tydex", "write_tydex", "tydex_text", "read_mapped_csv", "read_column_map",
           "read_run", "to_si", "from_si", "si_unit"]
