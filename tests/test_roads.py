"""Obstacle roads and their compiled grid form."""

import math

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.road.obstacles import Cleat, Pothole, Step, TrapezoidalBump
from tyrelab.road.spec import road_from_spec


def test_cleat_section():
    c = Cleat(0.05, 0.05, start=5.0)
    assert c.height(4.999, 0.0) == 0.0
    assert c.height(5.0, 0.0) == 0.05
    assert c.height(5.05, 1.9) == 0.05
    assert c.height(5.0501, 0.0) == 0.0


def test_oblique_cleat_reaches_left_side_first():
    c = Cleat(0.05, 0.05, angle=45.0, start=5.0)
    # at y = 1 m the leading edge is 1 m earlier (tan 45 = 1)
    assert c.height(4.01, 1.0) == 0.05
    assert c.height(4.01, -1.0) == 0.0
    # width across the cleat is 50 mm: along x it is 50 / cos 45 mm
    assert c.height(5.0 + 0.05 / math.cos(math.pi / 4) - 1e-4, 0.0) == 0.05


def test_bevel_cuts_the_corners():
    c = Cleat(0.05, 0.05, bevel=0.01, start=0.0)
    assert c.height(0.0, 0.0) == pytest.approx(0.04)
    assert c.height(0.005, 0.0) == pytest.approx(0.045)
    assert c.height(0.025, 0.0) == pytest.approx(0.05)


@pytest.mark.parametrize("road, corners", [
    (Step(0.05, start=5.0), [(5.0, 0.05)]),
    (Step(-0.05, start=5.0), [(5.0, 0.0)]),
    (Cleat(0.0763, 0.0763, start=5.0), [(5.0, 0.0763), (5.0763, 0.0763)]),
    (Cleat(0.05, 0.05, start=0.0), [(0.0, 0.05), (0.05, 0.05)]),
    (Cleat(0.038, 0.038, start=-0.019), [(-0.019, 0.038), (0.019, 0.038)]),
    (Pothole(0.05, 0.3, 0.5, start=5.0), [(5.0, 0.0), (5.3, 0.0)]),
])
def test_grid_keeps_the_corners_a_wheel_rolls_over(road, corners):
    """Bilinear grids are exact only at nodes: the upper corners of an edge must be
    nodes, or the compiled road rounds them off (a 76.3 mm cleat on a plain 5 mm
    grid would lose its trailing corner)."""
    g = road.grid()
    for x, h in corners:
        assert g.height(x, 0.1) == pytest.approx(h, abs=1e-12)


def test_trapezoid_grid_is_exact_everywhere():
    road = TrapezoidalBump(0.15, 0.6, 0.5)
    g = road.grid()
    x = np.linspace(4.0, 8.0, 10001)
    np.testing.assert_allclose(g.height(x, 0.3), road.height(x, 0.3), atol=1e-12)


def test_outside_the_grid_the_edge_continues():
    g = Step(0.05, start=5.0).grid()
    assert g.height(-100.0, 0.0) == 0.0
    assert g.height(1000.0, 0.0) == pytest.approx(0.05)


@pytest.mark.parametrize("spec, kind, attrs", [
    ("cleat:50x50", Cleat, {"width": 0.05, "cleat_height": 0.05, "angle": 0.0}),
    ("cleat:100x100@45", Cleat, {"width": 0.1, "angle": 45.0}),
    ("cleat:50x50@45/5", Cleat, {"bevel": 0.005}),
    ("bump:150", TrapezoidalBump, {"bump_height": 0.15}),
    ("bump:150x500x300", TrapezoidalBump, {"ramp_length": 0.5, "top_length": 0.3}),
    ("step:-50", Step, {"step_height": -0.05}),
    ("pothole:50x300x400", Pothole, {"depth": 0.05, "length": 0.3, "width": 0.4}),
])
def test_road_names(spec, kind, attrs):
    road = road_from_spec(spec)
    assert isinstance(road, kind)
    for k, v in attrs.items():
        assert getattr(road, k) == pytest.approx(v)


@pytest.mark.parametrize("spec", ["nowhere", "cleat:50", "cleat:axb", "cleat:50x50@x", "step:0",
                                  "cleat:-5x50", "missing.crg"])
def test_bad_road_names(spec):
    with pytest.raises(InputError):
        road_from_spec(spec)
