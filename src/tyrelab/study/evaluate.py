"""Evaluate a study: each run's chapter 5 metrics against its reference (``metrics.parquet``).

:func:`evaluate_study` compares every finished run that has a reference --
the reference model's run of the same condition in the store, or the
measured files of the condition read with :func:`tyrelab.measure.read_run`
-- and returns one row per compared run (written atomically to
``<folder>/metrics.parquet``). The reference model's own run is compared
with itself (``is_reference``: every error zero, a check of the chain).
Several measured files for one condition are repeats: the first is the
reference, each other one gives a row ``model = "measured repeatability"``
(thesis Table 5-1, :func:`tyrelab.validate.compare.repeatability`). A run
whose comparison fails keeps its row, with NaN metrics and the ``error``.

Metrics. Discrete obstacles: the thesis's segmented cleat metrics (m%RE,
80%RE, RMS of the disturbance; m%RE, RMS of the matched response peaks)
and the others of :data:`~tyrelab.validate.compare.METRICS` (Sprague-Geers
and Russell over the disturbance; PSD, peak load, pseudo-damage over the
whole record). Rough tracks: the normal-fit μ%err, σ%err and the others.
Metrics that do not apply to a group are NaN. ``near_zero_samples`` of
``compared_samples`` counts the denominators the near-zero rule of
:mod:`tyrelab.validate.metrics` replaced by its floor (``|m| < floor``, the
floor from :func:`~tyrelab.validate.metrics.relative_error_floor` exactly as
:func:`~tyrelab.validate.compare.compare_aligned` applies it): obstacles,
the disturbance samples and the matched response peaks; tracks, the two
denominators of eq. 5.4 (the measured mean and standard deviation).

Each comparison -- the compared channel, the disturbance segment from the
reference's own contact with the obstacle, the metrics -- is
:mod:`tyrelab.study.comparison`'s.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import pandas as pd

from ..signal import atomic_output
from ..validate.compare import METRICS
from ..validate.segments import Segments
from ..validate.thesis import TABLE_5_15_ROWS
from .comparison import (CHANNEL, FALLBACK_CHANNEL, compare_to_reference, disturbance_segments,
                         obstacle_of)
from .spec import GROUPS, RunSpec, StudySpec
from .runner import RunWarning, kept_warnings, warning_messages
from .store import Store

REPEATABILITY = "measured repeatability"
SEGMENT_COLUMNS = ["disturbance_start_s", "disturbance_end_s", "response_start_s",
                   "response_end_s"]
LABEL_COLUMNS = ["key", "reference", "is_reference", "tyre", "model", "contact", "test",
                 "obstacle", "group", "road", "speed_kmh", "load", "channel"]
COLUMNS = [*LABEL_COLUMNS, *METRICS, "near_zero_samples", "compared_samples", *SEGMENT_COLUMNS,
           "segment_method", "n_response_peaks", "shift_s", "error", "warnings"]
METRICS_FILE = "metrics.parquet"


def _segment_columns(seg: Segments | None) -> dict:
    if seg is None:
        return {"segment_method": "none (track)"}
    return dict(zip(SEGMENT_COLUMNS, (*seg.disturbance, *seg.response)), segment_method=seg.method)


def _labels(run: RunSpec, key: str, reference: str, is_reference: bool) -> dict:
    return {"key": key, "reference": reference, "is_reference": is_reference,
            "tyre": run.tyre.name, "model": run.model.name, "contact": run.model.contact,
            "test": run.test, "obstacle": TABLE_5_15_ROWS.get(run.test, (run.group, run.test))[1],
            "group": run.group, "road": run.road, "speed_kmh": round(run.speed_kmh, 9),
            "load": str(run.load)}


def _error_text(exc: Exception) -> str:
    return f"{type(exc).__name__}: {' '.join(str(exc).split()) or type(exc).__name__}"


class _Evaluator:
    """The caches of one evaluation: tyres, reference signals and their segments."""

    def __init__(self, spec: StudySpec, store: Store):
        self.spec, self.store = spec, store
        self.keys = spec.run_keys()
        self._tyres, self._signals, self._segments = {}, {}, {}

    def test_of(self, run: RunSpec):
        for test in self.spec.tests:
            if test.name == run.test and run.speed in test.speeds and run.load in test.loads:
                return test
        raise KeyError(run.test)

    def tyre(self, run: RunSpec) -> tuple[float, float, float]:
        """(free radius, half width, static centre height) of the run's tyre at its load."""
        key = (run.tyre, run.load)
        if key not in self._tyres:
            from ..rig.trailer import load_case_wheel_load
            from ..tyre.library import load_tyre
            tyre = load_tyre(run.tyre.file, run.tyre.pressure)
            load = load_case_wheel_load(run.load) if isinstance(run.load, str) else float(run.load)
            r0 = tyre.unloaded_radius
            self._tyres[key] = (r0, 0.5 * tyre.width, r0 - tyre.static_deflection(load))
        return self._tyres[key]

    def reference_signal(self, source) -> pd.DataFrame:
        """A reference's signal: a run key (str) or a measured file (Path), read once."""
        if source not in self._signals:
            if len(self._signals) >= 2:  # a condition's runs are adjacent: keep the last two
                self._signals.pop(next(iter(self._signals)))
            if isinstance(source, Path):
                from ..measure.io import read_run
                self._signals[source] = read_run(source, column_map=self.spec.column_map(source))
            else:
                self._signals[source] = self.store.signal(source)
        return self._signals[source]

    def segments(self, run: RunSpec, source) -> Segments | None:
        """The condition's segments from its reference (None on a track); raises on failure."""
        if run.group != GROUPS[0]:
            return None
        key = (source, run.road, run.tyre, run.load)
        if key not in self._segments:
            try:
                ref = self.reference_signal(source)
                radius, half_width, centre = self.tyre(run)
                channel = CHANNEL if CHANNEL in ref.columns else FALLBACK_CHANNEL
                self._segments[key] = disturbance_segments(
                    ref, obstacle_of(run.road, half_width), radius, centre, channel)
            except Exception as exc:  # remembered: every model of the condition fails alike
                self._segments[key] = exc
        seg = self._segments[key]
        if isinstance(seg, Exception):
            raise seg
        return seg

    def row(self, run: RunSpec, key: str, source, label: str, is_reference: bool,
            sim_source=None) -> dict:
        """One row: ``sim_source`` (default the run's key) against ``source``."""
        row = _labels(run, key, label, is_reference)
        with kept_warnings() as caught:  # kept with the row (a worker's)
            try:
                ref = self.reference_signal(source)
                seg = self.segments(run, source)
                row.update(_segment_columns(seg))
                if sim_source is None:
                    sim = self.store.signal(key)
                else:
                    sim = self.reference_signal(sim_source)
                row.update(compare_to_reference(sim, ref, seg, "auto" if isinstance(source, Path)
                                                else 0.0))
                row["error"] = ""
            except Exception as exc:  # recorded, not raised: the other runs go on
                row["error"] = _error_text(exc)
        row["warnings"] = "\n".join(warning_messages(caught))
        return row

    def rows(self, run: RunSpec) -> list[dict]:
        """The rows of one run: none (not finished, no reference), its comparison, and for
        the first model of a condition with repeated measurements, their scatter."""
        key, test = self.keys[run], self.test_of(run)
        files = self.spec.reference_files(run)
        out = []
        if len(files) > 1 and run.model == self.spec.test_models(test)[0]:
            for f in files[1:]:
                row = self.row(run, f.name, files[0], files[0].name, False, sim_source=f)
                row.update(model=REPEATABILITY, contact="")
                out.append(row)
        if not self.store.is_finished(key):
            return out
        if files:
            out.append(self.row(run, key, files[0], files[0].name, False))
        elif test.reference_model is not None:
            ref_run = self.spec.reference_run(run)
            ref_key = key if ref_run is None else self.keys[ref_run]
            if not self.store.is_finished(ref_key):
                row = _labels(run, key, ref_key, ref_run is None)
                row["error"] = f"the reference run {ref_key} ({test.reference_model}) is not finished"
                out.append(row)
            else:
                out.append(self.row(run, key, ref_key, ref_key, ref_run is None))
        return out


def condition_rows(spec: StudySpec, store: Store, runs: list) -> list[dict]:
    """The rows of ``runs`` (the runs of one condition, which share a reference), in order."""
    ev = _Evaluator(spec, store)
    return [row for run in runs for row in ev.rows(run)]


def conditions(runs: list) -> list[list]:
    """``runs`` cut where the condition (test, speed, load, tyre) changes: a condition's runs
    are adjacent in a spec's runs and read the same reference."""
    groups: list[list] = []
    for run in runs:
        if groups and (groups[-1][0].test, groups[-1][0].speed, groups[-1][0].load,
                       groups[-1][0].tyre) == (run.test, run.speed, run.load, run.tyre):
            groups[-1].append(run)
        else:
            groups.append([run])
    return groups


def evaluate_study(spec: StudySpec, store: Store, progress: bool = True,
                   client=None) -> pd.DataFrame:
    """The metrics of every compared run of ``spec`` in ``store`` (module notes); the runs of
    soil tests are evaluated by :func:`tyrelab.study.soil.soil_curves` instead.

    With a Dask ``client`` whose workers share this process's disk (the study's local
    cluster), each condition's runs are evaluated on a worker, the longest conditions
    first; the rows are the same, in the same order, as in this process alone.

    Returns
    -------
    pandas.DataFrame
        One row per compared run, columns :data:`COLUMNS`; also written
        atomically to ``<store folder>/metrics.parquet``.
    """
    from tqdm import tqdm
    runs = [r for r in spec.runs() if not r.is_soil_run]  # soil tests: tyrelab.study.soil
    rows = []
    bar = tqdm(total=len(runs), unit="run", desc="evaluate", disable=not progress)
    with bar:
        if client is None:
            ev = _Evaluator(spec, store)
            for run in runs:
                rows.extend(ev.rows(run))
                bar.update(1)
        else:
            from distributed import as_completed

            from .records import expected_cost
            from .runner import completed
            groups = conditions(runs)
            futures = [client.submit(condition_rows, spec, store, g, pure=False,
                                     priority=sum(expected_cost(r) for r in g)) for g in groups]
            size = {f.key: len(g) for f, g in zip(futures, groups)}
            for done in completed(as_completed(futures)):
                bar.update(size[done.key])
            for f, group in zip(futures, groups):
                try:
                    rows.extend(f.result())
                except Exception:  # the worker died: this condition is evaluated here
                    rows.extend(condition_rows(spec, store, group))
    df = pd.DataFrame(rows).reindex(columns=COLUMNS)
    for col in (*METRICS, *SEGMENT_COLUMNS, "shift_s", "speed_kmh"):
        df[col] = df[col].astype(float)
    for col in ("near_zero_samples", "compared_samples", "n_response_peaks"):
        df[col] = df[col].astype("Int64")
    for col in ("key", "reference", "error", "segment_method", "channel", "warnings"):
        df[col] = [v if isinstance(v, str) else "" for v in df[col]]
    # what the comparisons warned of in the workers, here, each once (a measured file with
    # the opposite sign is compared with every model)
    for note in dict.fromkeys(n for text in df["warnings"] for n in text.splitlines() if n):
        warnings.warn(note, RunWarning, stacklevel=2)
    df["is_reference"] = df["is_reference"].fillna(False).astype(bool)
    write_metrics(df, store.folder / METRICS_FILE)
    return df


def write_metrics(df: pd.DataFrame, path) -> None:
    """Write a metrics table to ``path`` (Parquet) atomically."""
    with atomic_output(Path(path)) as tmp:
        df.to_parquet(tmp, index=False)
