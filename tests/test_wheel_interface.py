"""The wheel interface: one registry, one wheel step, every rig takes every model.

A toy contact model written the way ARCHITECTURE.md says ("Adding a contact
model": one module with a parameter record, a build function, a compiled
geometry and one ``register_contact`` line) is driven on every rig; it is a
rigid disc on a level road, so its results must equal the point model's
there and the rigs' static facts must hold for it. It runs in a subprocess
with its own compile cache, so the toy's record type never enters the
package's cache index.
"""

from __future__ import annotations

import pytest
from kept_cache import kept_home, run_driver

from tyrelab.errors import InputError
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.registry import contact_models, handling_models

TOY_MODULE = '''
"""A toy contact model: a rigid disc touching the road straight below its centre."""
from typing import NamedTuple

import numba as nb

from tyrelab.road.grid import road_height
from tyrelab.tyre.registry import ContactModel, register_contact
from tyrelab.tyre.wheel import ContactGeometry


class ToyParams(NamedTuple):
    unloaded_radius: float


def toy_params(tyre, grid, **options):
    return ToyParams(float(tyre.unloaded_radius))


@nb.njit(cache=True)
def toy_contact(params, road, pose):
    h = road_height(road, pose.cx, pose.cy)
    return ContactGeometry(params.unloaded_radius - (pose.cz - h), pose.cx, pose.cy, h,
                           0.0, 0.0, 1.0, 0.0)


register_contact(ContactModel("toy", ToyParams, toy_params, geometry=toy_contact))
'''

DRIVER = '''
import json, sys
import numpy as np
import toy_contact  # noqa: F401  (registers "toy")
import tyrelab
from tyrelab.rig.static_press import static_press
from tyrelab.rig.rolling import roll
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel

tyre = load_tyre("xzl-16.00R20")
res = {}
for name in ("toy", "point"):
    m = TyreModel(tyre, name)
    d = [0.02, 0.04]
    res[name + "_press"] = static_press(m, d)["load"].tolist()
    run = tyrelab.simulate(model=name, road="flat", duration=1.0, progress=False)
    res[name + "_trailer_fz"] = run["FZW"].tolist()
    q = tyrelab.simulate(model=name, road="flat", rig="quarter-vehicle", duration=1.0,
                         progress=False)
    res[name + "_quarter_fz"] = q["FZW"].tolist()
    r = roll(m, "flat", speed=0.5, load=20000.0, duration=0.5, progress=False)
    res[name + "_rolling_fz"] = r["FZW"].tolist()
    drop = tyrelab.simulate(model=name, rig="drop", duration=2.0, progress=False)
    res[name + "_drop_defl"] = drop["DEFLECT"].tolist()
    res[name + "_drop_fz0"] = float(drop["FZW"].iloc[0])
    w = tyrelab.simulate(model=name, rig="wheel-drop", duration=1.0, progress=False)
    res[name + "_wheeldrop_defl"] = w["DEFLECT"].tolist()
res["static_defl_lc1"] = tyre.static_deflection(23297.0)
res["law_at_d"] = tyre.vertical_law.static_load(np.array([0.02, 0.04])).tolist()
json.dump(res, sys.stdout)
'''


@pytest.fixture(scope="module")
def toy_results():
    """The driver's results; the toy module and its compile cache are kept between runs
    (``tests/kept_cache.py``: the rig loops over the toy compile once, not in every run)."""
    return run_driver(kept_home("tyrelab-toy-model", "toy_contact.py", TOY_MODULE, DRIVER),
                      DRIVER, timeout=600)


def test_toy_model_press_is_its_vertical_law(toy_results):
    """On the plate a disc touching below its centre presses with k(d) exactly."""
    assert toy_results["toy_press"] == pytest.approx(toy_results["law_at_d"], rel=1e-9)


@pytest.mark.parametrize("rig", ["trailer_fz", "quarter_fz", "rolling_fz", "drop_defl",
                                 "wheeldrop_defl"])
def test_toy_model_equals_point_model_on_a_level_road(toy_results, rig):
    """Two independent implementations of a rigid disc on a level road agree on every rig."""
    toy = toy_results["toy_" + rig]
    point = toy_results["point_" + rig]
    assert len(toy) == len(point) > 100
    scale = max(abs(v) for v in point)
    assert max(abs(a - b) for a, b in zip(toy, point)) <= 1e-9 * scale


def test_rigs_start_in_equilibrium_with_the_toy_model(toy_results):
    fz = toy_results["toy_trailer_fz"]
    assert max(fz) - min(fz) < 1e-6 * fz[0]
    rolling = toy_results["toy_rolling_fz"]
    assert rolling == pytest.approx([20000.0] * len(rolling), rel=1e-9)


def test_drop_test_overshoots_the_static_deflection_but_less_than_twice(toy_results):
    """Dropped from just touching, an underdamped tyre passes its static deflection
    and (damping taking energy) stays below twice it, as a linear spring would reach."""
    static = toy_results["static_defl_lc1"]
    assert toy_results["toy_drop_fz0"] == 0.0
    peak = max(toy_results["toy_drop_defl"])
    assert static < peak < 2.0 * static


def test_unknown_models_fail_with_the_known_names():
    tyre = load_tyre("xzl-16.00R20")
    with pytest.raises(InputError) as err:
        TyreModel(tyre, "brush")
    for name in ("point", "volume", "enveloping", "ring", "ring-tp"):
        assert name in str(err.value)
    with pytest.raises(InputError) as err:
        TyreModel(tyre, "point", handling="brush")
    assert "pac89" in str(err.value) and "mf" in str(err.value)


def test_registry_lists_every_builtin_model_once():
    assert list(contact_models()) == ["point", "volume", "enveloping", "enveloping-edge", "ring", "ring-tp",
                                      "rigid"]
    assert list(handling_models()) == ["none", "pac89", "mf", "tmeasy", "tmsimple", "fiala"]
