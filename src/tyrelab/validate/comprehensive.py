"""Magnitude and phase error measures the thesis found missing.

Both measures split the disagreement of two transient histories into a
magnitude part and a phase part, from the time integrals
``I_mm = int m^2``, ``I_pp = int p^2`` and ``I_mp = int m p``.

The integrals are sums over the common samples times the (median) step, or
trapezoidal integrals when a time vector is given; the ratios do not depend
on the step for a uniform time base.

A tyre force carries a large static part that dominates these integrals;
``baseline`` (a number, or ``"mean"`` for the mean of the measurement) is
subtracted from both signals first so that the dynamic part is compared.

References
----------
.. [1] Sprague, M. A., Geers, T. L. (2004). A spectral-element method for
   modelling cavitation in transient fluid-structure interaction.
   Int. J. Numer. Meth. Engng 60, 2467-2499 (magnitude, phase and
   comprehensive error: M = sqrt(I_pp / I_mm) - 1,
   P = arccos(I_mp / sqrt(I_mm I_pp)) / pi, C = sqrt(M^2 + P^2)).
.. [2] Russell, D. M. (1997). Error measures for comparing transient data,
   part I: development of a comprehensive error measure. Proc. 68th Shock
   and Vibration Symposium, 175-184 (RM = sign(r) log10(1 + |r|),
   r = (I_pp - I_mm) / sqrt(I_pp I_mm), RP = arccos(I_mp / sqrt(I_pp I_mm)) / pi,
   RC = sqrt(pi / 4 (RM^2 + RP^2))).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from .metrics import _pair


def _integrals(p, m, t=None, baseline=None):
    p, m = _pair(p, m)
    if baseline is not None:
        b = float(np.mean(m)) if isinstance(baseline, str) and baseline == "mean" else baseline
        if isinstance(b, str):
            raise InputError(f"baseline must be a number or 'mean', got '{b}'", field="baseline")
        p, m = p - b, m - b
    if t is None:
        i_mm, i_pp, i_mp = float(np.sum(m * m)), float(np.sum(p * p)), float(np.sum(m * p))
    else:
        t = np.asarray(t, dtype=float)
        i_mm = float(np.trapezoid(m * m, t))
        i_pp = float(np.trapezoid(p * p, t))
        i_mp = float(np.trapezoid(m * p, t))
    for energy, which in ((i_mm, "the measurement"), (i_pp, "the prediction")):
        if not energy > 0.0:
            raise InputError(f"magnitude/phase error undefined: {which} equals the baseline "
                             "throughout (a constant signal)")
    return i_mm, i_pp, i_mp


def _phase(i_mm, i_pp, i_mp) -> float:
    c = i_mp / math.sqrt(i_mm * i_pp)
    return math.acos(min(1.0, max(-1.0, c))) / math.pi


def sprague_geers(p, m, t=None, baseline=None) -> dict:
    """Sprague-Geers magnitude ``M``, phase ``P`` and comprehensive ``C`` error [1].

    ``M`` is 0 for equal energy, +1 for a prediction twice the measurement;
    ``P`` is 0 in phase, 0.5 for a quarter-period shift of a sine, 1 for
    opposite sign.
    """
    i_mm, i_pp, i_mp = _integrals(p, m, t, baseline)
    mag = math.sqrt(i_pp / i_mm) - 1.0
    ph = _phase(i_mm, i_pp, i_mp)
    return {"SG_M": mag, "SG_P": ph, "SG_C": math.hypot(mag, ph)}


def russell(p, m, t=None, baseline=None) -> dict:
    """Russell's magnitude ``RM``, phase ``RP`` and comprehensive ``RC`` error [2]."""
    i_mm, i_pp, i_mp = _integrals(p, m, t, baseline)
    r = (i_pp - i_mm) / math.sqrt(i_pp * i_mm)
    rm = math.copysign(math.log10(1.0 + abs(r)), r)
    rp = _phase(i_mm, i_pp, i_mp)
    return {"R_M": rm, "R_P": rp, "R_C": math.sqrt(math.pi / 4.0 * (rm * rm + rp * rp))}
