"""The validation metrics of the thesis, chapter 5, exactly as defined there.

``p`` is the predicted (simulated) and ``m`` the measured signal on one time
base (:func:`tyrelab.validate.align.align`); the measurement is taken as the
correct value (thesis 5.1).

Near-zero rule (relative errors)
--------------------------------
Eq. 5.2 divides by the measured value, which is zero whenever a tyre loses
contact. Here the denominator is never smaller than a *floor*::

    %RE_i = |p_i - m_i| / max(|m_i|, floor) * 100

with ``floor = floor_fraction * max|m|`` over the compared samples and
``floor_fraction = 0.01`` (1 % of the segment's peak measured magnitude)
unless given. So a sample with a vanishing measured value counts as an
absolute error relative to 1 % of the peak, not as inf or NaN. A segment
whose measured values are all zero has no relative error: InputError. The
same rule, with an explicit ``floor``, applies to the signed scalar percentage
error of eq. 5.4 (:func:`percent_error`); without a floor a zero measured
value there raises InputError. No metric returns NaN or inf.

The peaks of the oscillatory response
-------------------------------------
Thesis 5.2 computes the response errors "only for the peaks of the oscillatory
response that followed the cleat impact", because "the response during
simulations and during experimental tests did not have the same oscillatory
period" -- the trailer's oscillation, whose period its hitch model missed. The
peaks are therefore those of that oscillation: both signals' responses are
low-passed (:func:`oscillation`: zero phase, 4th-order Butterworth) at
:data:`RESPONSE_BAND_HZ` = 10 Hz before their extrema are found and paired.
10 Hz lies between the trailer's body modes (pitch and roll on the tyres,
2.5-4 Hz; the XZL campaign's response oscillates at about 3.3 Hz) and the
tyre's belt modes (the XZL's lowest 16.9 Hz lateral and 22.7 Hz in-plane,
thesis Table 3-3), so it keeps the trailer's oscillation whole and takes out
the belt's ringing and the tread's ripple, which a flexible-ring reference
has and an analytic model cannot: on the raw signal each of their wiggles of
more than 5 % of the range counted as an oscillation peak and was paired with
a trailer peak of the other signal (docs/consistency.md: the response error
after the 76.3 mm cleat at 27 km/h fell from 188-752 % to 9-64 %). The
metrics vary little for a band edge of 8-15 Hz; below 6 Hz the filter starts
to shave the trailer's own peaks.

References
----------
.. [1] Thesis chapter 5, eqs. 5.1 (RMS error), 5.2 (%RE), 5.4 (%E); the
   mean of the %RE vector (m%RE), the 80 % relative error (80%RE) and the
   response-peak errors are defined in section 5.2.
"""

from __future__ import annotations

import numpy as np
from scipy.signal import find_peaks

from ..errors import InputError

FLOOR_FRACTION = 0.01
#: upper edge [Hz] of the band whose extrema are the response's peaks (module notes)
RESPONSE_BAND_HZ = 10.0


def _pair(p, m, what: str = "signals"):
    p = np.asarray(p, dtype=float).ravel()
    m = np.asarray(m, dtype=float).ravel()
    if p.shape != m.shape:
        raise InputError(f"{what}: prediction has {p.size} samples, measurement {m.size}")
    if p.size == 0:
        raise InputError(f"{what}: no samples to compare")
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(m))):
        raise InputError(f"{what}: NaN or inf in the compared samples")
    return p, m


def rms_error(p, m) -> float:
    """Root-mean-square error, thesis eq. 5.1: sqrt(mean((p - m)^2))."""
    p, m = _pair(p, m)
    return float(np.sqrt(np.mean((p - m) ** 2)))


def relative_error_floor(m, floor_fraction: float = FLOOR_FRACTION) -> float:
    """The near-zero floor of the denominator: ``floor_fraction * max|m|``."""
    m = np.asarray(m, dtype=float)
    peak = float(np.max(np.abs(m))) if m.size else 0.0
    if not peak > 0.0:
        raise InputError("relative error undefined: every measured value is zero")
    if not 0.0 < floor_fraction <= 1.0:
        raise InputError(f"floor_fraction must be in (0, 1], got {floor_fraction}",
                         field="floor_fraction")
    return floor_fraction * peak


def relative_error(p, m, floor: float | None = None,
                   floor_fraction: float = FLOOR_FRACTION) -> np.ndarray:
    """Percentage relative error vector, thesis eq. 5.2 with the near-zero rule.

    ``%RE = |p - m| / max(|m|, floor) * 100``; ``floor`` defaults to
    :func:`relative_error_floor` of ``m``.
    """
    p, m = _pair(p, m)
    if floor is None:
        floor = relative_error_floor(m, floor_fraction)
    if not floor > 0.0:
        raise InputError(f"relative-error floor must be positive, got {floor}", field="floor")
    return np.abs(p - m) / np.maximum(np.abs(m), floor) * 100.0


def mean_relative_error(p, m, **kw) -> float:
    """m%RE: the mean of the %RE vector (thesis 5.1 and 5.2)."""
    return float(np.mean(relative_error(p, m, **kw)))


def relative_error_percentile(p, m, q: float = 80.0, **kw) -> float:
    """80%RE: the error that ``q`` % of the samples do not exceed (thesis 5.2).

    The empirical quantile (inverted CDF): the smallest %RE value such that
    at least ``q`` % of the samples have an error at or below it.
    """
    if not 0.0 < q <= 100.0:
        raise InputError(f"percentile must be in (0, 100], got {q}", field="q")
    return float(np.percentile(relative_error(p, m, **kw), q, method="inverted_cdf"))


def percent_error(p: float, m: float, floor: float = 0.0) -> float:
    """Signed percentage error, thesis eq. 5.4: (p - m) / m * 100.

    If ``|m| < floor`` the denominator (only) is ``floor`` with the sign of
    ``m`` (positive for m = 0). With ``floor = 0`` a zero ``m`` raises InputError.
    """
    p, m = float(p), float(m)
    if not (np.isfinite(p) and np.isfinite(m)):
        raise InputError("percentage error of NaN or inf")
    den = m if abs(m) >= floor else (floor if m >= 0 else -floor)
    if den == 0.0:
        raise InputError("percentage error undefined: the measured value is zero")
    return (p - m) / den * 100.0


def oscillation(t, y, band_hz: float = RESPONSE_BAND_HZ) -> np.ndarray:
    """The part of ``y`` below ``band_hz``: a zero-phase 4th-order Butterworth low-pass
    (forward and backward, :func:`scipy.signal.sosfiltfilt`) of the whole record.

    The ends are extended by point reflection (scipy's odd padding), so a segment cut
    from a record can be filtered alone. A time base that is not uniform (a measured
    file) is filtered on a uniform one at its median step and interpolated back.
    """
    from scipy.signal import butter, sosfiltfilt
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.shape != y.shape or t.size < 2 or np.any(np.diff(t) <= 0):
        raise InputError("the oscillation needs an increasing time base, one per sample",
                         field="RUNTIME")
    if not band_hz > 0:
        raise InputError(f"the response band must be positive, got {band_hz} Hz",
                         field="response_band_hz")
    step = float(np.median(np.diff(t)))
    uniform = bool(np.max(np.abs(np.diff(t) - step)) <= 0.01 * step)
    tu = t if uniform else t[0] + step * np.arange(int(np.floor((t[-1] - t[0]) / step)) + 1)
    yu = y if uniform else np.interp(tu, t, y)
    nyquist = 0.5 / step
    if band_hz >= nyquist or yu.size < 16:  # nothing above the band is sampled
        return y.copy()
    sos = butter(4, band_hz, fs=1.0 / step, output="sos")
    out = sosfiltfilt(sos, yu)
    return out if uniform else np.interp(t, tu, out)


def response_extrema(y, prominence: float, kind: str = "both"):
    """Indices and types (+1 maximum, -1 minimum) of oscillation peaks, in time order.

    A peak counts if its prominence is at least ``prominence`` (in signal
    units), which keeps measurement noise from adding peaks.
    """
    y = np.asarray(y, dtype=float)
    if kind not in ("both", "max", "min"):
        raise InputError(f"peak kind must be 'both', 'max' or 'min', got '{kind}'", field="kind")
    idx, sign = [], []
    if kind in ("both", "max"):
        i, _ = find_peaks(y, prominence=prominence)
        idx.append(i), sign.append(np.ones(i.size, int))
    if kind in ("both", "min"):
        i, _ = find_peaks(-y, prominence=prominence)
        idx.append(i), sign.append(-np.ones(i.size, int))
    idx, sign = np.concatenate(idx), np.concatenate(sign)
    order = np.argsort(idx, kind="stable")
    return idx[order], sign[order]


def match_peaks(p, m, kind: str = "both", prominence_fraction: float = 0.05,
                max_peaks: int | None = None):
    """Pair the response peaks of ``p`` and ``m`` peak by peak, not in time.

    The k-th maximum of the prediction is paired with the k-th maximum of the
    measurement (minima likewise), as the thesis does because the simulated
    and measured oscillation periods differ (section 5.2). The prominence
    threshold is ``prominence_fraction`` of the measured peak-to-peak range.

    Returns
    -------
    (pred_values, meas_values, pred_index, meas_index) : arrays of the pairs.
    """
    p = np.asarray(p, dtype=float)
    m = np.asarray(m, dtype=float)
    span = float(np.ptp(m)) if m.size else 0.0
    prom = prominence_fraction * span if span > 0 else np.inf
    ip, sp = response_extrema(p, prom, kind)
    im, sm = response_extrema(m, prom, kind)
    pairs_p, pairs_m = [], []
    for s in (1, -1):
        a, b = ip[sp == s], im[sm == s]
        n = min(a.size, b.size) if max_peaks is None else min(a.size, b.size, max_peaks)
        pairs_p.append(a[:n]), pairs_m.append(b[:n])
    a, b = np.concatenate(pairs_p), np.concatenate(pairs_m)
    order = np.argsort(b, kind="stable")
    a, b = a[order], b[order]
    return p[a], m[b], a, b


def response_peak_errors(p, m, kind: str = "both", prominence_fraction: float = 0.05,
                         floor_fraction: float = FLOOR_FRACTION) -> dict:
    """m%RE and RMS error of the matched response peaks (thesis 5.2).

    Returns a dict with ``mRE_peaks_pct``, ``rms_peaks`` and ``n_peaks``; with
    no matched peak it raises InputError (no silent NaN). The %RE floor is
    ``floor_fraction`` of the largest measured magnitude in the response.
    """
    p, m = _pair(p, m, "response")
    pv, mv, _, _ = match_peaks(p, m, kind, prominence_fraction)
    if pv.size == 0:
        raise InputError("no response peaks to compare (the response segment has no "
                         "oscillation above the prominence threshold)")
    floor = relative_error_floor(m, floor_fraction)
    return {"mRE_peaks_pct": mean_relative_error(pv, mv, floor=floor),
            "rms_peaks": rms_error(pv, mv), "n_peaks": int(pv.size)}


def disturbance_errors(p, m, q: float = 80.0, floor_fraction: float = FLOOR_FRACTION) -> dict:
    """The three disturbance metrics of the thesis: m%RE, 80%RE, RMS error."""
    p, m = _pair(p, m, "disturbance")
    floor = relative_error_floor(m, floor_fraction)
    return {"mRE_pct": mean_relative_error(p, m, floor=floor),
            "RE80_pct": relative_error_percentile(p, m, q, floor=floor),
            "rms": rms_error(p, m)}
