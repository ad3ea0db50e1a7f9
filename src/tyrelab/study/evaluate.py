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

Channel: ``FZ_HUB``. The thesis compares what the trailer's six load cells
measured (5.1: "the measured and simulated load cell measurements will
thus be compared"; the sub-frame's acceleration could not be measured, so
the wheel's inertia could not be removed). ``FZ_HUB`` is that reading (the
tyre's vertical force less the wheel mass times its acceleration, tared
with the wheel hanging free); ``FZ`` is the tyre's own force at the wheel
centre and ``FZW`` the normal force in the contact point, which no load
cell sees. When either signal lacks ``FZ_HUB`` (a measured file mapped to
TYDEX ``FZ``, another rig) ``FZ`` is compared; the ``channel`` column says.

The disturbance (thesis 5.2: "the first section, where the tyre is in
contact with the obstacle") is taken from the *reference's own contact*
and used for every model of the condition:

1. reference with contact-point channels (every simulation) over a raised
   obstacle (cleat, bump): from the first to the last sample whose contact
   point ``Z_CP`` lies more than 1 % of the obstacle's height above the road
   (:func:`~tyrelab.validate.segments.segments_from_contact`; the flexible
   ring's contact point is force-weighted, so: the obstacle carries more
   than 1 % of the load);
2. otherwise, with ``X_WC`` in the road frame: the free circle about the
   reference's own wheel-centre path (``Z_WC``, else the static height)
   reaching the obstacle's profile, its highest point across the tyre's
   width (:func:`~tyrelab.validate.segments.segments_from_contour`; steps and
   potholes: their edges);
3. otherwise (a measured file without positions, a road of unknown
   geometry): the first excursion of the reference's force
   (:func:`~tyrelab.validate.segments.segments_from_signal`).

Why: :func:`~tyrelab.validate.segments.segments_from_geometry` cuts the free
circle at the *static* centre height. The wheel is thrown up by the cleat,
so the tyre leaves it well before that circle does, and the cut runs into
the unloading trough, where the reference's force is small and every
relative error large. Measured on the 50 mm cleat, 12 km/h, LC1 (6 s, FTire
TP = ring-tp as reference, channel FZ_HUB): the ring touches the cleat from
0.327 m before its leading edge to 0.253 m after its trailing edge (t =
1.402-1.591 s; the centre is then 33 mm above its static height); the
static free circle reaches 0.337 m on both sides (1.399-1.616 s): 25 ms
more at the end, 13 % of the window, all of it in the unloading trough
(the reference's FZ_HUB there is 6.7-8.1 kN, static 23.3 kN). The contact
fraction barely matters (0 % to 2 %: 1 ms). m%RE / 80%RE of the
disturbance, old -> this definition:

=========== ============= =============
variant     m%RE [%]      80%RE [%]
=========== ============= =============
OPC lk      36.7 -> 33.9  60.6 -> 56.5
OPC nlk     41.9 -> 39.9  63.6 -> 62.9
3D VC lk    35.9 -> 24.9  81.1 -> 17.0
3D VC nlk   39.3 -> 27.4  90.9 -> 18.6
3D ENV lk   25.8 -> 21.4  58.7 -> 22.6
3D ENV nlk  29.5 -> 25.5  58.7 -> 32.0
=========== ============= =============

The volume model goes from last on 80%RE (and within 1-3 points of the
point model on m%RE) to first on 80%RE and a clear second on m%RE (the
ranking of the three contact models on m%RE stays ENV, VC, OPC; on 80%RE it
turns from ENV, OPC, VC to VC, ENV, OPC); Spearman's ρ between
these six variants' ranking and the thesis's Table 5-2 (which ranks the
volume model first) rises from 0.38 to 0.83 over the five cleat metrics
(m%RE 0.26 -> 0.66, 80%RE -0.43 -> 1.0, RMS 0.71 -> 0.94; response m%RE
0.77 both, response RMS 0.60 -> 0.77, the response now starting where the
contact ends). With ``FZ`` instead of ``FZ_HUB`` and the old cut the volume
model ranks last on m%RE too (59.3 % against the point model's 54.2 %).
The circle about the reference's own centre path (rule 2) gives nearly the
contact window (1.399-1.597 s) and ρ = 0.78. With an analytic model as
reference, rule 1 reads that model's own contact point (for the enveloping
model the cams' effective contact), so the window is its contact.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import InputError
from ..signal import atomic_output
from ..validate.align import align
from ..validate.compare import (METRICS, THESIS_CLEAT, THESIS_TRACK, compare_aligned,
                                response_signals)
from ..validate.distributions import fit_normal
from ..validate.metrics import (FLOOR_FRACTION, RESPONSE_BAND_HZ, match_peaks,
                                relative_error_floor)
from ..validate.segments import (Segments, segments_from_contact, segments_from_contour,
                                 segments_from_signal)
from ..validate.thesis import TABLE_5_15_ROWS
from .spec import GROUPS, RunSpec, StudySpec
from .store import Store

#: the compared channel (the load cells' reading), and the one used when a signal lacks it
CHANNEL, FALLBACK_CHANNEL = "FZ_HUB", "FZ"
#: share of the obstacle's height the contact point must rise for contact (rule 1)
CONTACT_FRACTION = 0.01
REPEATABILITY = "measured repeatability"
OTHER_METRICS = [m for m in METRICS if m not in THESIS_CLEAT and m not in THESIS_TRACK]
SEGMENT_COLUMNS = ["disturbance_start_s", "disturbance_end_s", "response_start_s",
                   "response_end_s"]
LABEL_COLUMNS = ["key", "reference", "is_reference", "tyre", "model", "contact", "test",
                 "obstacle", "group", "road", "speed_kmh", "load", "channel"]
COLUMNS = [*LABEL_COLUMNS, *METRICS, "near_zero_samples", "compared_samples", *SEGMENT_COLUMNS,
           "segment_method", "n_response_peaks", "shift_s", "error"]
METRICS_FILE = "metrics.parquet"


@dataclass(frozen=True)
class Obstacle:
    """An obstacle's place on the road: ``kind`` "raised" (cleat, bump: the road returns
    to its base level) or "edge" (step, pothole); its profile (x, height) as seen across
    the tyre's width; ``height`` above the base (negative: a hole) [m]."""

    kind: str
    start: float
    end: float
    height: float
    profile_x: tuple
    profile_z: tuple


def obstacle_of(road: str, half_width: float = 0.0) -> Obstacle | None:
    """The obstacle of a road name, or None (flat road, tracks, random and CRG roads)."""
    from ..road import obstacles as ob
    from ..road.spec import road_from_spec
    try:
        r = road_from_spec(road)
    except InputError:
        return None
    if isinstance(r, ob.Cleat):
        a = np.radians(r.angle)
        reach = half_width * abs(np.tan(a))  # an oblique cleat meets one shoulder first
        lo, hi = r.start - reach, r.start + r.width / np.cos(a) + reach
        h = r.cleat_height
        return Obstacle("raised", lo, hi, h, (lo, lo, hi, hi), (0.0, h, h, 0.0))
    if isinstance(r, ob.TrapezoidalBump):
        xs = tuple(r.start + e for e in r._edges())
        h = r.bump_height
        return Obstacle("raised", xs[0], xs[-1], h, xs, (0.0, h, h, 0.0))
    if isinstance(r, ob.Step):
        return Obstacle("edge", r.start, r.start, r.step_height, (r.start,),
                        (max(r.step_height, 0.0),))
    if isinstance(r, ob.Pothole):
        end = r.start + r.length
        return Obstacle("edge", r.start, end, -r.depth, (r.start, end), (0.0, 0.0))
    return None


def _finite(df: pd.DataFrame, col: str) -> bool:
    return col in df.columns and bool(np.all(np.isfinite(df[col].to_numpy(dtype=float))))


def disturbance_segments(ref: pd.DataFrame, obstacle: Obstacle | None, radius: float,
                         centre_height: float, channel: str = CHANNEL) -> Segments:
    """Disturbance and response of a condition from its reference signal (module notes)."""
    t = ref["RUNTIME"].to_numpy(dtype=float)
    if obstacle is not None:
        if obstacle.kind == "raised" and _finite(ref, "Z_CP") and _finite(ref, "X_CP"):
            try:
                return segments_from_contact(
                    t, ref["Z_CP"].to_numpy(dtype=float), obstacle.height, 0.0,
                    CONTACT_FRACTION, ref["X_CP"].to_numpy(dtype=float),
                    (obstacle.start - radius, obstacle.end + radius))
            except InputError:
                pass  # the contact point never rose (e.g. it stayed on a rim): the contour
        if _finite(ref, "X_WC"):
            z = (ref["Z_WC"].to_numpy(dtype=float) if _finite(ref, "Z_WC")
                 else np.full(t.size, centre_height))
            return segments_from_contour(t, ref["X_WC"].to_numpy(dtype=float), z,
                                         obstacle.profile_x, obstacle.profile_z, radius)
    return segments_from_signal(t, ref[channel].to_numpy(dtype=float))


def near_zero_counts(aligned, seg: Segments | None, floor_fraction: float = FLOOR_FRACTION,
                     peak_kind: str = "both",
                     response_band_hz: float | None = RESPONSE_BAND_HZ) -> tuple[int, int]:
    """(denominators the near-zero floor replaced, denominators) of a comparison.

    The same cuts and floors as :func:`~tyrelab.validate.compare.compare_aligned`:
    with segments, the disturbance samples (floor from the disturbance) and the
    matched peaks of the response's oscillation (floor from it,
    :func:`~tyrelab.validate.compare.response_signals`); without, the measured
    mean and standard deviation of eq. 5.4 (floor from the whole record).
    """
    t, m = aligned.t, aligned.m
    if seg is None:
        floor = relative_error_floor(m, floor_fraction)
        mu, sigma = fit_normal(m)
        return int(abs(mu) < floor) + int(abs(sigma) < floor), 2
    md = m[seg.mask(t, "disturbance")]
    n = int(np.sum(np.abs(md) < relative_error_floor(md, floor_fraction)))
    pr, mr = response_signals(aligned, seg, response_band_hz)
    _, mv, _, _ = match_peaks(pr, mr, peak_kind)
    n += int(np.sum(np.abs(mv) < relative_error_floor(mr, floor_fraction)))
    return n, int(md.size + mv.size)


def compare_to_reference(sim: pd.DataFrame, ref: pd.DataFrame, seg: Segments | None,
                         shift: float | str = 0.0) -> dict:
    """Every metric of ``sim`` against ``ref`` (``seg`` None: a track) as row columns."""
    channel = CHANNEL if CHANNEL in sim.columns and CHANNEL in ref.columns else FALLBACK_CHANNEL
    aligned = align(sim, ref, channel, shift)
    res = compare_aligned(aligned, seg)
    used = [*(THESIS_CLEAT if seg is not None else THESIS_TRACK), *OTHER_METRICS]
    row = {m: float(res[m]) for m in used if m in res}
    near, compared = near_zero_counts(aligned, seg)
    row.update(channel=channel, near_zero_samples=near, compared_samples=compared,
               shift_s=aligned.shift, n_response_peaks=res["details"].get("n_response_peaks"))
    return row


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


def _condition_rows(spec: StudySpec, store: Store, runs: list) -> list[dict]:
    """The rows of ``runs`` (the runs of one condition, which share a reference), in order."""
    ev = _Evaluator(spec, store)
    return [row for run in runs for row in ev.rows(run)]


def _conditions(runs: list) -> list[list]:
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
    runs = [r for r in spec.runs() if r.slip is None]  # soil tests: tyrelab.study.soil
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
            from .runner import _completed
            groups = _conditions(runs)
            futures = [client.submit(_condition_rows, spec, store, g, pure=False,
                                     priority=sum(expected_cost(r) for r in g)) for g in groups]
            size = {f.key: len(g) for f, g in zip(futures, groups)}
            for done in _completed(as_completed(futures)):
                bar.update(size[done.key])
            for f, group in zip(futures, groups):
                try:
                    rows.extend(f.result())
                except Exception:  # the worker died: this condition is evaluated here
                    rows.extend(_condition_rows(spec, store, group))
    df = pd.DataFrame(rows).reindex(columns=COLUMNS)
    for col in (*METRICS, *SEGMENT_COLUMNS, "shift_s", "speed_kmh"):
        df[col] = df[col].astype(float)
    for col in ("near_zero_samples", "compared_samples", "n_response_peaks"):
        df[col] = df[col].astype("Int64")
    for col in ("key", "reference", "error", "segment_method", "channel"):
        df[col] = [v if isinstance(v, str) else "" for v in df[col]]
    df["is_reference"] = df["is_reference"].fillna(False).astype(bool)
    write_metrics(df, store.folder / METRICS_FILE)
    return df


def write_metrics(df: pd.DataFrame, path) -> None:
    """Write a metrics table to ``path`` (Parquet) atomically."""
    with atomic_output(Path(path)) as tmp:
        df.to_parquet(tmp, index=False)
