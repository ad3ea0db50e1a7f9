"""The handling models' rolling resistance moment, and the free rolling it makes.

References: MFeval 4.3.1's My for the Magic Formula (tests/data/mfeval); for Fiala, TMeasy
and TMsimple the numbers of Chrono's JSON files typed here by hand and Chrono's law
``My = -e Fz tanh(omega)`` (e the load centre's shift: Fiala's "Rolling Resistance" [m],
TMeasy's "Rolling Resistance Coefficient" times the unloaded radius); the balance of a
towed wheel, whose axle carries no torque: ``Fx r + My = 0`` with r the contact point's
lever.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from tyrelab import simulate
from tyrelab.api import make_tyre_model
from tyrelab.road.spec import road_from_spec
from tyrelab.tyre.chrono_json import read_chrono_tyre
from tyrelab.tyre.registry import handling_model
from tyrelab.tyre.wheel import WheelLoads, loads_table, pose

from mfeval_rows import mfeval_rows_on_the_wheel

DATA = Path(__file__).parent / "data"
MF61 = DATA / "mfeval" / "MagicFormula61_Parameters.tir"
#: Chrono's JSON files: (file, handling model, the load centre's shift e [m], by hand)
CHRONO = [("HMMWV_FialaTire.json", "fiala", 0.015),            # "Rolling Resistance": 0.015
          ("HMMWV_TMeasyTire.json", "tmeasy", 0.015 * 0.4699),  # coefficient x unloaded radius
          ("HMMWV_TMsimpleTire.json", "tmsimple", 0.015 * 0.4699)]


def test_the_magic_formulas_rolling_resistance_is_mfevals_my():
    """Every MFeval row without camber (507, combined slip to 0.3): the point model's wheel at
    MFeval's deflection, spin and speed carries MFeval's My about its axle besides the moment
    of its contact force (to 1e-6, as tests/test_mf_reference.py holds MFeval's other outputs;
    My up to 39 N m here)."""
    rows, c, centres = mfeval_rows_on_the_wheel()
    lever_z = c["pz"] - centres[:, 2]  # contact point below the centre
    of_the_force = lever_z * c["fx"] - c["px"] * c["fz"]
    assert np.abs(rows.My).max() > 30.0
    np.testing.assert_allclose(c["my"] - of_the_force, rows.My, rtol=1e-6, atol=1e-9)


@pytest.mark.parametrize("json, handling, shift", CHRONO, ids=[c[1] for c in CHRONO])
def test_chronos_rolling_resistance(json, handling, shift):
    """``My = -e Fz tanh(omega)``: the whole moment when rolling fast, 76 % of it at 1 rad/s,
    none standing, turned over rolling backwards."""
    model = handling_model(handling)
    params = model.build(read_chrono_tyre(DATA / "tir" / json))
    fz = 4900.0   # (a loaded radius of 0.4 m given: these laws' lever is R0's, not it)
    for omega, share in ((30.0, 1.0), (1.0, math.tanh(1.0)), (0.0, 0.0), (-30.0, -1.0)):
        got = model.rolling_resistance(params, fz, 0.0, 10.0, omega, 0.0, 0.0, 0.4)
        assert got == pytest.approx(-shift * fz * share, rel=1e-12, abs=1e-12)
    assert model.rolling_resistance(params, 0.0, 0.0, 10.0, 30.0, 0.0, 0.0, 0.4) == 0.0


@pytest.mark.parametrize("tyre, handling, relaxation", [
    (DATA / "tir" / "HMMWV_FialaTire.json", "fiala", "off"),
    (DATA / "tir" / "HMMWV_TMeasyTire.json", "tmeasy", "off"),
    (MF61, "mf", "off"),
    (MF61, "mf", "auto"),  # its USE_MODE 124: the carcass starts deflected as it rolls
], ids=["fiala", "tmeasy", "mf", "mf-lagged"])
def test_a_towed_wheel_starts_and_stays_in_free_rolling(tyre, handling, relaxation):
    """The rolling rig starts the wheel where its axle carries no torque: the hub's MY is 0
    and FXW pulls back with ``My / r`` (r the contact point's lever, R0 less the deflection)
    from the first sample to the last, at a constant spin. The slip stiffness makes that a
    slip of a few 1e-4; the Magic Formula's own offsets at zero slip add to it. Before, the
    rigs started at zero slip: MF's FXW began at +33 N and ran down to 0 (no rolling
    resistance was carried then)."""
    speed, load = 10.0, 4000.0
    out = simulate(tyre, "point", road="flat", speed=speed, load=load, rig="rolling",
                   duration=0.3, handling=handling, relaxation=relaxation)
    model = make_tyre_model(tyre, "point", handling=handling, relaxation="off")
    eq = model.equilibrium(load, speed)
    lever = model.tyre.unloaded_radius - eq.deflection
    wheel = model.wheel(road_from_spec("flat").grid(), load)
    at = pose(cz=lever, velocity=(speed, 0.0, 0.0), omega=eq.spin)
    loads = WheelLoads(*loads_table(wheel, np.array([at]))[0])
    rolling = handling_model(handling).rolling_resistance(wheel.handling, loads.fzw, loads.fxw,
                                                          speed, eq.spin, loads.kappa, 0.0, lever)
    assert rolling < -10.0
    assert np.abs(out["MY"]).max() < 1e-6 * load * lever
    np.testing.assert_allclose(out["FXW"], rolling / lever, rtol=1e-6)
    assert np.ptp(out["ROTSPEED"]) < 1e-9 * eq.spin


@pytest.mark.parametrize("kmh", [5, 40])
def test_chronos_pac89_drags_a_towed_wheel_by_its_coefficient_times_the_load(kmh):
    """Project Chrono's PAC89 (its HMMWV JSON's "Rolling Resistance": 0.015, typed here):
    ``My = -f_r Fz R_l`` with R_l the loaded radius, which is also the contact force's lever
    on the point model, so a towed wheel's balance ``Fx R_l + My = 0`` leaves the drag
    ``Fx = -f_r Fz tanh(omega)``: 225 N at 15 kN (before, none)."""
    out = simulate(DATA / "tir" / "HMMWV_Pac89Tire.json", "point", road="flat", speed=kmh / 3.6,
                   load=15000.0, rig="rolling", duration=0.5, handling="pac89")
    fz, fx, omega = (out[c].to_numpy() for c in ("FZW", "FXW", "ROTSPEED"))
    np.testing.assert_allclose(fx, -0.015 * fz * np.tanh(omega), rtol=1e-6)
    assert fx.mean() == pytest.approx(-225.0, rel=0.01)
