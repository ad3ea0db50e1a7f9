"""3D equivalent volume contact (thesis 2.3.2, 4.3, Table 4-1)."""

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import quad

from tyrelab.errors import InputError
from tyrelab.road.grid import RoadGrid
from tyrelab.road.obstacles import Flat, Step
from tyrelab.tyre.contact.shape import (carcass_discs, disc_intersection, profile_breaks,
                                        resample_shape, segment_area, segment_depth)
from tyrelab.tyre.contact.volume import volume_geometry, volume_params
from tyrelab.tyre.library import load_tyre

R = 0.6715


def segment(depth, r=R):
    """Circular segment area by hand: r^2 acos((r-d)/r) - (r-d) sqrt(2 r d - d^2)."""
    return r * r * math.acos((r - depth) / r) - (r - depth) * math.sqrt(2 * r * depth - depth ** 2)


def step_area_by_quadrature(height_above_low, step, xs, dx, r=R, moment=False):
    """Area (or first moment along s) of the disc below the gridded step, numerically:
    road 0 up to xs - dx, a straight ramp over the grid cell [xs - dx, xs], ``step`` after."""
    def column(s):
        c = math.sqrt(max(r * r - s * s, 0.0))
        road = step * min(max((s - xs + dx) / dx, 0.0), 1.0)
        return max(c - (height_above_low - road), 0.0) * (s if moment else 1.0)
    return quad(column, -r, r, points=[xs - dx, xs], limit=400, epsabs=1e-14, epsrel=1e-12)[0]


def test_segment_depth_inverts_the_segment_area():
    for d in (1e-5, 0.003, 0.05, 0.12, 0.4, 0.9, 1.2):
        assert segment_area(d, R) == pytest.approx(segment(d), rel=1e-12)
        assert segment_depth(segment(d), R) == pytest.approx(d, rel=1e-9)


def step_grid(step=0.05, xs=0.0, dx=0.005):
    x = np.arange(-2.0, 2.0 + dx / 2, dx)
    z = np.where(x >= xs - 1e-12, step, 0.0)
    return RoadGrid(-2.0, -1.0, dx, 2.0, np.column_stack([z, z]))


@pytest.mark.parametrize("xs", [0.0, 0.1, -0.23, 0.31])
def test_disc_over_a_step_has_the_analytic_area(xs):
    """With the step edge under the centre the area is half of each segment plus the
    grid cell's ramp (a triangle dx x step), exactly."""
    grid = step_grid(0.05, xs)
    params = volume_params(load_tyre(), grid)
    zc = 0.62  # centre 0.62 m above the low road: 51.5 mm below it, 1.5 mm into the top
    area, ms, mq = disc_intersection(grid.surface(), params.profile_breaks, 0.005, R, 0.0, 0.0,
                                     zc, 1.0, 0.0, 1.0, -R, R)
    if xs == 0.0:
        exact = 0.5 * segment(R - zc) + 0.5 * segment(R - zc + 0.05) + 0.5 * 0.005 * 0.05
        assert area == pytest.approx(exact, rel=1e-12)
    assert area == pytest.approx(step_area_by_quadrature(zc, 0.05, xs, 0.005), rel=1e-9)
    assert ms == pytest.approx(step_area_by_quadrature(zc, 0.05, xs, 0.005, moment=True),
                               rel=1e-8, abs=1e-12)


def test_equal_discs_take_the_equivalent_flat_depth_over_a_step():
    """Square section, perpendicular step: every disc cuts the same area, so the
    deflection is the depth of the flat cut with that area (segment inverted)."""
    tyre = replace(load_tyre(), shape=None)
    grid = step_grid(0.05, 0.0)
    zc = 0.62
    geo = volume_geometry(tyre, grid, 0.0, 0.0, zc).iloc[0]
    area = 0.5 * segment(R - zc) + 0.5 * segment(R - zc + 0.05) + 0.5 * 0.005 * 0.05
    # depth of the flat cut with this area, by bisection on the hand formula
    lo, hi = 0.0, 0.2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if segment(mid) < area else (lo, mid)
    assert geo.deflection == pytest.approx(lo, abs=1e-9)
    # the step pushes the wheel back: the normal leans against the direction of travel
    assert geo.nx < 0.0 and geo.nz > 0.0
    assert 0.0 - 1e-12 < geo.deflection and np.all(np.isfinite(geo.to_numpy()))


def test_flat_road_deflection_and_normal_for_the_shaped_tyre():
    tyre = load_tyre()
    for grid in (Flat().grid(), step_grid(0.05, 5.0)):  # the second is flat where the wheel is
        geo = volume_geometry(tyre, grid, 0.4, 0.1, R - 0.063).iloc[0]
        assert geo.deflection == pytest.approx(0.063, abs=1e-12)
        np.testing.assert_allclose(geo[["px", "py", "pz", "nx", "ny", "nz"]].to_numpy(float),
                                   [0.4, 0.1, 0.0, 0.0, 0.0, 1.0], atol=1e-12)


def test_wheel_above_the_road_has_no_contact():
    grid = step_grid(0.05, 0.0)
    geo = volume_geometry(load_tyre(), grid, 0.0, 0.0, R + 0.06).iloc[0]
    assert geo.deflection <= 0.0


def test_carcass_discs_follow_table_4_1():
    tyre = load_tyre()
    offsets, radii, widths = carcass_discs(tyre)
    assert widths.sum() == pytest.approx(tyre.width)
    np.testing.assert_allclose(offsets, -offsets[::-1])
    np.testing.assert_allclose(radii, radii[::-1])
    # 9 table points, resampled to width ratios 0, 0.125, ..., 1 -> 8 discs per half.
    # The outermost disc spans 0.875-1: the table at 0.875 lies between (0.8676, 0.9417)
    # and (0.8950, 0.8834); at 1.0 it is 0.7669; the disc takes the mean of its ends.
    assert offsets.size == 16
    assert radii[8] == pytest.approx(R)
    at_0875 = 0.9417 + (0.875 - 0.8676) / (0.8950 - 0.8676) * (0.8834 - 0.9417)
    assert radii[-1] == pytest.approx(R * 0.5 * (at_0875 + 0.7669), rel=1e-12)
    assert offsets[-1] == pytest.approx(0.9375 * tyre.width / 2)


def test_square_section_and_resampling():
    tyre = replace(load_tyre(), shape=None)
    offsets, radii, widths = carcass_discs(tyre)
    np.testing.assert_allclose(radii, R)
    table = resample_shape(np.array([[1.0, 0.0], [0.9, 0.8], [0.8, 1.0]]))
    np.testing.assert_allclose(table[:, 1], [0.0, 0.5, 1.0])
    np.testing.assert_allclose(table[:, 0], [1.0, 1.0 - 0.1 * 0.5 / 0.8, 0.8])
    with pytest.raises(InputError):
        resample_shape(np.ones((11, 2)))
    with pytest.raises(InputError):
        volume_params(load_tyre(), Flat().grid(), bogus=1)


def test_profile_breaks_mark_the_kinks():
    z = np.array([0, 0, 0, 1, 2, 2, 2], float)
    nxt = profile_breaks(np.column_stack([z, z]))
    # slopes 0 0 1 1 0 0: kinks at nodes 2 and 4 (and the last node)
    np.testing.assert_array_equal(nxt, [2, 2, 4, 4, 6, 6, 6])
    assert profile_breaks(np.array([[0.0, 1.0], [0.0, 0.0]])) is None


def test_a_step_lifts_the_volume_model_gradually_without_nan():
    tyre = load_tyre()
    grid = Step(0.05, start=0.0).grid()
    table = volume_geometry(tyre, grid, np.linspace(-0.8, 0.8, 81), 0.0, R - 0.05)
    assert np.all(np.isfinite(table[["deflection", "px", "py", "pz", "nx", "ny", "nz"]].to_numpy()))
    rho = table["deflection"].to_numpy()
    assert rho[0] == pytest.approx(0.05, abs=1e-12) and rho[-1] == pytest.approx(0.10, abs=1e-12)
    assert np.all(np.diff(rho) >= -1e-12)
