"""Fidelity of the campaign's reference (issue: the ring's damping at trailer
frequencies, equilibrium at the start of every run).

* The thesis's drop-test procedure (eqs. 3.1-3.7) is checked on an analytic
  damped oscillation and on the point model, whose tyre damper is known.
* The ring (even blocks and tread pattern) gives the thesis's 2.66 N s/mm
  in the simulated drop test evaluated as the thesis did, while its modal
  damping of modes 2 and 3 (Table 3-3) stays where the identification put it.
* Rolling does not wash the ring's damping out: after a cleat, the trailer's
  pitch and roll decay with damping ratios within 20 % of the analytic
  models' at 3, 12 and 42 km/h (the thesis found constant-damper models
  "representative of the real tyre damping" after its cleats, 5.2.1).
* Every model starts in static equilibrium on every rolling rig: the first
  2 s on a flat road stay within 0.2 % of their mean (for the tread
  pattern, whose lugs make the force ripple, the means of each second).
"""

import math

import numpy as np
import pytest

from tyrelab.fit.damping import drop_test_damping, free_decay, trailer_drop_damping
from tyrelab.rig.quarter_vehicle import QuarterVehicle
from tyrelab.rig.rolling import roll
from tyrelab.rig.trailer import Trailer
from tyrelab.tyre.library import modal_table
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.ring.modal import ring_modal

#: thesis 3.4.1: the drop test's damping of the XZL at 300 kPa [N s/m]
THESIS_DROP_DAMPING = 2660.0


def test_drop_test_procedure_recovers_an_analytic_pendulum():
    """eqs. 3.1-3.7 on x = A exp(-xi wn t) cos(wd t) + offset recover c and k exactly."""
    inertia, lever, wheels = 45000.0, 3.0, 2
    c, k = 2660.0, 660e3                                  # per tyre
    wn = math.sqrt(wheels * k * lever ** 2 / inertia)     # eq. 3.4
    xi = wheels * c * lever ** 2 / (2 * wn * inertia)     # eq. 3.5
    wd = wn * math.sqrt(1 - xi ** 2)
    t = np.arange(0.0, 4.0, 1e-4)
    # the rim falls from rest onto its springs: a cosine start, a constant offset
    z = 0.6 - 0.03 * np.exp(-xi * wn * t) * (np.cos(wd * t) + xi * wn / wd * np.sin(wd * t))
    result = drop_test_damping(t, z, inertia, lever, wheels)
    assert result.ratio == pytest.approx(xi, rel=1e-3)
    assert result.frequency == pytest.approx(wn / (2 * math.pi), rel=1e-3)
    assert result.damping == pytest.approx(c, rel=2e-3)
    assert result.stiffness == pytest.approx(k, rel=2e-3)


def test_drop_test_of_the_point_model_returns_its_damper(xzl):
    """The pendulum assumption holds on the trailer: the point model's viscous
    2.66 N s/mm comes back within 3 % (the hitch moves the axle on an arc and the
    damper ramps in over the first 2 mm of deflection)."""
    result = trailer_drop_damping(Trailer(TyreModel(xzl, "point"), "LC1"))
    assert result.damping == pytest.approx(xzl.vertical_damping, rel=0.03)


@pytest.mark.parametrize("contact", ["ring", "ring-tp"])
def test_ring_reproduces_the_thesis_drop_test(xzl, contact):
    """Issue point 1: 2.66 N s/mm within 10 %, and the trailer's pitch damping
    ratio within 20 % of the analytic models' (the point model's drop test)."""
    ring = trailer_drop_damping(Trailer(TyreModel(xzl, contact), "LC1"))
    point = trailer_drop_damping(Trailer(TyreModel(xzl, "point"), "LC1"))
    assert ring.damping == pytest.approx(THESIS_DROP_DAMPING, rel=0.10)
    assert ring.ratio == pytest.approx(point.ratio, rel=0.20)


def test_free_decay_recovers_an_analytic_oscillation():
    """A damped cosine with a ripple on it: ratio and frequency back to 1 %."""
    t = np.arange(0.0, 2.0, 1e-3)
    xi, f = 0.035, 3.2
    w = 2 * math.pi * f
    x = 0.01 * np.exp(-xi * w * t) * np.cos(w * math.sqrt(1 - xi * xi) * t + 0.4) + 0.3
    x += 2e-5 * np.sin(2 * math.pi * 41.0 * t)          # tread ripple
    got = free_decay(t, x)
    assert got.ratio == pytest.approx(xi, rel=0.01)
    assert got.frequency == pytest.approx(f, rel=0.01)


def _trailer_decay(model, kmh):
    """Pitch and roll damping ratios of the trailer's free decay after its test
    wheel leaves a 20 mm cleat (LC1): 2 s from 0.3 s after FZW is back at its
    static value."""
    signal = Trailer(model, "LC1").run("cleat:20x50", kmh / 3.6, duration=4.5 + 10.0 / kmh,
                                       progress=False)
    t = signal["RUNTIME"].to_numpy()
    fz = signal["FZW"].to_numpy()
    peak = int(np.argmax(fz))
    back = peak + int(np.argmax(fz[peak:] < np.median(fz[:200])))
    window = (t >= t[back] + 0.3) & (t <= t[back] + 2.3)
    return (free_decay(t[window], signal["PITCH"].to_numpy()[window], 2.6).ratio,
            free_decay(t[window], signal["ROLL"].to_numpy()[window], 3.2).ratio)


@pytest.fixture(scope="module")
def analytic_decay(xzl):
    return {(name, kmh): _trailer_decay(TyreModel(xzl, name), kmh)
            for name in ("point", "volume", "enveloping") for kmh in (3, 12, 42)}


@pytest.mark.parametrize("kmh", [3, 12, 42])
def test_ring_damps_the_rolling_trailer_like_the_analytic_models(xzl, analytic_decay, kmh):
    """Issue point 1 on the rolling trailer: the ring's pitch and roll damping
    ratios within 20 % of each analytic model's at the same speed."""
    pitch, roll_ = _trailer_decay(TyreModel(xzl, "ring"), kmh)
    for name in ("point", "volume", "enveloping"):
        ref_pitch, ref_roll = analytic_decay[(name, kmh)]
        assert pitch == pytest.approx(ref_pitch, rel=0.20), name
        assert roll_ == pytest.approx(ref_roll, rel=0.20), name


def test_ring_modal_damping_of_modes_2_and_3_stays(xzl):
    """Table 3-3 damping of modes 2 and 3: exact at 300 kPa (fitted), and at
    550 kPa (predicted) no worse than before the drop-test damping (+9.5 %, -10.6 %)."""
    table = modal_table("xzl-16.00R20").set_index("mode")
    for pressure, limit in ((300e3, 0.005), (550e3, 0.11)):
        model = ring_modal(xzl, pressure=pressure).set_index("mode")
        for mode in (2, 3):
            measured = table.loc[mode, f"damping_pct_{pressure / 1e3:.0f}kPa"]
            assert model.loc[mode, "damping_pct"] == pytest.approx(measured, rel=limit), mode


def _flat_within(signal, channels, share, window=None):
    """Every sample (or, with ``window`` samples, every window's mean) within
    ``share`` of the mean of the whole record."""
    for name in channels:
        x = signal[name].to_numpy()
        mean = x.mean()
        if window is not None:
            x = x[: x.size // window * window].reshape(-1, window).mean(axis=1)
        assert np.abs(x - mean).max() <= share * abs(mean), \
            f"{name}: {np.abs(x - mean).max():.4g} from its mean {mean:.6g}"


def _window(contact):
    """The tread pattern's lugs make the force ripple at the lug passing
    frequency (+-0.4 to 1.5 % at 3-42 km/h, and the trailer answers it by
    +-0.3 % in 0.25 s means): for ring-tp the equilibrium is checked on the
    means of the two seconds, which a start transient (or a start at the
    wrong height) would separate."""
    return 1000 if contact == "ring-tp" else None


MODELS = ["point", "volume", "enveloping", "ring", "ring-tp"]


@pytest.mark.parametrize("kmh", [3, 42])
@pytest.mark.parametrize("case", ["LC1", "LC2", "LC3"])
@pytest.mark.parametrize("contact", MODELS)
def test_trailer_starts_in_equilibrium(xzl, contact, case, kmh):
    run = Trailer(TyreModel(xzl, contact), case).run("flat", kmh / 3.6, duration=2.0,
                                                     progress=False)
    _flat_within(run, ("FZ", "FZ_HUB", "Z_WC"), 0.002, _window(contact))
    assert run["FZ"].mean() == pytest.approx(Trailer(TyreModel(xzl), case).setup.wheel_load,
                                             rel=0.002)


@pytest.mark.parametrize("kmh", [3, 42])
@pytest.mark.parametrize("contact", MODELS)
def test_quarter_vehicle_and_rolling_rig_start_in_equilibrium(xzl, contact, kmh):
    model = TyreModel(xzl, contact)
    vehicle = QuarterVehicle(model)
    run = vehicle.run("flat", kmh / 3.6, duration=2.0, progress=False)
    _flat_within(run, ("FZ", "Z_WC"), 0.002, _window(contact))
    rolled = roll(model, "flat", kmh / 3.6, load="LC2", duration=2.0, progress=False)
    _flat_within(rolled, ("FZ",), 0.002, _window(contact))


def test_ring_hub_force_differs_from_the_contact_force_by_the_belt_inertia(xzl):
    """Issue point 4: on the trailer over the 76 mm cleat at 42 km/h the rim's
    vertical force goes negative while the contact force never does; the
    difference is the belt's inertia, checked here at a fixed axle height.
    Momentum balance of the belt (weight not applied, blocks massless):
    M dV_cm/dt = F_patch - F_rim, checked step by step to 1 % of the peak
    contact force."""
    from tyrelab.road.spec import road_from_spec
    from tyrelab.tyre.ring.records import KIN_PSI
    from tyrelab.tyre.wheel import WheelLoads, loads_table, pose

    model = TyreModel(xzl, "ring")
    speed, load, dt = 42 / 3.6, 23291.0, 1e-3
    grid = road_from_spec("cleat:76.3x76.3").grid()
    eq = model.equilibrium(load, speed)
    wheel = model.wheel(grid, load)._replace(state=eq.state)
    params, state = wheel.contact, wheel.state
    mass = params.segment_mass * params.n_segments
    height = xzl.unloaded_radius - eq.deflection

    def belt_velocity_z(omega):
        psi = state.kinematics[KIN_PSI]
        e1z, e2z = -math.sin(psi), math.cos(psi)   # spin axis y: E1 = cos f - sin up
        vz = (state.v1 * e1z + state.v2 * e2z
              + omega * (-state.p1 * e2z + state.p2 * e1z))
        return vz.mean()

    omega = eq.spin
    v_before = belt_velocity_z(omega)
    rows = []
    for x in np.arange(3.5, 6.5, speed * dt):        # the cleat is at 5 m
        out = WheelLoads(*loads_table(wheel, pose(x, 0.0, height, velocity=(speed, 0.0, 0.0),
                                                  omega=omega), dt)[0])
        v_after = belt_velocity_z(omega)
        # contact-patch resultant, W axes -> world z: x_W = a x n, y_W = n x x_W
        n = np.array([out.nx, out.ny, out.nz])
        xw = np.cross([0.0, 1.0, 0.0], n)
        xw /= np.linalg.norm(xw)
        yw = np.cross(n, xw)
        patch_z = out.fxw * xw[2] + out.fyw * yw[2] + out.fzw * n[2]
        rows.append((out.fz, out.fzw, patch_z, mass * (v_after - v_before) / dt))
        v_before = v_after
    fz, fzw, patch_z, inertia = np.array(rows).T
    assert fzw.min() >= 0.0
    residual = patch_z - fz - inertia
    # the belt's inertia is a large part of the difference over the cleat
    assert np.abs(inertia).max() > 0.1 * fzw.max()
    assert np.abs(residual).max() < 0.01 * fzw.max()
