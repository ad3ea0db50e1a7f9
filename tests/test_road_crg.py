"""OpenCRG reading and writing, checked against the ASAM C library (pycrg) and pyopencrg."""

from pathlib import Path

import numpy as np
import pycrg
import pyopencrg
import pytest

from tyrelab.errors import InputError
from tyrelab.road.crg import CrgRoad, write_crg
from tyrelab.road.grid import road_heights
from tyrelab.road.spec import road_from_spec

DATA = Path(__file__).parent / "data" / "roads"
FILES = sorted(DATA.glob("*.crg"))
TOL = 1e-6  # m, the agreement the issue asks for


def _reference(path, u, v):
    """Heights from the ASAM C library, no modifiers (NaN where the file is empty)."""
    with pycrg.DataSet.open(path, apply_modifiers=False) as ds:
        cp = ds.create_contact_point()
        return cp.uv_to_z_many(u, v)


def _uv_range(path):
    with pycrg.DataSet.open(path, apply_modifiers=False) as ds:
        return ds.u_range(), ds.v_range()


def test_all_reference_files_are_here():
    assert len(FILES) == 11


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
@pytest.mark.parametrize("v_offset", [0.0, 0.4])
def test_heights_agree_with_c_library(path, v_offset):
    (u0, u1), (v0, v1) = _uv_range(path)
    rng = np.random.default_rng(8608)
    u = rng.uniform(u0, u1, 3000)
    v = rng.uniform(v0, v1, 3000)
    ref = _reference(path, u, v)
    valid = np.isfinite(ref)
    assert valid.sum() >= 1000
    road = CrgRoad(path, v_offset=v_offset)
    z = road.height(u, v - v_offset)
    assert np.max(np.abs(z[valid] - ref[valid])) < TOL
    assert np.all(np.isfinite(z))  # empty cells are filled, never NaN
    # the compiled grid form the contact models query
    g = road.grid()
    out = np.empty(u.size)
    road_heights(g.surface(), u, v - v_offset, out)
    assert np.max(np.abs(out[valid] - ref[valid])) < TOL
    assert np.all(np.isfinite(g.z))


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_extent_is_the_files_uv_range_shifted(path):
    (u0, u1), (v0, v1) = _uv_range(path)
    xmin, xmax, ymin, ymax = CrgRoad(path, v_offset=0.25).extent()
    assert xmin == pytest.approx(u0, abs=1e-9) and xmax == pytest.approx(u1, abs=1e-9)
    assert ymin == pytest.approx(v0 - 0.25, abs=1e-9) and ymax == pytest.approx(v1 - 0.25, abs=1e-9)


@pytest.mark.parametrize("name", ["handmade_straight.crg", "belgian_block.crg",
                                  "handmade_curved_banked_sloped.crg"])
def test_empty_cells_follow_the_c_librarys_keep_last_policy(name):
    path = DATA / name
    with pycrg.DataSet.open(path, apply_modifiers=False) as ds:
        raw = ds.grid()
        ds.modifier_set_int(pycrg.MOD_GRID_NAN_MODE, pycrg.GRID_NAN_KEEP_LAST)
        ds.modifiers_apply()
        filled = ds.grid()
    assert np.isnan(raw.z).any()
    road = CrgRoad(path)
    # node heights on the file's own nodes, minus reference line and banking
    rel = road.height(raw.u[:, None], raw.v[None, :]) - raw.ref_z[:, None] - raw.bank[:, None] * raw.v
    assert np.max(np.abs(rel - filled.z)) < TOL


def test_minimalist_header_puts_v_from_zero_to_width_like_the_c_library():
    # the minimalist file is the same road as handmade_straight.crg (its own comment says so),
    # whose v runs -1.5 .. 1.5; with v in [0, width] it is shifted by +1.5 m
    mini = CrgRoad(DATA / "handmade_straight_minimalist.crg")
    full = CrgRoad(DATA / "handmade_straight.crg")
    assert mini.extent()[2:] == pytest.approx((0.0, 3.0))
    rng = np.random.default_rng(3)
    u, v = rng.uniform(0, 22, 500), rng.uniform(-1.5, 1.5, 500)
    assert np.max(np.abs(mini.height(u, v + 1.5) - full.height(u, v))) < TOL


def test_road_spec_reads_a_crg_at_an_offset():
    road = road_from_spec(f"{DATA / 'halfround_4in.crg'}@1.5")
    assert isinstance(road, CrgRoad) and road.v_offset == 1.5
    # a half-round of radius 4 in: 101.6 mm high, 203.2 mm long, a little after u = 50 m
    u = np.linspace(49, 52, 30001)
    z = road.height(u, 0.0 * u)
    assert z.max() == pytest.approx(0.1016, rel=0.02)
    on = u[z > 1e-6]
    assert on[-1] - on[0] == pytest.approx(0.2032, abs=0.02)
    assert 50.0 <= on[0] and on[-1] <= 50.3


# --- writing -------------------------------------------------------------------

def _roads_to_write():
    """(road, grid spacing to write at): CRG roads, a 2D obstacle, a 3D obstacle (coarsened)."""
    return [(CrgRoad(DATA / "belgian_block.crg"), None),
            (CrgRoad(DATA / "handmade_curved_banked_sloped.crg"), None),
            (road_from_spec("bump:150"), None), (road_from_spec("cleat:50x50@30"), (0.01, 0.02))]


@pytest.mark.parametrize("fmt", ["KDBI", "LDFI", "KRBI", "LRFI"])
@pytest.mark.parametrize("index", range(4))
def test_written_crg_reads_back_in_pycrg_and_pyopencrg(tmp_path, fmt, index):
    road, spacing = _roads_to_write()[index]
    path = write_crg(road, tmp_path / "road.crg", spacing=spacing, fmt=fmt)
    xmin, xmax, ymin, ymax = road.extent()
    rng = np.random.default_rng(index)
    x, y = rng.uniform(xmin, xmax, 1000), rng.uniform(ymin, ymax, 1000)
    want = road.grid(spacing).height(x, y)
    with pycrg.DataSet.open(path) as ds:  # as any OpenCRG user would open it
        z_c = ds.create_contact_point().uv_to_z_many(x, y)
    z_py = pyopencrg.read(path).uv_to_z(x, y)
    # single precision formats keep ~7 digits: heights of ~2 m (belgian block) lose ~1e-7 m
    assert np.max(np.abs(z_c - want)) < TOL
    assert np.max(np.abs(z_py - want)) < TOL
    assert np.max(np.abs(CrgRoad(path).height(x, y) - want)) < TOL
    assert [p.name for p in tmp_path.iterdir()] == ["road.crg"]


def test_failed_write_leaves_no_file(tmp_path, monkeypatch):
    def broken(path, *args, **kwargs):
        Path(path).write_text("$CT\npartial")
        raise RuntimeError("disk full")

    monkeypatch.setattr(pycrg, "write", broken)
    with pytest.raises(RuntimeError):
        write_crg(road_from_spec("bump:150"), tmp_path / "road.crg")
    assert list(tmp_path.iterdir()) == []


# --- bad input -----------------------------------------------------------------

def _corrupt(tmp_path, name, edit):
    data = (DATA / name).read_bytes()
    path = tmp_path / f"bad_{name}"
    path.write_bytes(edit(data))
    return path


@pytest.mark.parametrize("name, edit", [
    ("belgian_block.crg", lambda b: b[:1_000_000]),            # binary cut mid-record
    ("belgian_block.crg", lambda b: b[:-3]),                    # a few bytes lost
    ("halfround_4in.crg", lambda b: b[:len(b) - 80 * 200]),     # whole blocks lost
    ("handmade_straight.crg", lambda b: b[:3000]),              # text cut short
    ("handmade_straight.crg", lambda b: b.replace(b"#:LRFI", b"#:LXXI")),
    ("handmade_straight.crg", lambda b: b.replace(b"REFERENCE_LINE_INCREMENT", b"REFERENCE_LINE_INCRXMENT")),
    ("handmade_straight.crg", lambda b: b.replace(b"$ROAD_CRG", b"$ROAD_CXG")),
    ("handmade_straight.crg", lambda b: b"not a crg file\n"),
    ("handmade_straight.crg", lambda b: b""),
])
def test_bad_files_give_an_input_error_naming_the_file(tmp_path, name, edit):
    path = _corrupt(tmp_path, name, edit)
    with pytest.raises(InputError) as info:
        CrgRoad(path)
    assert str(path) in str(info.value)


def test_missing_file_is_an_input_error(tmp_path):
    with pytest.raises(InputError, match="no such OpenCRG file"):
        CrgRoad(tmp_path / "nothing.crg")


def test_cross_section_without_any_height_is_an_input_error(tmp_path):
    text = (DATA / "handmade_straight_minimalist.crg").read_text().splitlines()
    sep = next(i for i, line in enumerate(text) if line.startswith("$$$$"))
    # blank out the 5th cross section entirely
    width = len(text[sep + 5])
    text[sep + 5] = " *missing*" * (width // 10)
    path = tmp_path / "hole.crg"
    path.write_text("\n".join(text) + "\n")
    with pytest.raises(InputError, match="no valid height"):
        CrgRoad(path)


def test_a_final_newline_after_binary_data_is_tolerated(tmp_path):
    path = _corrupt(tmp_path, "halfround_4in.crg", lambda b: b + b"\n")
    x = np.linspace(49, 52, 301)
    want = CrgRoad(DATA / "halfround_4in.crg").height(x, 0 * x)
    assert np.array_equal(CrgRoad(path).height(x, 0 * x), want)
