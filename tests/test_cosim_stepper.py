"""The stepping API (tyrelab.cosim): a host that moves the wheel as a rig does gets the rig's loads.

* Stepped with the kinematics of a rolling-rig run (wheel centre and spin at
  each step), the stepper returns the rig's own channels bit for bit: the same
  kernel (``wheel_step``), the same records, one call per step.
* A step of ``n`` sub-steps is the mean of ``n`` steps along the centre's
  extrapolated path (what "sub-stepping" promises).
* The frames: on a flat road a yawed, rolling wheel has the C-axis loads of
  the same wheel heading +x (the road has no direction), and the road-frame
  loads are the C-axis loads turned by the yaw and the inclination.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from tyrelab.api import make_tyre_model
from tyrelab.cosim import WheelCentre, wheel_stepper
from tyrelab.errors import InputError
from tyrelab.rig.rolling import roll

SPEED = 12 / 3.6
#: the rolling rig's kinematics that the host replays, as the stepper's record takes them
KINEMATICS = ("X_WC", "Y_WC", "Z_WC", "VX_WC", "VY_WC", "VZ_WC", "ROTSPEED")
#: the rig's channels a step returns (CentreLoads field -> signal channel)
LOADS = {"fx": "FX", "fy": "FY", "fz": "FZ", "mx": "MX", "my": "MY", "mz": "MZ", "fxw": "FXW",
         "fyw": "FYW", "fzw": "FZW", "deflection": "DEFLECT", "px": "X_CP", "py": "Y_CP",
         "pz": "Z_CP", "kappa": "LONGSLIP", "alpha": "SLIPANGL"}


def replay(stepper, run, dt=1e-3) -> dict[str, np.ndarray]:
    """Step ``stepper`` through the wheel-centre kinematics of a rig run; the loads by channel."""
    rows = run[list(KINEMATICS)].to_numpy()
    out = np.empty((len(rows), len(LOADS)))
    t = 0.0
    for k, row in enumerate(rows):
        loads = stepper.step(t, WheelCentre(*row), dt)
        out[k] = [getattr(loads, f) for f in LOADS]
        t += dt
    return {ch: out[:, j] for j, ch in enumerate(LOADS.values())}


# (tyre, contact model, load [N], start x [m], duration [s]): the cleat starts at x = 5 m;
# the ring's run is the stretch over the cleat only (its default test is kept short)
CASES = {
    "point": ("xzl-16.00R20", "point", 23.29e3, None, 2.0),
    "enveloping-pac89": ("hmmwv-pac89", "enveloping", 10e3, 4.3, 0.8),
    "ring": ("xzl-16.00R20", "ring", 23.29e3, 4.3, 0.6),
}


@pytest.mark.parametrize("case", list(CASES))
def test_the_stepper_gives_the_rolling_rigs_loads_bit_for_bit(case):
    tyre, contact, load, x0, duration = CASES[case]
    model = make_tyre_model(tyre, contact)
    run = roll(model, "cleat:50x50", speed=SPEED, load=load, x_start=x0, duration=duration,
               progress=False)
    stepper = wheel_stepper(model=model, road="cleat:50x50", load=load, speed=SPEED)
    assert stepper.sub_steps(1e-3) == 1          # the rig's step is within the model's stable step
    got = replay(stepper, run)
    for channel, values in got.items():
        np.testing.assert_array_equal(values, run[channel].to_numpy(), err_msg=channel)
    assert run["FZ"].max() > 1.2 * load                                # the cleat was hit
    assert stepper.time == pytest.approx(len(run) * 1e-3, abs=1e-12)


def test_a_step_of_n_sub_steps_is_the_mean_of_n_steps_along_the_path():
    """The ring over the cleat: one stepper takes 2 ms steps of two 1 ms sub-steps, another
    1 ms steps at the centre moved along its velocity; forces and moments of the first are
    the means of the second's pairs, its contact point and deflection the second's last."""
    model = make_tyre_model("xzl-16.00R20", "ring")
    load = 23.29e3
    one = wheel_stepper(model=model, road="cleat:50x50", load=load, speed=SPEED, max_step=1e-3)
    two = wheel_stepper(model=model, road="cleat:50x50", load=load, speed=SPEED, max_step=1e-3)
    z = model.tyre.unloaded_radius - one.equilibrium.deflection
    assert one.sub_steps(2e-3) == 2
    t = 0.0
    for k in range(150):  # 0.3 s from x = 4.7 m: over the cleat
        centre = WheelCentre(4.7 + SPEED * t, 0.0, z, SPEED, 0.0, 0.0, one.equilibrium.spin)
        coarse = one.step(t, centre, 2e-3)
        a = two.step(t, centre, 1e-3)
        b = two.step(t + 1e-3, centre._replace(x=centre.x + SPEED * 1e-3), 1e-3)
        for f in ("fx", "fy", "fz", "mx", "my", "mz", "fxw", "fyw", "fzw"):
            assert getattr(coarse, f) == pytest.approx(0.5 * (getattr(a, f) + getattr(b, f)),
                                                       rel=1e-12, abs=1e-9), f
        for f in ("deflection", "px", "pz"):
            assert getattr(coarse, f) == getattr(b, f), f
        t += 2e-3
    assert max(coarse.fz, a.fz, b.fz) > 0          # still in contact at the end


def _rotation(yaw: float, inclination: float) -> np.ndarray:
    """Columns: the C-axis x, y, z of a wheel at ``yaw`` and ``inclination`` in the road frame."""
    cy, sy, ci, si = math.cos(yaw), math.sin(yaw), math.cos(inclination), math.sin(inclination)
    x = np.array([cy, sy, 0.0])
    y = np.array([-sy * ci, cy * ci, si])
    return np.column_stack([x, y, np.cross(x, y)])


@pytest.mark.parametrize("yaw", [0.3, -2.0])
def test_a_yawed_wheel_on_a_flat_road_has_the_loads_of_one_heading_x(yaw):
    """The PAC89 tyre on the point model, rolling with slip (a slip angle and a braking spin)
    and leaning: heading +x and heading ``yaw`` give the same C-axis loads (a flat road has no
    direction), and the road-frame loads are those turned into the road frame."""
    incl, slip = 0.05, 0.08
    kwargs = dict(tyre="hmmwv-pac89", model="point", road="flat", handling="pac89", load=10e3)
    c_axis = wheel_stepper(**kwargs)
    r0 = c_axis.model.tyre.unloaded_radius
    z = r0 - c_axis.model.tyre.static_deflection(10e3)
    v, omega = 10.0, 0.95 * 10.0 / r0

    def centre(heading):
        vx, vy = v * math.cos(heading + slip), v * math.sin(heading + slip)
        return WheelCentre(1.0, 2.0, z, vx, vy, 0.0, omega, incl, heading)

    straight = c_axis.step(0.0, centre(0.0), 1e-3)
    yawed = wheel_stepper(**kwargs).step(0.0, centre(yaw), 1e-3)
    road = wheel_stepper(**kwargs, frame="road").step(0.0, centre(yaw), 1e-3)
    assert abs(straight.fy) > 0.2 * straight.fz and straight.kappa < 0   # slip forces are there
    for f in ("fx", "fy", "fz", "mx", "my", "mz", "fxw", "fyw", "fzw", "deflection", "kappa",
              "alpha", "dmy_domega"):
        assert getattr(yawed, f) == pytest.approx(getattr(straight, f), rel=1e-9, abs=1e-6), f
    rot = _rotation(yaw, incl)
    np.testing.assert_allclose([road.fx, road.fy, road.fz], rot @ [yawed.fx, yawed.fy, yawed.fz],
                               rtol=1e-12, atol=1e-6)
    np.testing.assert_allclose([road.mx, road.my, road.mz], rot @ [yawed.mx, yawed.my, yawed.mz],
                               rtol=1e-12, atol=1e-6)


def test_the_loads_of_the_state_leave_it_as_it_is():
    """``loads`` evaluates the present state without advancing it: the ring's next step is the
    same with or without the look."""
    model = make_tyre_model("xzl-16.00R20", "ring")
    a = wheel_stepper(model=model, road="flat", load=23.29e3, speed=SPEED)
    b = wheel_stepper(model=model, road="flat", load=23.29e3, speed=SPEED)
    z = model.tyre.unloaded_radius - a.equilibrium.deflection
    centre = WheelCentre(0.0, 0.0, z, SPEED, 0.0, 0.0, a.equilibrium.spin)
    look = a.loads(centre)
    assert look.fz == pytest.approx(23.29e3, rel=0.02)        # the equilibrium carries its load
    assert a.step(0.0, centre, 1e-3) == b.step(0.0, centre, 1e-3)


def test_the_ring_measures_its_slip_against_its_free_rolling_radius():
    """The ring has no slip law of its own: its ``LONGSLIP`` and ``SLIPANGL`` are the wheel's
    kinematic slips (ISO 8855, TYDEX) against its free-rolling radius ``R_e = V / omega`` of
    the equilibrium it starts in. Stepped on a flat road at that equilibrium's height with
    the spin of kappa = 0.03 and a side speed of alpha = -2 deg, it reports them (kappa
    ``(omega R_e - V) / V`` to rounding; alpha as the point model with a handling model
    reports the same centre motion, to 1e-12). It reported 0 for both."""
    kappa, alpha = 0.03, -math.radians(2.0)
    got = {}
    for tyre, model, handling in (("xzl-16.00R20", "ring", None), ("hmmwv-pac89", "point", "pac89")):
        stepper = wheel_stepper(tyre, model, "flat", handling=handling, load=20e3, speed=SPEED)
        eq = stepper.equilibrium
        r_e = SPEED / eq.spin
        z = make_tyre_model(tyre, model).tyre.unloaded_radius - eq.deflection
        side = SPEED * math.tan(alpha)
        for sign in (1.0, -1.0):       # the side speed's sign against the slip angle's
            loads = stepper.loads(WheelCentre(0.0, 0.0, z, SPEED, sign * side, 0.0,
                                              (1.0 + kappa) * SPEED / r_e))
            got[model, sign] = loads.kappa, loads.alpha
        # the ring's against R_e; PAC89's is the contact point's, whose lever is the centre's
        # height z (Chrono's rolling resistance makes the HMMWV roll freely at a little slip:
        # R_e is not z)
        lever = r_e if model == "ring" else z
        assert got[model, 1.0][0] == pytest.approx((1.0 + kappa) * lever / r_e - 1.0, abs=1e-12)
    for sign in (1.0, -1.0):
        assert got["ring", sign][1] == pytest.approx(got["point", sign][1], abs=1e-12)
        assert abs(got["ring", sign][1]) == pytest.approx(abs(alpha), abs=1e-12)


def _over_soil(ground, model, metres, speed=4.0, dt=1e-3):
    """Step ``model``'s wheel along x over ``metres`` of ``ground`` at a fixed height, pressed
    40 mm below its unloaded radius; FZ and FX per step."""
    stepper = wheel_stepper(model=model, road=ground)
    z = model.tyre.unloaded_radius - 0.04
    out = []
    for k in range(int(round(metres / (speed * dt)))):
        loads = stepper.step(k * dt, WheelCentre(1.0 + speed * k * dt, 0.0, z, speed, 0.0, 0.0,
                                                 speed / z), dt)
        out.append((loads.fz, loads.fx))
    return np.array(out), stepper


def test_the_soils_moving_patch_follows_a_stepped_wheel(monkeypatch):
    """On soil laid over the road (its active patch held 3 m at a time here), the stepper moves
    the patch on as the wheel advances, as the rigs do: over 8 m of sandy loam the loads'
    means and RMS are the whole bed's to 1e-4 (measured 7e-5 for FX, 1e-7 for FZ), every
    sample but one in 500 is within 1 % of the range and none beyond 10 %. Not closer: each
    move lays the bed's origin again, which moves its nodes by rounding (3e-11 N in a load at
    the next step, measured), and a node at the contact's edge, or at its plastic threshold
    (a node yields only above its largest pressure so far), can then fall on the other side.
    A row of them across the tyre carries up to 190 N of shear (22 nodes of 20 mm under
    20 kPa): FX once steps off by 187 N (7 % of its range), three samples of 2000 by more
    than 1 N. A patch left where it was, the loads are 73-91 % off. A wheel stepped back
    behind the soil the patch holds is refused in one line."""
    from tyrelab.road.soil import load_soil, patch
    from tyrelab.road.soil.terrain import lay_soil
    from tyrelab.road.spec import road_from_spec

    model = make_tyre_model("xzl-16.00R20", "point")
    soil, _ = load_soil("sandy-loam")
    road = road_from_spec("flat")
    whole, _ = _over_soil(lay_soil(soil, road, 0.0, 10.0, moving=False), model, 8.0)
    monkeypatch.setattr(patch, "PATCH_LENGTH", 3.0)
    bed = lay_soil(soil, road, 0.0, 10.0)
    moved, stepper = _over_soil(bed, model, 8.0)
    assert bed.held()[0] > 5.0                                 # the patch did move on
    assert whole[:, 0].min() > 1e3                             # the wheel sank in all the way
    for j, name in enumerate(("FZ", "FX")):
        a, b = whole[:, j], moved[:, j]
        assert b.mean() == pytest.approx(a.mean(), rel=1e-4), name
        assert np.sqrt(np.mean(b ** 2)) == pytest.approx(np.sqrt(np.mean(a ** 2)), rel=1e-4), name
        off = np.abs(b - a) / np.ptp(a)
        assert np.mean(off > 0.01) <= 1 / 500 and off.max() < 0.10, name
    back = WheelCentre(2.0, 0.0, 0.6, 0.0, 0.0, 0.0, 0.0)
    with pytest.raises(InputError, match="reaches behind the soil the bed holds"):
        stepper.step(stepper.time, back, 1e-3)


def test_a_wheel_put_below_the_road_or_onto_its_rim_is_warned_once_each():
    """A host whose vertical axis points down puts the wheel centre 0.6 m *below* a flat road;
    the disc then finds the road 0.6 m from its centre as if beneath it: a deflection of
    R0 - 0.6 = 71.5 mm and an FZ pulling the wheel further down, finite and silent (and no
    contact at all once the centre is a radius deep). The stepper warns once, as the rigs'
    guards warn. Pressed to 0.26 m the XZL (R0 0.6715 m, RIM_RADIUS 0.254 m: 417.5 mm of
    room) has 411.5 mm of deflection and no warning; to 0.20 m, 471.5 mm: rim contact."""
    from tyrelab.guards import PhysicsWarning

    wheel = wheel_stepper("xzl-16.00R20", "point", "flat")

    def at(z):
        return WheelCentre(0.0, 0.0, z, 0.0, 0.0, 0.0, 0.0)

    with warnings.catch_warnings():
        warnings.simplefilter("error")               # any warning here fails the test
        wheel.loads(at(0.6))
        assert wheel.step(0.0, at(0.26), 1e-3).deflection == pytest.approx(0.4115)
    with pytest.warns(PhysicsWarning) as found:
        below = wheel.loads(at(-0.6))
        wheel.loads(at(-0.7))                         # the same finding: not again
        wheel.step(1e-3, at(0.20), 1e-3)
    assert [str(w.message).split(":")[0] for w in found] == [
        "the wheel centre is below the road at t = 0.001 s", "rim contact at t = 0.002 s"]
    assert "z = -0.6 m under the road's 0 m" in str(found[0].message)
    assert "472 mm is beyond the 418 mm" in str(found[1].message)   # 471.5, rounded
    assert below.fz < 0                               # why it must be said: it pulls downwards
    assert {w.filename for w in found} == {__file__}  # pointed at the host's call, not at tyrelab


@pytest.mark.parametrize("call, match", [
    (lambda s, c: s.step(0.0, c, 0.0), "positive"),
    (lambda s, c: s.step(0.0, c, float("nan")), "finite number"),
    (lambda s, c: s.step(0.5, c, 1e-3), "step on from where"),
    (lambda s, c: s.step(0.0, c._replace(z=float("inf")), 1e-3), "centre's z must be a finite"),
    (lambda s, c: s.step(0.0, tuple(c)[:5], 1e-3), "a wheel centre is x, y, z"),
])
def test_bad_steps_are_refused_with_one_line(call, match):
    stepper = wheel_stepper(model="point", road="flat")
    with pytest.raises(InputError, match=match):
        call(stepper, WheelCentre(0.0, 0.0, 0.6, 1.0, 0.0, 0.0, 1.0))
    assert stepper.time == 0.0


@pytest.mark.parametrize("kwargs, match", [
    (dict(model="nope"), "unknown model"),
    (dict(model="rigid"), "does not run on a rigid road"),
    (dict(road="cleat:zz"), "cannot read sizes"),
    (dict(frame="body"), "unknown frame"),
    (dict(load=1e9), "onto its rim"),
    (dict(max_step=-1.0), "internal step"),
])
def test_bad_wheels_are_refused_with_one_line(kwargs, match):
    with pytest.raises(InputError, match=match):
        wheel_stepper(**kwargs)


def test_the_page_lists_every_fmu_variable_with_its_unit():
    """docs/cosimulation.md's tables name every variable of the FMU (tyrelab.cosim.variables)
    with its unit, and nothing else; the variables carry the stepping API's records' fields
    (the calculated parameters its stepper's properties)."""
    import re
    from pathlib import Path

    from tyrelab.cosim import CentreLoads
    from tyrelab.cosim.stepper import WheelStepper
    from tyrelab.cosim.variables import CALCULATED, INPUTS, OUTPUTS, PARAMETERS, SOIL_PARAMETERS

    page = (Path(__file__).resolve().parents[1] / "docs" / "cosimulation.md").read_text()
    listed = {}
    for line in page.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")] if line.startswith("| `") else []
        if len(cells) >= 3:
            for name in re.findall(r"`([A-Z_]+)`", cells[0]):
                listed[name] = cells[1]
    table = INPUTS + OUTPUTS + PARAMETERS + SOIL_PARAMETERS + CALCULATED
    assert listed == {v.name: v.unit or "-" for v in table}
    assert all(isinstance(getattr(WheelStepper, v.field), property) for v in CALCULATED)
    assert [v.field for v in INPUTS] == list(WheelCentre._fields)
    assert [v.field for v in OUTPUTS] == list(CentreLoads._fields)
