"""The ring on the rigs: static equilibrium against the load-deflection table,
enveloping over a cleat, static press and footprint, tread pattern, CLI."""

import numpy as np
import pytest

from tyrelab.road.obstacles import Flat
from tyrelab.tyre.library import load_cases, load_tyre
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.wheel import WheelLoads, loads_table, pose

G = 9.80665


@pytest.fixture(scope="module")
def xzl300():
    return load_tyre("xzl-16.00R20", 300e3)


def _stand(model, load, seconds=1.5, dt=1e-3):
    """A rim of mass load/g standing on the ring on a flat road (free vertically,
    no spin); returns the centre heights."""
    tyre = model.tyre
    wheel = model.wheel(Flat().grid(), load)
    mass = load / G
    z = tyre.unloaded_radius - tyre.static_deflection(load)
    vz = 0.0
    heights = []
    for _ in range(int(seconds / dt)):
        row = loads_table(wheel, pose(0.0, 0.0, z, velocity=(0.0, 0.0, vz)), dt)[0]
        out = WheelLoads(*row)
        assert np.all(np.isfinite(row)) and out.fzw >= 0.0
        vz += dt * (out.fz / mass - G)
        z += dt * vz
        heights.append(z)
    return np.array(heights)


@pytest.mark.parametrize("pressure,case", [
    (300e3, "LC1"), (550e3, "LC3"),
    # 100 kPa is held out of the identification; the model is 10-17 % too soft
    # there (docs/ring.md), so it stands ~17 mm too low: a known failure
    pytest.param(100e3, "LC1", marks=pytest.mark.xfail(
        strict=True, reason="held-out 100 kPa prediction is 10-17 % too soft"))])
def test_standing_tyre_sits_at_table_deflection(pressure, case):
    tyre = load_tyre("xzl-16.00R20", pressure)
    load = float(load_cases().loc[case, "wheel_load_N"])
    z = _stand(TyreModel(tyre, contact="ring"), load)
    table = tyre.static_deflection(load)
    model = tyre.unloaded_radius - z[-300:].mean()
    # within 10 % of the deflection the load-deflection table gives
    assert abs(model - table) < 0.1 * table, f"model {model * 1e3:.1f} mm, table {table * 1e3:.1f} mm"


def test_free_rolling_tyre_sits_at_its_rolling_equilibrium(xzl300):
    """The same ring from walking pace to the top speed (88 km/h) on the trailer:
    it carries the wheel load where its own rolling equilibrium (found apart,
    at a fixed height, ``TyreModel.equilibrium``) says; at 12 km/h that is
    the table's deflection (10 %, the identification's accuracy); at 88 km/h
    it is less (the spinning belt's centrifugal growth presses it harder onto
    the road at a given height: docs/ring.md, "Starting in equilibrium"); the
    rolling resistance opposes the motion."""
    from tyrelab.rig.trailer import Trailer
    model = TyreModel(xzl300, contact="ring")
    trailer = Trailer(model, "LC1")
    load = trailer.setup.wheel_load
    deflections = []
    for kmh in (12.0, 88.0):
        run = trailer.run("flat", kmh / 3.6, 2.0)
        settled = run.iloc[-1000:]
        deflection = xzl300.unloaded_radius - settled["Z_WC"].mean()
        assert deflection == pytest.approx(model.equilibrium(load, kmh / 3.6).deflection,
                                           rel=0.01)
        deflections.append(deflection)
        assert np.all(run["FZW"] >= 0)
        # steady state: the mean normal force is the static wheel load (the rolling
        # resistance's pitch moment on the trailer shifts it by well under 1 %)
        assert settled["FZW"].mean() == pytest.approx(load, rel=0.02)
        # rolling resistance: against the motion, below 2 % of the load (truck tyres 0.5-1 %)
        assert -0.02 * load < settled["FXW"].mean() < 0.0
    table = xzl300.static_deflection(load)
    assert abs(deflections[0] - table) < 0.1 * table
    assert deflections[1] < deflections[0]


def test_ring_envelops_a_cleat_rigid_disc_does_not(xzl300):
    """Rolling at constant axle height over a cleat shorter than the contact
    patch: the ring's vertical force dips when the cleat is mid-patch
    (Zegelaar 1998, Schmeitz 2004); the rigid disc's force peaks there."""
    from tyrelab.road.obstacles import Cleat
    from tyrelab.rig.rolling import roll_over
    load = float(load_cases().loc["LC3", "wheel_load_N"])
    height = xzl300.unloaded_radius - xzl300.static_deflection(load)
    cleat = Cleat(0.0254, 0.0254, start=1.0)
    centre = 1.0 + 0.0127
    ring = roll_over(TyreModel(xzl300, contact="ring"), cleat, height, 0.6, 1.45, speed=0.25)
    x, fz = ring["x"], ring["FZ"]
    smooth = np.convolve(fz, np.ones(41) / 41, mode="same")
    mid = np.abs(x - centre) < 0.01
    peak_zone = (np.abs(x - centre) > 0.03) & (np.abs(x - centre) < 0.3)
    assert smooth[mid].mean() < 0.98 * smooth[peak_zone].max()
    # rigid disc (point contact) at the same axle height
    disc = TyreModel(xzl300, contact="point")
    xs = np.linspace(0.6, 1.45, 851)
    poses = [pose(x, 0.0, height) for x in xs]
    f = loads_table(disc.wheel(cleat.grid()), poses, 1e-3)[:, WheelLoads._fields.index("fz")]
    assert f[np.abs(xs - centre) < 0.01].mean() >= 0.999 * f.max()


def test_static_press_plate_and_cleat(xzl300):
    from tyrelab.rig.static_press import static_press
    model = TyreModel(xzl300, contact="ring")
    d = np.array([0.0, 0.02, 0.04, 0.06])
    plate = static_press(model, d)
    assert list(plate.columns) == ["deflection", "load", "FX", "FY", "DEFLECT"]
    assert abs(plate["load"].iloc[0]) < 50.0
    assert np.all(np.diff(plate["load"]) > 0)
    assert np.all(np.abs(plate["FX"]) < 0.02 * plate["load"].max())
    for direction in ("lateral", "longitudinal"):
        cleat = static_press(model, d, "cleat:51x51", direction)
        # on a cleat the tyre is softer than on the plate (thesis 3.3.4)
        assert np.all(cleat["load"].iloc[1:].to_numpy() < plate["load"].iloc[1:].to_numpy())
        assert np.all(np.diff(cleat["load"]) > 0)


def test_footprint_and_png(xzl300, tmp_path):
    from tyrelab.report.footprint import plot_footprint
    from tyrelab.rig.static_press import footprint
    res = footprint(TyreModel(xzl300, contact="ring"), 40e3)
    for key in ("x", "y", "pressure", "outline", "length", "width", "load"):
        assert key in res
    assert res["force"].sum() == pytest.approx(res["load"], rel=0.05)
    # the footprint of 40 kN carries 40 kN: the ring is pressed to its own deflection of the
    # load, not to the table's (where it carried 39.5 kN)
    assert res["load"] == pytest.approx(40e3, rel=2e-3)
    assert res["outline"].shape[1] == 2 and np.allclose(res["outline"][0], res["outline"][-1])
    path = plot_footprint(res, tmp_path / "fp.png")
    assert path.stat().st_size > 1000


def test_tread_pattern_blocks(xzl300):
    from tyrelab.tyre.ring.model import ring_params
    even = ring_params(xzl300, None)
    tp = ring_params(xzl300, None, tread_pattern=True)
    area = lambda cp: cp.block_area  # noqa: E731
    assert area(tp).sum() == pytest.approx(area(even).sum())
    # the blocks carry the rubber of their cells: grooves empty some cells, and
    # the areas vary with the pattern
    assert np.sum(area(tp) == 0) > 0
    assert np.std(area(tp)) > 0.2 * np.mean(area(tp))
    pattern = {"pitch": 0.1, "width": 0.3, "rows": ["##..", "..##"]}
    custom = ring_params(xzl300, None, tread_pattern=True, pattern=pattern)
    assert np.sum(area(custom) == 0) > 0


def test_modal_cli(capsys):
    from tyrelab.cli.main import main
    assert main(["modal", "--pressure", "300"]) == 0
    text = capsys.readouterr().out
    assert "lateral translation" in text and "measured_Hz" in text
    assert main(["modal", "--tyre", "nonexistent.tir"]) == 2


def test_trailer_over_cleat_ring_envelops(xzl300):
    """The trailer over the 50 mm cleat at 12 km/h: the ring runs, stays finite
    with a non-negative normal force, and its peak is below the rigid disc's."""
    from tyrelab.rig.trailer import Trailer
    runs = {m: Trailer(TyreModel(xzl300, contact=m), "LC1").run("cleat:50x50", 12 / 3.6, 2.5)
            for m in ("ring", "ring-tp", "point")}
    for m in ("ring", "ring-tp"):
        assert np.all(np.isfinite(runs[m].to_numpy(dtype=float)))
        assert runs[m]["FZW"].min() >= 0.0
        assert runs[m]["FZW"].max() < runs["point"]["FZW"].max()
