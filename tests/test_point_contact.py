"""One-point (roller) contact geometry (thesis 2.3.1)."""

import math

import numpy as np
import pytest

from tyrelab.road.grid import RoadGrid
from tyrelab.road.obstacles import Flat, Step
from tyrelab.tyre.contact.point import PointParams, point_contact
from tyrelab.tyre.wheel import pose

R0 = 0.6715


def contact(grid, cx, cy, cz, axis=(0.0, 1.0, 0.0)):
    geo = point_contact(PointParams(R0, grid.dx), grid.surface(), pose(cx, cy, cz, axis))
    return geo.deflection, np.array([geo.px, geo.py, geo.pz]), np.array([geo.nx, geo.ny, geo.nz])


def test_flat_road_contact_below_centre():
    rho, p, n = contact(Flat().grid(), 3.0, 0.2, R0 - 0.042)
    assert rho == pytest.approx(0.042, abs=1e-12)
    np.testing.assert_allclose(p, [3.0, 0.2, 0.0], atol=1e-12)
    np.testing.assert_allclose(n, [0, 0, 1], atol=1e-12)


def plane_grid(slope_x=0.0, slope_y=0.0):
    x = np.arange(-5, 5.001, 0.01)
    y = np.array([-2.0, 2.0])
    X, Y = np.meshgrid(x, y, indexing="ij")
    return RoadGrid(-5.0, -2.0, 0.01, 4.0, X * slope_x + Y * slope_y)


def test_ten_degree_plane_contact_point_and_normal_are_the_planes():
    m = math.tan(math.radians(10.0))
    grid = plane_grid(slope_x=m)
    n_plane = np.array([-math.sin(math.radians(10)), 0.0, math.cos(math.radians(10))])
    # centre at perpendicular distance R0 - 30 mm from the plane, above x = 0.2
    foot = np.array([0.2, 0.0, 0.2 * m])
    centre = foot + (R0 - 0.030) * n_plane
    rho, p, n = contact(grid, *centre)
    assert rho == pytest.approx(0.030, abs=1e-9)
    np.testing.assert_allclose(p, foot, atol=1e-9)       # foot of the perpendicular, not below the centre
    np.testing.assert_allclose(n, n_plane, atol=1e-9)


def test_banked_plane_contact_point_is_on_the_plane_below():
    m = math.tan(math.radians(10.0))
    grid = plane_grid(slope_y=m)
    rho, p, n = contact(grid, 0.0, 0.5, 0.5 * m + R0 - 0.02)
    assert rho == pytest.approx(0.02, abs=1e-9)
    np.testing.assert_allclose(p, [0.0, 0.5, 0.5 * m], atol=1e-9)
    # the roller sees the road only in its own plane: no lateral force
    np.testing.assert_allclose(n, [0, 0, 1], atol=1e-12)


def exact_distance(x, zc, xe, h):
    """Distance from a disc centre (x, zc) to the step profile (0 before xe, h after)."""
    ground = zc if x <= xe else math.hypot(x - xe, zc)
    top = zc - h if x >= xe else math.hypot(x - xe, zc - h)
    return min(ground, top)


@pytest.mark.parametrize("height", [0.05, 0.1, -0.05])
def test_step_geometry_is_exact(height):
    grid = Step(height, start=5.0).grid()
    for x in np.linspace(4.4, 5.6, 601):
        for zc in (R0 + max(height, 0) - 0.03, R0 - 0.01):
            rho, p, n = contact(grid, x, 0.0, zc)
            expected = R0 - exact_distance(x, zc, 5.0, height)
            # out of contact only the sign matters
            assert max(rho, 0.0) == pytest.approx(max(expected, 0.0), abs=1e-9)


def test_contact_point_on_a_step_corner_and_normal_towards_centre():
    grid = Step(0.05, start=5.0).grid()
    x = 5.0 - 0.2
    zc = 0.05 + math.sqrt(R0 ** 2 - 0.2 ** 2) - 0.005   # 5 mm into the corner
    rho, p, n = contact(grid, x, 0.0, zc)
    np.testing.assert_allclose(p, [5.0, 0.0, 0.05], atol=1e-9)
    expect = np.array([x - 5.0, 0.0, zc - 0.05])
    np.testing.assert_allclose(n, expect / np.linalg.norm(expect), atol=1e-9)
    assert n[0] < 0      # the corner pushes the wheel back
