"""Pacejka '89 handling forces (Bakker, Nyborg & Pacejka 1989; ADAMS PAC89 coefficients).

Expected values are computed here by hand from the published formula and
the HMMWV coefficients of tests/data/tir/HMMWV_Pac89Tire.json (read
independently of the package's .tir writer), in the PAC89 units (Fz kN,
alpha deg, kappa %), then converted to the W-axis as documented: Fy and Mz
change sign, Fx does not.
"""

import json
import math
import re
from importlib import resources

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.tyre.handling.pac89 import Pac89Params, pac89_forces, pac89_params
from tyrelab.tyre.library import load_tyre


@pytest.fixture(scope="module")
def coeffs(data_dir):
    text = (data_dir / "tir" / "HMMWV_Pac89Tire.json").read_text()
    js = json.loads(re.sub(r"//[^\n]*", "", text))
    a = [js["Lateral Coefficients"][f"a{i}"] for i in range(14)]
    b = [js["Longitudinal Coefficients"][f"b{i}"] for i in range(11)]
    c = [js["Aligning Coefficients"][f"c{i}"] for i in range(18)]
    return a, b, c


@pytest.fixture(scope="module")
def hmmwv():
    with resources.as_file(resources.files("tyrelab.tyre").joinpath("data", "hmmwv-pac89.tir")) as p:
        return load_tyre(p)


@pytest.fixture(scope="module")
def hp(hmmwv):
    return pac89_params(hmmwv)


def mf(x, b, c, d, e):
    return d * math.sin(c * math.atan(b * x - e * (b * x - math.atan(b * x))))


def test_the_shipped_file_carries_the_json_coefficients(hp, coeffs):
    a, b, c = coeffs
    np.testing.assert_array_equal(np.r_[hp.lateral, hp.longitudinal, hp.aligning], np.r_[a, b, c])


@pytest.mark.parametrize("fz_kn,alpha_deg", [(4.0, 1.0), (8.0, -3.0), (12.0, 6.0), (6.5, 0.3)])
def test_lateral_force_and_aligning_moment_by_hand(hp, coeffs, fz_kn, alpha_deg):
    a, _, c = coeffs
    # lateral (camber 0: Sh = a9 Fz + a10, Sv = a12 Fz + a13, all zero for this tyre)
    C = a[0]
    D = (a[1] * fz_kn + a[2]) * fz_kn
    B = a[3] * math.sin(2 * math.atan(fz_kn / a[4])) / (C * D)
    E = a[6] * fz_kn + a[7]
    fy = mf(alpha_deg, B, C, D, E)
    # aligning
    Cz = c[0]
    Dz = c[1] * fz_kn ** 2 + c[2] * fz_kn
    Bz = (c[3] * fz_kn ** 2 + c[4] * fz_kn) / (Cz * Dz)
    Ez = c[7] * fz_kn ** 2 + c[8] * fz_kn + c[9]
    mz = mf(alpha_deg, Bz, Cz, Dz, Ez)
    fx_w, fy_w, mz_w = pac89_forces(hp, fz_kn * 1e3, 0.0, math.radians(alpha_deg), 0.0)
    assert fy_w == pytest.approx(-fy, rel=1e-12)
    assert mz_w == pytest.approx(-mz, rel=1e-12)
    assert fx_w == pytest.approx(0.0, abs=1e-9)
    # physical sense in the W-axis: sliding left (alpha > 0) -> pushed right, trail behind
    assert np.sign(fy_w) == -np.sign(alpha_deg)
    assert np.sign(mz_w) == np.sign(alpha_deg)


@pytest.mark.parametrize("fz_kn,kappa", [(4.0, 0.02), (8.0, -0.1), (12.0, 0.25)])
def test_longitudinal_force_by_hand(hp, coeffs, fz_kn, kappa):
    _, b, _ = coeffs
    C = b[0]
    D = (b[1] * fz_kn + b[2]) * fz_kn
    B = (b[3] * fz_kn ** 2 + b[4] * fz_kn) * math.exp(-b[5] * fz_kn) / (C * D)
    E = b[6] * fz_kn ** 2 + b[7] * fz_kn + b[8]
    fx = mf(100 * kappa, B, C, D, E)
    fx_w, fy_w, _ = pac89_forces(hp, fz_kn * 1e3, kappa, 0.0, 0.0)
    assert fx_w == pytest.approx(fx, rel=1e-12)
    assert np.sign(fx_w) == np.sign(kappa)  # traction when driving
    assert fy_w == pytest.approx(0.0, abs=1e-9)


def test_peak_forces_equal_the_peak_factors(hp, coeffs):
    """With C > 1 the curve reaches D (the peak factor) exactly: by hand at 10 kN,
    D_y = (a1 Fz + a2) Fz and D_x = (b1 Fz + b2) Fz."""
    a, b, _ = coeffs
    alphas = np.radians(np.linspace(0.0, 30.0, 30001))
    fy = np.array([pac89_forces(hp, 10e3, 0.0, al, 0.0)[1] for al in alphas])
    assert -fy.min() == pytest.approx((a[1] * 10 + a[2]) * 10, rel=1e-6)
    kappas = np.linspace(0.0, 0.6, 30001)
    fx = np.array([pac89_forces(hp, 10e3, k, 0.0, 0.0)[0] for k in kappas])
    assert fx.max() == pytest.approx((b[1] * 10 + b[2]) * 10, rel=1e-6)


def test_cornering_stiffness_at_zero_slip(hp, coeffs):
    """dFy/dalpha at 0 is BCD = a3 sin(2 atan(Fz/a4)) per degree."""
    a, _, _ = coeffs
    d_alpha = 1e-6  # deg
    fy = pac89_forces(hp, 7e3, 0.0, math.radians(d_alpha), 0.0)[1]
    assert -fy / d_alpha == pytest.approx(a[3] * math.sin(2 * math.atan(7.0 / a[4])), rel=1e-6)


def test_camber_enters_in_degrees():
    """Shifts in camber (a8, a11) by hand: Sh = a8 gamma, Sv = a11 Fz gamma."""
    a = np.zeros(14)
    a[0] = 1.3        # C
    a[2] = 1000.0     # D = 1000 Fz
    a[3] = 1500.0     # BCD peak
    a[4] = 5.0
    a[8] = 0.1        # Sh = 0.1 deg per deg camber
    a[11] = 20.0      # Sv = 20 N per kN per deg
    hp = Pac89Params(lateral=a, longitudinal=np.zeros(11), aligning=np.zeros(18))
    fz, gamma = 5.0, 2.0
    D = 1000.0 * fz
    B = 1500.0 * math.sin(2 * math.atan(fz / 5.0)) / (1.3 * D)
    expect = mf(1.0 + 0.1 * gamma, B, 1.3, D, 0.0) + 20.0 * fz * gamma
    fy = pac89_forces(hp, fz * 1e3, 0.0, math.radians(1.0), math.radians(gamma))[1]
    assert fy == pytest.approx(-expect, rel=1e-12)


def test_no_force_without_load_and_never_nan(hp):
    assert pac89_forces(hp, 0.0, 0.1, 0.1, 0.0) == (0.0, 0.0, 0.0)
    assert pac89_forces(hp, -50.0, 0.1, 0.1, 0.0) == (0.0, 0.0, 0.0)
    for args in [(1e3, 5.0, 1.4, 0.3), (2e5, -3.0, -1.6, -0.2), (5e3, np.inf, 0.0, 0.0),
                 (5e3, 0.0, np.nan, 0.0)]:
        assert np.all(np.isfinite(pac89_forces(hp, *args)))


def test_missing_coefficients_name_the_file_and_key():
    with pytest.raises(InputError) as err:
        pac89_params(load_tyre("xzl-16.00R20", 300e3))
    assert "A0" in str(err.value) and "xzl-16.00R20" in str(err.value)


def test_hmmwv_is_a_complete_tyre(hmmwv):
    assert hmmwv.unloaded_radius == pytest.approx(0.464)
    assert hmmwv.width == pytest.approx(0.318)
    assert hmmwv.stiffness == "table"
    # Chrono's table: 53140 N at 0.1 m
    assert hmmwv.vertical_law.static_load(0.1) == pytest.approx(53140.0)
    assert hmmwv.with_stiffness("linear").vertical_law.static_load(0.01) == pytest.approx(3263.324234)


def test_rolling_backwards_turns_the_aligning_moment_over(hp, data_dir):
    """The pneumatic trail lies behind the contact centre in the direction of travel: rolling
    backwards at the same slip the lateral force is the same and the aligning moment turns
    over, as the Magic Formula's cos(alpha') = Vcx / Vc' turns it (checked on MFeval's 6.1
    example). Before, PAC89 kept its forward sign, steering a reversing wheel into its slide."""
    from tyrelab.tyre.handling.mf.model import MagicFormula
    from tyrelab.tyre.handling.pac89 import pac89_wheel_forces

    slide = 5.0 * math.tan(math.radians(3.0))          # the contact point slides left: alpha = 3 deg
    fwd = pac89_wheel_forces(hp, 15000.0, 5.0, 0.0, slide, 0.0)
    back = pac89_wheel_forces(hp, 15000.0, -5.0, 0.0, slide, 0.0)
    assert back[4] == pytest.approx(fwd[4]) and back[1] == pytest.approx(fwd[1])
    assert fwd[2] > 0.0 and back[2] == pytest.approx(-fwd[2])   # ISO-W: aligning when forwards
    mf = MagicFormula.from_tir(data_dir / "mfeval" / "MagicFormula61_Parameters.tir")
    mz = [float(mf.steady_state(6752.0, 0.0, math.radians(3.0), 0.0, v)["Mz"]) for v in (16.7, -16.7)]
    assert mz[0] > 0.0 and mz[1] == pytest.approx(-mz[0])
