"""A rigid disc rolled slowly over a step follows the exact geometric path."""

import math

import numpy as np
import pytest

from tyrelab.rig.quarter_vehicle import QuarterVehicle
from tyrelab.road.obstacles import Step
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.params import Tyre

R = 0.6715


def exact_centre_height(x, xe, h):
    """Centre of a disc of radius R rolling over a step of height h at xe."""
    reach = math.sqrt(2 * R * h - h * h)
    d = xe - x
    if d >= reach:
        return R
    if d > 0:
        return h + math.sqrt(R * R - d * d)
    return R + h


def test_rigid_disc_over_a_step():
    k = 1e9                       # N/m: a rigid disc, 23 um under the load below
    disc = Tyre("rigid disc", R, 0.4, vertical_stiffness=k, vertical_damping=5e5, stiffness="linear",
                wheel_mass=240.0, wheel_spin_inertia=50.0, damping_ramp=1e-7)
    qv = QuarterVehicle(TyreModel(disc), sprung_mass=2135.0, unsprung_mass=240.0)
    step = Step(0.05, start=0.5, spacing=0.005)
    run = qv.run(step, speed=0.05, duration=16.0, dt=1e-4, output_rate=200)
    x = run["X_WC"].to_numpy()
    sag = run["FZW"].to_numpy() / k                 # the disc's own (tiny) deflection
    path = np.array([exact_centre_height(xi, 0.5, 0.05) for xi in x])
    err = run["Z_WC"].to_numpy() + sag - path
    assert np.abs(err).max() < 1e-4
    # it did climb the whole step
    assert run["Z_WC"].iloc[-1] == pytest.approx(R + 0.05, abs=1e-4)
