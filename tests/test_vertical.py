"""The vertical law of thesis eq. 2.2 (shared by the analytic contact models)."""

import numpy as np
import pytest

from tyrelab.tyre.vertical import VerticalLaw, normal_force, static_load

TABLE_300 = np.array([[0, 0], [10, 3496], [20, 9445], [30, 15559], [40, 21968],
                      [50, 29011], [60, 37581], [70, 45717], [80, 54191]], float)


def law():
    return VerticalLaw.table(TABLE_300[:, 0] / 1e3, TABLE_300[:, 1], damping=2660.0, damping_ramp=0.002)


def test_spline_passes_through_table_3_2():
    np.testing.assert_allclose(law().static_load(TABLE_300[:, 0] / 1e3), TABLE_300[:, 1], atol=1e-6)


def test_extrapolation_is_the_end_tangent():
    lw = law()
    h = 1e-6
    end = 0.08
    slope_in = (lw.static_load(end) - lw.static_load(end - h)) / h
    slope_out = (lw.static_load(end + h) - lw.static_load(end)) / h
    assert slope_out == pytest.approx(slope_in, rel=1e-4)          # C1 at the last point
    # straight beyond: second difference vanishes
    f = lw.static_load(np.array([0.09, 0.10, 0.11]))
    assert f[0] - 2 * f[1] + f[2] == pytest.approx(0.0, abs=1e-6)
    # the slope carried on is the not-a-knot spline's end slope (scipy, independently)
    from scipy.interpolate import CubicSpline
    end_slope = CubicSpline(TABLE_300[:, 0] / 1e3, TABLE_300[:, 1])(0.08, 1)
    assert f[1] == pytest.approx(54191 + end_slope * 0.02, rel=1e-9)


def test_linear_law_is_k_rho():
    lw = VerticalLaw.linear(659.6e3, 2660.0)
    assert lw.static_load(0.042) == pytest.approx(659.6e3 * 0.042)


def test_damping_ramps_in_and_force_never_pulls():
    lw = law()
    # full damping beyond the ramp: F = k(rho) + c rho_dot
    assert normal_force(lw, 0.03, 0.1, 0.0) == pytest.approx(15559 + 266.0)
    # half-way up the ramp, smoothstep(0.5) = 0.5 of the damping
    rho = 0.001
    k = static_load(lw, rho)
    assert normal_force(lw, rho, 0.1, 0.0) == pytest.approx(k + 0.5 * 266.0)
    # rebound faster than the spring can follow: clipped at zero, no tension
    assert normal_force(lw, 0.01, -100.0, 0.0) == 0.0
    # lift-off
    assert normal_force(lw, -0.01, -1.0, 0.0) == 0.0


def test_normal_force_never_negative_or_nan():
    lw = law()
    rng = np.random.default_rng(1)
    for rho, rdot in zip(rng.uniform(-0.05, 0.2, 5000), rng.normal(0, 5, 5000)):
        f = normal_force(lw, rho, rdot, 0.0)
        assert np.isfinite(f) and f >= 0.0


def test_static_deflection_inverts_the_table():
    lw = law()
    assert lw.deflection_at(21968.0) == pytest.approx(0.040, abs=1e-9)
