"""Input limits, low speed, no-NaN guarantee, use modes and the compiled kernel."""

from __future__ import annotations

import warnings
from pathlib import Path

import numba
import numpy as np
import pandas as pd
import pytest

from tyrelab.errors import InputError
from tyrelab.tyre.handling.mf import MagicFormula, MFLimitWarning, mf_forces
from tyrelab.tyre.handling.mf.geometry import free_radius, load_62
from tyrelab.tyre.tir import parse_tir

DATA = Path(__file__).parent / "data" / "mfeval"
FORCES = ("Fx", "Fy", "Mx", "My", "Mz")


@pytest.fixture(scope="module")
def mf61():
    # ranges: ALPMAX 0.96, KPUMAX 1, CAMMAX 0.105, FZMAX 18000, PRESMAX 400000, VXLOW 1
    return MagicFormula.from_tir(DATA / "MagicFormula61_Parameters.tir")


def quiet(model, *args, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return model.steady_state(*args, **kw)


@pytest.mark.parametrize("index,value,limit,key", [
    (2, 1.2, 0.96, "ALPMAX"), (2, -1.2, -0.96, "ALPMIN"),
    (1, 1.5, 1.0, "KPUMAX"), (1, -1.2, -1.0, "KPUMIN"),
    (3, 0.2, 0.105, "CAMMAX"), (3, -0.2, -0.0873, "CAMMIN"),
])
def test_slip_and_camber_are_saturated_with_a_warning(mf61, index, value, limit, key):
    base = [6000.0, 0.05, 0.1, 0.01, 16.7]
    beyond, at = list(base), list(base)
    beyond[index], at[index] = value, limit
    with pytest.warns(MFLimitWarning, match=key):
        r = mf61.steady_state(*beyond)
    ref = quiet(mf61, *at)
    for q in ("Fx", "Fy", "Mz", "Mx"):
        assert r[q] == pytest.approx(ref[q], rel=1e-12), q


def test_load_above_fzmax_is_saturated_for_forces(mf61):
    with pytest.warns(MFLimitWarning, match="FZMAX"):
        r = mf61.steady_state(25000.0, 0.05, 0.1, 0.0, 16.7)
    ref = quiet(mf61, 18000.0, 0.05, 0.1, 0.0, 16.7)
    assert r["Fx"] == pytest.approx(ref["Fx"], rel=1e-12)
    assert r["Fy"] == pytest.approx(ref["Fy"], rel=1e-12)
    assert r["Fz"] == 25000.0  # the input load is reported, as MFeval does


def test_pressure_is_saturated(mf61):
    with pytest.warns(MFLimitWarning, match="PRESMAX"):
        r = mf61.steady_state(6000.0, 0.05, 0.1, 0.0, 16.7, pressure=5e5)
    ref = quiet(mf61, 6000.0, 0.05, 0.1, 0.0, 16.7, pressure=4e5)
    assert r["Fx"] == pytest.approx(ref["Fx"], rel=1e-12) and r["P"] == 4e5


def test_load_below_fzmin_warns():
    bus = MagicFormula.from_tir(DATA / "CityBus_Pac02Tire.tir")  # FZMIN = 1750
    with pytest.warns(MFLimitWarning, match="FZMIN"):
        r = bus.steady_state(1000.0, 0.0, 0.05, 0.0, 16.7)
    assert np.isfinite(r["Mx"]) and np.isfinite(r["Mz"])


def test_without_limit_checks_nothing_is_clipped(mf61):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        free = mf61.steady_state(6000.0, 0.05, 1.2, 0.0, 16.7, use_mode=211)
    clipped = quiet(mf61, 6000.0, 0.05, 1.2, 0.0, 16.7, use_mode=111)
    assert free["Fy"] != pytest.approx(clipped["Fy"], rel=1e-6)


def test_low_speed_mode_warns_and_fades_to_standstill(mf61):
    with pytest.warns(MFLimitWarning, match="VXLOW"):
        r = mf61.steady_state(6000.0, 0.1, 0.1, 0.0, np.array([0.0, 0.5, 1.0, 2.0]))
    assert r["My"][0] == 0.0
    assert r["kappa"][1] == pytest.approx(0.05)  # slip scaled by |Vx|/VXLOW
    # at standstill the slips are zero, so only the (smoothly zeroed) shifts remain
    assert abs(r["Fx"][0]) < 1e-9 and abs(r["Fy"][0]) < 1e-9
    assert abs(r["Fx"][1]) < abs(r["Fx"][3])


@pytest.mark.parametrize("mode", [111, 121, 211, 221])
def test_no_nan_anywhere(mf61, mode):
    grid = np.meshgrid([-100.0, 0.0, 1.0, 6752.0, 1e7], [-1.0, -0.5, 0.0, 2.0, 50.0],
                       [-1.5, -0.2, 0.0, 0.3, np.pi / 2], [-0.3, 0.0, 1.5],
                       [-20.0, -0.5, 0.0, 1e-9, 30.0], [0.0, 1e5, 6e5], indexing="ij")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = mf61.steady_state(*(g.ravel() for g in grid[:5]), pressure=grid[5].ravel(),
                              use_mode=mode)
    for name, values in r.items():
        assert np.all(np.isfinite(values)), name
    # finite by the equations themselves, not by the last-resort replacement
    assert not any("non-finite" in str(w.message) for w in caught)


def test_nan_input_and_turn_slip_mode_are_refused(mf61):
    with pytest.raises(InputError, match="alpha"):
        mf61.steady_state(6000.0, 0.0, np.nan, 0.0, 16.7)
    with pytest.raises(InputError, match="turn slip"):
        mf61.steady_state(6000.0, 0.0, 0.1, 0.0, 16.7, use_mode=112)


def test_alpha_star_changes_results_only_through_tan_and_sin(mf61):
    """Mode 121 differs from 111 at large slip (tan(alpha) != alpha), not at alpha = gamma = 0."""
    a = quiet(mf61, 6000.0, 0.1, 0.0, 0.0, 16.7, use_mode=111)
    b = quiet(mf61, 6000.0, 0.1, 0.0, 0.0, 16.7, use_mode=121)
    assert a["Fx"] == pytest.approx(b["Fx"], rel=1e-14)
    c = quiet(mf61, 6000.0, 0.0, 0.3, 0.0, 16.7, use_mode=111)
    d = quiet(mf61, 6000.0, 0.0, 0.3, 0.0, 16.7, use_mode=121)
    assert abs(c["Fy"] - d["Fy"]) > 1.0


@numba.njit(cache=True)
def _sum_fy(coefficients, loads, alpha):
    out = np.zeros(5)
    total = 0.0
    for i in range(loads.shape[0]):
        mf_forces(coefficients, 111, loads[i], 0.0, alpha, 0.0, 16.7, 0.0, out)
        total += out[1]
    return total


def test_mf_forces_is_callable_from_another_kernel(mf61):
    loads = np.array([3000.0, 6000.0, 9000.0])
    expected = quiet(mf61, loads, 0.0, 0.1, 0.0, 16.7)["Fy"].sum()
    assert _sum_fy(mf61.coefficients, loads, 0.1) == pytest.approx(expected, rel=1e-12)


def _as_62(text):
    return text.replace("FITTYP                   =    61", "FITTYP = 62")


def test_mf62_radius_equals_mf61_when_62_terms_are_zero():
    """With Q_CAM*, Q_FYS*, Q_FCY2 absent the 6.2 law is the 6.1 law: MFeval's 6.1 Rl holds."""
    text = (DATA / "MagicFormula61_Parameters.tir").read_text()
    m62 = MagicFormula.from_tir(parse_tir(_as_62(text), source="mf62.tir"))
    assert m62.version == "6.2"
    table = pd.read_csv(DATA / "MagicFormula61_Parameters.mode111.csv.gz")
    r = m62.steady_state(table["Fz"].to_numpy(), table["kappa"].to_numpy(),
                         table["alpha"].to_numpy(), table["gamma"].to_numpy(),
                         table["Vx"].to_numpy())
    np.testing.assert_allclose(r["Rl"], table["Rl"].to_numpy(), rtol=0, atol=1e-6)
    np.testing.assert_allclose(r["Fy"], table["Fy"].to_numpy(), rtol=1e-6, atol=1e-3)


def test_mf62_radius_solves_the_62_load_law_with_camber_terms():
    text = _as_62((DATA / "MagicFormula61_Parameters.tir").read_text()).replace(
        "Q_CAM                    =    0", "Q_CAM1 = 0.5\nQ_CAM2 = 2.0\nQ_CAM3 = 0.3\n"
        "Q_FCY2 = 0.5\nQ_FYS1 = 0.1")
    m = MagicFormula.from_tir(parse_tir(text, source="mf62cam.tir"))
    assert m.coefficient("Q_CAM3") == 0.3
    fz, gamma = np.array([3000.0, 6752.0, 10000.0]), np.array([0.05, -0.08, 0.1])
    r = m.steady_state(fz, 0.05, 0.1, gamma, 16.7)
    c = m.coefficients
    for i in range(fz.size):
        r_omega = free_radius(c, r["omega"][i])
        load, rho = load_62(c, r["Rl"][i], gamma[i], r["omega"][i], r_omega, 0.0,
                            r["Fx"][i], r["Fy"][i])
        assert load == pytest.approx(fz[i], abs=6752 * 1e-6)
        assert rho == pytest.approx(r["rho"][i], rel=1e-12)


def test_curvature_factor_above_one_is_limited_with_limit_checks_only():
    text = (DATA / "MagicFormula61_Parameters.tir").read_text().replace(
        "PEY1                     =    -0.34653", "PEY1 = 2.5")
    m = MagicFormula.from_tir(parse_tir(text, source="bad_ey.tir"))
    with pytest.warns(MFLimitWarning, match="curvature"):
        limited = m.steady_state(6752.0, 0.0, 0.2, 0.0, 16.7, use_mode=111)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        free = m.steady_state(6752.0, 0.0, 0.2, 0.0, 16.7, use_mode=211)
    assert limited["Fy"] != pytest.approx(free["Fy"], rel=1e-6)
