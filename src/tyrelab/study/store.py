"""The results store of a study: one folder, one file pair per run, an index table.

Layout of a study folder::

    runs/<key>.parquet   the run's signal table (tyrelab.signal form)
    runs/<key>.json      the run's record: its specification, status, wall time, error, warnings
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

How a run's table is stored (``[study] store`` of the spec, :data:`STORAGE`;
measured on the 200 runs of the built-in campaign by
``benchmarks/store_format.py``, docs/benchmarks.md):

* ``"compact"`` (the default): only the channels the study's evaluation and
  report read (:data:`COMPACT_CHANNELS`: time, the load cell's and the
  tyre's vertical force, the contact point's and the wheel centre's x and z);
  time and the compared force (``FZ_HUB``, or ``FZ`` in a run without it) as
  float64, the others rounded to float32; zstd with byte-stream split. The
  campaign takes 0.13 GB instead of 2.46 GB and every metric of
  :func:`tyrelab.study.evaluate.evaluate_study` is bit-identical. A soil test's
  run (its record has a ``slip``) also keeps, as float64, the channels its steady
  state is read from (:data:`SOIL_CHANNELS`), so its slip curve
  (:func:`tyrelab.study.soil.soil_curves`) is that of the full table. The other
  channels are gone: a study that needs them says ``"lossless"`` or ``"full"``.
* ``"lossless"``: every channel, float64, zstd with byte-stream split (1.35 GB).
* ``"full"``: every channel, float64, snappy -- the form of every store written
  before (2.46 GB).

Every form reads back as float64 columns (:func:`tyrelab.signal.read_signal`),
so stores of any form, and those written before, read alike. The form is not
part of a run's key: a run stored in one form is found finished when the
spec asks for another (delete its table to have it written again).
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

#: how a run's table is stored (module notes); ``[study] store`` of the spec
COMPACT, LOSSLESS, FULL = "compact", "lossless", "full"
STORAGE = (COMPACT, LOSSLESS, FULL)
DEFAULT_STORAGE = COMPACT
#: the channels a compact run keeps: what :mod:`tyrelab.study.evaluate` reads (time, the
#: compared force ``FZ_HUB`` or, without it, ``FZ``, and the contact point's and wheel
#: centre's x and z that place the disturbance) and the report plots (time, that force)
COMPACT_CHANNELS = ("RUNTIME", "FZ_HUB", "FZ", "X_CP", "Z_CP", "X_WC", "Z_WC")
#: what a compact soil-test run keeps besides, exactly: the drawbar pull, the driving torque,
#: the sinkage (with FZ, the steady means of :mod:`tyrelab.study.soil`) and the slip
SOIL_CHANNELS = ("FX", "TORQUE", "SINKAGE", "LONGSLIP")


def compact_float64(columns) -> tuple[str, ...]:
    """The channels of a compact run kept as float64: time and the compared force
    (``FZ_HUB``, or ``FZ`` when the run has no ``FZ_HUB``), so that the metrics computed
    from a compact run are those of the full one."""
    return ("RUNTIME", "FZ_HUB" if "FZ_HUB" in columns else "FZ")


def check_storage(value, source=None) -> str:
    """``value`` if it is one of :data:`STORAGE`, else an :class:`InputError` listing them."""
    if value not in STORAGE:
        raise InputError(f"unknown store form {value!r}; allowed: "
                         + ", ".join(f'"{s}"' for s in STORAGE), source=source, field="store")
    return value


def write_run(signal: pd.DataFrame, path, storage: str = DEFAULT_STORAGE, exact=()) -> None:
    """Write a run's signal table to ``path`` in the form ``storage`` (module notes); a compact
    run also keeps the channels ``exact`` (float64)."""
    check_storage(storage)
    if storage == FULL:
        write_signal(signal, path)  # today's form, byte for byte
        return
    if storage == LOSSLESS:
        write_signal(signal, path, compression="zstd", storage={"form": LOSSLESS})
        return
    keep = (*COMPACT_CHANNELS, *exact)
    kept = [c for c in signal.columns if c in keep]
    dropped = [c for c in signal.columns if c not in keep]
    table = signal[kept]
    table.attrs = {**signal.attrs, "units": {c: u for c, u in
                                             signal.attrs.get("units", {}).items() if c in kept}}
    double = (*compact_float64(kept), *exact)
    write_signal(table, path, compression="zstd", float32=[c for c in kept if c not in double],
                 storage={"form": COMPACT, "dropped": dropped})


def _write_json(path: Path, record: dict) -> None:
    """Write ``record`` as JSON to ``path`` atomically (temporary name, then rename)."""
    with atomic_output(path) as tmp, open(tmp, "w", encoding="utf-8") as fh:
        json.dump(record, fh, sort_keys=True, allow_nan=False)


class Store:
    """A study's results folder (created if missing)."""

    def __init__(self, folder, storage: str | None = None):
        """``storage``: how runs are written (:data:`STORAGE`); None: :data:`DEFAULT_STORAGE`."""
        self.folder = Path(folder)
        self._storage = None if storage is None else check_storage(storage)
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

    @property
    def storage(self) -> str:
        """How this store writes runs (:data:`STORAGE`): as given (``tyrelab.study.run`` gives
        the spec's ``[study] store``), else :data:`DEFAULT_STORAGE`."""
        return self._storage or DEFAULT_STORAGE

    def save(self, key: str, spec: dict, signal: pd.DataFrame, wall_time: float,
             warnings: list[str] = ()) -> None:
        """Store a finished run: its table first (in the form :attr:`storage`; a soil test's
        run, whose record has a ``slip`` or ``torque``, with :data:`SOIL_CHANNELS`), then its record, with
        the ``warnings`` the run raised (one per line)."""
        exact = SOIL_CHANNELS if (spec.get("slip"), spec.get("torque")) != (None, None) else ()
        write_run(signal, self.signal_path(key), self.storage, exact)
        _write_json(self.record_path(key), {**spec, "key": key, "status": DONE,
                                            "wall_time_s": float(wall_time),
                                            "simulated_s": float(signal["RUNTIME"].iloc[-1]
                                                                 - signal["RUNTIME"].iloc[0]),
                                            "error": "", "warnings": "\n".join(warnings)})

    def save_failure(self, key: str, spec: dict, error: str, wall_time: float = 0.0,
                     warnings: list[str] = ()) -> None:
        """Record a failed run (no table)."""
        self.signal_path(key).unlink(missing_ok=True)
        _write_json(self.record_path(key), {**spec, "key": key, "status": FAILED,
                                            "wall_time_s": float(wall_time), "simulated_s": 0.0,
                                            "error": str(error), "warnings": "\n".join(warnings)})

    def write_text(self, name: str, text: str) -> Path:
        """Write a text file of the study folder atomically; returns its path."""
        path = self.folder / name
        with atomic_output(path) as tmp:
            Path(tmp).write_text(text, encoding="utf-8")
        return path

    def signal(self, key: str, columns=None) -> pd.DataFrame:
        """The signal table of a finished run (only ``columns``, if given)."""
        if not self.is_finished(key):
            raise InputError(f"run {key} is not finished in this study", source=str(self.folder))
        return read_signal(self.signal_path(key), columns)

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
