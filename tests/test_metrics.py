"""Validation metrics on hand-made signals with known answers."""

import math

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.validate import (band_rms, compare_psd, cycles, fit_normal, match_peaks,
                              mean_relative_error, normal_fit_errors, peak_load_errors,
                              percent_error, pseudo_damage, psd, relative_error,
                              relative_error_percentile, response_peak_errors, rms_error,
                              russell, sprague_geers)
from tyrelab.signal import make_signal
from tyrelab.validate.compare import compare_runs
from tyrelab.validate.fatigue import peak_exceedances
from tyrelab.validate.metrics import RESPONSE_BAND_HZ, oscillation
from tyrelab.validate.segments import Segments


def test_rms_error_eq_5_1():
    assert rms_error([1, 2, 3], [1, 2, 5]) == pytest.approx(math.sqrt(4 / 3))
    assert rms_error([5, 5], [5, 5]) == 0.0


def test_relative_error_eq_5_2_and_mean():
    re = relative_error([110, 90, 100], [100, 100, 100])
    np.testing.assert_allclose(re, [10, 10, 0])
    assert mean_relative_error([110, 90, 100], [100, 100, 100]) == pytest.approx(20 / 3)


def test_re80_is_empirical_quantile():
    m = np.full(10, 100.0)
    p = m + np.arange(1, 11)  # errors 1 ... 10 %
    assert relative_error_percentile(p, m) == pytest.approx(8.0)
    assert relative_error_percentile(p, m, q=100) == pytest.approx(10.0)


def test_near_zero_rule_uses_one_percent_of_peak():
    # floor = 1 % of max|m| = 1 N: error 0.5 N at m = 0 counts as 50 %
    re = relative_error([100.0, 0.5, 2.0], [100.0, 0.0, -0.5])
    np.testing.assert_allclose(re, [0.0, 50.0, 250.0])
    assert np.all(np.isfinite(re))
    # explicit floor fraction
    np.testing.assert_allclose(relative_error([0.5], [0.0], floor=0.25), [200.0])
    with pytest.raises(InputError, match="every measured value is zero"):
        relative_error([1.0, 2.0], [0.0, 0.0])
    with pytest.raises(InputError):
        relative_error([1.0, np.nan], [1.0, 1.0])
    with pytest.raises(InputError):
        relative_error([1.0], [1.0, 2.0])


def test_percent_error_eq_5_4_signed_and_floored():
    assert percent_error(110, 100) == pytest.approx(10)
    assert percent_error(90, 100) == pytest.approx(-10)
    assert percent_error(1.0, 0.0, floor=2.0) == pytest.approx(50.0)
    assert percent_error(-3.0, -1.0, floor=2.0) == pytest.approx(100.0)  # (-3 - -1) / -2
    with pytest.raises(InputError, match="zero"):
        percent_error(1.0, 0.0)


def test_response_peaks_matched_peak_by_peak_not_in_time():
    t = np.arange(0, 2.0, 1e-3)
    m = 30e3 + 5e3 * np.sin(2 * np.pi * 2.0 * t)     # 4 maxima 35 kN, 4 minima 25 kN
    p = 30e3 + 5.5e3 * np.sin(2 * np.pi * 2.5 * t)   # other period, 35.5 / 24.5 kN
    pv, mv, _, _ = match_peaks(p, m)
    assert pv.size == 8
    res = response_peak_errors(p, m)
    assert res["n_peaks"] == 8
    assert res["rms_peaks"] == pytest.approx(500.0, rel=1e-9)
    expected = 0.5 * (500 / 35e3 + 500 / 25e3) * 100
    assert res["mRE_peaks_pct"] == pytest.approx(expected, rel=1e-9)
    # a point-by-point comparison would be far worse
    assert mean_relative_error(p, m) > 5 * expected


def test_the_oscillation_band_keeps_the_trailer_and_drops_the_belt():
    """A 4th-order Butterworth run forward and back has the gain 1 / (1 + (f/fc)^8): at
    the trailer's 3.3 Hz 0.99986 of the amplitude stays, of a 40 Hz belt ring 1.5e-5."""
    t = np.arange(0.0, 6.0, 1e-3)
    mid = (t > 2.0) & (t < 4.0)   # away from the ends
    for f, gain in ((3.3, 1 / (1 + (3.3 / 10) ** 8)), (40.0, 1 / (1 + 4.0 ** 8))):
        x = np.sin(2 * np.pi * f * t)
        y = oscillation(t, x, RESPONSE_BAND_HZ)   # zero phase: the same sine, scaled
        np.testing.assert_allclose(y[mid], gain * x[mid], atol=2e-5)
    # a non-uniform time base: filtered on a uniform one and interpolated back
    tn = np.sort(np.concatenate([t[::2], t[1::4] + 1e-4]))
    yn = oscillation(tn, np.sin(2 * np.pi * 3.3 * tn))
    np.testing.assert_allclose(yn[(tn > 2) & (tn < 4)], np.sin(2 * np.pi * 3.3 * tn[(tn > 2) & (tn < 4)]),
                               atol=2e-3)


def test_response_peaks_are_the_oscillations_not_the_belts_ringing():
    """The reference rings at 40 Hz (3 kN) on the trailer's 3.3 Hz oscillation; a model
    with the same oscillation and no ring has (nearly) no response error by the thesis's
    peaks of the oscillatory response, but every ring wiggle is a peak of the raw signal."""
    t = np.arange(0.0, 4.0, 1e-3)
    trailer = 23e3 + 12e3 * np.exp(-0.6 * t) * np.cos(2 * np.pi * 3.3 * t)
    ring = 3e3 * np.exp(-1.5 * t) * np.sin(2 * np.pi * 40 * t)
    seg = Segments((0.0, 0.2), (0.2, 4.0))
    model = make_signal({"RUNTIME": t, "FZ": trailer})
    reference = make_signal({"RUNTIME": t, "FZ": trailer + ring})
    banded = compare_runs(model, reference, segments=seg)
    raw = compare_runs(model, reference, segments=seg, response_band_hz=None)
    assert banded["mRE_response_pct"] < 0.5
    assert banded["details"]["n_response_peaks"] == 2 * 12      # 12 periods of 3.3 Hz in 3.8 s
    # raw, the reference's first maxima are ring wiggles, paired with the model's trailer
    # maxima in order: the pairs drift apart in time and in value
    assert raw["mRE_response_pct"] > 20 * banded["mRE_response_pct"]


def test_response_without_peaks_raises():
    with pytest.raises(InputError, match="no response peaks"):
        response_peak_errors(np.linspace(0, 1, 50), np.linspace(0, 1, 50) + 1)


def test_sprague_geers_and_russell_known_values():
    t = np.arange(4000) / 1000.0                     # 4 whole periods of 1 Hz
    m = np.sin(2 * np.pi * t)
    sg = sprague_geers(2 * m, m)
    assert sg["SG_M"] == pytest.approx(1.0) and sg["SG_P"] == pytest.approx(0.0, abs=1e-7)
    assert sg["SG_C"] == pytest.approx(1.0)
    quarter = sprague_geers(np.cos(2 * np.pi * t), m)
    assert quarter["SG_M"] == pytest.approx(0.0, abs=1e-12)
    assert quarter["SG_P"] == pytest.approx(0.5, abs=1e-9)
    assert sprague_geers(-m, m)["SG_P"] == pytest.approx(1.0)
    r = russell(2 * m, m)
    assert r["R_M"] == pytest.approx(math.log10(2.5))
    assert r["R_C"] == pytest.approx(math.sqrt(math.pi / 4) * math.log10(2.5), abs=1e-7)
    assert russell(0.5 * m, m)["R_M"] == pytest.approx(-math.log10(2.5))
    # baseline removal: a static load does not hide the dynamic error
    assert sprague_geers(30 + 2 * m, 30 + m, baseline=30.0)["SG_M"] == pytest.approx(1.0)
    with pytest.raises(InputError):
        sprague_geers(m, np.zeros_like(m))


def test_psd_band_rms_and_log_spectral_distance():
    fs = 1000.0
    t = np.arange(10000) / fs
    m = 3.0 * np.sin(2 * np.pi * 12.0 * t)
    f, pxx = psd(m, fs, segment_seconds=2.0)
    assert band_rms(f, pxx) == pytest.approx(3.0 / math.sqrt(2), rel=0.01)
    rng = np.random.default_rng(1)
    noise = rng.standard_normal(t.size)
    res = compare_psd(2 * noise, noise, fs, bands=((0, 100), (0, np.inf)), segment_seconds=1.0)
    assert res["0-100Hz"]["lsd_db"] == pytest.approx(10 * math.log10(4), rel=1e-9)
    assert res["0-infHz"]["rms_error_pct"] == pytest.approx(100.0, rel=1e-9)
    sine = compare_psd(m, m, fs, segment_seconds=2.0)
    assert sine["peak_freq_meas"] == pytest.approx(12.0)


def test_rainflow_damage_hand_counted():
    # ASTM E1049 by hand: full cycle of range 2; half cycles of 4, 6, 4, 2
    y = [0, 3, 1, 4, -2, 2, 0]
    c = cycles(y)
    assert sorted(map(tuple, c[:, [0, 2]].tolist())) == [(2, 0.5), (2, 1.0), (4, 0.5),
                                                          (4, 0.5), (6, 0.5)]
    assert pseudo_damage(y, slope=1) == pytest.approx(2 + 0.5 * (4 + 6 + 4 + 2))
    assert pseudo_damage(y, slope=2) == pytest.approx(4 + 0.5 * (16 + 36 + 16 + 4))
    assert pseudo_damage(2 * np.asarray(y), slope=5) == pytest.approx(32 * pseudo_damage(y))


def test_peak_loads_and_damage_ratio():
    assert peak_exceedances([0, 2, 0, 3, 0, 1], 1.5) == 2
    t = np.arange(2000) / 100.0
    m = 30e3 + 5e3 * np.sin(2 * np.pi * t)
    res = peak_load_errors(30e3 + 1.1 * (m - 30e3), m, slope=5.0)
    assert res["damage_ratio"] == pytest.approx(1.1 ** 5, rel=1e-9)
    assert res["max_error_pct"] == pytest.approx(500 / 35e3 * 100, rel=1e-6)
    assert res["eq_range_error_pct"] == pytest.approx(10.0, rel=1e-9)


def test_normal_fit_errors_eq_5_4():
    assert fit_normal([1, 2, 3, 4]) == pytest.approx((2.5, math.sqrt(1.25)))
    rng = np.random.default_rng(2)
    m = 30e3 + 4e3 * rng.standard_normal(5000)
    p = np.mean(m) + 1.5 * (m - np.mean(m))
    res = normal_fit_errors(p, m)
    assert res["mean_error_pct"] == pytest.approx(0.0, abs=1e-9)
    assert res["std_error_pct"] == pytest.approx(50.0, rel=1e-9)
    assert res["ks_meas"] < 0.03          # a normal sample is close to its fit
    u = normal_fit_errors(rng.uniform(0, 1, 5000), rng.uniform(0, 1, 5000))
    assert u["ks_pred"] > 0.05             # a uniform sample is not


def test_rainflow_from_the_reversals_counts_what_rainflow_counts_from_every_sample():
    """cycles() hands rainflow only the signal's reversal values (its own search is a Python
    loop over every sample); the cycles must be exactly those rainflow finds in the whole
    signal (the library run directly is the reference): plateaus, repeated first and last
    values, monotone and constant signals, two and three samples, and a long rough one."""
    import rainflow

    def direct(y):
        rows = [(r, m, c) for r, m, c, _, _ in rainflow.extract_cycles(np.asarray(y, float))]
        return np.array(rows, dtype=float).reshape(-1, 3)

    rng = np.random.default_rng(7)
    signals = [[1, 1, 1], [1, 2], [2, 2], [0, 1, 2, 3], [3, 3, 2, 2, 1], [1, 1, 2, 1],
               [0, 2, 1, 1], [0, 2, 0, 0], [5, 5, 5, 4, 5, 5], [0, 3, 1, 4, -2, 2, 0]]
    for n in range(2, 40):
        signals.append(rng.integers(0, 3, n))                       # many plateaus and ties
        signals.append(np.cumsum(rng.integers(-1, 2, n)))           # steps of -1, 0, +1
        signals.append(np.round(rng.standard_normal(n), 1))
    signals.append(np.round(30e3 + 4e3 * np.cumsum(rng.standard_normal(20000)) / 50, 0))
    for y in signals:
        expected = direct(y)
        got = cycles(y)
        assert got.shape == expected.shape and np.array_equal(got, expected), y


def test_ks_distance_is_scipys_statistic():
    """The KS distance to the fitted normal, computed without scipy's p-value, is the
    statistic scipy.stats.kstest returns, to the last bit (ties, skewed and tiny samples)."""
    from scipy import stats

    from tyrelab.validate.distributions import ks_distance

    rng = np.random.default_rng(3)
    samples = [rng.standard_normal(5000), rng.exponential(2.0, 3000), rng.integers(0, 5, 400),
               np.array([1.0, 2.0]), 30e3 + 4e3 * rng.standard_normal(126000)]
    for x in samples:
        x = np.asarray(x, dtype=float)
        mu, sigma = fit_normal(x)
        assert ks_distance(x, mu, sigma) == stats.kstest(x, "norm", args=(mu, sigma)).statistic
