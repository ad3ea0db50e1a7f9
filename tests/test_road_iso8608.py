"""ISO 8608 random roads: class values from the standard, spectra, seeds, 3D coherence."""

import numpy as np
import pytest
from scipy import integrate, signal

from tyrelab.errors import InputError
from tyrelab.road.iso8608 import (RandomRoad, angular_psd_at_omega0, gd_at_n0, iso8608_profile,
                                  iso8608_surface, iso_class, power_law)
from tyrelab.road.spectrum import fit_power_law

# ISO 8608:1995 table 1, geometric mean of each class, spatial frequency form (n0 = 0.1 cycles/m)
ISO_GD_N0 = dict(zip("ABCDEFGH", [16e-6, 64e-6, 256e-6, 1024e-6, 4096e-6, 16384e-6, 65536e-6, 262144e-6]))
# ... and the angular spatial frequency form (Omega0 = 1 rad/m)
ISO_PHI_OMEGA0 = dict(zip("ABCDEFGH", [1e-6, 4e-6, 16e-6, 64e-6, 256e-6, 1024e-6, 4096e-6, 16384e-6]))
THESIS = {"belgian paving": (3.48e-5, 1.6), "fatigue track": (3.42e-5, 2.9)}  # eq. 3.8, section 3.4.3


@pytest.mark.parametrize("cls", "ABCDEFGH")
def test_class_values_are_the_iso_table(cls):
    a, n = power_law(cls)
    assert n == 2.0
    assert gd_at_n0(a, n) == pytest.approx(ISO_GD_N0[cls], rel=1e-12)
    # the angular form of the standard is rounded to one digit: 1.006e-6 for class A
    assert angular_psd_at_omega0(a, n) == pytest.approx(ISO_PHI_OMEGA0[cls], rel=0.01)
    assert iso_class(a, n) == cls
    # the class limits are a factor 2 either side of the mean
    assert iso_class(a * 1.9, n) == cls and iso_class(a / 1.9, n) == cls


def test_thesis_tracks_fall_in_plausible_classes():
    # Gd(n0) of belgian paving 1.39e-3 m^3 (class D), fatigue track 2.72e-2 m^3 (class F)
    assert iso_class(*THESIS["belgian paving"]) == "D"
    assert iso_class(*THESIS["fatigue track"]) == "F"


@pytest.mark.parametrize("spec", ["C", (3.48e-5, 1.6), (3.42e-5, 2.9)])
def test_profile_variance_is_the_integral_of_the_spectrum(spec):
    a, n = power_law(spec)
    expected, _ = integrate.quad(lambda f: a * f ** -n, 0.05, 10.0, limit=200)
    var = np.mean([np.var(iso8608_profile(spec, 2000.0, 0.01, seed)[1]) for seed in range(4)])
    assert var == pytest.approx(expected, rel=0.03)


@pytest.mark.parametrize("cls", ["B", "C", "E"])
def test_synthesised_class_fits_back_to_the_iso_values(cls):
    fits = np.array([fit_power_law(iso8608_profile(cls, 1000.0, 0.01, seed)) for seed in range(8)])
    a, n = fits.mean(axis=0)
    assert gd_at_n0(a, n) == pytest.approx(ISO_GD_N0[cls], rel=0.05)
    assert n == pytest.approx(2.0, abs=0.05)
    assert iso_class(a, n) == cls


def test_profile_has_no_power_outside_the_band():
    x, z = iso8608_profile("D", 500.0, 0.01, seed=1)
    f, s = signal.welch(z, fs=100.0, nperseg=16384)
    inside = s[(f > 1) & (f < 9)].mean()
    assert s[f > 12].max() < 1e-4 * inside


def test_same_seed_same_road_other_seed_other_road():
    z1 = iso8608_profile("C", 50.0, 0.01, seed=7)[1]
    z2 = iso8608_profile("C", 50.0, 0.01, seed=7)[1]
    z3 = iso8608_profile("C", 50.0, 0.01, seed=8)[1]
    assert np.array_equal(z1, z2) and not np.allclose(z1, z3)
    s1 = iso8608_surface("C", 20.0, 1.0, (0.02, 0.02), seed=3)
    assert np.array_equal(s1, iso8608_surface("C", 20.0, 1.0, (0.02, 0.02), seed=3))


@pytest.mark.parametrize("spec", list(THESIS.values()), ids=list(THESIS))
def test_surface_profiles_have_the_target_spectrum(spec):
    fits = []
    for seed in range(6):
        road = RandomRoad(spec, length=1000.0, width=0.4, spacing=(0.02, 0.02), seed=seed)
        fits.append(fit_power_law(road, y=0.0))
    a, n = np.mean(fits, axis=0)
    assert a == pytest.approx(spec[0], rel=0.05)
    assert n == pytest.approx(spec[1], abs=0.05)


def _isotropic_coherence(f, d, w, f_max=10.0):
    """Real coherence of two profiles d apart on an isotropic surface with S2 ~ |k|^-(w+1)."""
    t_max = np.sqrt(max(f_max ** 2 / f ** 2 - 1.0, 0.0))
    dens = lambda t: (1 + t * t) ** (-(w + 1) / 2)  # noqa: E731
    num, _ = integrate.quad(lambda t: dens(t) * np.cos(2 * np.pi * f * d * t), 0, t_max, limit=400)
    den, _ = integrate.quad(dens, 0, t_max, limit=400)
    return num / den


@pytest.mark.parametrize("d", [0.1, 0.3])
def test_parallel_tracks_have_isotropic_coherence(d):
    w = 2.0
    sxy, sxx, syy = 0.0, 0.0, 0.0
    for seed in range(4):
        z = iso8608_surface("C", 400.0, 0.4, (0.01, 0.01), seed=seed)
        j = int(round(d / 0.01))
        f, pxy = signal.csd(z[:, 0], z[:, j], fs=100.0, nperseg=8000)
        sxy = sxy + pxy
        sxx = sxx + signal.welch(z[:, 0], fs=100.0, nperseg=8000)[1]
        syy = syy + signal.welch(z[:, j], fs=100.0, nperseg=8000)[1]
    rho = np.real(sxy) / np.sqrt(sxx * syy)
    for lo, hi in [(0.3, 0.6), (1.0, 2.0), (2.0, 4.0)]:
        sel = (f >= lo) & (f <= hi)
        fc = np.sqrt(lo * hi)
        assert rho[sel].mean() == pytest.approx(_isotropic_coherence(fc, d, w), abs=0.1)


def test_random_road_is_a_road_with_a_finite_grid():
    road = RandomRoad("D", length=20.0, width=2.0, seed=2, start=5.0, taper=1.0)
    xmin, xmax, ymin, ymax = road.extent()
    assert (xmin, ymin, ymax) == (5.0, -1.0, 1.0) and xmax == pytest.approx(25.0)
    g = road.grid()
    assert np.all(np.isfinite(g.z)) and g.z.shape == (2001, 201)
    assert road.height(5.0, 0.3) == pytest.approx(0.0, abs=1e-12)  # tapered to zero at the start
    profile = RandomRoad("D", length=20.0, width=None, seed=2)
    assert not profile.varies_in_y()
    assert profile.height(3.0, -1.0) == pytest.approx(profile.height(3.0, 1.7))


@pytest.mark.parametrize("bad", ["Z", (0.0, 2.0), (1e-5, -1.0), "x"])
def test_bad_class_is_an_input_error(bad):
    with pytest.raises(InputError):
        power_law(bad)
