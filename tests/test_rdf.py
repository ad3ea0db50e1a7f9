"""Adams road data files (.rdf): the public examples, every 2D type, units, round trips, bad files."""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import tyrelab
from tyrelab.errors import InputError
from tyrelab.road.crg import CrgRoad
from tyrelab.road.mesh import MeshRoad
from tyrelab.road.obstacles import Cleat
from tyrelab.road.rdf import read_rdf, write_rdf
from tyrelab.road.rdf_profiles import LEFT_TRACK_Y
from tyrelab.road.spec import road_from_spec

DATA = Path(__file__).parent / "data" / "roads"
UNITS_M = "[UNITS]\nLENGTH = 'meter'\nANGLE = 'degree'\n"


def _file(tmp_path, text, name="road.rdf"):
    path = tmp_path / name
    path.write_text(text)
    return path


def _two_d(kind, params, units=UNITS_M):
    body = "\n".join(f"{k} = {v}" for k, v in params.items())
    return f"{units}[MODEL]\nMETHOD = '2D'\nROAD_TYPE = '{kind}'\n[PARAMETERS]\n{body}\n"


# --- the two public example files --------------------------------------------

def test_plateau_road_heights_are_its_table_rows():
    """Every (XZ_DATA) row of the file, read here from its text, is the road's height there
    (both tracks, any y), and half-way between two rows the height is their mean."""
    path = DATA / "plateau_road.rdf"
    lines = path.read_text().splitlines()
    rows = [[float(t) for t in ln.split()] for ln in lines[lines.index("(XZ_DATA)") + 1:] if ln.strip()]
    rows = np.array(rows)
    assert rows.shape == (46, 3)
    road = read_rdf(path)
    for y in (0.0, 0.7, -1.9, LEFT_TRACK_Y):
        np.testing.assert_array_equal(road.height(rows[:, 0], y), rows[:, 2])
    mid = 0.5 * (rows[1:, 0] + rows[:-1, 0])
    np.testing.assert_allclose(road.height(mid, 0.0), 0.5 * (rows[1:, 2] + rows[:-1, 2]), atol=1e-12)
    # picked by hand from the file: 54.000 0.510, 110.000 4.900 (the plateau), 230 back to 0
    assert road.height(54.0, 0.0) == 0.510 and road.height(120.0, 0.0) == 4.900
    assert road.height(230.0, 0.0) == 0.0 and road.height(5000.0, 0.0) == 0.0
    assert not road.varies_in_y()
    # the plateau starts rising after x = 40 m: a run starts 5 m before that
    assert road.run_start == 35.0
    # rows every 3.5 and 5 m lie on the grid's nodes: the compiled road is exact
    x = np.random.default_rng(1).uniform(30.0, 260.0, 20000)
    np.testing.assert_allclose(road.grid().height(x, 0.3), road.height(x, 0.3), atol=1e-12)


def test_sample_shell_heights():
    """ENVE's sample: a 20 km x 40 km plane, 0.1 higher for y >= 20000, vertical elements at the step."""
    road = read_rdf(DATA / "sample_shell.rdf")
    assert isinstance(road, MeshRoad)
    # node 5 (20000, 40000, 0.1) and node 7 (20000, 0, 0)
    assert road.height(20000.0, 40000.0) == 0.1 and road.height(20000.0, 0.0) == 0.0
    # inside element "1 6 2" (z = 0) and "4 0 5" (z = 0.1): flat triangles
    assert road.height(5000.0, 10000.0) == 0.0 and road.height(5000.0, 30000.0) == 0.1
    # the step along y = 20000: its top edge is the highest surface there
    assert road.height(7000.0, 19999.9) == 0.0 and road.height(7000.0, 20000.0) == 0.1
    np.testing.assert_array_equal(road.friction([1.0, 1.0], [1.0, 39999.0]), [1.0, 1.0])


def test_shell_interior_point_is_barycentric(tmp_path):
    """Triangle A(0,0,0.1) B(2,0,0.3) C(0,1,0.5), 1-based ids; P(0.5,0.25) has barycentric
    weights (0.5, 0.25, 0.25), so z = 0.05 + 0.075 + 0.125 = 0.25 (by hand)."""
    text = ("[MODEL]\nMETHOD = '3D'\n[NODES]\n{ id x y z }\n1 0 0 0.1\n2 2 0 0.3\n3 0 1 0.5\n"
            "4 2 1 0.2\n[ELEMENTS]\n{ n1 n2 n3 mu }\n1 2 3 0.8\n2 4 3 0.6\n")
    road = read_rdf(_file(tmp_path, text))
    assert road.height(0.5, 0.25) == pytest.approx(0.25, abs=1e-15)
    assert road.friction(0.5, 0.25) == 0.8 and road.friction(1.8, 0.9) == 0.6
    # the second triangle B(2,0,0.3) D(2,1,0.2) C(0,1,0.5) at (1.5, 0.75): weights 0.25, 0.5, 0.25
    assert road.height(1.5, 0.75) == pytest.approx(0.25 * 0.3 + 0.5 * 0.2 + 0.25 * 0.5, abs=1e-15)


# --- plank = the built-in cleat ----------------------------------------------

PLANK_MM = _two_d("plank", {"HEIGHT": 50, "START": 5000, "LENGTH": 50, "BEVEL_EDGE_LENGTH": 0,
                            "DIRECTION": 0, "MU": 1.0, "OFFSET": 0},
                  units="[UNITS]\nLENGTH = 'mm'\nANGLE = 'degree'\nFORCE = 'newton'\n")


def test_plank_is_the_cleat_road_and_drives_the_same(tmp_path):
    path = _file(tmp_path, PLANK_MM, "plank.rdf")
    plank, cleat = road_from_spec(str(path)), road_from_spec("cleat:50x50")
    x = np.random.default_rng(3).uniform(3.0, 8.0, 50000)
    x = np.concatenate([x, [5.0, 5.05, 4.9999, 5.0501]])
    np.testing.assert_array_equal(plank.height(x, 0.4), cleat.height(x, 0.4))
    gp, gc = plank.grid(), cleat.grid()
    assert (gp.x0, gp.dx, gp.y0, gp.dy) == (gc.x0, gc.dx, gc.y0, gc.dy)
    np.testing.assert_array_equal(gp.z, gc.z)
    assert plank.run_start == cleat.run_start and plank.extent() == cleat.extent()
    runs = [tyrelab.simulate(model="volume", road=r, duration=2.5, progress=False) for r in (plank, cleat)]
    assert runs[0]["FZW"].max() > 1.2 * runs[0]["FZW"].iloc[0]  # the wheel did hit the cleat
    for ch in ("FX", "FZ", "FZW", "Z_WC"):
        np.testing.assert_array_equal(runs[0][ch].to_numpy(), runs[1][ch].to_numpy())


def test_oblique_bevelled_plank_is_the_oblique_cleat(tmp_path):
    """LENGTH and BEVEL_EDGE_LENGTH are measured along x: 60 mm along x at 30 degrees is a
    cleat 60 cos 30 = 51.96 mm wide across its edges."""
    c30 = math.cos(math.radians(30))
    path = _file(tmp_path, _two_d("plank", {"HEIGHT": 0.04, "START": 5.0, "LENGTH": 0.06,
                                            "BEVEL_EDGE_LENGTH": 0.01, "DIRECTION": 30}))
    plank = read_rdf(path)
    cleat = Cleat(0.06 * c30, 0.04, angle=30.0, bevel=0.01 * c30, start=5.0)
    rng = np.random.default_rng(4)
    x, y = rng.uniform(3.5, 6.5, 50000), rng.uniform(-2, 2, 50000)
    np.testing.assert_array_equal(plank.height(x, y), cleat.height(x, y))
    # the left side (y > 0) meets it first; along x at y = 0 it spans START to START + LENGTH
    edge = 5.0 - math.tan(math.radians(30))  # the leading edge at y = 1 m
    assert plank.height(edge, 1.0) == pytest.approx(0.04 - 0.01 * c30, abs=1e-12)
    assert plank.height(edge + 0.03, 1.0) == pytest.approx(0.04) and plank.height(edge, -1.0) == 0.0
    assert plank.height(5.03, 0.0) == pytest.approx(0.04) and plank.height(5.061, 0.0) == 0.0


# --- the other 2D types, against hand-computed geometry ------------------------

def test_ramp_roof_pothole_sine(tmp_path):
    ramp = read_rdf(_file(tmp_path, _two_d("ramp", {"HEIGHT": 0.1, "START": 2.0, "SLOPE": 0.5})))
    np.testing.assert_allclose(ramp.height([1.9, 2.0, 2.1, 2.2, 2.4, 9.0], 0.0),
                               [0, 0, 0.05, 0.1, 0.1, 0.1], atol=1e-15)
    down = read_rdf(_file(tmp_path, _two_d("ramp", {"HEIGHT": -0.1, "START": 2.0, "SLOPE": 1})))
    assert down.height(2.05, 0) == pytest.approx(-0.05) and down.height(3.0, 0) == pytest.approx(-0.1)
    roof = read_rdf(_file(tmp_path, _two_d("roof", {"HEIGHT": 0.08, "START": 1.0, "LENGTH": 0.4})))
    np.testing.assert_allclose(roof.height([0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5], 0.0),
                               [0, 0, 0.04, 0.08, 0.04, 0, 0], atol=1e-15)
    hole = read_rdf(_file(tmp_path, _two_d("pot_hole", {"DEPTH": 0.05, "START": 5.0, "LENGTH": 0.3})))
    np.testing.assert_array_equal(hole.height([5.0, 5.01, 5.29, 5.3 + 1e-9], 1.0), [0, -0.05, -0.05, 0])
    assert hole.grid().height(5.15, 0.0) == -0.05 and hole.grid().height(5.0, 0.0) == 0.0
    sine = read_rdf(_file(tmp_path, _two_d("sine", {"AMPLITUDE": 0.02, "WAVE_LENGTH": 0.8,
                                                    "START": 1.0, "LENGTH": 1.6})))
    # s = 0.2, 0.4, 0.6 m: a quarter, a half, three quarters of a wave; it ends at 2 waves
    np.testing.assert_allclose(sine.height([0.9, 1.2, 1.4, 1.6, 2.6, 2.7], 0.0),
                               [0, 0.02, 0, -0.02, 0, 0], atol=1e-15)
    # sampled every 5 mm (< 1/50 of the wave): grid error below A (pi dx / l)^2 / 2
    x = np.linspace(0.5, 3.0, 20001)
    bound = 0.02 * (math.pi * 0.005 / 0.8) ** 2 / 2
    assert np.max(np.abs(sine.grid().height(x, 0) - sine.height(x, 0))) <= bound


def test_sine_sweep_linear_and_logarithmic(tmp_path):
    p = {"START": 1.0, "END": 4.0, "AMPLITUDE_AT_START": 0.01, "AMPLITUDE_AT_END": 0.03,
         "WAVE_LENGTH_AT_START": 1.0, "WAVE_LENGTH_AT_END": 0.5}
    lin = read_rdf(_file(tmp_path, _two_d("sine_sweep", p), "lin.rdf"))
    # linear frequency 1 -> 2 cycles/m over 3 m: phase 2 pi s (1 + s / 6); the first zero
    # after the start where s + s^2/6 = 1/2 cycle: s = 3 (sqrt(4/3) - 1) = 0.4641 m
    s1 = 3 * (math.sqrt(4 / 3) - 1)
    f = lambda s: float(lin.height(1.0 + s, 0.0))  # noqa: E731
    assert brentq(f, 0.3, 0.6, xtol=1e-12) == pytest.approx(s1, abs=1e-9)
    # 4.5 cycles over the sweep end it at a zero; amplitude 0.02 half-way, at a quarter phase
    assert abs(f(3.0)) < 1e-15 and f(-0.01) == 0.0 and f(3.01) == 0.0
    s_q = brentq(lambda s: s * (1 + s / 6) - 1.25, 0.5, 3)  # 1.25 cycles: sin = 1
    assert f(s_q) == pytest.approx(0.01 + 0.02 * s_q / 3, abs=1e-12)
    log = read_rdf(_file(tmp_path, _two_d("sine_sweep", {**p, "SWEEP_TYPE": 1}), "log.rdf"))
    # logarithmic: every cycle shorter than the last by the same factor, exp(-l0 / s_inf),
    # s_inf = l0 L / (l0 - l1) = 6 m
    g = lambda s: float(log.height(1.0 + s, 0.0))  # noqa: E731
    s = np.linspace(0.01, 2.99, 3000)
    z = log.height(1.0 + s, 0.0)
    rising = np.flatnonzero((z[:-1] < 0) & (z[1:] >= 0))  # upward zero crossings: whole cycles
    up = [brentq(g, s[i], s[i + 1], xtol=1e-13) for i in rising]
    assert len(up) >= 3
    lengths = np.diff([0.0, *up])
    np.testing.assert_allclose(lengths[1:] / lengths[:-1], math.exp(-1 / 6), rtol=1e-9)
    assert lengths[0] == pytest.approx(6 * (1 - math.exp(-1 / 6)), rel=1e-9)


def test_offset_rotation_and_lateral_offset(tmp_path):
    base = {"HEIGHT": 0.05, "START": 5.0, "LENGTH": 0.05}
    raised = read_rdf(_file(tmp_path, _two_d("plank", {**base, "OFFSET": 0.2}), "a.rdf"))
    assert raised.height(0.0, 0.0) == pytest.approx(0.2) and raised.height(5.02, 0) == pytest.approx(0.25)
    # the file's x axis pointing along -x: the plank lies at x = -5.05 .. -5.0
    turned = read_rdf(_file(tmp_path, _two_d("plank", {**base, "ROTATION_ANGLE_XY_PLANE": 180}), "b.rdf"))
    assert turned.height(-5.02, 0.3) == 0.05 and turned.height(5.02, 0.0) == 0.0
    assert turned.run_start == pytest.approx(-5.05 - 5.0)
    g = turned.grid()
    assert g.height(-5.0, 0.0) == pytest.approx(0.05) and g.height(-5.05, 0.0) == pytest.approx(0.05)
    # two tracks: the test wheel's path y = 0 is the right track
    tracks = _two_d("poly_line", {}) + "(XZ_DATA)\n0 0 0\n1 0.2 0.1\n2 0 0\n"
    road = read_rdf(_file(tmp_path, tracks, "c.rdf"))
    assert road.height(1.0, 0.0) == 0.1 and road.height(1.0, LEFT_TRACK_Y) == 0.2
    assert road.height(1.0, LEFT_TRACK_Y / 2) == pytest.approx(0.15) and road.varies_in_y()
    moved = road_from_spec(f"{tmp_path / 'c.rdf'}@{LEFT_TRACK_Y}")
    assert moved.height(1.0, 0.0) == 0.2
    x = np.random.default_rng(5).uniform(-1, 3, 5000)
    y = np.random.default_rng(6).uniform(-2, 4, 5000)
    np.testing.assert_allclose(road.grid().height(x, y), road.height(x, y), atol=1e-12)


# --- units ------------------------------------------------------------------------

@pytest.mark.parametrize("unit, scale", [("mm", 1000.0), ("cm", 100.0), ("inch", 1 / 0.0254),
                                         ("foot", 1 / 0.3048), ("km", 1e-3)])
def test_units_convert_to_metres(tmp_path, unit, scale):
    rows = np.array([[0.0, 0.0, 0.0], [1.0, 0.1, 0.05], [1.5, -0.02, 0.0], [3.0, 0.0, 0.0]])
    metric = _two_d("poly_line", {"OFFSET": 0.01}) + "(XZ_DATA)\n" + "\n".join(
        " ".join(repr(float(v)) for v in r) for r in rows) + "\n"
    other = _two_d("poly_line", {"OFFSET": 0.01 * scale},
                   units=f"[UNITS]\nLENGTH = '{unit}'\n") + "(XZ_DATA)\n" + "\n".join(
        " ".join(repr(float(v * scale)) for v in r) for r in rows) + "\n"
    a, b = read_rdf(_file(tmp_path, metric, "m.rdf")), read_rdf(_file(tmp_path, other, "u.rdf"))
    x, y = np.linspace(-1, 4, 501), np.linspace(-1, 3, 501)
    np.testing.assert_allclose(b.height(x, y), a.height(x, y), rtol=1e-12, atol=1e-15)


def test_angle_units(tmp_path):
    deg = read_rdf(_file(tmp_path, _two_d("plank", {"HEIGHT": 0.05, "START": 5, "LENGTH": 0.05,
                                                    "DIRECTION": 20}), "d.rdf"))
    rad = read_rdf(_file(tmp_path, _two_d("plank", {"HEIGHT": 0.05, "START": 5, "LENGTH": 0.05,
                                                    "DIRECTION": math.radians(20)},
                                          units="[UNITS]\nANGLE = 'radians'\n"), "r.rdf"))
    x, y = np.random.default_rng(7).uniform(4, 6, 5000), np.random.default_rng(8).uniform(-2, 2, 5000)
    np.testing.assert_array_equal(rad.height(x, y), deg.height(x, y))


# --- round trips --------------------------------------------------------------------

def test_cleat_round_trip_through_a_2d_file(tmp_path):
    cleat = road_from_spec("cleat:76.3x76.3")
    back = read_rdf(write_rdf(cleat, tmp_path / "cleat.rdf", method="2D"))
    g = cleat.grid()
    xn = g.x0 + g.dx * np.arange(g.z.shape[0])
    np.testing.assert_array_equal(back.height(xn, 0.0), cleat.height(xn, 0.0))  # written nodes: bit for bit
    x = np.random.default_rng(9).uniform(3.0, 21.0, 50000)
    np.testing.assert_allclose(back.height(x, 1.0), g.height(x, 1.0), atol=1e-12)  # linear between
    np.testing.assert_allclose(back.grid().height(x, -1.0), g.height(x, -1.0), atol=1e-12)
    assert not back.varies_in_y()


def test_crg_round_trip_through_a_3d_shell(tmp_path):
    crg = CrgRoad(DATA / "handmade_banked.crg")
    back = read_rdf(write_rdf(crg, tmp_path / "banked.rdf", method="3D", mu=0.9))
    g = crg.grid()
    nx, ny = g.z.shape
    X, Y = np.meshgrid(g.x0 + g.dx * np.arange(nx), g.y0 + g.dy * np.arange(ny), indexing="ij")
    # every node is read bit for bit; the query there rounds only in the last digit
    nodes = back.vertices[np.lexsort((back.vertices[:, 1], back.vertices[:, 0]))]
    np.testing.assert_array_equal(nodes, np.column_stack([X.ravel(), Y.ravel(), crg.height(X, Y).ravel()]))
    np.testing.assert_allclose(back.height(X, Y), crg.height(X, Y), rtol=0, atol=1e-15)
    # each cell is split from node (i, j) to (i+1, j+1): its centre is the mean of those two
    cx, cy = X[:-1, :-1] + g.dx / 2, Y[:-1, :-1] + g.dy / 2
    np.testing.assert_allclose(back.height(cx, cy), 0.5 * (g.z[:-1, :-1] + g.z[1:, 1:]), atol=1e-12)
    assert np.all(back.friction(cx, cy) == 0.9)
    # a mesh written as a shell reads back the same mesh
    again = read_rdf(write_rdf(back, tmp_path / "again.rdf", method="3D"))
    np.testing.assert_array_equal(again.vertices, back.vertices)
    np.testing.assert_array_equal(again.triangles, back.triangles)


# --- bad files: each an InputError naming file and line ------------------------------

SHELL = "[MODEL]\nMETHOD = '3D'\n[NODES]\n1 0 0 0\n2 1 0 0\n3 0 1 0\n[ELEMENTS]\n"
BAD = {
    "non-numeric": (_two_d("plank", {"HEIGHT": "abc", "START": 5, "LENGTH": 0.05}), 8, "HEIGHT"),
    "nan in a row": (_two_d("poly_line", {}) + "(XZ_DATA)\n0 0 0\n1 nan 0\n", 11, "finite"),
    "inf node": (SHELL.replace("2 1 0 0", "2 inf 0 0") + "1 2 3 1\n", 5, "finite"),
    "bad node id": (SHELL + "1 2 7 1\n", 8, "node 7"),
    "degenerate": (SHELL.replace("3 0 1 0", "3 2 0 0") + "1 2 3 1\n", 8, "degenerate"),
    "unknown type": (_two_d("stochastic_uneven", {}), 6, "unknown ROAD_TYPE"),
    "unknown unit": (_two_d("flat", {}, units="[UNITS]\nLENGTH = 'furlong'\n"), 2, "furlong"),
    "row width": (_two_d("poly_line", {}) + "(XZ_DATA)\n0 0 0\n1 0\n", 11, "2 values"),
    "x decreasing": (_two_d("poly_line", {}) + "(XZ_DATA)\n0 0 0\n2 0 0\n1 0 0\n", 12, "increase"),
    "missing key": (_two_d("plank", {"START": 5, "LENGTH": 0.05}), 7, "HEIGHT"),
    "header": ("[MODEL\nMETHOD = '2D'\n", 1, "block header"),
    "duplicate node": (SHELL.replace("3 0 1 0", "2 0 1 0") + "1 2 3 1\n", 6, "twice"),
    "zero slope": (_two_d("ramp", {"HEIGHT": 0.1, "START": 1, "SLOPE": 0}), 10, "SLOPE"),
    "unterminated": (_two_d("flat", {}).replace("'flat'", "'flat"), 6, "unterminated"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_files_name_file_and_line(tmp_path, case):
    text, line, fragment = BAD[case]
    path = _file(tmp_path, text, "bad.rdf")
    with pytest.raises(InputError, match=fragment) as info:
        read_rdf(path)
    assert info.value.source == str(path) and info.value.line == line
    assert str(info.value).startswith(f"{path}, line {line}: ")


@pytest.mark.parametrize("text, fragment", [
    (UNITS_M, "no \\[MODEL\\] block"),
    (_two_d("poly_line", {}), "XZ_DATA"),
    ("[MODEL]\nMETHOD = '3D'\n[NODES]\n1 0 0 0\n", "ELEMENTS"),
])
def test_missing_blocks(tmp_path, text, fragment):
    path = _file(tmp_path, text, "missing.rdf")
    with pytest.raises(InputError, match=fragment) as info:
        read_rdf(path)
    assert info.value.source == str(path)


def test_spec_names_a_missing_file(tmp_path):
    with pytest.raises(InputError, match="no such Adams road data file"):
        road_from_spec(str(tmp_path / "nowhere.rdf"))


def test_cli_exports_rdf_and_obj_that_read_back_as_the_road(tmp_path):
    """`tyrelab road export ROAD -o FILE.rdf|.obj`: the file read back as a road
    has the road's heights at its grid nodes."""
    from tyrelab.cli.main import main
    from tyrelab.road.spec import road_from_spec

    road = road_from_spec("cleat:50x50")
    grid = road.grid()
    x = grid.x0 + grid.dx * np.arange(grid.z.shape[0])
    for name in ("c.rdf", "c.obj"):
        out = tmp_path / name
        assert main(["road", "export", "cleat:50x50", "-o", str(out)]) == 0
        back = road_from_spec(str(out))
        np.testing.assert_allclose(back.height(x, np.zeros_like(x)), road.height(x, np.zeros_like(x)),
                                   rtol=0, atol=1e-12)
