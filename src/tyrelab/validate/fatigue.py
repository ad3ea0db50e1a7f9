"""Peak loads, extremes and rainflow pseudo-damage: what histogram fits hide.

The thesis (5.3.2) found that the measured fatigue-track force had single
peak loads that only one model reproduced, that "the peak loads are
statistically not relevant but are extremely important for the outcome of the
test", and that a normal fit cannot show them. This module compares the
extremes and the durability content of two force histories.

Pseudo-damage: cycles are counted by rainflow (ASTM E1049-85, through the
maintained PyPI package ``rainflow``) and summed with a Basquin S-N slope
``k``::

    D = sum_i n_i * (S_i / S_ref)^k

with ``n_i`` = 1 for a full and 0.5 for a half cycle of range ``S_i``. Only
ratios of D matter for validation; the damage-equivalent range over
``n_ref`` cycles, ``S_eq = (D / n_ref)^(1/k) * S_ref``, is in force units.
The default slope ``k = 5`` is a common choice for welded steel structures
(the loaded chassis, not the tyre); state the slope used with the result.

References
----------
.. [1] ASTM E1049-85 (2017). Standard practices for cycle counting in fatigue
   analysis (rainflow counting, section 5.4.4).
.. [2] Basquin, O. H. (1910). The exponential law of endurance tests.
   Proc. ASTM 10, 625-630.
.. [3] Thesis chapter 5, section 5.3.2 and Figure 5-16.
"""

from __future__ import annotations

import numpy as np
import rainflow

from ..errors import InputError
from .metrics import percent_error, relative_error_floor

DEFAULT_SLOPE = 5.0


def _series(y, what="signal") -> np.ndarray:
    y = np.asarray(y, dtype=float).ravel()
    if y.size < 2 or not np.all(np.isfinite(y)):
        raise InputError(f"{what}: needs two or more finite samples")
    return y


def reversal_values(y: np.ndarray) -> np.ndarray:
    """The values of the reversal points :func:`rainflow.reversals` finds in ``y`` (three or
    more samples), found with array operations: the first and the last sample, and every
    sample where the signal turns, a repeated value counting once (a plateau is one point).

    The counting needs only these values, and the series of them has itself exactly these
    reversals (between two turns the signal is monotone, each turn changes direction, so
    the values strictly alternate), so rainflow counts the same cycles from them. Its own
    search is a Python loop over every sample: 5 of the 21 s a study's evaluation took on
    the built-in campaign's 200 runs.
    """
    keep = np.empty(y.size, dtype=bool)
    keep[0] = True
    np.not_equal(y[1:], y[:-1], out=keep[1:])
    distinct = y[keep]
    step = np.diff(distinct)
    turns = step[:-1] * step[1:] < 0.0   # rainflow's own test, on the same differences
    return np.concatenate((y[:1], distinct[1:-1][turns], y[-1:]))


def cycles(y) -> np.ndarray:
    """Rainflow cycles of ``y`` [1]: array of rows (range, mean, count)."""
    y = _series(y)
    if y.size >= 3:
        points = reversal_values(y)
        if points.size == 2:
            # rainflow takes a two-point series as one point; a repeated first value makes
            # it see both ends, as it sees them in y
            points = np.concatenate((points[:1], points))
        y = points
    rows = [(rng, mean, count) for rng, mean, count, _, _ in rainflow.extract_cycles(y)]
    return np.array(rows, dtype=float).reshape(-1, 3)


def pseudo_damage(y, slope: float = DEFAULT_SLOPE, ref_range: float = 1.0) -> float:
    """Relative fatigue damage ``sum n_i (S_i / S_ref)^k`` [1, 2]."""
    if not slope > 0 or not ref_range > 0:
        raise InputError("S-N slope and reference range must be positive", field="slope")
    c = cycles(y)
    return float(np.sum(c[:, 2] * (c[:, 0] / ref_range) ** slope)) if c.size else 0.0


def equivalent_range(y, slope: float = DEFAULT_SLOPE, n_ref: float = 1e6) -> float:
    """Damage-equivalent constant range over ``n_ref`` cycles, in signal units."""
    return float((pseudo_damage(y, slope) / n_ref) ** (1.0 / slope))


def extremes(y, quantiles=(0.01, 0.99, 0.999)) -> dict:
    """Maximum, minimum and the given quantiles of a force history."""
    y = _series(y)
    out = {"max": float(np.max(y)), "min": float(np.min(y))}
    for q in quantiles:
        out[f"q{q * 100:g}"] = float(np.quantile(y, q))
    return out


def peak_exceedances(y, threshold: float) -> int:
    """Number of separate excursions of ``y`` above ``threshold`` (upcrossings)."""
    y = _series(y)
    above = y > threshold
    return int(above[0]) + int(np.sum(~above[:-1] & above[1:]))


def peak_load_errors(p, m, slope: float = DEFAULT_SLOPE, threshold: float | None = None) -> dict:
    """Extremes, peak counts and pseudo-damage of ``p`` against ``m``.

    ``p`` and ``m`` need not share a time base. % errors follow eq. 5.4 with
    the near-zero floor of :mod:`tyrelab.validate.metrics`. ``threshold``
    (default: mean + 3 standard deviations of ``m``) counts peak loads.

    Returns a dict: ``max_error_pct``, ``min_error_pct``, ``q99.9_error_pct``,
    ``n_peaks_pred``, ``n_peaks_meas`` (excursions above the threshold),
    ``damage_ratio`` (D_pred / D_meas), ``eq_range_error_pct``.
    """
    p, m = _series(p, "prediction"), _series(m, "measurement")
    floor = relative_error_floor(m)
    ep, em = extremes(p), extremes(m)
    if threshold is None:
        threshold = float(np.mean(m) + 3.0 * np.std(m))
    dp, dm = pseudo_damage(p, slope), pseudo_damage(m, slope)
    if not dm > 0:
        raise InputError("the measurement has no load cycles: damage ratio undefined")
    sp, sm = (dp / 1e6) ** (1 / slope), (dm / 1e6) ** (1 / slope)
    return {"max_error_pct": percent_error(ep["max"], em["max"], floor),
            "min_error_pct": percent_error(ep["min"], em["min"], floor),
            "q99.9_error_pct": percent_error(ep["q99.9"], em["q99.9"], floor),
            "threshold": threshold,
            "n_peaks_pred": peak_exceedances(p, threshold),
            "n_peaks_meas": peak_exceedances(m, threshold),
            "damage_ratio": dp / dm, "slope": slope,
            "eq_range_error_pct": percent_error(sp, sm)}

