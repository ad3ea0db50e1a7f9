"""The results store of a study: one folder, one file pair per run, an index table.

Layout of a study folder::

    runs/<key>.parquet   the run's signal table (tyrelab.signal form)
    runs/<key>.json      the run's record: its specification, status, wall time, error
    index.parquet        every record as one table (rebuilt from the records)

``key`` is derived from the run's complete specification (the study spec's
``run_key``), so a run whose tyre, model, road, speed, load, step or package
version changes gets a new key and is computed again, while every other run
is found finished and skipped.

What "finished" means, and why a partial file never looks complete: the
signal table is written to a temporary name and renamed when whole
(:func:`tyrelab.signal.write_signal`); the record is written the same way
*after* it. A run is finished only when its record says ``"done"`` and its
table exists, so a study killed at any instant loses only the runs in
flight, and a record of a failed run (status ``"failed"``, the error's one
line) is kept for the report and retried on the next run of the study.
"""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from ..errors import InputError
from ..io_atomic import atomic_output
from ..signal import read_signal, write_signal

#: status of a run's record
DONE, FAILED = "done", "failed"


def _write_json(path: Path, record: dict) -> None:
    """Write ``record`` as JSON to ``path`` atomically (temporary name, then rename)."""
    with atomic_output(path) as tmp, open(tmp, "w", encoding="utf-8") as fh:
        json.dump(record, fh, sort_keys=True, allow_nan=False)


class Store:
    """A study's results folder (created if missing)."""

    def __init__(self, folder):
        self.folder = Path(folder)
        self.runs = self.folder / "runs"
        try:
            self.runs.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise InputError(f"cannot create the results folder ({exc.strerror})",
                             source=str(self.folder)) from None
        for stale in self.runs.glob(".tyrelab-*.part"):  # left by a killed writer
            stale.unlink(missing_ok=True)

    def signal_path(self, key: str) -> Path:
        return self.runs / f"{key}.parquet"

    def record_path(self, key: str) -> Path:
        return self.runs / f"{key}.json"

    def record(self, key: str) -> dict | None:
        """The record of run ``key``, or None if there is none (or it is unreadable)."""
        try:
            return json.loads(self.record_path(key).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None

    def is_finished(self, key: str) -> bool:
        rec = self.record(key)
        return rec is not None and rec.get("status") == DONE and self.signal_path(key).is_file()

    def save(self, key: str, spec: dict, signal: pd.DataFrame, wall_time: float) -> None:
        """Store a finished run: its table first, then its record."""
        write_signal(signal, self.signal_path(key))
        _write_json(self.record_path(key), {**spec, "key": key, "status": DONE,
                                            "wall_time_s": float(wall_time),
                                            "simulated_s": float(signal["RUNTIME"].iloc[-1]
                                                                 - signal["RUNTIME"].iloc[0]),
                                            "error": ""})

    def save_failure(self, key: str, spec: dict, error: str, wall_time: float = 0.0) -> None:
        """Record a failed run (no table)."""
        self.signal_path(key).unlink(missing_ok=True)
        _write_json(self.record_path(key), {**spec, "key": key, "status": FAILED,
                                            "wall_time_s": float(wall_time), "simulated_s": 0.0,
                                            "error": str(error)})

    def write_text(self, name: str, text: str) -> Path:
        """Write a text file of the study folder atomically; returns its path."""
        path = self.folder / name
        with atomic_output(path) as tmp:
            Path(tmp).write_text(text, encoding="utf-8")
        return path

    def signal(self, key: str) -> pd.DataFrame:
        """The signal table of a finished run."""
        if not self.is_finished(key):
            raise InputError(f"run {key} is not finished in this study", source=str(self.folder))
        return read_signal(self.signal_path(key))

    def index(self) -> pd.DataFrame:
        """Every run's record as one table (one row per run, sorted by key)."""
        records = [json.loads(p.read_text(encoding="utf-8")) for p in sorted(self.runs.glob("*.json"))]
        return pd.DataFrame.from_records(records)

    def write_index(self) -> pd.DataFrame:
        """Rebuild ``index.parquet`` from the records (atomically); returns the index."""
        index = self.index()
        with atomic_output(self.folder / "index.parquet") as tmp:
            index.to_parquet(tmp, index=False)
        return index
