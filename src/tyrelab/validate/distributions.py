"""Force distributions on rough tracks: normal fits and their errors (thesis 5.3).

Over Belgian paving or a fatigue track a point-by-point comparison fails (a
small change of path gives a different input), so the thesis fits a normal
distribution (eq. 5.3) to the force samples of each run and compares the
mean and standard deviation with the signed percentage error of eq. 5.4.

The fit is the maximum-likelihood one: the sample mean and the standard
deviation with divisor n. The thesis also notes (5.3.1, 5.3.3) that many
simulated force distributions are *not* normal, which the two parameters
hide; so each fit is reported with its Kolmogorov-Smirnov distance to the
fitted normal, its skewness and excess kurtosis.

Near-zero rule: eq. 5.4 divides by the measured mean or standard deviation;
the denominator is at least 1 % of the largest measured magnitude
(:data:`tyrelab.validate.metrics.FLOOR_FRACTION`), the rule of
:mod:`tyrelab.validate.metrics`.

References
----------
.. [1] Thesis chapter 5, eqs. 5.3 (normal density) and 5.4 (%E),
   Tables 5-11 to 5-14.
"""

from __future__ import annotations

import numpy as np
from scipy import stats

from ..errors import InputError
from .metrics import FLOOR_FRACTION, percent_error, relative_error_floor


def _samples(x, what="samples") -> np.ndarray:
    x = np.asarray(x, dtype=float).ravel()
    if x.size < 2:
        raise InputError(f"{what}: a distribution needs at least two samples")
    if not np.all(np.isfinite(x)):
        raise InputError(f"{what}: NaN or inf in the samples")
    return x


def fit_normal(x) -> tuple[float, float]:
    """Maximum-likelihood normal fit (eq. 5.3): (mean, standard deviation, ddof 0)."""
    x = _samples(x)
    return float(np.mean(x)), float(np.std(x))


def ks_distance(x, mu: float, sigma: float) -> float:
    """Kolmogorov-Smirnov distance ``D = sup |F_n(x) - Phi((x - mu) / sigma)|`` of the samples'
    empirical distribution from a normal one (``sigma > 0``).

    Over the sorted samples ``x_(1) <= ... <= x_(n)``, ``D = max(D+, D-)`` with
    ``D+ = max_i (i/n - Phi_i)`` and ``D- = max_i (Phi_i - (i-1)/n)``: the statistic of
    :func:`scipy.stats.kstest`, computed as it computes it, without the p-value, which
    scipy evaluates exactly for large n (28 ms for a 100 m track at 1 kHz: half of a
    study's evaluation) and which no table here reports.
    """
    xs = np.sort(np.asarray(x, dtype=float).ravel())
    n = xs.size
    cdf = stats.norm.cdf(xs, mu, sigma)
    d_plus = np.max(np.arange(1.0, n + 1) / n - cdf)
    d_minus = np.max(cdf - np.arange(0.0, n) / n)
    return float(max(d_plus, d_minus))


def _ks(x, mu: float, sigma: float) -> float:
    """KS distance to the fitted normal; a constant signal (no spread) is 1, not normal at all."""
    return 1.0 if sigma == 0.0 else ks_distance(x, mu, sigma)


def normality(x) -> dict:
    """How normal the samples are: KS distance to the fitted normal, skew, excess kurtosis.

    A constant signal has no spread; its KS distance is reported as 1 (not
    normal at all) and skew and kurtosis as 0.
    """
    x = _samples(x)
    mu, sigma = fit_normal(x)
    ks = _ks(x, mu, sigma)
    if sigma == 0.0:
        return {"ks": ks, "skew": 0.0, "kurtosis": 0.0}
    return {"ks": ks, "skew": float(stats.skew(x)), "kurtosis": float(stats.kurtosis(x))}


def normal_fit_errors(p, m, floor_fraction: float = FLOOR_FRACTION) -> dict:
    """μ%err and σ%err of the normal fits (eq. 5.4, Tables 5-11 to 5-14).

    ``p`` and ``m`` need not have the same length or time base.

    Returns
    -------
    dict
        ``mean_error_pct``, ``std_error_pct`` (signed), the fitted
        ``mu_pred``, ``sigma_pred``, ``mu_meas``, ``sigma_meas`` and the KS
        distances ``ks_pred``, ``ks_meas``.
    """
    p, m = _samples(p, "prediction"), _samples(m, "measurement")
    mu_p, s_p = fit_normal(p)
    mu_m, s_m = fit_normal(m)
    floor = relative_error_floor(m, floor_fraction)
    return {"mean_error_pct": percent_error(mu_p, mu_m, floor),
            "std_error_pct": percent_error(s_p, s_m, floor),
            "mu_pred": mu_p, "sigma_pred": s_p, "mu_meas": mu_m, "sigma_meas": s_m,
            "ks_pred": _ks(p, mu_p, s_p), "ks_meas": _ks(m, mu_m, s_m)}


def histogram_density(x, bins=40, range_=None):
    """Probability density histogram: (bin centres, density), for Figure 5-14."""
    x = _samples(x)
    density, edges = np.histogram(x, bins=bins, range=range_, density=True)
    return 0.5 * (edges[:-1] + edges[1:]), density
