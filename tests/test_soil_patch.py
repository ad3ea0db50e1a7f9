"""The soil's active patch (tyrelab.road.soil.patch): a run longer than the patch holds only a
few metres of soil at once, and drives as it would over the whole bed."""

from __future__ import annotations

import numpy as np
import pytest

from tyrelab.rig.quarter_vehicle import QuarterVehicle
from tyrelab.rig.registry import G
from tyrelab.rig.single_wheel import single_wheel
from tyrelab.road.soil import patch
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel

LOAD, SPEED, DURATION = 23.3e3, 2.0, 6.0      # a 15 m bed: 12 m driven, 3 m of margins


def _wheel_run(model, length=None, monkeypatch=None):
    if length is not None:
        monkeypatch.setattr(patch, "PATCH_LENGTH", length)
    return single_wheel(TyreModel(load_tyre(), model), "sandy-loam", LOAD, SPEED, slip=0.3,
                        duration=DURATION, progress=False, return_bed=True)


@pytest.mark.parametrize("model", ["rigid", "point"])
@pytest.mark.parametrize("length", [6.0, 3.0])
def test_a_moving_patch_drives_as_the_whole_bed(model, length, monkeypatch):
    """Held 6 m at a time (the patch moves on four times) or 3 m (too short for a chunk: it
    grows to what a chunk needs), the single-wheel run's pull, load, torque and sinkage are
    those over the whole 15 m bed to 1e-9 of their range, and the rut the patch holds at the
    end is the whole bed's at the same nodes to 1e-12 m."""
    whole, whole_bed = _wheel_run(model)
    moved, bed = _wheel_run(model, length, monkeypatch)
    assert whole_bed.h0.shape[0] == 751 and bed.h0.shape[0] < 0.5 * whole_bed.h0.shape[0]
    for c in ("FX", "FZ", "MY", "SINKAGE"):
        a, b = whole[c].to_numpy(), moved[c].to_numpy()
        np.testing.assert_allclose(b, a, rtol=0, atol=1e-9 * np.ptp(a), err_msg=c)
    first = int(round((bed.x0 - whole_bed.x0) / bed.dx))
    assert first > 0 and bed.rut.max() > 0.02
    np.testing.assert_allclose(bed.rut, whole_bed.rut[first:first + bed.h0.shape[0]], rtol=0,
                               atol=1e-12)


def test_the_quarter_vehicle_drives_a_moving_patch_as_the_whole_bed(monkeypatch):
    """The quarter vehicle at 3 m/s over 9 m of sandy loam: its hub's travel and its wheel
    load with the patch held 5 m at a time are those over the whole bed to 1e-9 of their
    range."""
    tm = TyreModel(load_tyre(), "point")
    mu = tm.tyre.wheel_mass
    quarter = QuarterVehicle(tm, sprung_mass=LOAD / G - mu, unsprung_mass=mu)
    whole = quarter.run("flat", 3.0, 3.0, terrain="sandy-loam", progress=False)
    monkeypatch.setattr(patch, "PATCH_LENGTH", 5.0)
    moves = []
    follow = patch.SoilPatch.follow

    def counted(self, x_behind, x_ahead):
        record = follow(self, x_behind, x_ahead)
        moves.append(record is not None)
        return record

    monkeypatch.setattr(patch.SoilPatch, "follow", counted)
    moved = quarter.run("flat", 3.0, 3.0, terrain="sandy-loam", progress=False)
    assert sum(moves) >= 2                                   # it did move on
    for c in ("Z_WC", "FZ", "FX"):
        a, b = whole[c].to_numpy(), moved[c].to_numpy()
        np.testing.assert_allclose(b, a, rtol=0, atol=1e-9 * np.ptp(a), err_msg=c)
