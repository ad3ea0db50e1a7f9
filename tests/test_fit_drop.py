"""Tyre damping from the trailer drop test (thesis 3.4.1): the rig fitted to the trace, and
the thesis's pendulum (eqs. 3.1-3.7) beside it.

Round trips: the trailer (point model, both wheels) with a known damper and
a known load-deflection curve is dropped; the trace is fitted back starting
from a wrong damper. Noise on the trace degrades both routes by stated bounds.
"""

import dataclasses

import numpy as np
import pytest

from tyrelab.fit.damping import drop_release, drop_test_damping, fit_drop_trace, lowpass
from tyrelab.rig.trailer import Trailer
from tyrelab.tyre.model import TyreModel

TRUE_DAMPING = 4000.0     # N s/m per tyre, not the XZL's 2660


def _drop(tyre, load_case="LC1"):
    trailer = Trailer(TyreModel(tyre, "point"), load_case)
    run = trailer.drop(duration=3.0, progress=False)
    return run["RUNTIME"].to_numpy(), run["Z_WC"].to_numpy(), trailer


@pytest.fixture(scope="module")
def truth(xzl):
    return dataclasses.replace(xzl, vertical_damping=TRUE_DAMPING)


@pytest.fixture(scope="module")
def trace(truth):
    return _drop(truth)


def test_rig_fit_recovers_the_damper_from_a_wrong_start(xzl, trace):
    t, z, _ = trace
    start = dataclasses.replace(xzl, vertical_damping=1500.0)
    fit = fit_drop_trace(t, z, start)
    assert fit.damping == pytest.approx(TRUE_DAMPING, rel=0.002)
    assert fit.stiffness_scale == pytest.approx(1.0, abs=0.002)
    assert fit.rms < 1e-5                      # m: the trace is reproduced
    assert fit.evaluations < 100


def test_rig_fit_recovers_a_stiffer_curve(xzl):
    """The trace of a tyre 20 % stiffer than the file says: the fit finds the factor."""
    stiff = dataclasses.replace(xzl, vertical_damping=TRUE_DAMPING,
                                load_deflection=xzl.load_deflection * [1.0, 1.2],
                                vertical_stiffness=1.2 * xzl.vertical_stiffness)
    t, z, _ = _drop(stiff)
    fit = fit_drop_trace(t, z, xzl)
    assert fit.stiffness_scale == pytest.approx(1.2, rel=0.005)
    assert fit.damping == pytest.approx(TRUE_DAMPING, rel=0.01)


def test_pendulum_assumption_on_the_trailer(trace):
    """Eqs. 3.1-3.7 on the same trace: within 2 % of the damper (the pendulum ignores the
    axle's arc, the curve's nonlinearity and the damper's ramp at touch-down)."""
    t, z, trailer = trace
    p = drop_test_damping(t, z, trailer.setup.inertia[1, 1], trailer.geometry.hitch_to_axle)
    assert float(p.damping) == pytest.approx(TRUE_DAMPING, rel=0.02)


def test_noise_degrades_both_routes_gracefully(xzl, trace):
    """0.5 mm of white noise on a 75 mm drop: the rig fit within 1 %, the pendulum (after the
    10 Hz low-pass; without it the extremes are noise) within 3 %."""
    t, z, trailer = trace
    noisy = z + np.random.default_rng(11).normal(0.0, 5e-4, z.size)
    fit = fit_drop_trace(t, noisy, xzl)
    assert fit.damping == pytest.approx(TRUE_DAMPING, rel=0.01)
    assert fit.rms == pytest.approx(5e-4, rel=0.1)          # what is left is the noise
    p = drop_test_damping(t, lowpass(t, noisy, 10.0), trailer.setup.inertia[1, 1],
                          trailer.geometry.hitch_to_axle)
    assert float(p.damping) == pytest.approx(TRUE_DAMPING, rel=0.03)


def _held(t, z, hold=1.5, noise=1e-4, seed=3):
    """The trace as a logger started ``hold`` seconds before the release records it: at rest
    until then, the logger's clock and zero its own, ``noise`` [m] on every sample."""
    pre = np.arange(0.0, hold, t[1] - t[0])
    tt = np.r_[pre, t + hold] + 12.0
    zz = np.r_[np.full(pre.size, z[0]), z] - 0.3
    return tt, zz + np.random.default_rng(seed).normal(0.0, noise, tt.size)


@pytest.mark.parametrize("hold", [0.0, 0.003, 1.5])
def test_the_release_is_found_where_the_rim_leaves_its_rest(trace, hold):
    """The rim is let go at ``12 + hold`` s on the logger's clock: the estimate is within 3 ms
    (three samples; at most 2.6 ms over 20 noise seeds) through 0.1 mm of noise, whether the
    record starts at, just before or long before the release; the fit refines it."""
    t, z, _ = trace
    tt, zz = _held(t, z, hold)
    assert drop_release(tt, zz) == pytest.approx(12.0 + hold, abs=3e-3)


def test_a_trace_held_before_the_release_fits_as_one_that_starts_there(xzl, trace):
    """1.5 s at rest before the release (a logger started early): the damper within 1 %, the
    release within 1 ms. Read from the first sample as the release, the fit gave 44 times the
    damper."""
    t, z, _ = trace
    tt, zz = _held(t, z)
    fit = fit_drop_trace(tt, zz, xzl)
    assert fit.damping == pytest.approx(TRUE_DAMPING, rel=0.01)
    assert fit.release == pytest.approx(13.5, abs=1e-3)
    assert fit.rms == pytest.approx(1e-4, rel=0.1)          # what is left is the noise


def test_lowpass_keeps_the_trailer_decay():
    t = np.arange(0.0, 3.0, 1e-3)
    x = np.exp(-0.8 * t) * np.cos(2 * np.pi * 2.7 * t)
    y = lowpass(t, x, 10.0)
    assert np.max(np.abs(y - x)[200:-200]) < 1e-3
