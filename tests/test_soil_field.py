"""The soil for a wheel a host drives anywhere (tyrelab.road.soil.field): a window of the soil that
moves with the wheel in x and y, keeping the state of the nodes it still holds."""

import math

import numpy as np
import pytest

from tyrelab.api import make_tyre_model
from tyrelab.cosim.kernel import WheelCentre
from tyrelab.cosim.stepper import wheel_stepper
from tyrelab.errors import InputError
from tyrelab.road.soil import load_soil
from tyrelab.road.soil.field import lay_soil_field
from tyrelab.road.spec import road_from_spec

SOIL, _ = load_soil("sandy-loam")


@pytest.fixture(scope="module")
def paving():
    return road_from_spec("belgian-paving")     # heights that vary along x and across


def test_a_moved_window_keeps_the_state_of_the_nodes_it_still_holds(paving):
    """Every node the window holds before and after a move keeps its rut, mobilized shear and
    stress exactly; every node it newly holds is fresh soil on the road's height at that node
    (the road's own bilinear height, less the level); the nodes stay on one lattice, and the
    window then holds the box asked for. A box it holds already moves nothing."""
    field = lay_soil_field(SOIL, paving, 20.0, 0.3, level_at=20.0, size=1.0)
    bed = field.bed
    rng = np.random.default_rng(7)
    bed.ground.z[:] = bed.base - 0.02 * rng.random(bed.base.shape)
    bed.shear[:] = rng.random(bed.shear.shape)   # both components of every node's shear
    bed.sigma[:] = 1e5 * rng.random(bed.base.shape)
    before = {(round((bed.x0 + i * bed.dx) / 0.02), round((bed.y0 + k * bed.dy) / 0.02)):
              (bed.ground.z[i, k], tuple(bed.shear[i, k]), bed.sigma[i, k])
              for i in range(bed.base.shape[0]) for k in range(bed.base.shape[1])}
    assert field.cover(19.8, 20.1, 0.1, 0.5) is None                   # held already
    new = field.cover(20.1, 20.6, -0.2, 0.1, toward=(0.8, -0.6), behind=0.1)
    assert new is field.bed and new is not bed
    x_lo, x_hi, y_lo, y_hi = field.held()
    assert x_lo <= 20.1 and 20.6 <= x_hi and y_lo <= -0.2 and 0.1 <= y_hi
    assert new.base.shape == bed.base.shape                        # the same size
    level = float(paving.height(20.0, 0.0))
    kept = fresh = 0
    for i in range(new.base.shape[0]):
        for k in range(new.base.shape[1]):
            x, y = new.x0 + i * new.dx, new.y0 + k * new.dy
            node = (round(x / 0.02), round(y / 0.02))
            assert abs(x / 0.02 - node[0]) < 1e-6 and abs(y / 0.02 - node[1]) < 1e-6  # the lattice
            if node in before:
                assert (new.ground.z[i, k], tuple(new.shear[i, k]), new.sigma[i, k]) == before[node]
                kept += 1
            else:
                assert new.base[i, k] == pytest.approx(float(paving.height(x, y)) - level, abs=1e-12)
                assert new.ground.z[i, k] == new.base[i, k]
                assert not new.shear[i, k].any() and new.sigma[i, k] == 0.0
                fresh += 1
    assert kept > 100 and fresh > 100


def _drive(model, field, path, dt=1e-3):
    """Step a wheel along ``path(t) -> (x, y, vx, vy, omega, yaw)`` on ``field``; its loads and
    how many times the window moved."""
    stepper = wheel_stepper(model=model, road=field)
    z = model.tyre.unloaded_radius - 0.04
    out, moves, last = [], 0, field.bed
    for k in range(int(round(path.duration / dt))):
        x, y, vx, vy, omega, yaw = path(k * dt)
        loads = stepper.step(k * dt, WheelCentre(x, y, z, vx, vy, 0.0, omega, 0.0, yaw), dt)
        out.append((loads.fz, loads.fx, loads.fy))
        moves += field.bed is not last
        last = field.bed
    return np.array(out), moves


class Bend:
    """8 m round a 5 m radius to the left at 2 m/s from (1, -0.9) (a vehicle's right wheel),
    heading 0.05 rad inside the path (a slip angle: a side force)."""
    duration = 4.0

    def __call__(self, t, v=2.0, radius=5.0):
        th = v * t / radius
        return (1.0 + radius * math.sin(th), -0.9 + radius * (1.0 - math.cos(th)),
                v * math.cos(th), v * math.sin(th), v / 0.6, th + 0.05)


class ThereAndBack:
    """1.5 m forward along x at 1 m/s from (1, 0.4), then 1.5 m back over the rut."""
    duration = 3.0

    def __call__(self, t):
        v = 1.0 if t < 1.5 else -1.0
        x = 1.0 + (t if t < 1.5 else 3.0 - t)
        return x, 0.4, v, 0.0, v / 0.6, 0.0


@pytest.mark.parametrize("path", [Bend(), ThereAndBack()], ids=["bend", "there-and-back"])
def test_a_wheel_on_a_moving_window_has_the_loads_of_the_whole_field(path):
    """The soil wheel (Wong-Reece, its per-node pass for a yawed wheel) round a bend and back
    over its own rut, on a 6 m window that moves with it, against a 30 m field that never moves:
    the same loads sample by sample to 1e-9 of their range (measured 2e-14 round the bend: a
    moved window's nodes are the same nodes, the rut under the wheel kept). Sunk in
    throughout, the side force there round the bend (> 1 kN), the rolling resistance on the
    way back lower than on the way out, where the rut was not yet (the soil's plastic memory:
    a node yields only above its largest pressure so far)."""
    model = make_tyre_model("xzl-16.00R20", "rigid")
    x, y = path(0.0)[:2]
    whole, still = _drive(model, lay_soil_field(SOIL, road_from_spec("flat"), x, y, size=30.0),
                          path)
    moved, moves = _drive(model, lay_soil_field(SOIL, road_from_spec("flat"), x, y, size=6.0),
                          path)
    assert still == 0 and moves >= 1
    assert whole[:, 0].min() > 1e3
    for j, name in enumerate(("FZ", "FX", "FY")):
        np.testing.assert_allclose(moved[:, j], whole[:, j], rtol=0,
                                   atol=1e-9 * max(np.ptp(whole[:, j]), 1.0), err_msg=name)
    n = len(whole) // 2
    if isinstance(path, Bend):
        assert whole[n:, 2].mean() > 1e3
    else:
        out, back = whole[n // 2:n, 1].mean(), -whole[n + n // 2:, 1].mean()
        assert 0.0 < back < out


def test_a_field_too_large_or_too_fine_or_a_step_too_far_is_one_line():
    """Refused in one line: a field above the memory allowed, one finer than its spacing, and
    a host step that would take the wheel further than a field within that memory holds."""
    road = road_from_spec("flat")
    with pytest.raises(InputError, match="above the .* GiB allowed"):
        lay_soil_field(SOIL, road, 0.0, 0.0, size=2000.0)
    with pytest.raises(InputError, match="at least two spacings"):
        lay_soil_field(SOIL, road, 0.0, 0.0, size=0.01)
    field = lay_soil_field(SOIL, road, 0.0, 0.0, size=2.0)
    stepper = wheel_stepper(model=make_tyre_model("xzl-16.00R20", "rigid"), road=field)
    with pytest.raises(InputError, match="the wheels reach in one step .* above the .* GiB allowed"):
        stepper.step(0.0, WheelCentre(0.0, 0.0, 0.6, 1e8, 0.0, 0.0, 1e8 / 0.6), 1e-3)  # 100 km
    assert field.held() == (-1.0, 1.0, -1.0, 1.0)                 # nothing moved


def _convoy(fields, dt=1e-3, v=2.0, gap=3.0, metres=8.0):
    """A front wheel and a rear wheel ``gap`` [m] behind it (a vehicle's axles) driven ``metres``
    along x at ``v``, on ``fields`` (one each, or one shared); each host step steps the front
    wheel, then the rear. Their loads, ``(steps, wheel, FZ/FX)``."""
    model = make_tyre_model("xzl-16.00R20", "rigid")
    steppers = [wheel_stepper(model=model, road=f) for f in fields]
    z = model.tyre.unloaded_radius - 0.04
    out = []
    for k in range(int(round(metres / (v * dt)))):
        row = []
        for stepper, x in zip(steppers, (gap + v * k * dt, v * k * dt)):
            loads = stepper.step(k * dt, WheelCentre(x, 0.5, z, v, 0.0, 0.0, v / z), dt)
            row.append((loads.fz, loads.fx))
        out.append(row)
    return np.array(out)


def test_the_rear_wheel_runs_in_the_front_wheels_rut_on_a_shared_field():
    """Two wheels 3 m apart on one field, stepped one after the other (as a host steps a
    vehicle's wheel models): the field holds both, so its 6 m window, moved with them, gives the
    loads of a 30 m field that never moves (to 1e-9 of their range), and the rear wheel runs
    in the front wheel's rut: at the same height over the same stretch it meets soil already
    sunk and pressed, so it carries less and rolls with less resistance (the multi-pass effect
    of terramechanics; measured FZ 14.8 kN front, 6.6 kN rear; FX 2.08 kN, 0.65 kN). Each on a
    field of its own, the rear wheel meets fresh soil: its loads are the front's, 3 m later
    (to 1e-10 N)."""
    flat = road_from_spec("flat")
    shared = lay_soil_field(SOIL, flat, 1.5, 0.5, size=6.0)
    moved = _convoy([shared, shared])
    still = _convoy([lay_soil_field(SOIL, flat, 1.5, 0.5, size=30.0)] * 2)
    apart = _convoy([lay_soil_field(SOIL, flat, 1.5, 0.5, size=30.0) for _ in range(2)])
    assert shared.held()[0] > 0.0                                  # the window moved on
    for w in range(2):
        for j in range(2):
            np.testing.assert_allclose(moved[:, w, j], still[:, w, j], rtol=0,
                                       atol=1e-9 * np.ptp(still[:, w, j]))
    lag = 1500                                     # 3 m at 2 m/s: the same stretch of soil
    front, rear = still[500:-lag, 0], still[500 + lag:, 1]
    assert rear[:, 0].mean() < 0.9 * front[:, 0].mean()          # less carried in the rut
    assert 0.0 < rear[:, 1].mean() < 0.5 * front[:, 1].mean()     # and less resistance
    np.testing.assert_allclose(apart[500 + lag:, 1], apart[500:-lag, 0], rtol=0,
                               atol=1e-9 * np.ptp(apart[:, 0, 0]))
