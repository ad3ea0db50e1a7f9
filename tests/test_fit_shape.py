"""The carcass [SHAPE] table from the measured contour (thesis 3.3.2, 4.3, Table 4-1).

The models resample a [SHAPE] table to equally spaced points (ADAMS/Tire,
tyrelab.tyre.contact.shape.resample_shape), so the fit is a polyline with
equally spaced knots. Round trip: a contour drawn from such a table comes
back exactly; from Table 4-1's own polyline the fit stays near Table 4-1 and
is closer to that contour than Table 4-1 itself is once the models resample it.
"""

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.fit.shape import fit_carcass_shape, fold_profile, profile_centre, shape_rms
from tyrelab.tyre.contact.shape import resample_shape

R0, HALF = 0.6715, 0.219
#: thesis Table 4-1 (radial, width)
TABLE_4_1 = np.array([[1, 0], [1, 0.137], [1, 0.2557], [0.9956, 0.4566], [0.9854, 0.6621],
                      [0.9665, 0.7763], [0.9417, 0.8676], [0.8834, 0.895], [0.7669, 1]])


def _contour(table, n=147):
    y = np.linspace(-HALF, HALF, n)
    t = np.asarray(table, float)
    return y, np.interp(np.abs(y) / HALF, t[:, 1], t[:, 0]) * R0


def test_a_contour_of_an_equal_step_table_comes_back_exactly():
    truth = np.column_stack([[1.0, 0.999, 0.995, 0.99, 0.98, 0.965, 0.94, 0.9, 0.85, 0.78],
                             np.linspace(0, 1, 10)])
    y, r = _contour(truth)
    fit = fit_carcass_shape(y, r, R0, HALF, points=10)
    assert fit.table == pytest.approx(truth, abs=1e-6)
    assert fit.rms < 1e-6


def test_table_4_1_contour():
    """Within 0.016 of Table 4-1's radius ratios at its own width ratios (11 mm of radius at the
    shoulder bend, which equal steps cannot hold), and closer to its contour (RMS 0.0024) than
    Table 4-1 as the models resample it (0.0046)."""
    y, r = _contour(TABLE_4_1)
    fit = fit_carcass_shape(y, r, R0, HALF)
    t = fit.table
    assert 2 <= t.shape[0] <= 10
    assert t[0, 1] == 0.0 and t[-1, 1] == 1.0 and np.all(np.diff(t[:, 1]) > 0)
    assert np.all((t[:, 0] > 0) & (t[:, 0] <= 1.0))
    at = np.interp(TABLE_4_1[:, 1], t[:, 1], t[:, 0])
    assert np.max(np.abs(at - TABLE_4_1[:, 0])) < 0.02
    prof = fold_profile(y, r, R0, HALF)
    thesis = shape_rms(TABLE_4_1, prof.width_ratio, prof.radius_ratio)   # resampled, as the models
    assert fit.rms < thesis
    assert shape_rms(t, prof.width_ratio, prof.radius_ratio) == pytest.approx(fit.rms, rel=1e-6)
    # the fitted table is already equally spaced: resampling leaves it as it is
    assert resample_shape(t) == pytest.approx(t)


def test_one_half_or_both_and_the_asymmetry():
    y, r = _contour(TABLE_4_1)
    right = y >= 0
    both = fit_carcass_shape(y, r, R0, HALF, points=9)
    one = fit_carcass_shape(y[right], r[right], R0, HALF, points=9)
    assert one.table == pytest.approx(both.table, abs=1e-6)
    assert both.profile.asymmetry == pytest.approx(0.0, abs=1e-12)
    skew = r + np.where(y < 0, 0.002, 0.0)         # the left half 2 mm proud
    assert fold_profile(y, skew, R0, HALF).asymmetry == pytest.approx(0.002 / R0, rel=0.01)


@pytest.mark.parametrize("offset", [HALF, 0.3, -0.5])
def test_a_section_scanned_from_one_side_is_centred_on_its_shoulders(offset):
    """A laser run across the tyre from one sidewall gives y of one sign (0 to 438 mm) with the
    crown in the middle. Read as distances from the centre line, the sidewall became the
    crown: the [SHAPE] came out reversed (0.76 at the centre, 1.0 at the edge). Centred on the
    shoulders' midpoint, it is the centred contour's table; a half from the centre line (crown
    at y = 0) and a centred contour are not moved."""
    y, r = _contour(TABLE_4_1)
    centred = fit_carcass_shape(y, r, R0, HALF, points=8)
    scanned = fit_carcass_shape(y + offset, r, R0, HALF, points=8)
    assert scanned.profile.centre == pytest.approx(offset, abs=1e-9)
    assert scanned.table == pytest.approx(centred.table, abs=1e-9)
    right = y >= 0
    assert profile_centre(y[right], r[right]) == 0.0 and profile_centre(y, r) == 0.0


def test_noise_on_the_contour_degrades_gracefully():
    """1 mm of noise on each radius (0.0015 of R0): the table within 0.002 of the noise-free fit."""
    y, r = _contour(TABLE_4_1, n=301)
    clean = fit_carcass_shape(y, r, R0, HALF, points=8)
    noisy = fit_carcass_shape(y, r + np.random.default_rng(1).normal(0, 0.001, r.size), R0, HALF, points=8)
    assert noisy.table == pytest.approx(clean.table, abs=0.002)


def test_bad_profiles_are_refused():
    with pytest.raises(InputError, match="at least 3"):
        fit_carcass_shape([0.0, 0.1], [0.6, 0.6])
    with pytest.raises(InputError, match="2 to 10"):
        fit_carcass_shape(*_contour(TABLE_4_1), R0, HALF, points=12)
