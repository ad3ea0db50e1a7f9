"""Displacement spectral density (Welch) and the power-law fit of eq. 3.8."""

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.road.iso8608 import RandomRoad, iso8608_profile
from tyrelab.road.spectrum import displacement_spectral_density, fit_power_law, road_profile

THESIS = [(3.48e-5, 1.6), (3.42e-5, 2.9)]


def test_sinusoid_power_is_half_the_amplitude_squared():
    # one-sided density: a sine of amplitude a holds variance a^2/2 at its frequency
    dx, a, f0 = 0.01, 0.025, 1 / 0.76
    x = dx * np.arange(40001)
    phi, s = displacement_spectral_density((x, a * np.sin(2 * np.pi * f0 * x)))
    near = np.abs(phi - f0) < 0.1
    assert np.sum(s[near]) * (phi[1] - phi[0]) == pytest.approx(a * a / 2, rel=0.01)
    assert phi[np.argmax(s)] == pytest.approx(f0, abs=phi[1] - phi[0])


def test_white_noise_level_is_two_sigma_squared_dx():
    dx, sigma = 0.02, 0.003
    z = np.random.default_rng(0).normal(0, sigma, 200_000)
    phi, s = displacement_spectral_density(z, spacing=dx)
    assert np.mean(s[(phi > 1) & (phi < 20)]) == pytest.approx(2 * sigma ** 2 * dx, rel=0.02)


def test_fit_of_an_exact_power_law_is_exact():
    phi = np.linspace(0.01, 20, 5000)
    a, n = fit_power_law(phi, 3.48e-5 * phi ** -1.6)
    assert a == pytest.approx(3.48e-5, rel=1e-5) and n == pytest.approx(1.6, abs=1e-5)


@pytest.mark.parametrize("a, n", THESIS + [(2.56e-6, 2.0), (1e-6, 3.0)])
def test_synthesised_roads_come_back_within_5_percent(a, n):
    fits = np.array([fit_power_law(iso8608_profile((a, n), 1000.0, 0.01, seed)) for seed in range(8)])
    a_fit, n_fit = fits.mean(axis=0)
    assert a_fit == pytest.approx(a, rel=0.05)
    assert n_fit == pytest.approx(n, abs=0.05)


@pytest.mark.parametrize("a, n", THESIS)
def test_100_m_tracks_come_back_on_average(a, n):
    # the thesis's tracks are 100 m long: one periodogram each, so average more seeds
    fits = np.array([fit_power_law(iso8608_profile((a, n), 100.0, 0.01, seed)) for seed in range(40)])
    a_fit, n_fit = fits.mean(axis=0)
    assert a_fit == pytest.approx(a, rel=0.05)
    assert n_fit == pytest.approx(n, abs=0.05)


def test_road_and_its_profile_give_the_same_spectrum():
    road = RandomRoad((3.48e-5, 1.6), length=100.0, width=None, seed=4)
    x, z = road_profile(road)
    assert x[1] - x[0] == pytest.approx(0.01)
    phi1, s1 = displacement_spectral_density(road)
    phi2, s2 = displacement_spectral_density((x, z))
    assert np.allclose(phi1, phi2) and np.allclose(s1, s2)


def test_several_lines_of_a_3d_road_average():
    road = RandomRoad("C", length=100.0, width=1.0, spacing=(0.02, 0.02), seed=4)
    phi, s_many = displacement_spectral_density(road, lines=5)
    _, s_one = displacement_spectral_density(road, y=0.0)
    assert phi.shape == s_many.shape and not np.allclose(s_many, s_one)


@pytest.mark.parametrize("data, kwargs", [
    (np.zeros(100), {}),                                  # no spacing
    ((np.arange(5.0), np.zeros(5)), {}),                  # too short
    (np.r_[np.zeros(50), np.nan, np.zeros(50)], {"spacing": 0.01}),
])
def test_bad_profiles_are_input_errors(data, kwargs):
    with pytest.raises(InputError):
        displacement_spectral_density(data, **kwargs)


def test_band_without_lines_is_an_input_error():
    x, z = iso8608_profile("C", 10.0, 0.01, seed=0)
    with pytest.raises(InputError):
        fit_power_law((x, z), band=(0.01, 0.02))
