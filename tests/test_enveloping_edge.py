"""The enveloping model as the thesis describes its ADAMS implementation (``enveloping-edge``).

Only the cams on the contact patch's outline enter the effective plane (thesis 4.4: "the
cams were arranged on the outline of the contact patch"; 5.4: "obstacles on the inside of
the contact patch were disregarded"). On a 2D road every row of cams sees the same road,
so the outline is the grid with the front and rear cams weighted ``N_WIDTH`` and the
others 2: the plane is worked by hand with those weights, as ``test_enveloping`` does for
the grid. On a 3D road an obstacle inside the patch must not move the plane at all.
"""

import math

import numpy as np
import pytest

from test_enveloping import AE_, BE_, H, R0, cleat, drop, half_length
from tyrelab.errors import InputError
from tyrelab.road.grid import RoadGrid
from tyrelab.tyre.contact.enveloping import effective_road, enveloping_geometry
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel


def outline_on_cleat_by_hand(xc, cz, n_length=15, n_width=10):
    """Deflection and slope of the outline cams' plane over the cleat [0, H] (2D road)."""
    def cam(u):
        d = 0.0 if 0.0 <= u <= H else min(abs(u), abs(u - H))
        return max(0.0, H - drop(d))
    rho0 = R0 - (cz - cam(xc))          # the centre cam sizes the patch
    ls = 2 * 0.9 * half_length(rho0)     # eq. 2.6
    u = np.linspace(-ls / 2, ls / 2, n_length)
    weight = np.full(n_length, 2.0)      # the two side rows
    weight[[0, -1]] = n_width            # the leading and trailing edge: every row
    w = np.array([cam(xc + ui) for ui in u])
    su = (weight * u * w).sum() / (weight * u * u).sum()
    s_star = su * AE_ ** 2 / math.sqrt(BE_ ** 2 + su ** 2 * AE_ ** 2)
    w0 = (weight * w).sum() / weight.sum() - (su * s_star - drop(s_star))
    return R0 - (cz - w0) / math.sqrt(1 + su * su), su


@pytest.mark.parametrize("xc", [-0.45, -0.2, 0.0, 0.025, 0.1, 0.3])
def test_outline_plane_over_a_cleat_by_hand(xc):
    cz = R0 - 0.05
    table = enveloping_geometry(load_tyre("xzl-16.00R20", 300e3), cleat().grid(), xc, 0.0, cz,
                                cam_layout="outline")
    rho, su = outline_on_cleat_by_hand(xc, cz)
    assert table["deflection"].iloc[0] == pytest.approx(rho, abs=2e-6)
    n = np.array([-su, 0.0, 1.0]) / math.sqrt(1 + su * su)
    np.testing.assert_allclose(table[["nx", "ny", "nz"]].to_numpy()[0], n, atol=1e-5)


def block_road(side=0.06, height=0.02, dx=0.005):
    """A square block, ``side`` wide and long, centred at the origin, on flat ground (3D)."""
    n = 401
    x = (np.arange(n) - n // 2) * dx
    z = np.where((np.abs(x)[:, None] <= side / 2) & (np.abs(x)[None, :] <= side / 2), height, 0.0)
    return RoadGrid(float(x[0]), float(x[0]), dx, dx, z)


def test_an_obstacle_inside_the_patch_is_not_seen_by_the_outline():
    """A 20 mm block under the wheel centre, far from the patch's edges: the outline cams
    stand on flat ground, so the plane is the ground (height and slopes exactly zero);
    every cam of the grid sees it. Thesis 5.4: obstacles inside the patch disregarded."""
    tyre = load_tyre("xzl-16.00R20", 300e3)
    grid = block_road()
    cz = R0 - 0.04
    outline = effective_road(tyre, grid, 0.0, 0.0, cz, cam_layout="outline").iloc[0]
    full = effective_road(tyre, grid, 0.0, 0.0, cz).iloc[0]
    # the block's reach into the outline: the nearest outline cam stands ls/2 ahead, where
    # an ellipse of the XZL's cams has dropped more than the block is high
    ls_half = 0.9 * outline["half_length"]
    assert drop(ls_half - 0.03) > 0.02 and outline["half_width"] > 0.03
    assert (outline["height"], outline["slope"], outline["camber"]) == (0.0, 0.0, 0.0)
    assert full["height"] > 1e-3


@pytest.mark.parametrize("n_width", [2, 10])
def test_two_cams_along_the_patch_are_all_on_its_outline(n_width):
    """With two cams along the patch every cam is a leading or trailing edge cam, so the
    outline is the grid, on a 3D road too (an identity, checked to the last bit)."""
    tyre = load_tyre("xzl-16.00R20", 300e3)
    grid = block_road(side=0.3)
    xs = np.linspace(-0.5, 0.5, 41)
    a = effective_road(tyre, grid, xs, 0.05, R0 - 0.04, n_length=2, n_width=n_width)
    b = effective_road(tyre, grid, xs, 0.05, R0 - 0.04, n_length=2, n_width=n_width,
                       cam_layout="outline")
    np.testing.assert_array_equal(a.to_numpy(), b.to_numpy())


def test_the_edge_model_is_the_outline_layout_and_refuses_another():
    tyre = load_tyre("xzl-16.00R20", 300e3)
    grid = cleat().grid()
    edge = TyreModel(tyre, "enveloping-edge").contact_params(grid)
    assert edge.outline_only and not TyreModel(tyre, "enveloping").contact_params(grid).outline_only
    with pytest.raises(InputError, match="cam_layout"):
        TyreModel(tyre, "enveloping-edge", options={"cam_layout": "grid"}).contact_params(grid)
    with pytest.raises(InputError, match="cam_layout must be one of grid, outline"):
        effective_road(tyre, grid, 0.0, cam_layout="edges")


def test_outline_plane_on_a_3d_road_from_its_cams_one_by_one():
    """On a road that varies across (random heights every 10 mm), the outline's plane is the
    least-squares plane through the heights of the outline cams alone: each cam's height
    taken by itself (a 1 x 1 layout at the cam's place), the cams placed by eq. 2.6 and the
    patch's width, the plane's slopes fitted here. Fails if an inner row's two outline cams
    are rested at other places than the grid's ends (the row's first and last cam)."""
    tyre = load_tyre("xzl-16.00R20", 300e3)
    rng = np.random.default_rng(3)
    dx = 0.01
    z = np.cumsum(rng.normal(0.0, 0.002, (301, 121)), axis=0) + rng.normal(0.0, 0.004, (301, 121))
    grid = RoadGrid(-1.5, -0.6, dx, dx, z - z[150, 60])
    cz = R0 - 0.06
    for xc in (-0.15, 0.0, 0.137):
        got = effective_road(tyre, grid, xc, 0.0, cz, cam_layout="outline").iloc[0]
        n_length, n_width = 15, 10
        ls = 2 * 0.9 * got["half_length"]                         # eq. 2.6
        u = np.linspace(-ls / 2, ls / 2, n_length)
        v = np.linspace(-got["half_width"], got["half_width"], n_width)
        uu, vv = np.meshgrid(u, v, indexing="ij")
        on = np.zeros(uu.shape, bool)
        on[[0, -1], :] = True                                     # leading and trailing edge
        on[:, [0, -1]] = True                                     # the two sides
        w = np.array([cam_heights_at(tyre, grid, xc + a, b) for a, b in zip(uu[on], vv[on])])
        slope = (uu[on] * w).sum() / (uu[on] ** 2).sum()
        camber = (vv[on] * w).sum() / (vv[on] ** 2).sum()
        assert on.sum() == 46 and abs(slope) > 1e-3 and abs(camber) > 1e-3
        assert got["slope"] == pytest.approx(slope, abs=1e-12)
        assert got["camber"] == pytest.approx(camber, abs=1e-12)
        s_star = slope * AE_ ** 2 / math.sqrt(BE_ ** 2 + slope ** 2 * AE_ ** 2)  # touch point
        assert got["height"] == pytest.approx(w.mean() - (slope * s_star - drop(s_star)), abs=1e-6)


def cam_heights_at(tyre, grid, x, y):
    """The height of one cam (a 1 x 1 layout) at (x, y), heading +x."""
    return effective_road(tyre, grid, x, y, R0 - 0.06, n_width=1, n_length=1)["height"].iloc[0]
