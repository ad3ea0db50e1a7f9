"""Compare a simulated run with a measured one: all metrics in one call.

:func:`compare_runs` aligns the simulation onto the measurement's time base
(:mod:`.align`), splits the record into disturbance and response
(:mod:`.segments`) when asked, and computes

* the thesis metrics (chapter 5): m%RE, 80%RE and RMS error of the
  disturbance, m%RE and RMS error of the matched peaks of the response's
  oscillation (:mod:`.metrics`, *The peaks of the oscillatory response*), μ%err and
  σ%err of normal fits (over the whole compared record);
* the additional ones: Sprague-Geers and Russell magnitude/phase/combined
  errors of the dynamic part (both signals taken about the measured mean;
  over the disturbance when the record is segmented, else over the whole
  record), and over the whole record a PSD comparison (uniform measured
  time step only), extremes, peak-load counts and rainflow pseudo-damage.

:func:`repeatability` applies the same metrics to two measurements of one
test (thesis Table 5-1); :func:`beside_repeatability` puts a model's metrics
next to that scatter.

Flat metric names (columns of the tables) are listed in :data:`METRICS` with
their unit and whether lower is better.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..errors import InputError
from .align import Aligned, align
from .comprehensive import russell, sprague_geers
from .distributions import normal_fit_errors
from .fatigue import DEFAULT_SLOPE, peak_load_errors
from .metrics import (FLOOR_FRACTION, RESPONSE_BAND_HZ, disturbance_errors, oscillation,
                      response_peak_errors)
from .segments import Segments, segments_from_signal
from .spectra import compare_psd, sample_rate

#: metric -> (unit, description). All are "lower |value| is better".
METRICS: dict[str, tuple[str, str]] = {
    "mRE_disturbance_pct": ("%", "mean % relative error of the disturbance (eq. 5.2)"),
    "RE80_disturbance_pct": ("%", "80 % relative error of the disturbance"),
    "rms_disturbance_N": ("N", "RMS error of the disturbance (eq. 5.1)"),
    "mRE_response_pct": ("%", "mean % relative error of the matched response peaks"),
    "rms_response_N": ("N", "RMS error of the matched response peaks"),
    "mean_error_pct": ("%", "normal-fit mean % error (eq. 5.4)"),
    "std_error_pct": ("%", "normal-fit standard-deviation % error (eq. 5.4)"),
    "SG_M": ("-", "Sprague-Geers magnitude error"),
    "SG_P": ("-", "Sprague-Geers phase error"),
    "SG_C": ("-", "Sprague-Geers combined error"),
    "R_C": ("-", "Russell combined error"),
    "psd_rms_error_pct": ("%", "% error of the dynamic RMS from the PSD"),
    "psd_lsd_dB": ("dB", "log-spectral distance"),
    "max_error_pct": ("%", "% error of the peak load"),
    "damage_ratio_log10": ("-", "log10 of the pseudo-damage ratio (0 = equal)"),
}

THESIS_CLEAT = ["mRE_disturbance_pct", "RE80_disturbance_pct", "rms_disturbance_N",
                "mRE_response_pct", "rms_response_N"]
THESIS_TRACK = ["mean_error_pct", "std_error_pct"]


def resolve_segments(aligned: Aligned, segments) -> Segments | None:
    """``None`` (no split), ``"auto"`` (from the measured signal) or a Segments."""
    if segments is None or isinstance(segments, Segments):
        return segments
    if segments == "auto":
        return segments_from_signal(aligned.t, aligned.m)
    raise InputError(f"segments must be 'auto', none or a Segments, got '{segments}'",
                     field="segments")


def _cut(aligned: Aligned, seg: Segments, which: str):
    sel = seg.mask(aligned.t, which)
    if sel.sum() < 2:
        raise InputError(f"the {which} segment {getattr(seg, which)} s holds fewer than "
                         "two compared samples", field="segments")
    return aligned.t[sel], aligned.p[sel], aligned.m[sel]


def response_signals(aligned: Aligned, seg: Segments,
                     band_hz: float | None = RESPONSE_BAND_HZ):
    """``(p, m)`` of the response segment whose peaks are compared: its oscillation below
    ``band_hz`` (:func:`.metrics.oscillation` of the response alone, so that nothing of
    the disturbance leaks into it); ``band_hz`` None: the raw samples."""
    t, p, m = _cut(aligned, seg, "response")
    if band_hz is not None:
        p, m = oscillation(t, p, band_hz), oscillation(t, m, band_hz)
    return p, m


def compare_aligned(aligned: Aligned, segments=None, slope: float = DEFAULT_SLOPE,
                    floor_fraction: float = FLOOR_FRACTION, peak_kind: str = "both",
                    response_band_hz: float | None = RESPONSE_BAND_HZ) -> dict:
    """All metrics for an aligned pair; see the module docstring.

    ``response_band_hz``: the response's peaks are those of the oscillation below this
    frequency (:data:`.metrics.RESPONSE_BAND_HZ`, thesis 5.2; None: of the raw signal).
    Returns a dict of flat scalar metrics (keys of :data:`METRICS`, where
    they apply) plus ``"details"`` with the sub-results.
    """
    seg = resolve_segments(aligned, segments)
    t, p, m = aligned.t, aligned.p, aligned.m
    out: dict = {}
    details: dict = {"shift_s": aligned.shift, "dropped": aligned.dropped,
                     "channel": aligned.channel, "segments": seg}
    if seg is not None:
        _, pd_, md_ = _cut(aligned, seg, "disturbance")
        dist = disturbance_errors(pd_, md_, floor_fraction=floor_fraction)
        pr, mr = response_signals(aligned, seg, response_band_hz)
        resp = response_peak_errors(pr, mr, kind=peak_kind, floor_fraction=floor_fraction)
        out.update({"mRE_disturbance_pct": dist["mRE_pct"], "RE80_disturbance_pct":
                    dist["RE80_pct"], "rms_disturbance_N": dist["rms"],
                    "mRE_response_pct": resp["mRE_peaks_pct"],
                    "rms_response_N": resp["rms_peaks"]})
        details["n_response_peaks"] = resp["n_peaks"]
        p_dyn, m_dyn = pd_, md_
    else:
        p_dyn, m_dyn = p, m
    nf = normal_fit_errors(p, m, floor_fraction)
    out.update({"mean_error_pct": nf["mean_error_pct"], "std_error_pct": nf["std_error_pct"]})
    details["normal_fit"] = nf
    sg = sprague_geers(p_dyn, m_dyn, baseline=float(np.mean(m_dyn)))
    out.update(sg)
    out["R_C"] = russell(p_dyn, m_dyn, baseline=float(np.mean(m_dyn)))["R_C"]
    try:
        fs = sample_rate(t)
    except InputError:
        fs = None  # non-uniform measured time base: no PSD
        details["psd_skipped"] = (
            f"{aligned.dropped} measured samples are missing (NaN), so the compared ones are not "
            "evenly spaced" if aligned.dropped else "the measured time step is not uniform")
    if fs is not None:
        spec = compare_psd(p, m, fs, segment_seconds=min(t[-1] - t[0], 2.0))
        band = spec["0-infHz"]
        out.update({"psd_rms_error_pct": band["rms_error_pct"], "psd_lsd_dB": band["lsd_db"]})
        details["psd"] = spec
    peaks = peak_load_errors(p, m, slope=slope)
    out.update({"max_error_pct": peaks["max_error_pct"],
                "damage_ratio_log10": float(np.log10(peaks["damage_ratio"]))
                if peaks["damage_ratio"] > 0 else -np.inf})
    if not np.isfinite(out["damage_ratio_log10"]):
        raise InputError("the prediction has no load cycles: damage ratio is zero")
    details["peak_loads"] = peaks
    out["details"] = details
    return out


def compare_runs(sim: pd.DataFrame, meas: pd.DataFrame, channel: str = "FZ",
                 segments=None, shift: float | str = 0.0, max_shift: float | None = None,
                 **kw) -> dict:
    """Align ``sim`` onto ``meas`` and compute every metric (:func:`compare_aligned`)."""
    return compare_aligned(align(sim, meas, channel, shift, max_shift), segments, **kw)


def repeatability(meas_a: pd.DataFrame, meas_b: pd.DataFrame, **kw) -> dict:
    """The measurement's own scatter: run ``meas_a`` compared as if it were a model
    against ``meas_b`` (thesis Table 5-1); same options as :func:`compare_runs`."""
    return compare_runs(meas_a, meas_b, **kw)


def metric_row(result: dict, metrics=None) -> dict:
    """The scalar metrics of a result, in :data:`METRICS` order."""
    names = metrics or [k for k in METRICS if k in result]
    return {k: result[k] for k in names if k in result}


def beside_repeatability(model: dict, scatter: dict, name: str = "model") -> pd.DataFrame:
    """A model's metrics beside the measurement scatter and their ratio.

    Rows: ``name``, ``"measured repeatability"``, ``"ratio"`` (|model| /
    |scatter|). Where the scatter is zero there is no ratio: the cell holds
    the text ``"scatter is zero"`` (never inf or NaN).
    """
    a, b = metric_row(model), metric_row(scatter)
    cols = [k for k in a if k in b]
    ratio = {}
    for k in cols:
        num, den = abs(a[k]), abs(b[k])
        ratio[k] = num / den if den > 0 else "scatter is zero"
    return pd.DataFrame([{k: a[k] for k in cols}, {k: b[k] for k in cols}, ratio],
                        index=[name, "measured repeatability", "ratio"])
