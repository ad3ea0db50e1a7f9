"""The analytic tyre models on soil: a flexible wheel in series with the soil bed.

Three facts of terramechanics that the series contact must reproduce (Wong, Theory of
Ground Vehicles, 2.4): a tyre so stiff that it cannot flatten is the rigid wheel; on a
ground so stiff that it cannot sink the tyre deflects as it does on a rigid road (its own
vertical law carries the load); and between the two, a stiffer tyre (higher inflation)
flattens less and so sinks deeper than a softer one.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

import tyrelab
from tyrelab.rig.single_wheel import single_wheel
from tyrelab.road.soil.params import Soil
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel

LOAD, SPEED = 23.3e3, 1.0
#: simulated time [s] and the start of its steady part [s]
DURATION, STEADY = 3.0, 1.5


def _steady(model, soil, slip, **kw):
    run = single_wheel(model, soil, LOAD, SPEED, slip=slip, duration=DURATION, progress=False, **kw)
    steady = run[run["RUNTIME"] > STEADY]
    return {c: steady[c].mean() for c in ("FX", "FZ", "TORQUE", "SINKAGE", "DEFLECT")}


def test_a_tyre_too_stiff_to_flatten_is_the_rigid_wheel():
    """The point model's tyre at 1e9 N/m (deflection ~23 um: no flat wider than a node) pulls,
    sinks and takes the torque of the rigid wheel on the same soil, to 1 %."""
    stiff = replace(load_tyre(), stiffness="linear", vertical_stiffness=1e9)
    flexible = _steady(TyreModel(stiff, "point"), "sandy-loam", 0.2)
    rigid = _steady(TyreModel(stiff, "rigid"), "sandy-loam", 0.2)
    assert flexible["DEFLECT"] < 1e-4
    for channel in ("FX", "TORQUE", "SINKAGE"):
        assert flexible[channel] == pytest.approx(rigid[channel], rel=0.01), channel


def test_on_a_ground_too_stiff_to_sink_the_tyre_deflects_as_on_a_rigid_road():
    """On a soil a thousand times stiffer than any in the library the tyre's deflection is the
    vertical law's static deflection under the load (what the point model gives on a rigid
    plate, thesis eq. 2.2) to 1 %, and the soil sinks by under 1 % of it."""
    hard = Soil(n=1.0, kc=0.0, kphi=1e11, cohesion=1e3, friction_angle=0.6, janosi_k=0.01,
                elastic_stiffness=1e12, damping=0.0)
    tyre = load_tyre()
    rolled = _steady(TyreModel(tyre, "point"), hard, 0.0)
    deflection = tyre.static_deflection(LOAD)
    assert rolled["FZ"] == pytest.approx(LOAD, rel=1e-3)
    assert rolled["DEFLECT"] == pytest.approx(deflection, rel=0.01)
    assert rolled["SINKAGE"] < 0.01 * deflection


def test_a_stiffer_tyre_sinks_deeper():
    """The XZL at 550 kPa flattens less than at 100 kPa, so it sinks deeper on sandy loam; both
    sink less than the rigid wheel of the same size."""
    soft = _steady(TyreModel(load_tyre(pressure=100e3), "point"), "sandy-loam", 0.2)
    hard = _steady(TyreModel(load_tyre(pressure=550e3), "point"), "sandy-loam", 0.2)
    rigid = _steady(TyreModel(load_tyre(), "rigid"), "sandy-loam", 0.2)
    assert hard["DEFLECT"] < soft["DEFLECT"]
    assert soft["SINKAGE"] < hard["SINKAGE"] < rigid["SINKAGE"]


def test_every_analytic_model_runs_on_soil_through_simulate():
    """point, volume and enveloping through ``simulate``: the same flexible wheel on soil (their
    footprint is the soil's), each carrying the dead weight."""
    runs = {m: tyrelab.simulate(model=m, rig="single-wheel", terrain="lete-sand", load=LOAD,
                                speed=SPEED, rig_options={"slip": 0.1}, duration=2.0,
                                progress=False) for m in ("point", "volume", "enveloping")}
    for m, run in runs.items():
        assert run["FZ"].iloc[-500:].mean() == pytest.approx(LOAD, rel=0.05), m
        assert (run["FZW"] >= 0).all() and not run.isna().any().any()
    assert runs["volume"]["FX"].to_numpy() == pytest.approx(runs["point"]["FX"].to_numpy())
