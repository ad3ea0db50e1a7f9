"""The soil bed behind the terrain interface: its queries, its answer to a tread block, and the
ring (which reads the ground through the interface only) rolling on it."""

from __future__ import annotations

import numba as nb
import numpy as np
import pytest

from tyrelab.rig.single_wheel import single_wheel
from tyrelab.road.grid import RoadGrid
from tyrelab.road.soil.params import Soil
from tyrelab.road.soil.scm import soil_bed
from tyrelab.road.soil.terrain import soil_contact
from tyrelab.road.terrain import terrain_height, terrain_is_rigid, terrain_kind, terrain_names
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel

LOAD, SPEED = 23.3e3, 1.0


@nb.njit
def _heights(bed, xs, ys):
    out = np.empty(xs.size)
    for k in range(xs.size):
        out[k] = terrain_height(bed, xs[k], ys[k])
    return out, terrain_is_rigid(bed)


def test_the_soil_is_a_deformable_terrain_whose_surface_is_the_rut():
    """Registered as "soil", not rigid; after a rigid wheel has passed, the interface's height
    is the undisturbed height less the rut at every node, and bilinear between nodes
    (numpy's interpolation of the rut, written here)."""
    assert "soil" in terrain_names() and terrain_kind("soil").rigid is False
    _, bed = single_wheel(TyreModel(load_tyre(), "rigid"), "sandy-loam", LOAD, SPEED, slip=0.2,
                          duration=1.0, length=4.0, progress=False, return_bed=True)
    rut = bed.rut
    assert rut.max() > 0.03                                   # the wheel left a rut
    i, k = np.unravel_index(np.argmax(rut), rut.shape)
    xs = bed.x0 + bed.dx * np.array([i, i, i + 0.5, i + 0.25])
    ys = bed.y0 + bed.dy * np.array([k, k + 3, k, k + 0.5])
    h, rigid = _heights(bed, xs, ys)
    assert not rigid
    surface = bed.h0 - rut
    expected = [surface[i, k], surface[i, k + 3], 0.5 * (surface[i, k] + surface[i + 1, k]),
                np.mean([[surface[i, k], surface[i, k + 1]]]) * 0.75
                + np.mean([[surface[i + 1, k], surface[i + 1, k + 1]]]) * 0.25]
    assert h == pytest.approx(expected, abs=1e-12)


def test_a_block_and_a_linear_soil_in_series_share_the_force():
    """A block of secant stiffness kb pressed p into a fresh linear soil (n = 1, kc = 0: sigma =
    kphi s, yielding at once under a far stiffer elastic line): the soil sinks by
    Delta = kb p / (kb + kphi A) and carries kb (p - Delta); the node keeps Delta less the
    elastic rebound sigma / K_e; the shear is capped at A (c + sigma tan phi)."""
    soil = Soil(n=1.0, kc=0.0, kphi=2e6, cohesion=1e3, friction_angle=np.radians(30.0),
                janosi_k=0.01, elastic_stiffness=1e9, damping=0.0)
    bed = soil_bed(soil, RoadGrid(-1.0, -1.0, 0.02, 0.02, np.zeros((101, 101))))
    area, p, fn = 0.04 * 0.04, 0.01, 500.0
    kb = fn / p
    carried, f1, f2 = soil_contact(bed, 0.0, 0.0, p, area, 0.0, 0.0, fn, 3000.0, 0.0, 1e-3)
    delta = kb * p / (kb + soil.kphi * area)
    assert carried == pytest.approx(kb * (p - delta), rel=1e-6)
    sigma = soil.kphi * delta
    assert bed.rut[50, 50] == pytest.approx(delta - sigma / soil.elastic_stiffness, rel=1e-6)
    assert f1 == pytest.approx(area * (soil.cohesion + sigma * np.tan(soil.friction_angle)), rel=1e-9)
    assert f2 == 0.0


def test_the_ring_on_soil_agrees_with_the_flexible_wheel():
    """Two independent ways of a flexible tyre on soil -- the ring's tread blocks each in series
    with the soil under them, and the analytic flexible wheel (the vertical law in series
    with the flattened footprint) -- carry the dead weight, pull within 10 % of each other
    on LETE sand at s = 0.2, and both sink less than the rigid wheel. From s = 0 their pulls
    rise alike, over the soil's shear displacement (Janosi's K): the ring's rise to s = 0.1
    and 0.2 within 10 % of the flexible wheel's (2 and 7 % measured), to s = 0.02 below it,
    its blocks' own shear in series softening it (by about a fifth at the patch's stress),
    but above half of it. When the blocks met the soil with their own stiffness only, the
    soil's strength a mere cap, the ring's rise to 0.02 was 2.9 times the flexible wheel's,
    to 0.1 1.4 times: its pull all but saturated by s = 0.05."""
    steady = {}
    for model, slips in (("ring", (0.0, 0.02, 0.1, 0.2)), ("point", (0.0, 0.02, 0.1, 0.2)),
                         ("rigid", (0.2,))):
        for slip in slips:
            run = single_wheel(TyreModel(load_tyre(), model), "lete-sand", LOAD, SPEED, slip=slip,
                               duration=2.0, progress=False)
            part = run[run["RUNTIME"] > 1.0]
            assert (run["FZW"] >= 0).all() and not run.isna().any().any()
            steady[model, slip] = {c: part[c].mean() for c in ("FX", "FZ", "SINKAGE")}
    assert steady["ring", 0.2]["FZ"] == pytest.approx(LOAD, rel=0.01)
    assert steady["ring", 0.2]["FX"] == pytest.approx(steady["point", 0.2]["FX"], rel=0.10)
    assert max(steady["ring", 0.2]["SINKAGE"], steady["point", 0.2]["SINKAGE"]) < \
        steady["rigid", 0.2]["SINKAGE"]

    def rise(model, slip):
        return steady[model, slip]["FX"] - steady[model, 0.0]["FX"]

    for slip in (0.1, 0.2):
        assert rise("ring", slip) == pytest.approx(rise("point", slip), rel=0.10)
    assert 0.5 * rise("point", 0.02) < rise("ring", 0.02) < rise("point", 0.02)


def test_the_tester_measures_every_models_slip_as_it_prescribes_it():
    """``LONGSLIP`` is the tester's slip from the wheel's spin and the model's ``R_e``, whatever
    the model: at a prescribed slip it is that slip at every sample, to rounding, for the rigid
    wheel, the point model and the ring (which, with no slip of its own, wrote 0)."""
    for model in ("rigid", "point", "ring"):
        run = single_wheel(TyreModel(load_tyre(), model), "lete-sand", LOAD, SPEED, slip=0.01,
                           duration=0.3, progress=False)
        assert run["LONGSLIP"].to_numpy() == pytest.approx(0.01, abs=1e-12), model


def test_the_ring_under_the_torque_of_a_slip_finds_that_slip():
    """Given the torque the prescribed s = 0.01 took, the free ring settles at that slip, to
    0.001, with its pull to 1 % (as the rigid wheel does: test_soil_rigid_wheel.py). Under
    9.1 kN m, past what s = 0.4 takes (8.8 kN m), it turns at a slip near 0.7 with the soil's
    moment on it within 2 % of the torque (1 % measured). At the 1 ms step, before the ring took
    its rim's spin change at once (test_ring_rim), its rim and belt wound each other up there:
    the moment swung by +-450 kN m, the spin from -16 to 71 rad/s."""
    tm = TyreModel(load_tyre(), "ring")
    kw = dict(duration=3.0, progress=False)
    held = single_wheel(tm, "lete-sand", LOAD, SPEED, slip=0.01, **kw)
    held = held[held["RUNTIME"] >= 1.5]
    free = single_wheel(tm, "lete-sand", LOAD, SPEED, torque=float(held["TORQUE"].mean()), **kw)
    free = free[free["RUNTIME"] >= 1.5]
    assert free["LONGSLIP"].mean() == pytest.approx(0.01, abs=0.001)
    assert free["FX"].mean() == pytest.approx(held["FX"].mean(), rel=0.01)
    grip = single_wheel(tm, "lete-sand", LOAD, SPEED, torque=9100.0, **kw)
    grip = grip[grip["RUNTIME"] >= 1.5]
    assert (-grip["MY"]).to_numpy() == pytest.approx(9100.0, rel=0.02)
    assert ((grip["LONGSLIP"] > 0.0) & (grip["LONGSLIP"] < 1.0)).all()
