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
built-in campaign runs it; a measurement's time starts where a simulation's
does (the wheel 5 m before the obstacle at the stated speed).

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
    load [N], and its signal table (``RUNTIME`` [s] and ``FZW`` [N] at least)."""

    road: str
    speed: float
    load: str | float
    signal: pd.DataFrame


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


def simulate_run(tyre, rp, run: CleatRun) -> np.ndarray:
    """The ring's FZW [N] on the trailer for ``run``, at the measurement's times."""
    from ..rig.trailer import Trailer
    from ..tyre.model import TyreModel

    t = run.signal["RUNTIME"].to_numpy(float)
    model = TyreModel(tyre, "ring", options={"parameters": rp})
    trailer = Trailer(model, run.load, left=TyreModel(tyre, "point"))
    sim = trailer.run(run.road, run.speed, float(t[-1]) + 1e-3, progress=False)
    return np.interp(t, sim["RUNTIME"].to_numpy(), sim["FZW"].to_numpy())


def run_error(tyre, rp, run: CleatRun) -> np.ndarray:
    """Model minus measured FZW at the measurement's times, over the measured peak."""
    measured = run.signal["FZW"].to_numpy(float)
    return (simulate_run(tyre, rp, run) - measured) / np.abs(measured).max()


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
    """Per run: road, speed, set ("fit" or "held out") and the RMS error of FZW in %
    of the measured peak with ring parameters ``before`` and ``after``."""
    rows = []
    for label, group in (("fit", runs), ("held out", held_out)):
        for run in group:
            e0 = run_error(tyre, before, run)
            e1 = e0 if after is before else run_error(tyre, after, run)
            rows.append({"road": run.road, "speed_kmh": run.speed * 3.6, "set": label,
                         "rms_before_pct": 100 * float(np.sqrt(np.mean(e0 ** 2))),
                         "rms_after_pct": 100 * float(np.sqrt(np.mean(e1 ** 2)))})
    return pd.DataFrame(rows, columns=["road", "speed_kmh", "set", "rms_before_pct", "rms_after_pct"])
