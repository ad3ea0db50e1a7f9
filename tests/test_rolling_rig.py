"""The fixed-height rolling test (Zegelaar, Schmeitz) and the footprint, for every model."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tyrelab.rig.rolling import roll
from tyrelab.rig.static_press import footprint, geometric_footprint
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel

LOAD = 23297.0  # LC1 wheel load [N]
CLEAT_START, CLEAT_H = 5.0, 0.05


@pytest.fixture(scope="module")
def xzl():
    return load_tyre("xzl-16.00R20", 300e3)


@pytest.fixture(scope="module")
def cleat_runs(xzl):
    return {m: roll(TyreModel(xzl, m), "cleat:50x50", speed=0.5, load=LOAD, x_start=3.5,
                    duration=6.0, progress=False) for m in ("point", "volume", "enveloping")}


@pytest.mark.parametrize("model", ["point", "volume", "enveloping"])
def test_rolling_on_a_level_road_carries_the_static_load(xzl, model):
    run = roll(TyreModel(xzl, model), "flat", speed=0.5, load=LOAD, duration=1.0, progress=False)
    np.testing.assert_allclose(run["FZW"], LOAD, rtol=1e-6)
    assert run["Z_WC"].iloc[0] == pytest.approx(xzl.unloaded_radius - xzl.static_deflection(LOAD))


def test_a_rigid_disc_meets_the_cleat_edge_where_geometry_says(xzl, cleat_runs):
    """The roller contact moves from the ground to the cleat's front edge (x = 5 m,
    height h) once the edge is nearer the axle than the ground: at x = x_edge -
    sqrt(H^2 - (H - h)^2) for axle height H; from there the force rises."""
    run = cleat_runs["point"]
    height = run["Z_WC"].iloc[0]
    x_touch = CLEAT_START - math.sqrt(height ** 2 - (height - CLEAT_H) ** 2)
    rising = run["X_WC"][run["FZW"] > LOAD * 1.001].iloc[0]
    # 0.1 % of the load is 0.04 mm of deflection, 0.1 mm of travel; a sample is 0.5 mm
    assert rising == pytest.approx(x_touch, abs=0.001)


def test_enveloping_lengthens_and_swallows_the_cleat(cleat_runs):
    """Schmeitz's cams: the force rises earlier (lengthening) and peaks lower (swallowing)
    than a rigid disc's; the volume model also peaks lower."""
    point, env, vol = cleat_runs["point"], cleat_runs["enveloping"], cleat_runs["volume"]

    def onset(run):
        return run["X_WC"][run["FZW"] > LOAD * 1.001].iloc[0]

    assert onset(env) < onset(point) - 0.02
    assert env["FZW"].max() < point["FZW"].max()
    assert vol["FZW"].max() < point["FZW"].max()


def test_geometric_footprint_of_a_square_section_is_the_chord(xzl):
    """A square carcass (no [SHAPE]) cut by the plate: every disc's chord is
    2 sqrt(R0^2 - (R0 - d)^2) long and the width is the tyre's width."""
    from dataclasses import replace
    square = replace(xzl, shape=None)
    d = 0.04
    fp = geometric_footprint(square, d, 40e3)
    r0 = square.unloaded_radius
    assert fp["length"] == pytest.approx(2 * math.sqrt(r0 ** 2 - (r0 - d) ** 2), rel=1e-12)
    assert fp["width"] == pytest.approx(square.width, rel=1e-12)
    assert fp["force"].sum() == pytest.approx(40e3, rel=1e-12)


def test_footprint_of_an_analytic_model_carries_the_plate_load(xzl):
    """Pressed to the law's deflection for 40 kN, the volume model's plate carries 40 kN
    (its equivalent-volume deflection equals the rigid disc's on a plate, thesis 2.3.2)."""
    fp = footprint(TyreModel(xzl, "volume"), 40e3)
    assert fp["load"] == pytest.approx(40e3, rel=2e-3)
