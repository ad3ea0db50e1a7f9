"""The ring's damping from dynamic cleat runs (thesis 4.5, recommendation II of 6.2).

FTire/fit could not use the trailer's cleat runs, so the thesis found FTire's
damping "by brute force": it changed the damping parameters, keeping the
ratios between them, until the simulated trailer over the 50 mm cleats
looked like the measured one (4.5, Figures 4-17 and 4-18). Here the same
idea as an optimisation: factors scale the ring's damping,

* ``patch``: the contact patch's damping ``PATCH_DAMPING`` (what the trailer
  sees at 2-4 Hz, the drop test's damping; docs/ring.md, "Damping"), and
* ``structure``: the foundation dampers ``DAMPING_RADIAL``, ``_TANGENTIAL``,
  ``_LATERAL``, ``_TORSION`` together, their ratios kept as the thesis kept
  them (the modal damping of Table 3-3),

and the free ones (by default ``patch`` only: the foundation dampers come
from the modal test, and FZW over cleats cannot tell them apart within the
model's own sensitivity, see below) are fitted (least squares on their
logarithms, scipy's ``least_squares``) to the normal force FZW of a stated
subset of measured runs of the trailer,
each resampled at the measurement's times and divided by the measurement's
peak. The other runs are held out and reported with the same error before
and after. Runs are the trailer with the ring on the test wheel and the
point model (same vertical law) on the left wheel on flat ground, as the
built-in campaign runs it. A measurement's clock is its logger's: each run
is first placed by cross-correlation of FZW with the ring at the starting
parameters (:func:`aligned`), then every parameter set is compared at its own
best shift within :data:`SHIFT_RANGE` of that (:func:`aligned_error`; the
shift is reported).

Identifiability (measured on the XZL, LC1, 50 mm cleat at 12 km/h, the
"measurement" made by the model itself with the factors 1.6 and 0.6): the
RMS error of FZW is 0 at the truth; 0.28 % of the peak with ``patch`` 6 % off;
but 0.68-0.69 % for every ``structure`` from 0.7 to 1.3 (and 1.8 % at 0.5),
a plateau at the level by which any small change moves the ring's response
over a cleat (docs/ring.md, "Performance": the blocks meet the cleat's edges
at another phase). So ``patch`` is found from cleat runs; ``structure`` is
not, and is left to the modal test.
"""

from __future__ import annotations

import dataclasses
import math
from typing import NamedTuple

import numpy as np
import pandas as pd

from ..errors import InputError


class CleatRun(NamedTuple):
    """A measured trailer run: road name, towing speed [m/s], load case or wheel
    load [N], and its signal table (``RUNTIME`` [s] and ``FZW`` [N] at least);
    ``shift`` [s] delays the simulation to meet the measurement (a simulation
    starts with the wheel 5 m before the obstacle), None until :func:`aligned`
    estimates it."""

    road: str
    speed: float
    load: str | float
    signal: pd.DataFrame
    shift: float | None = None


class RingDampingFit(NamedTuple):
    """Result of :func:`fit_ring_damping`."""

    #: the ring parameters with the fitted damping
    parameters: object
    #: the fitted factors on PATCH_DAMPING and on the foundation dampers
    patch: float
    structure: float
    #: per run: road, speed, set ("fit" or "held out"), RMS error of FZW in % of the
    #: measured peak, before and after
    table: pd.DataFrame


def scaled_damping(rp, patch: float, structure: float):
    """``rp`` with ``PATCH_DAMPING`` times ``patch`` and the four foundation dampers
    times ``structure`` (their ratios kept)."""
    return dataclasses.replace(rp, cp=rp.cp * patch, cr=rp.cr * structure, ct=rp.ct * structure,
                               cy=rp.cy * structure, cb=rp.cb * structure)


#: the simulation that finds a run's shift runs this much [s] longer than the measurement, so the
#: obstacle is met even when the logger started after the simulation's 5 m run-up would have
ALIGN_MARGIN = 3.0
#: how far [s] the best alignment may move a run from its cross-correlation shift
SHIFT_RANGE = 0.05


def _trailer_run(tyre, rp, run: CleatRun, duration: float) -> pd.DataFrame:
    from ..rig.trailer import Trailer
    from ..tyre.model import TyreModel

    model = TyreModel(tyre, "ring", options={"parameters": rp})
    trailer = Trailer(model, run.load, left=TyreModel(tyre, "point"))
    return trailer.run(run.road, run.speed, duration, progress=False)


def _fzw_at(sim: pd.DataFrame, t) -> np.ndarray:
    """The simulation's FZW at times ``t`` of its own clock (before its start: its first
    value, the trailer towed on flat)."""
    return np.interp(t, sim["RUNTIME"].to_numpy(), sim["FZW"].to_numpy())


def simulate_run(tyre, rp, run: CleatRun) -> np.ndarray:
    """The ring's FZW [N] on the trailer for ``run``, at the measurement's times less its
    ``shift`` (none: 0)."""
    t = run.signal["RUNTIME"].to_numpy(float) - (run.shift or 0.0)
    return _fzw_at(_trailer_run(tyre, rp, run, max(float(t[-1]), 0.0) + 1e-3), t)


def aligned(tyre, rp, run: CleatRun) -> CleatRun:
    """``run`` with a starting ``shift``: the delay of the ring's run at ``rp`` with the largest
    cross-correlation of FZW with the measurement (:func:`tyrelab.validate.align.estimate_shift`;
    the simulation runs :data:`ALIGN_MARGIN` longer than the measurement). A run that has one
    is returned as it is. Only a start: the impact's place is geometric, but the damping
    shapes the response after it, and so the correlation's peak (3.7 ms early for a patch
    damping 1.6 times the start's); :func:`aligned_error` aligns each parameter set at its
    best."""
    from ..validate.align import estimate_shift

    if run.shift is not None:
        return run
    t = run.signal["RUNTIME"].to_numpy(float)
    span = float(t[-1] - t[0])
    sim = _trailer_run(tyre, rp, run, span + ALIGN_MARGIN)
    shift = estimate_shift(sim["RUNTIME"].to_numpy(), sim["FZW"].to_numpy(), t,
                           run.signal["FZW"].to_numpy(float))
    return run._replace(shift=float(shift))


def aligned_error(tyre, rp, run: CleatRun) -> tuple[np.ndarray, float]:
    """Model minus measured FZW at the measurement's times, over the measured peak, at the
    shift within :data:`SHIFT_RANGE` of ``run.shift`` (none: 0) that makes its RMS least,
    and that shift [s]. The measurement's clock is the logger's: each parameter set is
    compared where it matches best, so a fit cannot trade damping for timing."""
    from scipy.optimize import minimize_scalar

    t = run.signal["RUNTIME"].to_numpy(float)
    measured = run.signal["FZW"].to_numpy(float)
    peak = np.abs(measured).max()
    start = run.shift or 0.0
    sim = _trailer_run(tyre, rp, run, max(float(t[-1]) - start + SHIFT_RANGE, 0.0) + 1e-3)

    def error(shift):
        return (_fzw_at(sim, t - shift) - measured) / peak

    best = minimize_scalar(lambda s: float(np.mean(error(s) ** 2)), method="bounded",
                           bounds=(start - SHIFT_RANGE, start + SHIFT_RANGE),
                           options={"xatol": 1e-6})
    shift = float(best.x)
    return error(shift), shift


def run_error(tyre, rp, run: CleatRun) -> np.ndarray:
    """Model minus measured FZW at the measurement's times, over the measured peak, best
    aligned (:func:`aligned_error`)."""
    return aligned_error(tyre, rp, run)[0]


def _check(runs, what):
    for k, run in enumerate(runs):
        if not isinstance(run, CleatRun):
            raise InputError(f"{what} run {k + 1}: expected a CleatRun(road, speed, load, signal)",
                             field="runs")
        cols = set(run.signal.columns)
        if not {"RUNTIME", "FZW"} <= cols or len(run.signal) < 10:
            raise InputError(f"{what} run {k + 1} ({run.road}): its signal needs RUNTIME and FZW "
                             "and at least 10 samples", field="runs")
        if not (np.all(np.isfinite(run.signal["FZW"])) and np.abs(run.signal["FZW"]).max() > 0):
            raise InputError(f"{what} run {k + 1} ({run.road}): FZW must be finite and not all 0",
                             field="runs")


def fit_ring_damping(tyre, runs, held_out=(), parameters=None, free=("patch",), bounds=(0.2, 5.0),
                     max_nfev=30, progress=None) -> RingDampingFit:
    """Fit the ring's patch and structural damping to measured trailer runs.

    Parameters
    ----------
    tyre : Tyre
        The tyre (its ring parameters are the start unless ``parameters``).
    runs, held_out : sequence of CleatRun
        The runs fitted, and the runs only predicted.
    parameters : RingParameters, optional
        Starting ring parameters.
    free : tuple of {"patch", "structure"}
        The factors fitted; the others stay 1.
    bounds : (float, float)
        Range of both factors.
    max_nfev : int
        Budget of the optimiser (each evaluation simulates every fitted run).
    progress : callable, optional
        Called with the cost after each evaluation.
    """
    from scipy.optimize import least_squares

    from ..tyre.ring.parameters import ring_parameters

    runs, held_out = list(runs), list(held_out)
    if not runs:
        raise InputError("at least one run to fit is needed", field="runs")
    _check(runs, "fitted")
    _check(held_out, "held-out")
    lo, hi = bounds
    if not (0 < lo < 1 < hi and math.isfinite(hi)):
        raise InputError(f"bounds must satisfy 0 < low < 1 < high, got {bounds}", field="bounds")
    free = tuple(free)
    if not free or any(f not in ("patch", "structure") for f in free) or len(set(free)) != len(free):
        raise InputError(f"free must name 'patch' and/or 'structure', got {free}", field="free")
    rp0 = parameters if parameters is not None else ring_parameters(tyre)
    runs = [aligned(tyre, rp0, run) for run in runs]
    held_out = [aligned(tyre, rp0, run) for run in held_out]

    def factors(x):
        value = dict(zip(free, np.exp(x)))
        return float(value.get("patch", 1.0)), float(value.get("structure", 1.0))

    def residuals(x):
        rp = scaled_damping(rp0, *factors(x))
        r = np.concatenate([run_error(tyre, rp, run) / math.sqrt(len(run.signal)) for run in runs])
        if progress is not None:
            progress(float(r @ r))
        return r

    k = len(free)
    sol = least_squares(residuals, np.zeros(k), bounds=(np.full(k, math.log(lo)), np.full(k, math.log(hi))),
                        diff_step=0.05, max_nfev=max_nfev, xtol=1e-3, ftol=1e-6)
    patch, structure = factors(sol.x)
    rp = scaled_damping(rp0, patch, structure)
    return RingDampingFit(rp, patch, structure, run_table(tyre, rp0, rp, runs, held_out))


def run_table(tyre, before, after, runs=(), held_out=()) -> pd.DataFrame:
    """Per run: road, speed, set ("fit" or "held out"), the simulation's ``shift_s`` to the
    measurement at ``after`` (:func:`aligned_error`, from :func:`aligned` at ``before`` where a
    run has no shift) and the RMS error of FZW in % of the measured peak with ring parameters
    ``before`` and ``after``, each at its own best alignment."""
    rows = []
    for label, group in (("fit", runs), ("held out", held_out)):
        for run in group:
            run = aligned(tyre, before, run)
            e0, shift = aligned_error(tyre, before, run)
            if after is not before:
                e1, shift = aligned_error(tyre, after, run)
            else:
                e1 = e0
            rows.append({"road": run.road, "speed_kmh": run.speed * 3.6, "set": label,
                         "shift_s": shift,
                         "rms_before_pct": 100 * float(np.sqrt(np.mean(e0 ** 2))),
                         "rms_after_pct": 100 * float(np.sqrt(np.mean(e1 ** 2)))})
    return pd.DataFrame(rows, columns=["road", "speed_kmh", "set", "shift_s", "rms_before_pct",
                                       "rms_after_pct"])
