"""The thesis's built-in tracks (section 3.4.3) against what the thesis says about them."""

import numpy as np
import pycrg
import pytest

from tyrelab.road.base import Road
from tyrelab.road.crg import write_crg
from tyrelab.road.spec import road_from_spec
from tyrelab.road.spectrum import displacement_spectral_density, fit_power_law
from tyrelab.road.tracks import ANGLE, TRACKS

NAMES = ["belgian-paving", "fatigue-track", "corrugations", "corrugations-angled", "trapezoidal-bump"]


@pytest.fixture(scope="module")
def roads():
    return {name: TRACKS[name]() for name in NAMES}


def test_the_five_names():
    assert sorted(TRACKS) == sorted(NAMES)


@pytest.mark.parametrize("name", NAMES)
def test_tracks_are_deterministic_finite_4_m_wide_roads(roads, name):
    road = roads[name]
    assert isinstance(road, Road) and road_from_spec(name).name == road.name
    g = road.grid()
    again = TRACKS[name]().grid()
    assert np.array_equal(g.z, again.z)
    assert np.all(np.isfinite(g.z))
    xmin, xmax, ymin, ymax = road.extent()
    assert (ymin, ymax) == (-2.0, 2.0)
    assert g.nbytes <= 64e6  # 100 m x 4 m at 10 mm fits in 64 MB


@pytest.mark.parametrize("name", ["belgian-paving", "fatigue-track", "corrugations"])
def test_random_and_corrugated_tracks_are_100_m_long(roads, name):
    x = np.arange(0.0, 120.0, 0.005)
    z = roads[name].height(x, np.zeros_like(x))
    on = x[np.abs(z) > 1e-6]
    assert on[-1] - on[0] == pytest.approx(100.0, abs=0.6)
    assert on[0] >= 4.9  # nothing before the 5 m run-in


@pytest.mark.parametrize("name, a, n", [("belgian-paving", 3.48e-5, 1.6), ("fatigue-track", 3.42e-5, 2.9)])
def test_track_spectrum_fits_the_thesis_values(roads, name, a, n):
    a_fit, n_fit = fit_power_law(roads[name])
    assert a_fit == pytest.approx(a, rel=0.05)
    assert n_fit == pytest.approx(n, abs=0.05)


def test_belgian_paving_blocks_are_134_mm_long_with_random_widths(roads):
    road = roads["belgian-paving"]
    start = 5.0
    # along the road, the joints (rounded edges, several mm deep) recur every 134 mm
    y = np.linspace(-1.9, 1.9, 97)[:, None]
    joint = start + 0.134 * np.arange(100, 140)[None, :]
    centre = joint + 0.067
    assert np.median(road.height(centre, y) - road.height(joint, y)) > 0.005
    assert np.median(np.abs(road.height(centre, y) - road.height(joint + 0.03, y))) < 1e-4
    # across the road, joint positions differ from course to course and widths are 100-200 mm
    y = np.arange(-1.9, 1.9, 0.001)
    joints = []
    for k in (200, 201):
        h = road.height(np.full_like(y, start + 0.134 * k + 0.067), y)
        is_min = (h[1:-1] < h[:-2]) & (h[1:-1] <= h[2:]) & (h[1:-1] < h.max() - 0.006)
        joints.append(y[1:-1][is_min])
    widths = np.diff(joints[0])
    assert np.all((widths > 0.095) & (widths < 0.205)) and widths.std() > 0.01
    assert not np.allclose(joints[0][:5], joints[1][:5], atol=0.005)


def test_parallel_corrugations_760_mm_25_mm(roads):
    road = roads["corrugations"]
    assert not road.varies_in_y()
    x = np.arange(0.0, 110.0, 0.002)
    z = road.height(x, 0 * x)
    assert (z.max() - z.min()) / 2 == pytest.approx(0.025, rel=1e-3)
    phi, s = displacement_spectral_density((x, z), segment=60.0)
    assert phi[np.argmax(s)] == pytest.approx(1 / 0.76, abs=phi[1] - phi[0])
    assert np.allclose(road.height(x, 1.7), z)


def test_angled_corrugations_have_crests_at_the_angle(roads):
    road = roads["corrugations-angled"]
    assert road.varies_in_y()
    t = np.tan(np.radians(ANGLE))
    x = np.linspace(20.0, 30.0, 500)
    for y in (-1.5, 0.8):
        assert np.allclose(road.height(x - y * t, y), road.height(x, 0.0), atol=1e-12)
    # spacing normal to the crests is 760 mm: along x it is 0.76 / cos(angle)
    xs = np.arange(20.0, 80.0, 0.001)
    phi, s = displacement_spectral_density((xs, road.height(xs, 0 * xs)), segment=60.0)
    assert phi[np.argmax(s)] == pytest.approx(np.cos(np.radians(ANGLE)) / 0.76, abs=phi[1] - phi[0])


def test_trapezoidal_bump_is_150_mm(roads):
    x = np.linspace(0, 20, 20001)
    assert roads["trapezoidal-bump"].height(x, 0 * x).max() == pytest.approx(0.150)


def test_track_exports_to_crg(tmp_path, roads):
    road = roads["fatigue-track"]
    path = write_crg(road, tmp_path / "fatigue.crg", spacing=(0.05, 0.05), fmt="KRBI")
    rng = np.random.default_rng(0)
    x, y = rng.uniform(5, 105, 1000), rng.uniform(-2, 2, 1000)
    want = road.grid((0.05, 0.05)).height(x, y)
    with pycrg.DataSet.open(path) as ds:
        got = ds.create_contact_point().uv_to_z_many(x, y)
    assert np.max(np.abs(got - want)) < 1e-6


@pytest.mark.parametrize("name", ["belgian-paving", "fatigue-track", "corrugations-angled"])
def test_building_a_track_grid_stays_within_64_mb(name):
    import gc
    import tracemalloc

    gc.collect()
    tracemalloc.start()
    try:
        grid = TRACKS[name]().grid()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert grid.z.shape[1] == 401 and grid.dx <= 0.01 and grid.dy <= 0.01
    assert peak <= 64e6


def test_a_track_is_built_once_and_runs_leave_it_as_built(roads):
    """``road_from_spec`` builds each track once per process (``road.spec.built_track``: a
    study runs each many times), which is only right while nothing writes into its grid:
    a trailer run over the paving, on rigid ground and on a soil laid over it (the soil's
    bed is written as the wheel passes), leaves the shared grid equal to a fresh build's."""
    import tyrelab

    shared = road_from_spec("belgian-paving")
    assert road_from_spec("BELGIAN-PAVING") is shared and shared.grid() is shared.grid()
    for terrain in (None, "sandy-loam"):  # 2 s at 18 km/h: over the first 5 m of blocks
        tyrelab.simulate(model="point", road="belgian-paving", terrain=terrain, speed=5.0,
                         duration=2.0, progress=False)
    fresh = roads["belgian-paving"].grid()
    assert np.array_equal(shared.grid().z, fresh.z) and shared.grid().x0 == fresh.x0
