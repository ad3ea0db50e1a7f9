"""Disturbance / response segmentation and time alignment."""

import math

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.signal import make_signal
from tyrelab.validate import (align, estimate_shift, segments_from_geometry,
                              segments_from_signal, segments_from_speed)
from tyrelab.validate.segments import contact_reach


def pulse_then_ringing(fs=200.0, n=400, t0=0.5, T=0.1, noise=0.0, seed=0):
    t = np.arange(n) / fs
    y = np.full(n, 30e3)
    on = (t >= t0) & (t < t0 + T)
    y[on] += 20e3 * np.sin(np.pi * (t[on] - t0) / T)
    after = t >= t0 + T
    ta = t[after] - (t0 + T)
    y[after] += -8e3 * np.exp(-3.0 * ta) * np.sin(2 * np.pi * 4.0 * ta)
    if noise:
        y += noise * np.random.default_rng(seed).standard_normal(n)
    return t, y


def test_contact_reach_of_free_circle():
    # R = 0.8, centre 0.7 m high, 50 mm cleat: d = sqrt(0.64 - 0.65^2)
    assert contact_reach(0.8, 0.7, 0.05) == pytest.approx(math.sqrt(0.64 - 0.65 ** 2))
    assert contact_reach(0.8, 0.7, 0.0) == pytest.approx(math.sqrt(0.64 - 0.49))


def test_segments_from_speed_and_geometry():
    t = np.arange(0, 4, 0.001)
    seg = segments_from_speed(t, speed=5.0, x0=0.0, obstacle_start=10.0, obstacle_end=10.05,
                              obstacle_height=0.05, free_radius=0.8, centre_height=0.7)
    d = math.sqrt(0.64 - 0.65 ** 2)
    assert seg.disturbance == pytest.approx(((10 - d) / 5, (10.05 + d) / 5))
    assert seg.response == pytest.approx(((10.05 + d) / 5, t[-1]))
    seg2 = segments_from_geometry(t, 5.0 * t, 10.0, 10.05, 0.05, 0.8, 0.7,
                                  response_seconds=0.5)
    assert seg2.response[1] == pytest.approx(seg2.disturbance[1] + 0.5)
    with pytest.raises(InputError, match="never reaches"):
        segments_from_speed(t, 5.0, 0.0, 100.0, 100.05, 0.05, 0.8, 0.7)
    with pytest.raises(InputError):
        segments_from_geometry(t, -t, 1.0, 1.1, 0.05, 0.8, 0.7)


def test_segments_from_signal_noise_free():
    t, y = pulse_then_ringing()
    seg = segments_from_signal(t, y)
    assert seg.disturbance == pytest.approx((0.5, 0.6), abs=1e-12)
    assert seg.response == pytest.approx((0.6, t[-1]))
    assert seg.mask(t, "disturbance").sum() == 21  # samples 100 ... 120


def test_segments_from_signal_with_noise():
    t, y = pulse_then_ringing(noise=100.0)
    seg = segments_from_signal(t, y)
    dt = t[1] - t[0]
    assert abs(seg.disturbance[0] - 0.5) <= 2 * dt
    assert abs(seg.disturbance[1] - 0.6) <= 2 * dt


def test_segments_from_constant_signal_raises():
    with pytest.raises(InputError, match="constant"):
        segments_from_signal(np.arange(50.0), np.ones(50))


def test_estimate_shift_recovers_a_delay():
    t = np.arange(0, 3, 0.01)
    meas = np.exp(-((t - 1.5) / 0.1) ** 2)
    sim = np.exp(-((t - 1.5 + 0.2037) / 0.1) ** 2)  # simulation early by 0.2037 s
    assert estimate_shift(t, sim, t, meas) == pytest.approx(0.2037, abs=0.002)


def test_align_interpolates_simulation_onto_measurement():
    t_meas = np.arange(0, 1.0001, 0.01)
    t_sim = np.arange(-0.2, 0.8001, 0.001)
    sim = make_signal({"RUNTIME": t_sim, "FZ": 1000 + 100 * t_sim})
    meas = make_signal({"RUNTIME": t_meas, "FZ": np.full(t_meas.size, 1000.0)})
    a = align(sim, meas, shift=0.1)
    # p(t) = sim(t - 0.1) = 1000 + 100 (t - 0.1); only t - 0.1 <= 0.8 compared
    assert a.t[-1] == pytest.approx(0.9)
    np.testing.assert_allclose(a.p, 1000 + 100 * (a.t - 0.1), rtol=1e-12)
    meas.loc[3, "FZ"] = np.nan
    assert align(sim, meas).dropped == 1
    with pytest.raises(InputError, match="no channel FY"):
        align(sim, meas, channel="FY")
    bad = make_signal({"RUNTIME": [0.0, 0.0, 1.0], "FZ": [1.0, 1.0, 1.0]})
    with pytest.raises(InputError, match="strictly increasing"):
        align(sim, bad)
