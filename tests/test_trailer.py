"""The towed test trailer (thesis 3.4, 5.2)."""

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from tyrelab.road.obstacles import Flat
from tyrelab.rig.trailer import Trailer
from tyrelab.tyre.model import TyreModel

G = 9.80665
# thesis Table 3-4: wheel load [kg] per load case
TABLE_3_4 = {"LC1": 2375, "LC2": 3895, "LC3": 5095}


@pytest.mark.parametrize("case", ["LC1", "LC2", "LC3"])
@pytest.mark.parametrize("stiffness", ["table", "linear"])
def test_static_test_wheel_load_is_the_load_case(xzl, case, stiffness):
    run = Trailer(TyreModel(xzl.with_stiffness(stiffness)), case).run(Flat(), 12 / 3.6, duration=3.0)
    target = TABLE_3_4[case] * G
    assert run["FZW"].iloc[-500:].mean() == pytest.approx(target, rel=0.005)
    assert run["FZ"].iloc[-500:].mean() == pytest.approx(target, rel=0.005)
    # the left wheel, on the same flat ground, carries the same load
    assert run["FZ_LEFT"].iloc[-500:].mean() == pytest.approx(target, rel=0.005)
    # and the trailer does not drift: it starts in equilibrium
    assert run["FZW"].std() < 1e-6 * target


@pytest.mark.parametrize("load", [15000.0, 30000.0])   # below LC1 (no ballast) and above
def test_wheel_load_in_newtons(xzl, load):
    run = Trailer(TyreModel(xzl), load).run(Flat(), 5.0, duration=1.0)
    assert run["FZW"].mean() == pytest.approx(load, rel=0.005)


def test_cleat_run_conserves_and_stays_physical(xzl):
    run = Trailer(TyreModel(xzl), "LC1").run("cleat:50x50", 12 / 3.6)
    fz = run["FZW"].to_numpy()
    assert np.all(np.isfinite(run.to_numpy()))
    assert fz.min() >= 0.0
    # before the cleat the wheel rolls at the static load
    before = run["X_WC"] < 4.0
    assert fz[before.to_numpy()] == pytest.approx(TABLE_3_4["LC1"] * G, rel=1e-6)
    # the cleat loads the wheel well above static, and the wheel leaves the
    # ground after it (the rigid disc's impulse-like response, thesis Fig 5-4)
    assert fz.max() > 2.0 * TABLE_3_4["LC1"] * G
    assert fz.min() == 0.0
    # the point contact pushes back on the cleat's leading corner (FX < 0)
    on_cleat = (run["X_CP"] > 4.99) & (run["X_CP"] < 5.0001) & (run["FZW"] > 0)
    assert (run.loc[on_cleat, "FX"] < 0).all() and on_cleat.any()


def test_perpendicular_cleat_gives_no_lateral_force(xzl):
    run = Trailer(TyreModel(xzl), "LC1").run("cleat:50x50", 12 / 3.6, duration=3.0)
    assert np.abs(run["FY"]).max() < 1e-6 * run["FZW"].max()


def test_inclination_is_the_frames_roll_of_the_axle(xzl):
    """INCLANGL is the wheel plane's angle to the road's normal (TYDEX), here the level road's
    z axis. The trailer's axle is its body's y axis, Ry(pitch) Rx(roll) (0, 1, 0): its
    inclination is asin(cos(PITCH) sin(ROLL)), from the frame's own channels. Over an
    oblique cleat the frame rolls; the point model's INCLANGL, measured from its contact
    normal, which lies in the disc's own plane, was 0 throughout."""
    run = Trailer(TyreModel(xzl), "LC1").run("cleat:50x50@45", 12 / 3.6, duration=3.0)
    expected = np.arcsin(np.cos(run["PITCH"]) * np.sin(run["ROLL"]))
    assert np.abs(expected).max() > np.radians(1.0)           # the case: the frame rolls
    np.testing.assert_allclose(run["INCLANGL"], expected, rtol=0, atol=1e-12)


def test_results_are_deterministic(xzl):
    a = Trailer(TyreModel(xzl), "LC2").run("bump:150", 8 / 3.6)
    b = Trailer(TyreModel(xzl), "LC2").run("bump:150", 8 / 3.6)
    np.testing.assert_array_equal(a.to_numpy(), b.to_numpy())


def test_left_wheel_model_is_the_one_given(xzl):
    """A left wheel of another contact model (volume, for a point test wheel) starts in the
    same static equilibrium -- every channel identical until the test wheel meets the cleat
    -- and then really is another tyre: the trailer's roll after the cleat differs."""
    import tyrelab
    from tyrelab.errors import InputError
    same = tyrelab.simulate(model="point", road="cleat:50x50", duration=2.5, progress=False)
    other = tyrelab.simulate(model="point", road="cleat:50x50", duration=2.5, progress=False,
                             left_wheel="volume")
    assert other.attrs["metadata"]["left_wheel"] == "volume"
    assert same.attrs["metadata"]["left_wheel"] == "point"
    t = same["RUNTIME"].to_numpy()
    before = t < 1.0  # the tyre touches the cleat (x = 5 m - 0.34 m) at about 1.4 s
    for channel in ("FZ_HUB", "FX_HUB", "FY_HUB", "MX"):
        a, b = same[channel].to_numpy(), other[channel].to_numpy()
        assert np.max(np.abs(a[before] - b[before])) <= 1e-9 * max(np.max(np.abs(a)), 1.0), channel
    # the left tyre matters after the cleat (the trailer rolls; a cambered wide tyre sits on
    # its shoulder, a disc does not): on the test wheel's load, over 1 kN
    assert np.max(np.abs(same["FZ_HUB"] - other["FZ_HUB"])) > 1000.0
    with pytest.raises(InputError, match="left"):
        Trailer(TyreModel(xzl, "point"), left=TyreModel(xzl.with_stiffness("linear"), "point"))
    with pytest.raises(InputError, match="trailer"):
        tyrelab.simulate(rig="rolling", left_wheel="point", duration=0.1)


def test_a_road_with_a_grade_is_no_road_for_the_trailer_or_the_rolling_rig():
    """The trailer's hitch and left wheel stay on level ground: on a measured road that rises
    1.21 m over 22 m (handmade_sloped.crg, from the OpenCRG distribution) its frame rolls to
    follow the test wheel, 31 deg at 30 km/h ("overturned", with advice about obstacles);
    the rolling rig holds its axle at a fixed height and ends on its rim. A warning says why
    before the run. The medians of the run's first and last quarter, not its range or a
    fitted line, tell a grade from obstacles and rough tracks between level ends, which are
    these rigs' work and say nothing."""
    from pathlib import Path

    import tyrelab
    from tyrelab.guards import PhysicsWarning, check_level_for_trailer, level_change
    from tyrelab.road.spec import road_from_spec

    sloped = Path(__file__).parent / "data" / "roads" / "handmade_sloped.crg"
    road = road_from_spec(str(sloped))
    x0, x1 = road.extent()[:2]
    z0, z1 = road.height(np.array([x0, x1]), np.zeros(2))
    end = float(z1 - z0)
    assert end == pytest.approx(1.21, abs=0.01)                 # the file's own rise
    assert 0.5 * end < level_change(road, x0, x1) <= end
    for rig, words in (("trailer", "hitch and left wheel stay on level ground"),
                       ("rolling", "holds its axle at a fixed height")):
        with warnings.catch_warnings(record=True) as found:
            warnings.simplefilter("always")
            tyrelab.simulate(model="point", rig=rig, road=str(sloped), speed=30 / 3.6, progress=False)
        said = [str(w.message) for w in found if issubclass(w.category, PhysicsWarning)]
        assert "from the first quarter" in said[0] and words in said[0], said
        assert "quarter-vehicle rig" in said[0]
        assert "overturned" in said[1] or "rim contact" in said[1]      # what it explains
    for name in ("pothole:500x2000x600", "belgian-paving", "fatigue-track", "corrugations-angled",
                 "step:100", "iso8608:H"):
        road = road_from_spec(name)
        x0, x1 = road.extent()[:2]
        assert check_level_for_trailer(road, x0, x1, 2.4) is None, name


@pytest.mark.parametrize("rig", ["trailer", "quarter-vehicle", "rolling"])
def test_a_run_that_ends_before_the_road_relief_says_so(rig):
    """The 50 x 50 cleat's edge is at x = 5 m (obstacles.Cleat's start). Towed at 12 km/h from
    x = 0 for 1.0 s, the wheel ends 3.33 m along and reaches R0 = 0.7 m ahead of its centre:
    the run never meets the cleat, the whole record is level rolling, and a warning says so
    with the least duration that would meet it, (5 - R0) / v. Run for 1.6 s it meets the
    cleat and nothing is said."""
    import tyrelab
    from tyrelab.guards import PhysicsWarning
    from tyrelab.tyre.library import load_tyre

    r0, v = load_tyre().unloaded_radius, 12 / 3.6
    for duration, warned in ((1.0, True), (1.6, False)):
        with warnings.catch_warnings(record=True) as found:
            warnings.simplefilter("always")
            run = tyrelab.simulate(model="point", rig=rig, road="cleat:50x50", speed=v,
                                   duration=duration, progress=False)
        said = [str(w.message) for w in found if issubclass(w.category, PhysicsWarning)]
        said = [s for s in said if "before its first relief" in s]
        assert bool(said) == warned, said
        if warned:
            assert f"run it for at least {(5.0 - r0) / v:.3g} s" in said[0] and "x = 5 m" in said[0]
            fz = run["FZW"].to_numpy()
            assert fz.max() - fz.min() < 1e-6 * fz.mean()     # level rolling throughout, as it says


def test_first_relief_along_the_wheel_path():
    from pathlib import Path

    from tyrelab.guards import first_relief
    from tyrelab.road.spec import road_from_spec

    data = Path(__file__).parent / "data" / "roads"
    assert first_relief(road_from_spec("flat"), 0.0) is None
    assert first_relief(road_from_spec("cleat:50x50"), 0.0) == pytest.approx(5.0, abs=0.005)
    assert 50.0 <= first_relief(road_from_spec(str(data / "halfround_4in.crg")), 0.0) <= 50.3
    assert first_relief(road_from_spec(str(data / "handmade_sloped.crg")), 0.0) < 1.0  # a grade


MF61 = Path(__file__).resolve().parents[1] / "examples" / "data" / "MagicFormula61_Parameters.tir"


@pytest.fixture(scope="module")
def offset_tyre_runs(tmp_path_factory):
    """The MF 6.1 example tyre, whose forces at zero slip do not vanish (PHY1, PVY1, QSY1:
    -43 N across, -46 N of drag at 4 kN), on the trailer on a flat road at 3 and 42 km/h;
    its TYRESIDE made 'UNKNOWN', so that both wheels carry the tyre as measured (the file
    says 'RIGHT': the left wheel would be mirrored, test below)."""
    from tyrelab.api import make_tyre_model
    text = MF61.read_text()
    unknown = text.replace("TYRESIDE                 =    'RIGHT'", "TYRESIDE                 =    'UNKNOWN'")
    assert unknown != text
    path = tmp_path_factory.mktemp("mf61") / "MagicFormula61_unknown_side.tir"
    path.write_text(unknown)
    model = make_tyre_model(tyre=str(path), model="point", handling="mf")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return {kmh: (Trailer(model, 4000.0), Trailer(model, 4000.0).run(Flat(), kmh / 3.6,
                                                                          duration=2.0))
                for kmh in (3, 42)}


@pytest.mark.parametrize("kmh", [3, 42])
def test_a_tyre_with_force_offsets_starts_the_trailer_balanced(offset_tyre_runs, kmh):
    """The frame starts where the tyres' own forces leave it still: over 2 s every load and
    angle stays within 1e-6 of its value (started from the static loads, the test wheel's
    load swung by 25 N, 0.6 %, as the frame rolled into that balance)."""
    _, run = offset_tyre_runs[kmh]
    for name in ("FZ", "FZ_LEFT", "FX", "FY"):
        x = run[name].to_numpy()
        assert np.abs(x - x[0]).max() <= 1e-6 * 4000.0, name
    for name in ("PITCH", "ROLL"):
        x = run[name].to_numpy()
        assert np.abs(x - x[0]).max() <= 1e-9, name


def test_a_tyre_measured_on_the_right_is_mirrored_on_the_left_wheel():
    """The MF 6.1 example states TYRESIDE 'RIGHT': the trailer's right (test) wheel carries it
    as measured and its left wheel mirrored, as a vehicle mounts it. The pair is then a mirror
    image about the frame's middle: the offsets' side forces and moments oppose and the frame
    balances with equal loads and no roll (with the same tyre as measured on both, their
    offsets moved 25 N of load between the wheels, 30 N m about the roll axis)."""
    from tyrelab.api import make_tyre_model
    model = make_tyre_model(tyre=str(MF61), model="point", handling="mf")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = Trailer(model, 4000.0).run(Flat(), 42 / 3.6, duration=0.5)
    assert abs(run["FY"].iloc[0]) > 20.0                                  # the offsets are there
    assert np.abs(run["FZ"] - run["FZ_LEFT"]).max() <= 1e-9 * 4000.0
    assert np.abs(run["ROLL"]).max() <= 1e-12


@pytest.mark.parametrize("kmh", [3, 42])
def test_the_balanced_trailer_holds_its_roll_moments_by_hand(offset_tyre_runs, kmh):
    """Statics about the hitch's roll axis (the frame's x axis) at the start, from the run's
    channels:
    the wheel loads' lever (+-track/2), the lateral forces' and the tyres' moments about the
    wheel centres (the outputs' MX), the weight's lever as the frame rolls, and the tyres'
    yaw moment about the hitch projected by the pitch (the universal joint's roll axis tilts
    with the frame). The left wheel is taken to give the test wheel's FY, FX, MX and MZ
    (same tyre, same slip; its load differs by 0.6 %, so do they by as much of their
    share): those moments cancel to within that, where the load transfer alone is 30 N m."""
    trailer, run = offset_tyre_runs[kmh]
    g, s = trailer.geometry, trailer.setup
    row = run.iloc[0]  # the start
    th, ph = row["PITCH"], row["ROLL"]
    half, L = 0.5 * g.track, g.hitch_to_axle
    lever_z = row["Z_WC"] - s.hitch_height                 # wheel centre above the hitch
    transfer = half * (row["FZ_LEFT"] - row["FZ"])        # sum of r_y Fz
    lateral = -lever_z * 2.0 * row["FY"]                  # sum of -r_z Fy
    moments = 2.0 * row["MX"]
    weight = -math.sin(ph) * s.cg[2] * (-s.mass * G)      # r_cg,y (-m g), cg[1] = 0
    yaw = 2.0 * (-L * math.cos(th)) * row["FY"] + 2.0 * row["MZ"]
    roll_moment = math.cos(th) * (transfer + lateral + moments + weight) - math.sin(th) * yaw
    assert abs(transfer) > 25.0
    assert abs(roll_moment) < 0.007 * (abs(transfer) + abs(moments))
