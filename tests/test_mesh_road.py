"""Triangle-mesh roads: exact queries, the compiled grid as a cache, OBJ files, a cleat as a mesh."""

import math
from pathlib import Path

import numpy as np
import pytest
import trimesh  # noqa: F401 -- a required dependency (OBJ files): missing, this file fails, never skips
from scipy.spatial import Delaunay

import tyrelab
from tyrelab.errors import InputError
from tyrelab.road.crg import CrgRoad
from tyrelab.road.mesh import MeshRoad
from tyrelab.road.obstacles import Cleat
from tyrelab.road.spec import road_from_spec

DATA = Path(__file__).parent / "data" / "roads"


def cleat_mesh(width, height, angle=0.0, start=5.0, x0=3.0, x1=21.0, half=2.0):
    """A square cleat as a mesh: ground, two vertical walls and the top, each a quad strip
    across the road (the leading edge at x = start - y tan(angle))."""
    t = math.tan(math.radians(angle))
    wx = width / math.cos(math.radians(angle))
    zs = [0, 0, height, height, 0, 0]
    v = []
    for y in (-half, half):
        e = start - y * t
        v += [(x, y, z) for x, z in zip([x0, e, e, e + wx, e + wx, x1], zs)]
    tri = [(k, k + 1, 7 + k) for k in range(5)] + [(k, 7 + k, 6 + k) for k in range(5)]
    return MeshRoad(np.array(v, float), np.array(tri))


def _random_mesh(n=1200, seed=0, surface=lambda x, y: 0.05 * np.sin(3 * x) * np.cos(2 * y)):
    """Random nodes on the 4 m square and every 0.1 m along its rim (no sliver triangles),
    Delaunay triangles, heights from ``surface``."""
    rng = np.random.default_rng(seed)
    e = np.linspace(0, 4, 41)
    rim = np.vstack([np.column_stack([e, 0 * e]), np.column_stack([e, 0 * e + 4]),
                     np.column_stack([0 * e, e]), np.column_stack([0 * e + 4, e])])
    pts = np.unique(np.vstack([rng.uniform(0.05, 3.95, (n, 2)), rim]), axis=0)
    tri = Delaunay(pts).simplices
    return MeshRoad(np.column_stack([pts, surface(pts[:, 0], pts[:, 1])]), tri), pts, tri


# --- exact queries ---------------------------------------------------------------

def test_index_agrees_with_brute_force():
    """The bucket index finds the same triangle as testing every triangle."""
    road, pts, tri = _random_mesh(seed=1)
    rng = np.random.default_rng(2)
    q = rng.uniform(0, 4, (4000, 2))
    a, b, c = (np.column_stack([pts[tri[:, k]], road.vertices[tri[:, k], 2]]) for k in range(3))
    # barycentric weights of every point in every triangle, by Cramer's rule
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
    dx, dy = q[:, None, 0] - a[:, 0], q[:, None, 1] - a[:, 1]
    l1 = (dx * (c[:, 1] - a[:, 1]) - dy * (c[:, 0] - a[:, 0])) / det
    l2 = ((b[:, 0] - a[:, 0]) * dy - (b[:, 1] - a[:, 1]) * dx) / det
    inside = (l1 >= -1e-12) & (l2 >= -1e-12) & (l1 + l2 <= 1 + 1e-12)
    z = np.where(inside, (1 - l1 - l2) * a[:, 2] + l1 * b[:, 2] + l2 * c[:, 2], -np.inf).max(axis=1)
    np.testing.assert_allclose(road.height(q[:, 0], q[:, 1]), z, atol=1e-14)


def test_highest_surface_and_friction_per_triangle():
    """A deck 0.5 m over a road: the deck wins where they overlap, and its friction."""
    v = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [4, 4, 0],
                  [1, 1, 0.5], [3, 1, 0.5], [1, 3, 0.5]], float)
    road = MeshRoad(v, np.array([[0, 1, 3], [0, 3, 2], [4, 5, 6]]), friction=[0.9, 0.8, 0.3])
    np.testing.assert_array_equal(road.height([0.5, 1.5, 3.5], [0.5, 1.5, 3.5]), [0, 0.5, 0])
    np.testing.assert_array_equal(road.friction([3.5, 1.5, 0.5], [0.5, 1.5, 3.5]), [0.9, 0.3, 0.8])


def test_outside_the_mesh_the_rim_continues():
    """z = x + 2 y on the unit square: outside, the height of the nearest rim point."""
    v = np.array([[0, 0, 0], [1, 0, 1], [0, 1, 2], [1, 1, 3]], float)
    road = MeshRoad(v, np.array([[0, 1, 3], [0, 3, 2]]))
    np.testing.assert_allclose(road.height([2.0, -1.0, 0.5, 3.0], [0.5, -1.0, 5.0, 3.0]),
                               [2.0, 0.0, 2.5, 3.0], atol=1e-15)
    # a square footprint: the compiled grid continues its edges the same way
    g = road.grid()
    np.testing.assert_allclose(g.height([2.0, -1.0, 0.5], [0.5, -1.0, 5.0]), [2.0, 0.0, 2.5], atol=1e-12)
    # a hole: a ring of 8 cells around a missing centre cell (z = 0.1 x), queried in the hole
    xs = np.arange(4.0)
    nodes = np.array([(x, y, 0.1 * x) for x in xs for y in xs])
    tris = []
    for i in range(3):
        for j in range(3):
            if (i, j) != (1, 1):
                n = 4 * i + j
                tris += [(n, n + 4, n + 5), (n, n + 5, n + 1)]
    ring = MeshRoad(nodes, np.array(tris))
    assert ring.height(1.5, 1.1) == pytest.approx(0.15, abs=1e-15)  # nearest rim point (1.5, 1)


# --- the compiled grid is a cache: its error against the exact query ---------------

def test_grid_of_a_plane_is_exact():
    road, _, _ = _random_mesh(400, seed=3, surface=lambda x, y: 0.02 + 0.1 * x - 0.05 * y)
    assert road.grid_error(samples=50000) < 1e-12


def test_grid_error_within_the_stated_bound():
    """Continuous mesh: |grid - exact| <= 2 (largest slope difference) (cell diagonal)."""
    road, _, _ = _random_mesh(seed=4)
    g = np.einsum("ki,kij->kj", road._dz, road._inv)
    spread = np.max(np.linalg.norm(g[:, None, :] - g[None, :, :], axis=2))
    dx, dy = road.default_spacing
    err = road.grid_error(samples=100000)
    assert 0 < err <= 2 * spread * math.hypot(dx, dy)
    assert err < 1e-3  # 5 mm cells on a 0.05 m-high undulation (measured 0.1 mm)


def test_belgian_block_mesh_nodes_and_index():
    """The ASAM belgian block (680 000 triangles): nodes exact, grid error, and the bucket
    index tests a handful of triangles per query, not all of them (what keeps queries fast,
    counted instead of timed: a time would measure the machine)."""
    crg = CrgRoad(DATA / "belgian_block.crg")
    from tyrelab.road.mesh_files import grid_triangles
    v, t = grid_triangles(crg.grid())
    road = MeshRoad(v, t)
    rng = np.random.default_rng(5)
    x, y = rng.uniform(730, 740, 300_000), rng.uniform(-1.7, 1.7, 300_000)
    z = road.height(x, y)
    # (point, triangle) pairs the index hands to the barycentric test (white box: _buckets).
    # Buckets of side h = sqrt(area / triangles) = 10 mm / sqrt(2) here; each triangle's
    # bounding box, a 10 mm grid cell, overlaps (1 + sqrt(2))^2 = 5.8 buckets on average, so
    # a point meets about 6 candidates (measured 5.8) -- against 680 000 without the index
    pairs, _ = road._buckets.pairs(x, y)
    assert pairs.size / x.size < 10
    k = rng.integers(0, len(v), 2000)
    np.testing.assert_allclose(road.height(v[k, 0], v[k, 1]), v[k, 2], atol=1e-15)
    # the bilinear CRG and the two-triangle mesh differ inside cells, not at nodes
    assert 0 < np.max(np.abs(z - crg.height(x, y))) < 0.02


# --- a cleat as a mesh drives like the analytic cleat -------------------------------

def test_cleat_mesh_gives_the_cleats_volume_forces():
    """Perpendicular, with the mesh's first node off the 5 mm lattice (x0 = 3.0021 m): the
    grid is aligned to the walls, so the run is the analytic cleat's (to 1e-9)."""
    mesh = cleat_mesh(0.05, 0.05, x0=3.0021)
    cleat = Cleat(0.05, 0.05, start=5.0)
    x = np.random.default_rng(6).uniform(3, 21, 100000)
    np.testing.assert_array_equal(mesh.height(x, 0.7), cleat.height(x, 0.7))
    assert not mesh.varies_in_y()
    assert mesh.run_start == cleat.run_start == 0.0  # 5 m before the cleat's first wall
    a = tyrelab.simulate(model="volume", road=mesh, duration=2.5, progress=False)
    b = tyrelab.simulate(model="volume", road=cleat, duration=2.5, progress=False)
    assert b["FZW"].max() > 1.2 * b["FZW"].iloc[0]
    for ch in ("FX", "FZ", "FZW"):
        np.testing.assert_allclose(a[ch], b[ch], rtol=0, atol=1e-9 * b["FZW"].max())


def test_oblique_cleat_mesh_within_tolerance():
    """At 30 degrees no grid holds the edges: mesh and analytic cleat are both sampled every
    ~5 mm, at different nodes. Stated tolerance: FZW within 1 % of the peak over the whole
    run, peaks of FX and FY within 5 % (measured 0.5 %, 1.9 %, 3.3 %)."""
    mesh = cleat_mesh(0.05, 0.05, angle=30.0)
    cleat = Cleat(0.05, 0.05, angle=30.0, start=5.0)
    x, y = np.random.default_rng(7).uniform(3, 8, 50000), np.random.default_rng(8).uniform(-2, 2, 50000)
    np.testing.assert_array_equal(mesh.height(x, y), cleat.height(x, y))
    mesh.run_start = cleat.run_start
    a = tyrelab.simulate(model="volume", road=mesh, duration=2.5, progress=False)
    b = tyrelab.simulate(model="volume", road=cleat, duration=2.5, progress=False)
    peak = b["FZW"].max()
    assert np.max(np.abs(a["FZW"] - b["FZW"])) < 0.01 * peak
    for ch in ("FX", "FY"):
        assert abs(a[ch].abs().max() - b[ch].abs().max()) < 0.05 * b[ch].abs().max()
    assert b["FY"].abs().max() > 100.0  # an oblique cleat pushes sideways


# --- OBJ files --------------------------------------------------------------------------

def test_obj_round_trip(tmp_path):
    from tyrelab.road.mesh_files import read_obj, write_obj
    mesh = cleat_mesh(0.05, 0.05, x0=3.0021)
    back = read_obj(write_obj(mesh, tmp_path / "cleat.obj"))
    np.testing.assert_array_equal(back.vertices, mesh.vertices)
    np.testing.assert_array_equal(back.triangles, mesh.triangles)
    # any road as its grid; via the road name with a lateral offset
    crg = CrgRoad(DATA / "handmade_sloped.crg")
    write_obj(crg, tmp_path / "sloped.obj")
    road = road_from_spec(f"{tmp_path / 'sloped.obj'}@0.5")
    g = crg.grid()
    X, Y = np.meshgrid(g.x0 + g.dx * np.arange(g.z.shape[0]), g.y0 + g.dy * np.arange(g.z.shape[1]),
                       indexing="ij")
    np.testing.assert_allclose(road.height(X, Y - 0.5), g.z, rtol=0, atol=1e-15)


@pytest.mark.parametrize("text, line, fragment", [
    ("v 0 0 0\nv 1 0 x\nv 0 1 0\nf 1 2 3\n", 2, "non-numeric"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\n# a comment\nf 1 2 9\n", 5, "vertex 9"),
    ("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 4\nf 1 2 3\n", 6, "degenerate"),
    ("v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 1, "non-finite"),
])
def test_bad_obj_files_name_the_line(tmp_path, text, line, fragment):
    from tyrelab.road.mesh_files import read_obj
    path = tmp_path / "bad.obj"
    path.write_text(text)
    with pytest.raises(InputError, match=fragment) as info:
        read_obj(path)
    assert info.value.source == str(path) and info.value.line == line


def test_a_y_up_export_is_refused_saying_so(tmp_path):
    """Blender and glTF write Y up: the flat road of a cleat mesh, read as tyrelab reads (z up),
    is a vertical sheet. Refused naming the file and the likely cause, not read as walls."""
    from tyrelab.road.mesh_files import read_obj, write_obj
    mesh = cleat_mesh(0.05, 0.05)
    path = write_obj(mesh, tmp_path / "cleat.obj")
    lines = [f"v {x} {z} {-float(y)!r}" if line.startswith("v ") else line
             for line in path.read_text().splitlines()
             for x, y, z in [line.split()[1:4] if line.startswith("v ") else ("", "", "")]]
    (tmp_path / "y_up.obj").write_text("\n".join(lines) + "\n")
    with pytest.raises(InputError, match="no triangle faces up.*exported Y-up") as info:
        read_obj(tmp_path / "y_up.obj")
    assert info.value.source == str(tmp_path / "y_up.obj")


def test_bad_mesh_arrays():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)
    with pytest.raises(InputError, match="does not exist"):
        MeshRoad(v, np.array([[0, 1, 3]]))
    with pytest.raises(InputError, match="vertical"):
        MeshRoad(np.array([[0, 0, 0], [1, 0, 0], [0, 0, 1]], float), np.array([[0, 1, 2]]))
    with pytest.raises(InputError, match="friction"):
        MeshRoad(v, np.array([[0, 1, 2]]), friction=-1.0)
