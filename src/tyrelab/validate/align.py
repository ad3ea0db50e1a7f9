"""Bring a simulated and a measured run onto one time base.

Rule (stated once, used by every metric): the **measurement's** time base is
kept; the simulation is linearly interpolated onto it, optionally shifted by
``shift`` seconds, i.e. the compared prediction is
``p(t) = sim(t - shift)``. Only measured samples whose shifted time lies
inside the simulated interval are compared (no extrapolation), and samples
where either value is NaN (``NOTAVAIL`` in a TYDEX file) are dropped; the
number dropped is reported.

Both runs must follow one sign convention, the TYDEX C-axis system's (z up, the
road's force on the tyre; ``docs/formats.md``). A measurement whose compared
channel holds, on average, the opposite sign from the simulation's, each mean
larger than its own scatter, was almost surely logged on an axis pointing the
other way: :func:`check_signs` warns (:class:`SignWarning`) and names the
column map's ``-CHANNEL`` that reads it. The metrics are computed as given.

A shift can be estimated by cross-correlation (``shift="auto"``): the
mean-removed signals, each on its own clock from its first sample, are put on
a uniform grid at the measurement's median step, the lag with the largest
correlation (within ``max_shift``, else any that leaves a quarter of the
shorter record overlapping) is taken and refined to a fraction of a step by
a parabola through the three correlation values around the maximum.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.signal import correlate, correlation_lags

from ..errors import InputError


class SignWarning(UserWarning):
    """A measured channel seems to follow the opposite sign convention from the simulation's."""


@dataclass
class Aligned:
    """A prediction ``p`` and measurement ``m`` on the measured time ``t``."""

    t: np.ndarray
    p: np.ndarray
    m: np.ndarray
    shift: float = 0.0
    dropped: int = 0
    channel: str = "FZ"


def check_time(t, name: str = "RUNTIME", source=None) -> np.ndarray:
    """A time vector as floats; strictly increasing and finite, else InputError."""
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or t.size < 2:
        raise InputError("needs at least two samples", source=source, field=name)
    if not np.all(np.isfinite(t)):
        raise InputError("time holds NaN or inf", source=source, field=name)
    if np.any(np.diff(t) <= 0):
        i = int(np.argmax(np.diff(t) <= 0))
        raise InputError(f"time is not strictly increasing at sample {i + 1}",
                         source=source, field=name)
    return t


def interpolate_onto(t_sim, y_sim, t, shift: float = 0.0):
    """``sim(t - shift)`` by linear interpolation and a mask of samples inside."""
    t_sim = np.asarray(t_sim, dtype=float)
    tt = np.asarray(t, dtype=float) - shift
    inside = (tt >= t_sim[0]) & (tt <= t_sim[-1])
    return np.interp(tt, t_sim, np.asarray(y_sim, dtype=float)), inside


def estimate_shift(t_sim, y_sim, t_meas, y_meas, max_shift: float | None = None) -> float:
    """Time shift of the simulation that best matches the measurement.

    Returns ``s`` such that ``sim(t - s)`` has the largest cross-correlation
    with ``meas(t)``. Each record is taken on its own clock from its first
    sample, so a logger's clock (any reading, 10:42:07 as seconds) costs
    nothing; ``s`` is then on the measurement's clock. With ``max_shift``
    ``|s| <= max_shift``; without, any ``s`` that leaves at least a quarter
    of the shorter record overlapping (a logger started well before the
    obstacle, or stopped well after it, is found).
    """
    t_sim, t_meas = check_time(t_sim), check_time(t_meas)
    dt = float(np.median(np.diff(t_meas)))
    base = float(t_meas[0] - t_sim[0])  # the shift that lays the records' first samples together
    span_sim, span_meas = float(t_sim[-1] - t_sim[0]), float(t_meas[-1] - t_meas[0])
    grid = np.arange(0.0, max(span_sim, span_meas) + 0.5 * dt, dt)
    ys = _centred_on(grid, t_sim - t_sim[0], y_sim)
    ym = _centred_on(grid, t_meas - t_meas[0], y_meas)
    corr = correlate(ym, ys, mode="full")  # corr[lag] = sum ym[n + lag] * ys[n]
    lags = correlation_lags(ym.size, ys.size, mode="full")
    if max_shift is None:
        overlap = np.minimum(span_meas, lags * dt + span_sim) - np.maximum(0.0, lags * dt)
        allowed = overlap >= 0.25 * min(span_sim, span_meas) - 1e-12
    else:
        allowed = np.abs(base + lags * dt) <= max_shift + 1e-12
    if not allowed.any():
        raise InputError(f"no shift within {max_shift:g} s lets the simulation and the measurement "
                         "overlap", field="max_shift")
    k = int(np.argmax(np.where(allowed, corr, -np.inf)))
    frac = 0.0
    if 0 < k < corr.size - 1 and allowed[k - 1] and allowed[k + 1]:
        a, b, c = corr[k - 1], corr[k], corr[k + 1]
        denom = a - 2 * b + c
        if denom < 0:
            frac = 0.5 * (a - c) / denom
    return float(base + (lags[k] + frac) * dt)


def _centred_on(grid, t, y):
    """Signal on ``grid`` with its mean removed; zero outside its record."""
    y = np.asarray(y, dtype=float)
    ok = np.isfinite(y)
    t, y = np.asarray(t, dtype=float)[ok], y[ok]
    out = np.interp(grid, t, y - y.mean())
    out[(grid < t[0]) | (grid > t[-1])] = 0.0
    return out


def align(sim: pd.DataFrame, meas: pd.DataFrame, channel: str = "FZ",
          shift: float | str = 0.0, max_shift: float | None = None) -> Aligned:
    """Simulation interpolated onto the measurement's time base.

    Parameters
    ----------
    sim, meas : pandas.DataFrame
        Signal tables with ``RUNTIME`` and ``channel``.
    channel : str
        Compared channel (default normal force ``FZ``).
    shift : float or "auto"
        Seconds the simulation is delayed by, or estimated by
        :func:`estimate_shift`.
    max_shift : float, optional
        Limit of the estimated shift in seconds.
    """
    sim_name, meas_name = _named(sim, "simulation"), _named(meas, "measurement")
    for name, df, source in (("simulation", sim, sim_name), ("measurement", meas, meas_name)):
        for col in ("RUNTIME", channel):
            if col not in df.columns:
                raise InputError(f"the {name} has no channel {col}", field=col, source=source)
    t_sim = check_time(sim["RUNTIME"].to_numpy(), source=sim_name)
    t_meas = check_time(meas["RUNTIME"].to_numpy(), source=meas_name)
    y_sim = sim[channel].to_numpy(dtype=float)
    y_meas = meas[channel].to_numpy(dtype=float)
    if isinstance(shift, str):
        if shift != "auto":
            raise InputError(f"shift must be a number or 'auto', got '{shift}'", field="shift")
        shift = estimate_shift(t_sim, y_sim, t_meas, y_meas, max_shift)
    ok_sim = np.isfinite(y_sim)
    p, inside = interpolate_onto(t_sim[ok_sim], y_sim[ok_sim], t_meas, float(shift))
    keep = inside & np.isfinite(y_meas)
    if keep.sum() < 2:
        raise InputError("the simulation and the measurement do not overlap in time",
                         field="RUNTIME")
    dropped = int(np.sum(inside & ~np.isfinite(y_meas)))
    check_signs(p[keep], y_meas[keep], channel, meas_name)
    return Aligned(t_meas[keep], p[keep], y_meas[keep], float(shift), dropped, channel)


def _named(df: pd.DataFrame, role: str) -> str:
    """The run's file (``attrs["path"]``, set by :func:`~tyrelab.measure.io.read_run`), or
    its metadata's source, or its role."""
    return str(df.attrs.get("path") or df.attrs.get("metadata", {}).get("source") or role)


def check_signs(p, m, channel: str, source: str) -> bool:
    """Warn (:class:`SignWarning`) when the measured channel ``m`` and the prediction ``p``
    have means of opposite sign, each larger than its own standard deviation: one of the
    two was logged on an axis that points the other way. Returns True when it warned."""
    mp, mm = float(np.mean(p)), float(np.mean(m))
    if mp * mm < 0 and abs(mp) > float(np.std(p)) and abs(mm) > float(np.std(m)):
        signs = "negative against positive" if mm < 0 else "positive against negative"
        warnings.warn(f"{source}: the measured {channel} has on average the opposite sign to the "
                      f"simulated one ({signs}). tyrelab's channels follow the TYDEX C-axis "
                      f"system (z up, the road's force on the tyre: FZ > 0 under load); a logger "
                      f"column on an axis pointing the other way is read with '-{channel}' in "
                      "the column map", SignWarning, stacklevel=3)
        return True
    return False
