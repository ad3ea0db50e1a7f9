"""MF-Tyre 5.0 files (``FITTYP = 5``) and the friction ellipse of ``FE_METHOD = 'YES'``.

The file is Goodyear's 335/65R22.5 G275 MSA truck tyre at 40 psi (``tests/data/tir``):
MF-Tyre 5.0, the Pacejka 2002 coefficient set, measured in braking only (``KPUMAX = 0``),
with no combined-slip coefficients for the lateral force (``RBY1 = 0``) and
``FE_METHOD = 'YES'``. The coefficients below are typed from that file by hand.

Oracles: the Magic Formula's analytic peak (``D``) and slope at the curve's origin
(``Kya = PKY1 FNOMIN sin(2 atan(Fz / (PKY2 FNOMIN)))``, ``Kxk = PKX1 FNOMIN`` at the
nominal load); an implementation written here of the friction ellipse as Project Chrono's
``ChPac02Tire`` publishes it (angle form, ``acos`` / ``tan`` / ``hypot``), fed with the
file's pure-slip curves; the balance of the towed trailer.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.tyre.handling.mf.model import MagicFormula
from tyrelab.tyre.tir import parse_tir

FNOMIN = 16929.0
PDX1, PDX2 = 0.98412, -0.043414
PKX1, PKX2, PKX3 = 8.5834, 1.0235e-4, -0.066015
PDY1, PDY2 = -0.70977, 0.14161
PKY1, PKY2 = -14.584, 2.1214
PHY1, PHY2 = 4.7162e-3, 9.7415e-5
PVY1, PVY2 = 1.3920e-2, -1.1621e-2
SPEED = 16.5        # the file's LONGVL [m/s]
NO_LIMITS = 211     # MFeval's use mode without limit checks: the curves beyond the file's range


@pytest.fixture(scope="module")
def text(data_dir):
    return (data_dir / "tir" / "335_65R22_5_G275MSA_40psi.tir").read_text(encoding="latin-1")


def mf_of(text, source="335_40psi.tir"):
    return MagicFormula.from_tir(parse_tir(text, source=source))


def evaluate(mf, fz, kappa, alpha, use_mode=NO_LIMITS):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return mf.steady_state(fz, kappa, alpha, 0.0, SPEED, use_mode=use_mode)


def test_an_mf_tyre_5_0_file_is_read_with_the_5_x_equations(text):
    """The peaks are |D| = |PDY1| FNOMIN and PDX1 FNOMIN; the slopes at the curves' origins
    the cornering and slip stiffnesses. The longitudinal curve is taken at the ellipse's zero of
    lateral slip, sin(alpha + SHy + SVy / Kya) = 0, where the ellipse leaves it whole."""
    mf = mf_of(text)
    assert mf.version == "5.2" and mf.coefficient("FRICTION_ELLIPSE") == 1.0
    alpha = np.linspace(-0.4, 0.4, 400001)
    fy = evaluate(mf, FNOMIN, 0.0, alpha)["Fy"] - PVY1 * FNOMIN
    dy = abs(PDY1) * FNOMIN
    assert fy.max() == pytest.approx(dy, rel=1e-9) and -fy.min() == pytest.approx(dy, rel=1e-9)

    kya = PKY1 * FNOMIN * math.sin(2.0 * math.atan(1.0 / PKY2))
    h = 1e-6
    fy_h = evaluate(mf, FNOMIN, 0.0, np.array([-PHY1 - h, -PHY1 + h]))["Fy"]
    assert (fy_h[1] - fy_h[0]) / (2 * h) == pytest.approx(kya, rel=1e-6)

    alpha0 = -PHY1 - PVY1 * FNOMIN / kya
    kappa = np.linspace(-0.8, 0.8, 400001)
    fx = evaluate(mf, FNOMIN, kappa, alpha0)["Fx"]
    assert -fx.min() == pytest.approx(PDX1 * FNOMIN, rel=1e-9)
    fx_h = evaluate(mf, FNOMIN, np.array([-h, h]), alpha0)["Fx"]
    assert (fx_h[1] - fx_h[0]) / (2 * h) == pytest.approx(PKX1 * FNOMIN, rel=1e-6)


def chrono_friction_ellipse(fx0, fy0, kappa, alpha, fz):
    """Combined Fx, Fy by the friction ellipse in ``ChPac02Tire``'s angle form, from the pure
    forces ``fx0``, ``fy0`` at the slips (this file: no SHx, SVx)."""
    dfz = (fz - FNOMIN) / FNOMIN
    dx = abs(PDX1 + PDX2 * dfz) * fz
    dy = abs(PDY1 + PDY2 * dfz) * fz
    svy = fz * (PVY1 + PVY2 * dfz)
    shy = PHY1 + PHY2 * dfz
    ky = PKY1 * FNOMIN * math.sin(2.0 * math.atan(fz / (PKY2 * FNOMIN)))
    kappa_c, alpha_s = kappa, math.sin(alpha + shy + svy / ky)
    beta = math.acos(abs(kappa_c) / math.hypot(kappa_c, alpha_s))
    mu_x_act, mu_y_act = abs(fx0) / fz, abs(fy0 - svy) / fz
    mu_x_c = 1.0 / math.hypot(1.0 / mu_x_act, math.tan(beta) / (dy / fz))
    mu_y_c = math.tan(beta) / math.hypot(1.0 / (dx / fz), math.tan(beta) / mu_y_act)
    return fx0 * mu_x_c / mu_x_act, fy0 * mu_y_c / mu_y_act


@pytest.mark.parametrize("load", [0.6, 1.0, 1.4])
def test_combined_slip_is_the_friction_ellipse_of_the_pure_curves(text, load):
    fz = load * FNOMIN
    pacejka = mf_of(text.replace("'YES'", "'NO'"))   # its pure curves: Gxa(alpha = 0) = Gyk(kappa = 0) = 1
    ellipse = mf_of(text)
    kappas = np.array([-0.6, -0.2, -0.08, -0.03, -0.01])
    alphas = np.array([-0.15, -0.05, -0.01, 0.02, 0.08, 0.15])
    fx0 = evaluate(pacejka, fz, kappas, 0.0)["Fx"]
    fy0 = evaluate(pacejka, fz, 0.0, alphas)["Fy"]
    k, a = np.meshgrid(kappas, alphas, indexing="ij")
    got = evaluate(ellipse, fz, k, a)
    for i, kappa in enumerate(kappas):
        for j, alpha in enumerate(alphas):
            fx, fy = chrono_friction_ellipse(fx0[i], fy0[j], kappa, alpha, fz)
            assert got["Fx"][i, j] == pytest.approx(fx, rel=1e-9, abs=1e-6)
            assert got["Fy"][i, j] == pytest.approx(fy, rel=1e-9, abs=1e-6)


@pytest.mark.parametrize("alpha", [0.02, 0.05, 0.1, 0.2])
def test_braking_takes_the_side_force_away_as_the_file_asks(text, alpha):
    """With RBY1 = 0 Pacejka's weighting leaves the side force whole under any braking slip,
    the resultant outside the friction ellipse of the two peaks; the ellipse the file asks
    for takes the side force away as the braking force grows and keeps the resultant inside
    ``(Fx / Dx)^2 + (Fy / Dy)^2 <= 1`` (Dx, Dy the peaks at FNOMIN, typed from the file)."""
    kappas = np.linspace(0.0, -0.8, 81)
    dx, dy = PDX1 * FNOMIN, abs(PDY1) * FNOMIN
    pacejka = evaluate(mf_of(text.replace("'YES'", "'NO'")), FNOMIN, kappas, alpha)
    assert np.ptp(pacejka["Fy"]) < 1e-9 * abs(pacejka["Fy"][0])
    assert ((pacejka["Fx"] / dx) ** 2 + (pacejka["Fy"] / dy) ** 2).max() > 1.0
    ellipse = evaluate(mf_of(text), FNOMIN, kappas, alpha)
    assert np.all(np.diff(np.abs(ellipse["Fy"])) < 0.0)
    assert ((ellipse["Fx"] / dx) ** 2 + (ellipse["Fy"] / dy) ** 2).max() <= 1.0


def test_a_friction_ellipse_switch_that_is_neither_yes_nor_no_is_refused(text):
    with pytest.raises(InputError) as info:
        mf_of(text.replace("'YES'", "'MAYBE'"), source="fe.tir")
    message = str(info.value)
    assert "fe.tir" in message and "line 48" in message and "FE_METHOD" in message


def test_the_braking_only_tyre_starts_the_trailer_balanced(data_dir):
    """KPUMAX = 0: a forward difference of Fx at free rolling read the clipped flat side, the
    free-rolling spin's Newton steps ran off (to -5e7 rad/s) and the trailer's balance
    failed. Now it rolls still, carrying the file's lateral offsets."""
    from tyrelab import api
    from tyrelab.tyre.handling.mf.wheel import magic_formula_params, mf_rolling_radius
    from tyrelab.tyre.library import load_tyre

    speed = 40 / 3.6
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        signals = api.simulate(tyre=str(data_dir / "tir" / "335_65R22_5_G275MSA_40psi.tir"),
                               road="flat", load=FNOMIN, speed=speed, duration=1.0)
    for channel in ("FZ", "FZ_LEFT", "FX", "FY", "ROTSPEED"):
        assert np.ptp(signals[channel]) < 4e-3, channel
    params = magic_formula_params(load_tyre(data_dir / "tir" / "335_65R22_5_G275MSA_40psi.tir"))
    fz, spin = float(signals["FZW"].iloc[0]), float(signals["ROTSPEED"].iloc[0])
    assert spin * mf_rolling_radius(params, fz, spin) == pytest.approx(speed, rel=1e-3)
    fy = evaluate(MagicFormula.from_tir(data_dir / "tir" / "335_65R22_5_G275MSA_40psi.tir"), fz,
                  float(signals["LONGSLIP"].iloc[0]), float(signals["SLIPANGL"].iloc[0]), use_mode=111)["Fy"]
    assert float(signals["FYW"].iloc[0]) == pytest.approx(float(fy), rel=1e-6)


def test_a_tyre_that_cannot_roll_freely_is_refused_at_the_start(data_dir, tmp_path):
    """MFeval's MF 6.1 example with its slip range cut to driving (KPUMIN = 0) keeps its
    rolling resistance (QSY1 = 0.01): no slip in its range balances that drag (the force is
    clipped flat below zero slip), so no rig can start it rolling freely. One clear line
    instead of a wheel started out of balance."""
    from tyrelab import api

    text = (data_dir / "mfeval" / "MagicFormula61_Parameters.tir").read_text()
    cut = text.replace("KPUMIN                   =    -1 ", "KPUMIN                   =    0  ")
    assert cut != text
    (tmp_path / "drive_only.tir").write_text(cut)
    with pytest.raises(InputError, match="no free-rolling spin at 4000 N.*KPUMIN"):
        api.simulate(tyre=str(tmp_path / "drive_only.tir"), road="flat", load=4000.0, duration=0.1)
