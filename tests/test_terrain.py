"""The terrain interface (tyrelab.road.terrain): the ground as the compiled models see it.

Three kinds of facts. The registry: the rigid grid is registered as "rigid", an
unknown name lists the known ones. The grid's side: every interface function
agrees with the grid's own direct queries and with bilinear interpolation done
here by hand. Another kind of ground: a toy terrain record -- an analytic plane,
not a grid -- registered the way ARCHITECTURE.md says ("Adding a terrain"), takes
every contact model unchanged (none reads grid data: numba could not compile them
otherwise) and gives the analytic contact on it; its friction scale halves the
tangential forces; as a ground that says it is not rigid, it answers the tyre
through its contact function. The toy runs in a subprocess with its own compile
cache, so its record type never enters the package's cache index.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np
import pytest
from kept_cache import kept_home, run_driver

from tyrelab.errors import InputError
from tyrelab.road.grid import RoadGrid, RoadSurface, local_zmax, road_height
from tyrelab.road.terrain import (TerrainKind, terrain_block_max, terrain_blocks, terrain_contact,
                                  terrain_friction, terrain_height, terrain_height_gradient,
                                  terrain_is_rigid, terrain_kind, terrain_line_height, terrain_lines,
                                  terrain_names, terrain_penetration, terrain_range, terrain_row,
                                  terrain_row_height, terrain_zmax)

R0 = 0.6715


def test_the_grid_is_the_rigid_terrain_and_unknown_names_list_the_known_ones():
    assert "rigid" in terrain_names()
    kind = terrain_kind("rigid")
    assert kind.record is RoadSurface and kind.rigid and kind.description
    with pytest.raises(InputError) as err:
        terrain_kind("swamp")
    assert "swamp" in str(err.value) and "rigid" in str(err.value)


def test_a_ground_that_deforms_must_say_how_it_answers_the_tyre():
    rigid = terrain_kind("rigid")
    fields = {k: getattr(rigid, k) for k in ("height", "height_gradient", "penetration", "zmax",
                                             "range", "lines", "row", "line_height", "blocks",
                                             "block_max")}
    with pytest.raises(ValueError, match="contact"):
        TerrainKind("soil", RoadSurface, rigid=False, **fields)


# --- the grid's side of the interface -------------------------------------------------

@nb.njit
def _point_queries(road, xs, ys, zs, out):
    for k in range(xs.shape[0]):
        x, y = xs[k], ys[k]
        h, gx, gy = terrain_height_gradient(road, x, y)
        p, hp, gxp, gyp = terrain_penetration(road, x, y, zs[k])
        fn, f1, f2 = terrain_contact(road, x, y, p, 1e-3, 0.1, 0.2, 3.0, 4.0, 5.0, 1e-3)
        j, w = terrain_row(road, y)
        row = (terrain_height(road, x, y), h, gx, gy, p, hp, gxp, gyp,
               terrain_friction(road, x, y), fn, f1, f2,
               terrain_row_height(road, j, w, x), terrain_zmax(road, x - 0.05, x + 0.05))
        for q in range(len(row)):
            out[k, q] = row[q]


@nb.njit
def _lattice(road, k, y):
    j, w = terrain_row(road, y)
    return terrain_line_height(road, j, w, k)


@nb.njit
def _summary(road, i):
    return (terrain_lines(road), terrain_blocks(road), terrain_block_max(road, i),
            terrain_range(road), terrain_is_rigid(road))


def bilinear(grid, x, y):
    """The grid's height by hand: bilinear in the cell, the edge nodes continued beyond."""
    z = grid.z
    u = np.clip((x - grid.x0) / grid.dx, 0.0, z.shape[0] - 1)
    v = np.clip((y - grid.y0) / grid.dy, 0.0, z.shape[1] - 1)
    i = np.minimum(u.astype(int), z.shape[0] - 2)
    j = np.minimum(v.astype(int), z.shape[1] - 2)
    fu, fv = u - i, v - j
    return ((z[i, j] * (1 - fu) + z[i + 1, j] * fu) * (1 - fv)
            + (z[i, j + 1] * (1 - fu) + z[i + 1, j + 1] * fu) * fv)


def test_the_grid_answers_every_interface_query_with_its_own_values():
    rng = np.random.default_rng(4)
    grid = RoadGrid(-0.3, -0.2, 0.007, 0.013, rng.normal(0.0, 0.01, (77, 41)))
    road = grid.surface()
    n = 400
    xs = rng.uniform(-0.4, 0.3, n)  # beyond both ends of the grid too
    ys = rng.uniform(-0.25, 0.35, n)
    zs = bilinear(grid, xs, ys) + rng.normal(0.0, 0.005, n)
    out = np.zeros((n, 14))
    _point_queries(road, xs, ys, zs, out)
    (h, hg, gx, gy, p, hp, gxp, gyp, mu, fn, f1, f2, h_row, zmax) = out.T
    np.testing.assert_allclose(h, bilinear(grid, xs, ys), rtol=0, atol=1e-14)
    assert np.array_equal(h, [road_height(road, x, y) for x, y in zip(xs, ys)])
    assert np.array_equal(hg, h) and np.array_equal(hp, h)
    np.testing.assert_allclose(h_row, h, rtol=0, atol=1e-15)  # the same bilinear, summed by rows
    assert np.array_equal(p, h - zs)
    below = p > 0  # the gradient only where the point is below the ground, there the same
    assert below.sum() > 50 and (~below).sum() > 50
    assert np.array_equal(gxp[below], gx[below]) and np.all(gxp[~below] == 0.0)
    assert np.array_equal(gyp[below], gy[below]) and np.all(gyp[~below] == 0.0)
    # the gradient is the cell's: a central difference inside a cell agrees
    e = 1e-7
    inside = (np.abs(xs) < 0.25) & (ys > -0.15) & (ys < 0.3)
    for g, (ex, ey) in ((gx, (e, 0.0)), (gy, (0.0, e))):
        fd = (bilinear(grid, xs + ex, ys + ey) - bilinear(grid, xs - ex, ys - ey)) / (2 * e)
        ok = inside & (np.abs(fd - g) < 1e-5)  # rejects only points within e of a node line
        assert ok.sum() > 0.9 * inside.sum()
    # the rigid road keeps the tyre's friction and carries whatever the tyre pushes
    assert np.all(mu == 1.0)
    assert np.all(fn == 3.0) and np.all(f1 == 4.0) and np.all(f2 == 5.0)
    assert np.array_equal(zmax, [local_zmax(road, x - 0.05, x + 0.05) for x in xs])
    # a bound: above every node of the cells between x - 0.05 and x + 0.05 (the edge nodes
    # where that is beyond the grid), so above the bilinear road there
    nodes = grid.x0 + grid.dx * np.arange(grid.z.shape[0])
    for x, top in zip(xs, zmax):
        i0, i1 = (int(np.clip(k, 0, nodes.size - 1)) for k in
                  (np.floor((x - 0.05 - grid.x0) / grid.dx), np.ceil((x + 0.05 - grid.x0) / grid.dx)))
        assert top >= grid.z[i0:i1 + 1].max()
    (x_first, spacing, inv_spacing, count), (bx0, blen, nblocks), _, (lo, hi), rigid = \
        _summary(road, 0)
    assert (x_first, spacing, inv_spacing, count) == (grid.x0, grid.dx, 1.0 / grid.dx, 77)
    assert (lo, hi) == (grid.z.min(), grid.z.max()) and rigid
    # break line k on a row is the bilinear height there; the lines hold every kink
    for k in (0, 5, 40, 76):
        for y in (-0.25, -0.2, 0.031, 0.3, 0.4):
            assert _lattice(road, k, y) == pytest.approx(
                float(bilinear(grid, np.array(x_first + k * spacing), np.array(y))), abs=1e-15)
    # each block bounds the road over it; beyond the ends the end blocks
    assert nblocks == len(road.block_max) and bx0 == grid.x0
    for i in range(-2, nblocks + 2):
        top = _summary(road, i)[2]
        c = min(max(i, 0), nblocks - 1)
        span = (nodes >= bx0 + c * blen - 1e-12) & (nodes <= bx0 + (c + 1) * blen + 1e-12)
        assert top == road.block_max[c] and top >= grid.z[span].max()


def test_the_grid_tells_the_builds_what_they_precompute():
    """The Python side (terrain.Ground): a profile is uniform across and has its kinks,
    a 3D road has neither; the row maxima bound each pair of rows."""
    z = np.array([0, 0, 0, 1, 2, 2, 2], float)
    profile = RoadGrid(0.0, -1.0, 0.01, 2.0, np.column_stack([z, z]))
    assert profile.uniform_across()
    np.testing.assert_array_equal(profile.profile_breaks(), [2, 2, 4, 4, 6, 6, 6])
    assert profile.sampling_step() == 0.01
    rough = RoadGrid(0.0, 0.0, 0.01, 0.02, np.random.default_rng(1).normal(0, 0.01, (50, 5)))
    assert not rough.uniform_across() and rough.profile_breaks() is None
    assert rough.sampling_step() == 0.01
    per, maxima = rough.row_maxima(0.05)
    assert per == 5 and maxima.shape == (10, 4)
    for b in range(10):
        for j in range(4):
            assert maxima[b, j] == rough.z[b * per:(b + 1) * per + 1, j:j + 2].max()


# --- another kind of ground, in a subprocess ------------------------------------------

TOY_MODULE = '''
"""A toy terrain: the plane z = z0 + sx x + sy y over a rectangle, level beyond its edges.

Registered as the ARCHITECTURE.md recipe says; an analytic ground, not a grid. Its
break lines are every 5 cm (the plane is linear between any lines), its row handle is
(0, y), its blocks 0.5 m. It says it is not rigid, so the models ask it what it carries:
the fraction ``carry`` of the normal force the tyre pushes with (1: all of it, as a
rigid ground).
"""
from typing import NamedTuple

import numba as nb
import numpy as np

from tyrelab.road.terrain import TerrainKind, profile_breaks, register_terrain


class Plane(NamedTuple):
    z0: float
    sx: float
    sy: float
    x_lo: float
    y_lo: float
    y_hi: float
    spacing: float
    count: int
    block: float
    friction: float
    carry: float


@nb.njit
def _clamp(v, lo, hi):
    return min(max(v, lo), hi)


@nb.njit
def height(t, x, y):
    x_hi = t.x_lo + (t.count - 1) * t.spacing
    return t.z0 + t.sx * _clamp(x, t.x_lo, x_hi) + t.sy * _clamp(y, t.y_lo, t.y_hi)


@nb.njit
def gradient(t, x, y):
    x_hi = t.x_lo + (t.count - 1) * t.spacing
    gx = t.sx if t.x_lo < x < x_hi else 0.0
    gy = t.sy if t.y_lo < y < t.y_hi else 0.0
    return height(t, x, y), gx, gy


@nb.njit
def penetration(t, x, y, z):
    h, gx, gy = gradient(t, x, y)
    if h <= z:
        return h - z, h, 0.0, 0.0
    return h - z, h, gx, gy


@nb.njit
def exact_max(t, x0, x1):
    return max(height(t, x0, t.y_lo), height(t, x0, t.y_hi), height(t, x1, t.y_lo),
               height(t, x1, t.y_hi))


@nb.njit
def zmax(t, x0, x1):
    # the bound a grid of this plane gives inside it (tyrelab.road.grid.local_zmax: the
    # highest node of the ~4 cm blocks that [x0, x1] touches, here one 5 cm node spacing
    # each), looser than the exact one, so that the ring decides alike on the toy and on
    # its grid where its blocks sample their strips
    i0 = np.floor((x0 - t.x_lo) / t.spacing)
    i1 = np.floor((x1 - t.x_lo) / t.spacing) + 1.0
    return exact_max(t, t.x_lo + i0 * t.spacing, t.x_lo + i1 * t.spacing)


@nb.njit
def bounds(t):
    x_hi = t.x_lo + (t.count - 1) * t.spacing
    return (min(height(t, t.x_lo, t.y_lo), height(t, x_hi, t.y_hi), height(t, t.x_lo, t.y_hi),
                height(t, x_hi, t.y_lo)), exact_max(t, t.x_lo, x_hi))


@nb.njit
def lines(t):
    return t.x_lo, t.spacing, 1.0 / t.spacing, t.count


@nb.njit
def row(t, y):
    return 0, y


@nb.njit
def line_height(t, r, w, k):
    return height(t, t.x_lo + k * t.spacing, w)


@nb.njit
def blocks(t):
    return t.x_lo, t.block, int(np.ceil((t.count - 1) * t.spacing / t.block))


@nb.njit
def block_max(t, i):
    n = blocks(t)[2]
    i = min(max(i, 0), n - 1)
    return exact_max(t, t.x_lo + i * t.block, t.x_lo + (i + 1) * t.block)


@nb.njit
def friction(t, x, y):
    return t.friction


@nb.njit
def carried(t, x, y, penetration, area, v1, v2, fn, f1, f2, dt):
    return t.carry * fn, f1, f2


register_terrain(TerrainKind(
    "plane", Plane, height=height, height_gradient=gradient, penetration=penetration,
    zmax=zmax, range=bounds, lines=lines, row=row, line_height=line_height, blocks=blocks,
    block_max=block_max, friction=friction, contact=carried, rigid=False,
    description="a toy plane that carries a fraction of the tyre's push"))


class PlaneGround:
    """The Python side the models' builds ask (tyrelab.road.terrain.Ground)."""

    def __init__(self, sx, sy, friction=1.0, carry=1.0):
        self.record = Plane(0.3, sx, sy, -4.0, -2.0, 2.0, 0.05, 161, 0.5, friction, carry)

    def surface(self):
        return self.record

    def sampling_step(self):
        return self.record.spacing

    def uniform_across(self):
        return self.record.sy == 0.0

    def profile_breaks(self):
        t = self.record
        x = t.x_lo + t.spacing * np.arange(t.count)
        return profile_breaks(np.column_stack([t.z0 + t.sx * x] * 2)) if t.sy == 0.0 else None

    def row_maxima(self, length):
        return 1, np.zeros((0, 1))
'''

DRIVER = '''
import json, sys
import numpy as np
from toy_terrain import PlaneGround
from tyrelab.road.terrain import terrain_kind, terrain_names
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.wheel import loads_table

PLANES = ((0.12, 0.0), (-0.1, 0.06), (0.0, 0.0))
res = {"names": list(terrain_names()), "record": terrain_kind("plane").record.__name__}
tyre = load_tyre("xzl-16.00R20", 300e3)


def pose(c, axis=(0.0, 1.0, 0.0), v=(0.0, 0.0, 0.0), omega=0.0):
    return np.r_[c, axis, v, omega]


# the toy's loads only: the test's own process runs the same planes on a grid, on the
# package's compile cache, from the toy's record (in this process, with its own cache, the
# grid's kernels cost a cold run 10 s of compiles)
res["grid"] = PlaneGround(0.0, 0.0).record._asdict()
for sx, sy in PLANES:
    ground = PlaneGround(sx, sy)
    cx, cy = 0.3, 0.1
    cz = 0.3 + sx * cx + sy * cy + 0.62
    for model in ("point", "volume", "enveloping", "ring"):
        m = TyreModel(tyre, model)
        on_toy = loads_table(m.wheel(ground, 20e3), pose((cx, cy, cz)), 1e-3)[0]
        res[f"{model} {sx} {sy}"] = [on_toy.tolist(), None, [cx, cy, cz]]

# friction: the same slipping, yawed wheel on the plane at friction 1 and 1/2
hmmwv = load_tyre("hmmwv-pac89")
yaw = np.radians(3.0)
rolling = pose((0.3, 0.0, 0.3 + 0.3 * 0.02 + hmmwv.unloaded_radius - 0.03),
               axis=(np.sin(yaw), np.cos(yaw), 0.0), v=(5.0, 0.0, 0.0),
               omega=1.06 * 5.0 / (hmmwv.unloaded_radius - 0.03))
m = TyreModel(hmmwv, "point", handling="pac89")
res["friction"] = [loads_table(m.wheel(PlaneGround(0.02, 0.0, mu)), rolling, 1e-3)[0].tolist()
                   for mu in (1.0, 0.5)]
# a ground that is not rigid answers the tyre: half the normal force (the ring: one internal
# step, dt far below its step, and no patch element, whose force is not proportional)
for model in ("point", "ring"):
    m = TyreModel(tyre, model)
    p = pose((0.3, 0.1, 0.3 + 0.62))
    res[f"soft {model}"] = []
    for carry in (1.0, 0.5):
        wheel = m.wheel(PlaneGround(0.0, 0.0, carry=carry), 20e3)
        if model == "ring":
            wheel = wheel._replace(contact=wheel.contact._replace(patch_hysteresis_gain=0.0))
        res[f"soft {model}"].append(loads_table(wheel, p, 1e-6)[0].tolist())
json.dump(res, sys.stdout)
'''


def _grid_of(plane: dict, sx: float, sy: float) -> RoadGrid:
    """The toy's plane (its record's fields, slopes ``sx``, ``sy``) sampled on a road grid: its
    5 cm lines along x, 9 rows across."""
    x = plane["x_lo"] + plane["spacing"] * np.arange(plane["count"])
    y = np.linspace(plane["y_lo"], plane["y_hi"], 9)
    X, Y = np.meshgrid(x, y, indexing="ij")
    return RoadGrid(plane["x_lo"], plane["y_lo"], plane["spacing"], y[1] - y[0],
                    plane["z0"] + sx * X + sy * Y)


@pytest.fixture(scope="module")
def toy(xzl):
    """The driver's results; the toy module and its compile cache are kept between runs
    (``tests/kept_cache.py``: the toy's code compiles once, not in every run: 28 s). Each
    model's loads on the toy's planes sampled on a grid are added here, in this process."""
    from tyrelab.tyre.model import TyreModel
    from tyrelab.tyre.wheel import loads_table

    res = run_driver(kept_home("tyrelab-toy-terrain", "toy_terrain.py", TOY_MODULE, DRIVER),
                     DRIVER, timeout=1200)
    for sx, sy in PLANES:
        grid = _grid_of(res["grid"], sx, sy)
        for model in ("point", "volume", "enveloping", "ring"):
            on_toy, _, centre = res[f"{model} {sx} {sy}"]
            pose = np.r_[centre, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0]
            on_grid = loads_table(TyreModel(xzl, model).wheel(grid, 20e3), pose, 1e-3)[0]
            res[f"{model} {sx} {sy}"][1] = on_grid.tolist()
    return res


FX, FY, FZ, MX, MY, MZ, PX, PY, PZ, NX, NY, NZ, DEFL, DEFL_RATE, FXW, FYW, FZW = range(17)


def test_a_registered_terrain_is_listed(toy):
    assert toy["names"][0] == "rigid" and "plane" in toy["names"] and toy["record"] == "Plane"


PLANES = [(0.12, 0.0), (-0.1, 0.06), (0.0, 0.0)]


@pytest.mark.parametrize("model", ["point", "volume", "enveloping"])
@pytest.mark.parametrize("sx,sy", PLANES)
def test_the_analytic_models_give_the_plane_contact_on_the_toy_terrain(toy, model, sx, sy):
    """On a plane, every analytic model is a rigid disc on it: R0 minus the distance, in
    the wheel plane, from the centre to the plane's trace; the normal is the plane's
    (the point model's stays in the wheel plane: it reads the road in that plane only)."""
    loads, _, (cx, cy, cz) = toy[f"{model} {sx} {sy}"]
    dist = (cz - 0.3 - sx * cx - sy * cy) / math.sqrt(1 + sx * sx)
    assert loads[DEFL] == pytest.approx(R0 - dist, abs=1e-9)
    n = np.array([-sx, 0.0 if model == "point" else -sy, 1.0])
    np.testing.assert_allclose(loads[NX:NZ + 1], n / np.linalg.norm(n), atol=1e-9)
    assert loads[PZ] == pytest.approx(0.3 + sx * loads[PX] + sy * loads[PY], abs=1e-9)
    assert loads[FZW] > 1e4


@pytest.mark.parametrize("model", ["point", "volume", "enveloping", "ring"])
@pytest.mark.parametrize("sx,sy", PLANES)
def test_every_model_sees_the_toy_plane_as_the_same_plane_on_a_grid(toy, model, sx, sy):
    """The same plane sampled on a grid gives the same loads, the ring's too (its tread
    blocks read the toy through the interface only). The ring samples a block's strip
    where the ground's bound (terrain_zmax) says the road may reach it, so the toy bounds
    itself as its grid does (node spacing by node spacing): with its exact bound, the
    blocks the two decided differently pressed with their strip's mean on one and their
    tip's penetration on the other, 2e-5 of the load at a 1/6 ms internal step and
    2.2e-4 at 1/4 ms."""
    on_toy, on_grid, _ = toy[f"{model} {sx} {sy}"]
    scale = max(abs(v) for v in on_grid[:MZ + 1])
    assert scale > 1e4
    np.testing.assert_allclose(on_toy[:FZW + 1], on_grid[:FZW + 1], rtol=0, atol=1e-9 * scale)


def test_the_friction_scale_halves_the_tangential_forces(toy):
    full, half = (np.array(v) for v in toy["friction"])
    assert abs(full[FXW]) > 500.0 and abs(full[FYW]) > 500.0  # slipping and yawed: both
    assert half[FXW] == 0.5 * full[FXW] and half[FYW] == 0.5 * full[FYW]
    assert half[FZW] == full[FZW] and half[DEFL] == full[DEFL]


@pytest.mark.parametrize("model", ["point", "ring"])
def test_a_ground_that_is_not_rigid_answers_through_its_contact(toy, model):
    """The plane carrying half of what the tyre pushes halves the analytic wheel's normal
    force, and each tread block's of the ring, against the plane carrying all of it."""
    rigid, soft = (np.array(v) for v in toy[f"soft {model}"])
    assert rigid[FZW] > 1e4
    assert soft[FZW] == pytest.approx(0.5 * rigid[FZW], rel=1e-12)
    assert soft[DEFL] == rigid[DEFL]
