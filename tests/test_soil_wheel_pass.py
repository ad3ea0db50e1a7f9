"""The soil's pass under a wheel: its row-wise form (a wheel rolling straight, whose nodes along
a row share the surface above them and, in the same state, their stresses) against the
node-by-node form (any wheel), which a wheel yawed by 1e-9 rad takes."""

from __future__ import annotations

import numpy as np
import pytest

from tyrelab.rig.single_wheel import single_wheel
from tyrelab.road.grid import RoadGrid
from tyrelab.road.soil import load_soil
from tyrelab.road.soil.scm import soil_bed
from tyrelab.road.soil.wheel import wheel_loads
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel

RADIUS, WIDTH, YAW = 0.78, 0.4, 1e-9
FIELDS = ("fx", "fz", "my", "area", "normal", "dnormal")


def _rutted():
    """A bed a rigid wheel has driven over at slip 0.2 (a straight rut: uniform rows)."""
    _, bed = single_wheel(TyreModel(load_tyre(), "rigid"), "sandy-loam", 23.3e3, 1.0, slip=0.2,
                          duration=1.5, length=4.0, progress=False, return_bed=True)
    return bed


def _rough():
    """A fresh bed over a random rough surface (no two neighbours alike)."""
    rng = np.random.default_rng(7)
    grid = RoadGrid(-1.0, -1.0, 0.02, 0.02, 0.01 * rng.standard_normal((201, 101)))
    return soil_bed(load_soil("lete-sand")[0], grid)


def _worn():
    """A level bed whose nodes differ only in their rut, their undisturbed height or their mobilized
    shear, each taking one of three values (so neighbours are now alike, now not): ruts of 0, 29 and
    29.5 mm, so a wheel 30 mm deep reloads some nodes elastically and presses others into
    yield."""
    rng = np.random.default_rng(11)
    h0 = 0.0005 * rng.integers(0, 2, (201, 101))      # the surface the same, the rut 0.5 mm apart
    bed = soil_bed(load_soil("sandy-loam")[0], RoadGrid(-1.0, -1.0, 0.02, 0.02, h0))
    bed.ground.z[:] = -np.array([0.0, 0.029, 0.0295])[rng.integers(0, 3, bed.h0.shape)]
    bed.shear[:, ::2, 0] = 0.02 * rng.integers(0, 3, bed.shear[:, ::2, 0].shape)
    return bed


_rutted.depth, _rough.depth, _worn.depth = 0.03, 0.03, 0.0012   # (no surface at the flat)


def _pass(bed, x, z, flat, yaw, update):
    """One step's loads of a wheel centred at (x, 0.01, z) rolling forward at 1 m/s, slip 0.2.
    (The centre sits half a cell off the nodes across, so no node lies on the wheel's edge.)"""
    ax, ay = -np.sin(yaw), np.cos(yaw)
    loads = wheel_loads(bed, x, 0.01, z, ax, ay, 0.0, np.cos(yaw), np.sin(yaw), 0.0,
                        1.0 / (0.8 * RADIUS), RADIUS, WIDTH, flat, 1e-3, update)
    return {f: getattr(loads, f) for f in FIELDS}


@pytest.mark.parametrize("make", [_rutted, _rough, _worn])
@pytest.mark.parametrize("flat", [10.0, RADIUS - 0.03])
def test_rolling_straight_the_rows_give_what_the_nodes_give(make, flat):
    """The rigid wheel and a wheel cut flat, below the surface under it (its median; in the
    middle of the rut, on the rutted bed): straight and yawed by 1e-9 rad the loads agree to 1e-7
    (relative to the largest force) and so do the nodes' states after a step."""
    bed = make()
    rows = np.nonzero(bed.rut.max(axis=1) > 0)[0]
    i = int(rows.mean()) if rows.size else bed.h0.shape[0] // 2
    x = bed.x0 + i * bed.dx
    under = np.abs(bed.y0 + bed.dy * np.arange(bed.h0.shape[1]) - 0.01) < 0.5 * WIDTH
    z = np.median(bed.ground.z[i, under]) - make.depth + (RADIUS if flat > RADIUS else flat)
    straight, yawed = bed.fresh_copy(), bed.fresh_copy()
    a = _pass(straight, x, z, flat, 0.0, True)
    b = _pass(yawed, x, z, flat, YAW, True)
    assert a["fz"] > 1e3 and a["area"] > 0.05                  # a real contact
    scale = max(abs(a["fx"]), abs(a["fz"]))
    for f in FIELDS:
        size = scale * (RADIUS if f == "my" else 1.0)
        if f == "area":
            size = 1.0
        if f == "dnormal":
            size = max(abs(a[f]), 1.0)
        assert a[f] == pytest.approx(b[f], abs=1e-7 * size), f
    np.testing.assert_allclose(straight.ground.z, yawed.ground.z, rtol=0, atol=1e-9)
    np.testing.assert_allclose(straight.shear, yawed.shear, rtol=0, atol=1e-9)
