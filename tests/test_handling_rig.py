"""Handling forces on a rig: slip from the wheel's spin drives the spin to free rolling."""

import numpy as np
import pytest

from tyrelab.api import default_handling, make_tyre_model
from tyrelab.rig.trailer import Trailer
from tyrelab.tyre.library import load_tyre


def test_file_format_picks_the_handling_model(data_dir):
    assert default_handling(load_tyre(data_dir / "mfeval" / "MagicFormula61_Parameters.tir")) == "mf"
    assert default_handling(load_tyre()) == "none"
    # MF-Tyre 5.0 (FITTYP 5, PROPERTY_FILE_FORMAT 'MF_05'): the Magic Formula's 5.x equations
    assert default_handling(load_tyre(data_dir / "tir" / "335_65R22_5_G275MSA_40psi.tir")) == "mf"


@pytest.mark.parametrize("json,handling", [("HMMWV_TMeasyTire.json", "tmeasy"),
                                           ("HMMWV_TMsimpleTire.json", "tmsimple"),
                                           ("HMMWV_FialaTire.json", "fiala")])
def test_chrono_handling_models_never_give_nan(data_dir, json, handling):
    """Random loads and velocities, standstill included: finite forces always, none without
    load (TMeasy's slips stay finite at standstill through its 0.01 m/s, Fiala's through
    the slip's 1 m/s floor)."""
    import math

    from tyrelab.tyre.chrono_json import read_chrono_tyre
    from tyrelab.tyre.registry import handling_model

    model = handling_model(handling)
    params = model.build(read_chrono_tyre(data_dir / "tir" / json))
    rng = np.random.default_rng(3)
    for fz, v_long, v_sx, v_sy in rng.normal(0.0, [5e3, 20.0, 20.0, 20.0], size=(400, 4)):
        out = model.forces(params, fz, v_long, v_sx, v_sy, 0.0)
        assert all(math.isfinite(v) for v in out)
        if fz <= 0:
            assert out[:3] == (0.0, 0.0, 0.0)
    for v in (0.0, 1e-300):
        assert all(math.isfinite(x) for x in model.forces(params, 4000.0, v, v, 0.0, 0.0))


def test_magic_formula_wheel_settles_at_free_rolling(data_dir):
    """With no drive torque the spin must settle where the moment about the axle vanishes,
    I dw/dt = -r Fx + My = 0 (r the contact point's lever, My the Magic Formula's rolling
    resistance): the slip where MFeval-like steady forces balance so, found here with the
    Magic Formula's own evaluator; a slip sign opposite to MF's would make the spin run away."""
    from scipy.optimize import brentq

    from tyrelab.tyre.handling.mf import MagicFormula

    path = data_dir / "mfeval" / "MagicFormula61_Parameters.tir"
    model = make_tyre_model(path, handling="mf")
    fz0 = 4000.0
    run = Trailer(model, fz0).run("flat", 10.0, duration=3.0)
    mf = MagicFormula.from_tir(path)
    tail = run.iloc[-500:]
    fz, r = tail["FZW"].mean(), model.tyre.unloaded_radius - tail["DEFLECT"].mean()

    def moment(k):
        out = mf.steady_state(fz, k, 0.0, 0.0, 10.0)
        return float(-r * out["Fx"] + out["My"])
    kappa0 = brentq(moment, -0.05, 0.05)
    drag = float(mf.steady_state(fz, kappa0, 0.0, 0.0, 10.0)["Fx"])
    assert drag < -20.0  # the offsets and the rolling resistance: not free at zero slip
    assert tail["FXW"].mean() == pytest.approx(drag, abs=1e-3 * fz0)
    assert tail["LONGSLIP"].mean() == pytest.approx(kappa0, abs=1e-4)
    assert np.all(np.isfinite(run["ROTSPEED"])) and run["ROTSPEED"].std() < 0.01 * run["ROTSPEED"].mean()


def test_a_wheel_without_a_spin_inertia_in_its_file_rolls_over_a_cleat(data_dir, tmp_path):
    """The CityBus PAC2002 file (Chrono's) has no [INERTIA]: its wheel is the vehicle model's,
    as in many ADAMS files. The rigs turned it with 1e-3 kg m^2, and under the Magic
    Formula's slip stiffness its spin ran away past the force's peak on the 50 mm cleat:
    +-1e4 rad/s step to step, FXW swinging by +-13 kN, without a word. Now the rig turns a
    uniform disc of a tenth of the wheel load's mass, m R0^2 / 2 = 0.5 (0.1 x 30 kN / g)
    (0.548 m)^2 = 45.9 kg m^2, says so, and the wheel rolls on: its spin stays within a
    third of free rolling's 30 km/h / 0.548 m and its slip within the tyre's +-0.3."""
    import shutil
    import warnings

    import tyrelab

    tir = tmp_path / "bus.tir"
    shutil.copy(data_dir / "tir" / "CityBus_Pac02Tire.tir", tir)
    with warnings.catch_warnings(record=True) as found:
        warnings.simplefilter("always")
        run = tyrelab.simulate(tyre=str(tir), model="point", handling="mf", rig="trailer",
                               road="cleat:50x50", speed=30 / 3.6, load=30000.0, duration=3.0,
                               progress=False)
    said = [str(w.message) for w in found if "no spin inertia" in str(w.message)]
    inertia = 0.5 * (0.1 * 30000.0 / 9.80665) * 0.548 ** 2
    assert len(said) == 1 and "bus.tir" in said[0] and f"{inertia:.3g} kg m^2" in said[0]
    free = 30 / 3.6 / 0.548
    spin = run["ROTSPEED"].to_numpy()
    assert spin.min() > 2 / 3 * free and spin.max() < 4 / 3 * free
    assert np.abs(run["LONGSLIP"].to_numpy()).max() < 0.3


def test_a_reversing_wheel_driven_backwards_is_pulled_backwards(data_dir):
    """The CityBus (PAC2002) at -5 m/s, its wheel spinning 10 % faster backwards than it
    travels: the road pulls it backwards, as forwards at +5 m/s and 10 % faster it pulls it
    forwards, the Magic Formula's mirror image (its slip is -V_sx / V_x with the signed speed),
    with the same combined-slip FYW when it also slides sideways. Before, given the rigs' slip
    -V_sx / |V_x| there, the reversing wheel was pushed forwards (+23.9 kN) and its FYW took the
    braked wheel's reduction."""
    from tyrelab.road.spec import road_from_spec
    from tyrelab.tyre.wheel import WheelLoads, loads_table, pose

    model = make_tyre_model(data_dir / "tir" / "CityBus_Pac02Tire.tir", handling="mf")
    eq = model.equilibrium(30000.0, 5.0)
    re, height = 5.0 / eq.spin, model.tyre.unloaded_radius - eq.deflection
    wheel = model.wheel(road_from_spec("flat").grid(), 30000.0)
    poses = [pose(cz=height, velocity=(v, lateral, 0.0), omega=1.1 * v / re)
             for v in (5.0, -5.0) for lateral in (0.0, 0.3)]
    loads = loads_table(wheel, poses)
    fxw, fyw = (loads[:, WheelLoads._fields.index(k)] for k in ("fxw", "fyw"))
    assert fxw[0] > 20e3 and fxw[2] == pytest.approx(-fxw[0], rel=1e-9)
    assert fyw[3] == pytest.approx(fyw[1], rel=1e-9) and fyw[1] < 0.0
