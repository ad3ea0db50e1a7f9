"""The three analytic contact models side by side (thesis 2.3.1-2.3.3).

Facts every model must share on simple roads, and the one thing that tells
them apart on an oblique cleat.
"""

import math

import numpy as np
import pytest

from tyrelab.rig.static_press import static_press
from tyrelab.road.grid import RoadGrid
from tyrelab.road.obstacles import Cleat
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.wheel import WheelLoads, loads_table

MODELS = ("point", "volume", "enveloping")
R0 = 0.6715


@pytest.mark.parametrize("stiffness", ["linear", "table"])
def test_flat_plate_same_normal_force_for_all_models(stiffness):
    tyre = load_tyre("xzl-16.00R20", 300e3).with_stiffness(stiffness)
    d = np.array([0.005, 0.02, 0.045, 0.07, 0.09])
    loads = {m: static_press(TyreModel(tyre, m), d, "plate")["load"].to_numpy() for m in MODELS}
    # the law itself, by hand for the linear case: k * d
    if stiffness == "linear":
        np.testing.assert_allclose(loads["point"], tyre.vertical_stiffness * d, rtol=1e-9)
    for m in ("volume", "enveloping"):
        np.testing.assert_allclose(loads[m], loads["point"], rtol=1e-3)
        assert np.all(loads[m] > 0)


def loads_at(model, grid, centre, axis=(0.0, 1.0, 0.0)):
    """(force, contact point, normal, deflection, moment) of the road on a resting wheel."""
    pose = np.zeros(10)
    pose[0:3] = centre
    pose[3:6] = axis
    f = WheelLoads(*loads_table(model.wheel(grid), pose, dt=1e-3)[0])
    return (np.array([f.fx, f.fy, f.fz]), np.array([f.px, f.py, f.pz]),
            np.array([f.nx, f.ny, f.nz]), f.deflection, np.array([f.mx, f.my, f.mz]))


def inclined_plane(mx, my):
    x = np.arange(-4.0, 4.0001, 0.02)
    y = np.arange(-2.0, 2.0001, 0.05)
    X, Y = np.meshgrid(x, y, indexing="ij")
    return RoadGrid(-4.0, -2.0, 0.02, 0.05, 0.3 + mx * X + my * Y)


@pytest.mark.parametrize("model_name", ["volume", "enveloping"])
@pytest.mark.parametrize("mx,my", [(0.12, 0.0), (0.0, 0.08), (-0.1, 0.06)])
def test_inclined_plane_is_its_own_effective_plane(model_name, mx, my):
    grid = inclined_plane(mx, my)
    model = TyreModel(load_tyre("xzl-16.00R20", 300e3), model_name)
    cx, cy, cz = 0.3, 0.1, 0.3 + 0.3 * mx + 0.1 * my + 0.62
    force, point, normal, rho, _ = loads_at(model, grid, (cx, cy, cz))
    n_plane = np.array([-mx, -my, 1.0]) / math.sqrt(1 + mx * mx + my * my)
    np.testing.assert_allclose(normal, n_plane, atol=1e-9)
    # contact point on the plane
    assert point[2] == pytest.approx(0.3 + mx * point[0] + my * point[1], abs=1e-9)
    # rigid-disc deflection: R0 minus the distance, in the wheel plane y = cy, from the
    # centre to the line z = 0.3 + my cy + mx x
    dist = (cz - 0.3 - my * cy - mx * cx) / math.sqrt(1 + mx * mx)
    assert rho == pytest.approx(R0 - dist, abs=1e-9)
    assert np.all(np.isfinite(force))


def test_point_model_on_a_forward_incline_agrees():
    grid = inclined_plane(0.12, 0.0)
    model = TyreModel(load_tyre("xzl-16.00R20", 300e3), "point")
    cz = 0.3 + 0.12 * 0.3 + 0.62
    _, _, normal, rho, _ = loads_at(model, grid, (0.3, 0.1, cz))
    np.testing.assert_allclose(normal, np.array([-0.12, 0, 1]) / math.sqrt(1 + 0.12 ** 2), atol=1e-9)
    assert rho == pytest.approx(R0 - 0.62 / math.sqrt(1 + 0.12 ** 2), abs=1e-9)


def test_oblique_cleat_lateral_force_and_overturning_moment():
    """A 45 deg cleat reaches the left of the tread first (Cleat: positive angle):

    volume and enveloping contact see the left side lifted, tilt the effective
    plane and push the wheel to the right (Fy < 0) with a moment about the
    forward axis; on leaving, the right side is lifted and Fy > 0. The point
    model reads the road in the wheel plane only: Fy and Mx stay zero.
    """
    grid = Cleat(0.05, 0.05, angle=45.0, start=0.0).grid()
    tyre = load_tyre("xzl-16.00R20", 300e3)
    cz = R0 - 0.045
    xs = np.linspace(-0.6, 0.6, 25)
    for name in MODELS:
        model = TyreModel(tyre, name)
        fy = np.array([loads_at(model, grid, (x, 0.0, cz))[0][1] for x in xs])
        fz = np.array([loads_at(model, grid, (x, 0.0, cz))[0][2] for x in xs])
        mx = np.array([loads_at(model, grid, (x, 0.0, cz))[4][0] for x in xs])
        assert np.all(fz > 0) and np.all(np.isfinite(fy))
        if name == "point":
            np.testing.assert_allclose(fy, 0.0, atol=1e-9 * fz.max())
            np.testing.assert_allclose(mx, 0.0, atol=1e-9 * fz.max())
            continue
        # entering: left side up -> pushed right; leaving: pushed left
        assert fy[xs < -0.1].min() < -0.005 * fz.max()
        assert fy[xs > 0.15].max() > 0.005 * fz.max()
        assert np.abs(mx).max() > 0.005 * fz.max() * 0.5  # lever about half a metre


def test_perpendicular_cleat_gives_no_lateral_force_on_an_upright_wheel():
    grid = Cleat(0.05, 0.05, angle=0.0, start=0.0).grid()
    tyre = load_tyre("xzl-16.00R20", 300e3)
    for name in MODELS:
        model = TyreModel(tyre, name)
        for x in (-0.3, -0.1, 0.0, 0.2):
            force, _, normal, _, moment = loads_at(model, grid, (x, 0.0, R0 - 0.045))
            assert abs(force[1]) < 1e-9 * force[2]
            assert abs(moment[0]) < 1e-9 * force[2]


# --- on the trailer (each contact and handling model compiles its loop once, cached on disk;
# the golden traces compile the same ones but enveloping with pac89; a 3 s run then takes 10-30 ms)

@pytest.mark.parametrize("stiffness", ["linear", "table"])
def test_every_model_runs_on_the_built_in_tyres(stiffness):
    import tyrelab
    from importlib import resources
    with resources.as_file(resources.files("tyrelab.tyre").joinpath("data", "hmmwv-pac89.tir")) as p:
        hmmwv = str(p)
    for tyre, handling, load in (("xzl-16.00R20", "none", "LC1"), (hmmwv, "pac89", 15000.0)):
        for name in MODELS:
            df = tyrelab.simulate(tyre=tyre, model=name, road="cleat:50x50", speed=12 / 3.6,
                                  load=load, stiffness=stiffness, handling=handling, duration=3.0)
            fz = df["FZW"].to_numpy()
            assert np.all(np.isfinite(df[["FX", "FY", "FZ", "MX", "MY", "MZ"]].to_numpy()))
            assert np.all(fz >= 0.0)
            assert fz.max() > 1.05 * fz[:200].mean()  # the cleat is felt


def test_trailer_enveloping_peak_below_point_peak_over_the_cleat():
    import tyrelab
    peaks = {}
    for name in MODELS:
        df = tyrelab.simulate(model=name, road="cleat:50x50", speed=12 / 3.6, load="LC1",
                              stiffness="linear", duration=3.0)
        peaks[name] = df["FZW"].max()
    assert peaks["enveloping"] < peaks["point"]
    assert peaks["volume"] < peaks["point"]


@pytest.mark.parametrize("model_name", ["volume", "enveloping"])
def test_inclined_plane_with_a_wheel_heading_across_the_grid(model_name):
    """Heading 30 deg off the grid's x axis (the sampled, not node-aligned, walks)."""
    mx, my = 0.05, -0.07
    grid = inclined_plane(mx, my)
    model = TyreModel(load_tyre("xzl-16.00R20", 300e3), model_name)
    psi = math.radians(30.0)
    axis = (-math.sin(psi), math.cos(psi), 0.0)
    f = np.array([math.cos(psi), math.sin(psi)])  # heading: axis x e_z
    cx, cy = 0.2, -0.1
    cz = 0.3 + mx * cx + my * cy + 0.63
    _, point, normal, rho, _ = loads_at(model, grid, (cx, cy, cz), axis)
    np.testing.assert_allclose(normal, np.array([-mx, -my, 1.0]) / math.sqrt(1 + mx * mx + my * my),
                               atol=1e-9)
    # in the (vertical) wheel plane the road is the line t = A + B s: distance |A| / sqrt(1 + B^2)
    A = 0.3 + mx * cx + my * cy - cz
    B = mx * f[0] + my * f[1]
    assert rho == pytest.approx(R0 - abs(A) / math.sqrt(1 + B * B), abs=1e-9)
    assert point[2] == pytest.approx(0.3 + mx * point[0] + my * point[1], abs=1e-9)
