"""Transient slip (tyrelab.tyre.handling.relaxation): the handling forces build over the
relaxation length, as a first-order lag in distance (Pacejka 2012, section 7.2).

References: the relaxation lengths MFeval 4.3.1 computes for the Magic Formula files
(``sigmax``, ``sigmay`` in tests/data/mfeval), the analytic step response
``1 - exp(-x / sigma)``, and each model's own steady state (``relaxation="off"``).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tyrelab import simulate
from tyrelab.api import make_tyre_model
from tyrelab.cosim import WheelCentre, wheel_stepper
from tyrelab.errors import InputError
from tyrelab.road.obstacles import Flat
from tyrelab.tyre.handling.relaxation import use_mode_relaxes
from tyrelab.tyre.tir import parse_tir
from tyrelab.tyre.wheel import WheelLoads, loads_table, pose

MFEVAL = Path(__file__).parent / "data" / "mfeval"
TIR = Path(__file__).parent / "data" / "tir"
#: MFeval's table speed [m/s] (tests/data/mfeval/README.md)
SPEED = 16.7


def _mfeval_lengths(name, share):
    """MFeval's (sigmax, sigmay) at ``share`` (0.5, 1 or 1.5) of FNOMIN, no slip, no camber,
    and that load."""
    table = pd.read_csv(MFEVAL / f"{name}.mode111.csv.gz")
    load = share * table["Fz"].median()  # the grid's loads are 0.5, 1 and 1.5 FNOMIN
    row = table[np.isclose(table["Fz"], load) & (table["kappa"] == 0) & (table["alpha"] == 0)
                & (table["gamma"] == 0)].iloc[0]
    return row["sigmax"], row["sigmay"], row["Fz"]


def _stepper(tyre, load, relaxation, handling="mf", max_step=1e-4):
    tm = make_tyre_model(tyre, "point", handling=handling, relaxation=relaxation)
    return wheel_stepper(model=tm, load=load, speed=SPEED, road="flat", max_step=max_step)


def _response(wheel, kappa, tan_alpha, distance, dt):
    """FXW and FYW [N] after each step of ``dt`` [s] at constant slips from a free-rolling
    start, and the distance rolled at each step's end [m]."""
    eq = wheel.equilibrium
    z = wheel.model.tyre.unloaded_radius - eq.deflection
    n = int(round(distance / (SPEED * dt)))
    fx, fy = np.empty(n), np.empty(n)
    t = wheel.time
    for i in range(n):
        loads = wheel.step(t, WheelCentre(x=SPEED * t, y=0.0, z=z, vx=SPEED, vy=SPEED * tan_alpha,
                                          vz=0.0, omega=eq.spin * (1.0 + kappa)), dt)
        t += dt
        fx[i], fy[i] = loads.fxw, loads.fyw
    return fx, fy, SPEED * dt * np.arange(1, n + 1)


@pytest.mark.parametrize("tyre, relaxation, lengths", [
    (MFEVAL / "MagicFormula52_Parameters.tir", "auto", ("MagicFormula52_Parameters", 0.5)),
    (MFEVAL / "MagicFormula52_Parameters.tir", "auto", ("MagicFormula52_Parameters", 1.5)),
    (MFEVAL / "MagicFormula61_Parameters.tir", "file", ("MagicFormula61_Parameters", 0.5)),
    (MFEVAL / "MagicFormula61_Parameters.tir", "file", ("MagicFormula61_Parameters", 1.5)),
    ("hmmwv-pac89", (0.25, 0.6), (0.25, 0.6)),
    # Chrono's HMMWV Fiala JSON: "X Relaxation Length": 2.0, "Y Relaxation Length": 2.0
    (TIR / "HMMWV_FialaTire.json", "file", (2.0, 2.0)),
], ids=["mf52-PTX-PTY-half", "mf52-PTX-PTY-1.5", "mf61-stiffness-ratio-half",
        "mf61-stiffness-ratio-1.5", "pac89-given", "fiala-file"])
def test_the_force_builds_as_a_first_order_lag_over_the_relaxation_length(tyre, relaxation,
                                                                           lengths):
    """A slip step from free rolling, small enough for the forces to be linear in it: the
    force's change follows ``1 - exp(-x / sigma)`` with sigma the file's relaxation length as
    MFeval computes it (MF 5.2: PTX, PTY; MF 6.1: the slip stiffness over the carcass
    stiffness; at half and 1.5 times FNOMIN, as the lengths grow with the load), or the
    length given (MF 5.2's file asks for it by USE_MODE 14). Implicit Euler at
    h = dt V / sigma <= 0.012 differs from the exponential by less than 0.3 % of the step
    (x h e^(-x) / 2 at most 0.2 %)."""
    if isinstance(lengths[0], str):
        sigma_x, sigma_y, load = _mfeval_lengths(*lengths)
        handling = "mf"
    else:
        (sigma_x, sigma_y), load = lengths, 4900.0
        handling = "fiala" if str(tyre).endswith("FialaTire.json") else "pac89"
    dt = 1e-4
    assert SPEED * dt / min(sigma_x, sigma_y) <= 0.012
    for kappa, tan_alpha, which, sigma in ((1e-4, 0.0, 0, sigma_x), (0.0, 1e-4, 1, sigma_y)):
        base = _response(_stepper(tyre, load, "off", handling), 0.0, 0.0, 0.01, dt)[which][-1]
        steady = _response(_stepper(tyre, load, "off", handling), kappa, tan_alpha, 0.01,
                           dt)[which][-1]
        assert abs(steady - base) > 1.0  # a change well above rounding
        got = _response(_stepper(tyre, load, relaxation, handling), kappa, tan_alpha,
                        3 * sigma, dt)
        share = (got[which] - base) / (steady - base)
        expected = 1.0 - np.exp(-got[2] / sigma)
        assert np.abs(share - expected).max() < 3e-3, (which, np.abs(share - expected).max())


@pytest.mark.parametrize("tyre, handling, relaxation", [
    (MFEVAL / "MagicFormula61_Parameters.tir", "mf", "auto"),  # USE_MODE 124: relaxation
    (TIR / "van_TMeasyTire.json", "tmeasy", (0.2, 0.4)),
    (TIR / "HMMWV_FialaTire.json", "fiala", (0.3, 0.3)),
], ids=["mf61-own", "tmeasy-given", "fiala-given"])
def test_the_lag_ends_in_the_models_own_steady_state(tyre, handling, relaxation):
    """Combined slip well past the peak (kappa 0.1, alpha 6 deg), rolled 40 relaxation
    lengths: the lagged forces are the steady model's to 1e-9 (the steady state of the lag
    is exact, whatever the model's own slip definition). With given lengths, the first step
    is the steady model at the slips one implicit-Euler step reaches, ``g = h / (1 + h)`` of
    the kinematic ones (``h = dt V / sigma``; tan alpha for the lateral), to 1e-9."""
    load, dt, kappa, tan_alpha = 3000.0, 1e-3, 0.1, math.tan(math.radians(6))
    steady = _stepper(tyre, load, "off", handling, max_step=dt)
    lagged = _stepper(tyre, load, relaxation, handling, max_step=dt)
    # MF 6.1's lengths grow with the load: MFeval's at 0.5 FNOMIN (3376 N) bound those at 3 kN
    sigma = max(_mfeval_lengths("MagicFormula61_Parameters", 0.5)[:2]) if relaxation == "auto" \
        else max(relaxation)
    a = _response(steady, kappa, tan_alpha, 0.05, dt)
    b = _response(lagged, kappa, tan_alpha, 40 * sigma, dt)
    assert abs(a[0][-1]) > 500 and abs(a[1][-1]) > 500
    assert b[0][-1] == pytest.approx(a[0][-1], rel=1e-9)
    assert b[1][-1] == pytest.approx(a[1][-1], rel=1e-9)
    if relaxation != "auto":
        gx, gy = (SPEED * dt / s / (1 + SPEED * dt / s) for s in relaxation)
        first = _response(_stepper(tyre, load, "off", handling, max_step=dt), kappa * gx,
                          tan_alpha * gy, SPEED * dt, dt)
        assert b[0][0] == pytest.approx(first[0][0], rel=1e-9)
        assert b[1][0] == pytest.approx(first[1][0], rel=1e-9)
        assert abs(b[1][0]) < 0.5 * abs(a[1][-1])


def test_a_wheel_off_the_ground_lands_with_its_carcass_undeflected():
    """Rolled at a slip until the force has built, lifted clear of the road for one step and
    put down again: its first step back is a fresh wheel's first step at that slip, its
    carcass undeflected."""
    tyre, load = MFEVAL / "MagicFormula52_Parameters.tir", 4000.0
    wheel = _stepper(tyre, load, "auto", max_step=1e-3)
    fresh = _stepper(tyre, load, "auto", max_step=1e-3)
    fresh.wheel.lag.deflection[:] = 0.0  # (a rig starts it deflected as it rolls freely)
    eq = wheel.equilibrium
    z = wheel.model.tyre.unloaded_radius - eq.deflection
    omega = eq.spin * 1.05

    def centre(t, height):
        return WheelCentre(x=SPEED * t, y=0.0, z=height, vx=SPEED, vy=0.0, vz=0.0, omega=omega)
    built = _response(wheel, 0.05, 0.0, 1.0, 1e-3)[0][-1]
    t = wheel.time
    assert wheel.step(t, centre(t, z + 0.05), 1e-3).fzw == 0.0
    t += 1e-3
    landed = wheel.step(t, centre(t, z), 1e-3).fxw
    first = fresh.step(0.0, centre(0.0, z), 1e-3).fxw
    assert landed == pytest.approx(first, rel=1e-12)
    assert abs(first) < 0.2 * abs(built)


def test_the_spin_slope_is_the_lagged_steps_moment_derivative():
    """The rigs integrate the spin implicitly with d(spin moment)/d(omega): with a lag it is
    the derivative over one step of the moment the step gives (the deflection advanced from
    the same start), not the steady slip stiffness."""
    tyre, load, dt = MFEVAL / "MagicFormula52_Parameters.tir", 4000.0, 1e-3
    tm = make_tyre_model(tyre, "point", handling="mf", relaxation="auto")
    eq = tm.equilibrium(load, SPEED)
    r0 = tm.tyre.unloaded_radius
    for factor in (1.0, 1.02, 0.95):
        omega = eq.spin * factor
        h = 1e-6 * omega
        rows = []
        for w in (omega, omega + h):
            wheel = tm.wheel(Flat().grid(), load)
            wheel.lag.deflection[:] = (0.01, -0.004)  # a deflected carcass, the same for both
            p = pose(cz=r0 - eq.deflection, velocity=(SPEED, 0.0, 0.0), omega=w)
            rows.append(WheelLoads(*loads_table(wheel, np.array([p]), dt)[0]))
        a, b = rows
        assert a.dspin_domega == pytest.approx((b.my - a.my) / h, rel=1e-3)
        steady = tm.wheel(Flat().grid(), load)._replace(lag=tm.slip_lag()._replace(from_model=False))
        p = pose(cz=r0 - eq.deflection, velocity=(SPEED, 0.0, 0.0), omega=omega)
        full = WheelLoads(*loads_table(steady, np.array([p]), dt)[0]).dspin_domega
        assert abs(a.dspin_domega) < 0.2 * abs(full)  # dt V / sigma is ~0.1 here


@pytest.mark.parametrize("mode, relaxes", [
    ("4", False), ("14", True), ("124", True), ("-14", True), ("334", True), ("104", False),
    ("2", False), ("'YES'", False),
])
def test_the_files_use_mode_says_whether_the_slip_lags(mode, relaxes):
    """MF-Tyre's USE_MODE: its tens digit 1 (linear relaxation), 2 (non-linear) or 3 (rigid
    ring) asks for transient slip; the sign mirrors, the hundreds choose the contact."""
    tir = parse_tir(f"[MODEL]\nUSE_MODE = {mode}\n")
    assert use_mode_relaxes(tir) is relaxes


@pytest.mark.filterwarnings("ignore:.*no spin inertia")
def test_a_run_says_which_lag_it_used():
    """The files of MFeval's examples: MF 5.2 asks for relaxation (USE_MODE 14), the CityBus
    not (4); the run's metadata says what was used."""
    def used(tyre, **kw):
        out = simulate(tyre, "point", road="flat", speed=10.0, load=3000.0, rig="rolling",
                       duration=0.05, handling="mf", **kw)
        return out.attrs["metadata"]["relaxation"]
    assert used(MFEVAL / "MagicFormula52_Parameters.tir") == "file"
    assert used(MFEVAL / "CityBus_Pac02Tire.tir") == "off"
    assert used(MFEVAL / "MagicFormula52_Parameters.tir", relaxation="off") == "off"
    assert used(MFEVAL / "CityBus_Pac02Tire.tir", relaxation=(0.3, 0.5)) == "0.3,0.5"
    # the command line's form, which the refusal's message names, means the same lengths
    assert used(MFEVAL / "CityBus_Pac02Tire.tir", relaxation="0.3, 0.5") == "0.3,0.5"


@pytest.mark.parametrize("relaxation, words", [
    ("fil", "expected one of auto, off, file"),
    ((0.3,), "expected two lengths in metres"),
    ((0.3, math.nan), "expected two lengths in metres"),
    ((-0.1, 0.3), "expected two lengths in metres"),
    ("0.3,abc", "expected two lengths in metres, each 0 .no lag. to 100, got 0.3,abc"),
    ("0.3,0.5,0.1", "expected two lengths in metres"),
])
def test_an_impossible_relaxation_is_refused(relaxation, words):
    with pytest.raises(InputError, match=words) as info:
        make_tyre_model(MFEVAL / "MagicFormula52_Parameters.tir", "point", handling="mf",
                        relaxation=relaxation)
    assert info.value.field == "relaxation"


def test_file_lengths_of_a_model_without_them_are_refused():
    with pytest.raises(InputError, match="'pac89' handling model has no relaxation lengths"):
        make_tyre_model("hmmwv-pac89", "point", handling="pac89", relaxation="file")
