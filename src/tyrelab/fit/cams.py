"""The cam-count study of the enveloping model (thesis 6.2): accuracy against cost.

The thesis took Schmeitz's 5 x 6 cams (passenger-car tyres) as a start and
used 15 x 10 (N_LENGTH x N_WIDTH) for the XZL (4.4), and recommends finding
the number of cams a large tyre needs (6.2). :func:`cam_count_study` runs the
enveloping model at every pair of ``n_length`` x ``n_width`` on the towed
trailer over each road and speed, compares each run with a reference (another
contact model, e.g. the flexible ring, the enveloping model at a fine count,
or a measured run) and times it.

Metric (``error_pct``)
    The RMS error (thesis eq. 5.1, :func:`tyrelab.validate.metrics.rms_error`)
    of the normal force ``FZW`` against the reference over the disturbance,
    in per cent of the reference's peak ``|FZW|`` over the disturbance (``FZ``
    when the reference has no ``FZW``: a measurement). The simulation is
    interpolated onto the reference's time base
    (:func:`tyrelab.validate.align.align`). The thesis's m%RE over the same
    samples is given beside it (``mre_pct``) but not used to choose: it
    divides by the reference sample by sample, so the unloading trough after
    a cleat dominates it.

Disturbance
    From the reference alone, the same for every pair: the samples whose
    contact point ``Z_CP`` lies more than 1 % of the road's highest point
    above zero (the reference's contact with a raised obstacle, the study's
    rule 1, :func:`tyrelab.validate.segments.segments_from_contact`); when the
    reference has no contact-point channels (a measurement) or that finds no
    contact, the first excursion of the reference's force
    (:func:`~tyrelab.validate.segments.segments_from_signal`).

Cost (``wall_s_per_sim_s``)
    Wall-clock seconds per simulated second of the trailer run (both wheels:
    the left one by default the point model, as in the built-in campaign), the
    minimum over ``repeat`` timed runs after one untimed warm-up run of
    :data:`WARM_UP` s per configuration (compiling and caches excluded). The
    ``cams`` column (N_LENGTH x N_WIDTH) is the deterministic proxy.

Recommendation
    :mod:`.cam_choice` (:func:`~.cam_choice.recommend`).

The counts are set through the enveloping model's options ``n_length`` and
``n_width`` (:func:`tyrelab.tyre.contact.enveloping.enveloping_params`,
which otherwise reads N_LENGTH / N_WIDTH of ``[CONTACT_PATCH]``); the model
itself is not changed.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from .. import limits, resources
from ..errors import InputError
from ..guards import PhysicsWarning
from .cam_choice import ABS_TOL, COST_TOL, REL_TOL, recommend, rule_text, summarise

#: bounds of a cam count
MIN_CAMS, MAX_CAMS = 1, 20
#: simulated seconds of the untimed warm-up run of each configuration
WARM_UP = 0.05
#: fraction of the road's highest point the reference's contact point must exceed (disturbance)
CONTACT_FRACTION = 0.01
#: suffixes of a measured (or saved) reference run
REFERENCE_SUFFIXES = (".tdx", ".csv", ".parquet")
#: columns of the study's table
COLUMNS = ["n_length", "n_width", "cams", "road", "speed", "error_pct", "mre_pct",
           "wall_s_per_sim_s", "duration_s", "channel", "disturbance_start_s", "disturbance_end_s"]

METRIC = ("RMS error of {channel} over the disturbance, % of the reference's peak |{channel}| "
          "there (thesis eq. 5.1 normalised)")


@dataclass
class CamStudy:
    """The result of :func:`cam_count_study`.

    ``table``: one row per pair and condition (:data:`COLUMNS`; ``speed`` in
    m/s); ``summary``: one row per pair, error and cost averaged over the
    conditions, ``qualifies`` marking the pairs within the tolerance;
    ``recommended``: ``(n_length, n_width)``; ``metric``, ``rule``,
    ``reference``: what was measured and how the pair was chosen.
    """

    table: pd.DataFrame
    summary: pd.DataFrame
    recommended: tuple[int, int]
    metric: str
    rule: str
    reference: str
    tyre: str = ""
    notes: list = field(default_factory=list)


def check_counts(values, field: str) -> tuple[int, ...]:
    """Cam counts as a sorted tuple of distinct whole numbers in [1, 20]."""
    if isinstance(values, str) or np.ndim(values) == 0:
        values = (values,)
    out = sorted({limits.check_count(v, field, MIN_CAMS, MAX_CAMS, what="cam count") for v in values})
    if not out:
        raise InputError(f"{field}: at least one cam count is needed", field=field)
    return tuple(out)


# --- running ------------------------------------------------------------------------------------

def _tyre(tyre, pressure):
    from ..tyre.library import load_tyre
    from ..tyre.params import Tyre
    if pressure is not None:
        limits.check_pressure(pressure)
    return tyre if isinstance(tyre, Tyre) else load_tyre(tyre, pressure)


def check_reference(reference):
    """The reference, checked: ``("table", DataFrame, label)`` or ``("model", (contact, options), label)``."""
    if isinstance(reference, pd.DataFrame):
        return "table", reference, reference.attrs.get("metadata", {}).get("source", "a signal table")
    text = str(reference)
    if isinstance(reference, Path) or Path(text).suffix.lower() in REFERENCE_SUFFIXES:
        from ..measure.io import read_run
        if not Path(text).is_file():
            raise InputError(f"no such reference file '{text}'", field="reference")
        return "table", read_run(text), text
    name, _, counts = text.partition(":")
    options = {}
    if counts:
        if name != "enveloping":
            raise InputError(f"reference '{text}': only the enveloping model takes cam counts "
                             "(enveloping:NLxNW)", field="reference")
        try:
            nl, nw = (int(v) for v in counts.lower().split("x"))
        except ValueError:
            raise InputError(f"reference '{text}': expected enveloping:NLxNW, e.g. enveloping:9x9",
                             field="reference") from None
        options = {"n_length": check_counts(nl, "reference")[0], "n_width": check_counts(nw, "reference")[0]}
    from ..tyre.registry import contact_model
    contact_model(name)  # an unknown name lists the known ones
    return "model", (name, options), text


def _disturbance(ref: pd.DataFrame, road, channel: str):
    from ..validate.segments import segments_from_contact, segments_from_signal
    t = ref["RUNTIME"].to_numpy(dtype=float)
    if road is not None and all(c in ref.columns for c in ("Z_CP", "X_CP")):
        top = float(np.max(road.grid().z))
        if top > 0.0:
            try:
                return segments_from_contact(t, ref["Z_CP"].to_numpy(dtype=float), top, 0.0,
                                             CONTACT_FRACTION)
            except InputError:
                pass
    return segments_from_signal(t, ref[channel].to_numpy(dtype=float))


def condition_error(sim: pd.DataFrame, ref: pd.DataFrame, seg, channel: str, shift=0.0) -> dict:
    """``error_pct`` and ``mre_pct`` of ``sim`` against ``ref`` over ``seg``'s disturbance."""
    from ..validate.align import align
    from ..validate.metrics import mean_relative_error, relative_error_floor, rms_error
    a = align(sim, ref, channel, shift)
    mask = seg.mask(a.t, "disturbance")
    if int(mask.sum()) < 2:
        raise InputError(f"the disturbance ({seg.disturbance[0]:.4g}-{seg.disturbance[1]:.4g} s) holds "
                         "fewer than two compared samples", field="reference")
    p, m = a.p[mask], a.m[mask]
    peak = float(np.max(np.abs(m)))
    if not peak > 0:
        raise InputError(f"the reference's {channel} is zero over the disturbance", field="reference")
    return {"error_pct": rms_error(p, m) / peak * 100.0,
            "mre_pct": mean_relative_error(p, m, floor=relative_error_floor(m))}


def _timed(trailer, road, speed, duration, dt, rate, repeat):
    """(signal table, wall seconds) of the fastest of ``repeat`` runs after one warm-up."""
    with warnings.catch_warnings():   # a warm-up stops short of the obstacle on purpose
        warnings.simplefilter("ignore", PhysicsWarning)
        trailer.run(road, speed, WARM_UP, dt, rate, False)
    best, table = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        table = trailer.run(road, speed, duration, dt, rate, False)
        best = min(best, time.perf_counter() - t0)
    return table, best


def cam_count_study(tyre="xzl-16.00R20", n_length=(1, 3, 5, 7), n_width=(1, 3, 6),
                    roads=("cleat:50x50",), speeds=(12 / 3.6,), load="LC1", reference="ring",
                    pressure: float | None = None, duration: float | None = None, dt: float = 1e-3,
                    output_rate: float = 1000.0, left_wheel: str | None = "point", handling: str = "none",
                    repeat: int = 5,
                    rel_tol: float = REL_TOL, abs_tol: float = ABS_TOL, cost: str = "wall_s_per_sim_s",
                    cost_tol: float = COST_TOL, shift=0.0, progress=None, force: bool = False) -> CamStudy:
    """Error against cost of the enveloping model over ``n_length`` x ``n_width`` cams.

    Parameters
    ----------
    tyre : str or Tyre
        Built-in name or ``.tir`` path.
    n_length, n_width : sequence of int
        Cam counts along and across the patch, each 1 to 20.
    roads : sequence of str
        Road names (``"cleat:50x50"``, ...).
    speeds : sequence of float
        Towing speeds [m/s] (bounds of :func:`tyrelab.limits.check_speed`).
    load : str or float
        Load case (``"LC1"``-``"LC3"``) or wheel load [N].
    reference : str or DataFrame
        A contact model's name (``"ring"``, ``"ring-tp"``, ...), the
        enveloping model at given counts (``"enveloping:9x9"``: N_LENGTH x
        N_WIDTH), or a measured run (a signal table or a ``.tdx`` / ``.csv``
        / ``.parquet`` file, one road and one speed only; its time must match
        the simulation's, which starts at 0 with the test wheel at the road's
        ``run_start``, unless ``shift`` says otherwise: seconds or ``"auto"``).
    duration, dt, output_rate : float
        Simulated time [s] (default: to the road's end), step [s], output
        rate [Hz].
    left_wheel : str or None
        Contact model of the trailer's left wheel, on flat ground (default
        the point model; None: the model under test).
    handling : str
        Handling model of every run (default ``"none"``: the study is of the
        vertical response; the same for the reference and every pair).
    repeat : int
        Timed runs per configuration (the fastest counts).
    rel_tol, abs_tol, cost, cost_tol
        The recommendation rule (:func:`recommend`).
    progress : callable, optional
        Called with a short label after each simulation (reference runs
        included); :func:`study_runs` gives their number.
    force : bool
        Run even when the estimated wall time is above the limit.

    Returns
    -------
    CamStudy
    """
    from ..rig.trailer import Trailer, load_case_wheel_load
    from ..road.spec import road_from_spec
    from ..tyre.model import TyreModel

    lengths, widths = check_counts(n_length, "n_length"), check_counts(n_width, "n_width")
    rule_text(rel_tol, abs_tol, cost, cost_tol)  # the rule's arguments, checked before any work
    roads = [str(r) for r in ([roads] if isinstance(roads, str) else roads)]
    speeds = [limits.check_speed(v) for v in ([speeds] if np.ndim(speeds) == 0 else speeds)]
    if not roads or not speeds:
        raise InputError("at least one road and one speed are needed", field="roads")
    repeat = limits.check_count(repeat, "repeat", 1, 100)
    dt = limits.check_dt(dt)
    output_rate = limits.check_rate(output_rate, dt)
    if duration is not None:
        duration = limits.check_duration(duration, dt, output_rate)
    t = _tyre(tyre, pressure)
    from ..tyre.registry import handling_model
    handling_model(handling)  # an unknown name lists the known ones
    wheel_load = load_case_wheel_load(load) if isinstance(load, str) else float(load)
    wheel_load = limits.check_wheel_load(wheel_load, t)
    kind, ref_value, ref_label = check_reference(reference)
    if kind == "table" and (len(roads) > 1 or len(speeds) > 1):
        raise InputError("a measured reference is one run: give one road and one speed",
                         field="reference")
    road_objs = {r: road_from_spec(r, force=force) for r in roads}
    left = TyreModel(t, contact=left_wheel, handling=handling) if left_wheel else None

    def model(contact, options):
        return TyreModel(t, contact=contact, handling=handling, options=dict(options))

    pairs = [(nl, nw) for nl in lengths for nw in widths]
    probe = model("enveloping", {"n_length": lengths[-1], "n_width": widths[-1]})
    limits.check_stable_step(dt, [probe] if left is None else [probe, left], wheel_load)
    # the wall-time estimate of the whole study (warm-ups and repeats included)
    est = 0.0
    for r in roads:
        for v in speeds:
            run_time = duration or max(road_objs[r].extent()[1] - road_objs[r].run_start, 1.0) / v
            models = [probe] if left is None else [probe, left]
            est += len(pairs) * (repeat * run_time + WARM_UP) * resources.run_wall_time(models, 1.0, dt)
            if kind == "model":
                ref_models = [model(*ref_value)] + ([] if left is None else [left])
                est += resources.run_wall_time(ref_models, run_time, dt)
    resources.check_resources(f"a cam study of {len(pairs)} pairs x {len(roads) * len(speeds)} conditions",
                              wall_time=est, force=force, hint="use fewer pairs, roads or speeds")

    rows = []
    for r in roads:
        road = road_objs[r]
        for v in speeds:
            if kind == "model":
                ref = Trailer(model(*ref_value), load, left=left).run(road, v, duration, dt, output_rate,
                                                                      False)
                if progress:
                    progress(f"reference {ref_label} {r} {v * 3.6:.4g} km/h")
            else:
                ref = ref_value
            channel = "FZW" if "FZW" in ref.columns else "FZ"
            seg = _disturbance(ref, road if kind == "model" else None, channel)
            for nl, nw in pairs:
                trailer = Trailer(model("enveloping", {"n_length": nl, "n_width": nw}), load, left=left)
                sim, wall = _timed(trailer, road, v, duration, dt, output_rate, repeat)
                sim_time = float(sim["RUNTIME"].iloc[-1] - sim["RUNTIME"].iloc[0]) + 1.0 / output_rate
                err = condition_error(sim, ref, seg, channel, shift)
                rows.append({"n_length": nl, "n_width": nw, "cams": nl * nw, "road": r, "speed": v,
                             **err, "wall_s_per_sim_s": wall / sim_time, "duration_s": sim_time,
                             "channel": channel, "disturbance_start_s": seg.disturbance[0],
                             "disturbance_end_s": seg.disturbance[1]})
                if progress:
                    progress(f"{nl}x{nw} {r} {v * 3.6:.4g} km/h")
    table = pd.DataFrame(rows, columns=COLUMNS)
    rec = recommend(table, rel_tol, abs_tol, cost, cost_tol)
    return CamStudy(table=table, summary=summarise(table, rel_tol, abs_tol), recommended=rec,
                    metric=METRIC.format(channel=table["channel"].iloc[0]),
                    rule=rule_text(rel_tol, abs_tol, cost, cost_tol), reference=ref_label, tyre=t.name)


def study_runs(n_length, n_width, roads, speeds, reference) -> int:
    """Simulations :func:`cam_count_study` reports to ``progress`` (for a progress bar)."""
    conditions = len(roads) * len(speeds)
    ref = isinstance(reference, str) and Path(reference).suffix.lower() not in REFERENCE_SUFFIXES
    return conditions * (len(set(n_length)) * len(set(n_width)) + int(ref))


def tir_lines(pair) -> str:
    """The ``[CONTACT_PATCH]`` lines of a recommended pair."""
    nl, nw = pair
    return f"[CONTACT_PATCH]\nN_WIDTH  = {int(nw)}\nN_LENGTH = {int(nl)}"
