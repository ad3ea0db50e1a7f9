"""A test campaign in, a complete property file and a fit report out (thesis chapter 4).

``fit all`` on the example campaign built from the thesis's XZL data
(examples/xzl_campaign): the written file reads back, its models reproduce
Table 3-2, and the stand-in files give back what made them. Manifests and
test files with mistakes are refused in one line naming file, line and key.
"""

import copy
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from cli_process import run_tyrelab
from tyrelab.errors import InputError
from tyrelab.fit.campaign import read_campaign, read_test
from tyrelab.fit.workflow import STEPS, fit_campaign
from tyrelab.tyre.tir import read_tir, write_tir

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "xzl_campaign"
TABLE_3_2_300 = np.array([0, 3496, 9445, 15559, 21968, 29011, 37581, 45717, 54191.0])


@pytest.fixture(scope="module")
def fitted(tmp_path_factory):
    # every step but the ring (tests/test_ring_fit_campaign_fast.py, tests/test_fit_ring_campaign.py)
    result = fit_campaign(read_campaign(EXAMPLE), STEPS[:-1], skip_missing=True, skipped=("ring",))
    path = tmp_path_factory.mktemp("fit") / "xzl.tir"
    write_tir(result.tir, path)
    return result, path


def test_written_file_reads_back_and_its_models_give_table_3_2(fitted):
    from tyrelab.rig.static_press import static_press
    from tyrelab.tyre.library import load_tyre
    from tyrelab.tyre.model import TyreModel
    tyre = load_tyre(fitted[1])
    for model in ("point", "enveloping"):
        press = static_press(TyreModel(tyre, model), np.arange(1, 9) / 100)
        assert press["load"].to_numpy() == pytest.approx(TABLE_3_2_300[1:], abs=1.0)
    tir = read_tir(fitted[1])
    for section in ("MDI_HEADER", "UNITS", "MODEL", "DIMENSION", "OPERATING_CONDITIONS", "INERTIA",
                    "VERTICAL", "DEFLECTION_LOAD_CURVE", "SHAPE", "CONTACT_PATCH", "CONTACT_WIDTH_CURVE"):
        assert tir.has(section), section
    assert list(tir.sections)[-1] == "TYRELAB_FIT"
    assert tir.number("DIMENSION", "UNLOADED_RADIUS") == pytest.approx(0.6715)
    assert tir.number("OPERATING_CONDITIONS", "INFLPRES") == pytest.approx(300e3)
    assert tir.table("SHAPE").shape[0] <= 10


def test_stand_ins_give_back_what_made_them(fitted):
    """The drop trace was made at 2.66 N s/mm (3.4.1) with 0.1 mm noise: 0.5 %; the patch lengths
    on eq. 2.3 with PA1 0.15, PA2 7.06, written to 0.1 mm: 0.5 %; the held-out footprint image
    (LC1, a patch of the eq. 2.3 length and the contour's width) predicted within 2 mm."""
    result, path = fitted
    tir = read_tir(path)
    assert tir.number("VERTICAL", "VERTICAL_DAMPING") == pytest.approx(2660.0, rel=0.005)
    assert tir.number("TYRELAB_FIT", "DAMPING_PENDULUM_NS_PER_M") == pytest.approx(2660.0, rel=0.01)
    assert tir.number("CONTACT_PATCH", "PA1") == pytest.approx(0.15, rel=0.005)
    assert tir.number("CONTACT_PATCH", "PA2") == pytest.approx(7.06, rel=0.005)
    rows = {r["parameter"]: r for r in result.steps["patch"].rows}
    assert rows["PA1, PA2"]["held_out"]["footprint_LC1.png"] < 0.002
    assert rows["CONTACT_WIDTH_CURVE"]["held_out"]["footprint_LC1.png"] < 0.002
    assert tir.number("VERTICAL", "VERTICAL_STIFFNESS") == pytest.approx(
        np.dot(np.arange(9) / 100, TABLE_3_2_300) / np.dot(np.arange(9) / 100, np.arange(9) / 100))


def test_report_has_every_figure(fitted, tmp_path):
    from tyrelab.report.fit_report import figure_count, write_report
    result = fitted[0]
    write_report(result, tmp_path / "r.html")
    text = (tmp_path / "r.html").read_text()
    assert text.count("data:image/png;base64,") == figure_count(result) == 6
    for words in ("VERTICAL_STIFFNESS", "PA1, PA2", "held out", "ring: skipped on request", "Modal results"):
        assert words in text


def test_cli_fit_all_then_update_one_step(tmp_path):
    out = tmp_path / "xzl.tir"
    r = run_tyrelab("fit", "all", str(EXAMPLE), "-o", str(out), "--skip", "ring")
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "xzl_fit.html").is_file()
    assert "ring: skipped on request" in r.stdout and not read_tir(out).has("FLEXIBLE_RING")
    assert "VERTICAL_DAMPING" in r.stdout
    shape = read_tir(out).table("SHAPE")
    # a steeper curve, fitted into the existing file: its other sections stay
    (tmp_path / "press.csv").write_text("deflection_mm,load_kN\n0,0\n10,5\n20,11\n30,18\n")
    r = run_tyrelab("fit", "vertical", str(tmp_path / "press.csv"), "-o", str(out), "--no-report")
    assert r.returncode == 0, r.stderr
    tir = read_tir(out)
    assert tir.table("DEFLECTION_LOAD_CURVE")[:, 1] == pytest.approx([0, 5e3, 11e3, 18e3])
    assert tir.table("SHAPE") == pytest.approx(shape)
    assert tir.number("VERTICAL", "VERTICAL_DAMPING") == pytest.approx(2660.0, rel=0.005)


def test_cli_into_a_builtin_keeps_its_units(tmp_path):
    out = tmp_path / "shape.tir"
    r = run_tyrelab("fit", "shape", str(EXAMPLE), "--into", "xzl-16.00R20", "-o", str(out), "--no-report")
    assert r.returncode == 0, r.stderr
    text = out.read_text()
    assert "LENGTH = 'mm'" in text
    tir = read_tir(out)
    assert tir.number("VERTICAL", "VERTICAL_STIFFNESS") == pytest.approx(659.6e3)   # the base's
    assert tir.table("SHAPE").shape[0] == 8                                          # the fit's


def test_fit_ring_fits_first_what_its_start_lacks(tmp_path):
    """``fit ring CAMPAIGN`` on its own (issue "Lean and fast", point 4): a new file has no
    vertical law and no drop-test damping, so the campaign's own load-deflection and drop tests
    are fitted first; a start that has both (-o an existing fitted file) fits the ring only."""
    import argparse

    from tyrelab.cli.fit import _ring_steps
    from tyrelab.fit.campaign import read_campaign
    from tyrelab.tyre.library import load_tyre
    from tyrelab.tyre.tir import write_tir
    campaign = read_campaign(EXAMPLE)
    new = argparse.Namespace(into=None, output=str(tmp_path / "new.tir"), radius=None, width=None)
    assert _ring_steps(new, campaign) == ("vertical", "damping", "ring")
    write_tir(load_tyre("xzl-16.00R20").tir, tmp_path / "fitted.tir")
    fitted = argparse.Namespace(into=None, output=str(tmp_path / "fitted.tir"), radius=None, width=None)
    assert _ring_steps(fitted, campaign) == ("ring",)


@pytest.mark.parametrize("args, words", [
    (["fit", "vertical", "{tmp}/press.csv", "-o", "{tmp}/new.tir"], "needs the tyre's unloaded radius"),
    (["fit", "all", "{tmp}", "-o", "{tmp}/x.tir"], "no campaign manifest"),
    (["fit", "ring", "{tmp}", "-o", "{tmp}/x.tir"], "no campaign manifest"),
    (["fit", "all", str(EXAMPLE), "-o", "{tmp}/x.txt"], "must end in .tir"),
    (["fit", "patch", "{tmp}/fp.png", "-o", "{tmp}/x.tir"], "list it in a campaign.toml"),
    (["fit", "vertical", "{tmp}/bad.csv", "--radius", "600", "--width", "400", "-o", "{tmp}/x.tir"],
     "bad.csv, line 3: load_N: 'x' is not a number"),
])
def test_cli_bad_input_is_one_line(tmp_path, args, words):
    (tmp_path / "press.csv").write_text("deflection_mm,load_N\n0,0\n10,5000\n20,11000\n")
    (tmp_path / "bad.csv").write_text("deflection_mm,load_N\n0,0\n10,x\n")
    (tmp_path / "fp.png").write_bytes(b"")
    r = run_tyrelab(*[a.replace("{tmp}", str(tmp_path)) for a in args])
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and words in lines[0], r.stderr


def _campaign(tmp_path, body, files=("load_deflection.csv",)):
    for f in files:
        shutil.copy(EXAMPLE / f, tmp_path / f)
    (tmp_path / "campaign.toml").write_text(body)
    return tmp_path


LD = '[[test]]\nkind = "load_deflection"\nfile = "load_deflection.csv"\n' \
     'columns = { deflection = "deflection_mm", load = "load_N_300kPa" }\n'


@pytest.mark.parametrize("body, words", [
    ('[tyre]\nwidth = "438 mm"\n' + LD + 'kind2 = 1\n', "line 7: test[1].kind2: unknown key 'kind2'"),
    (LD + '[[test]]\nkind = "tread"\nfile = "x"\n', "line 6: test[2].kind: unknown test kind \"tread\""),
    (LD + '[[test]]\nkind = "modal"\nfile = "missing.csv"\n', "line 7: test[2].file: no such file"),
    ('[tyre]\nunloaded_radius = "671.5 kg"\n' + LD, "line 2: tyre.unloaded_radius: expected a number and "
                                                  "a unit of m"),
    (LD + 'step = -5\n', "line 5: test[1].step: expected a positive value"),
    # the example in the message is in the unit asked for
    ('[tyre]\nfnomin = "65 parsecs"\n' + LD, 'line 2: tyre.fnomin: expected a number and a unit of N, '
                                              'like "40 kN", got "65 parsecs"'),
    # the [tyre] values checked as a property file's, at their key (it named "<new>", RIM_RADIUS)
    ('[tyre]\nunloaded_radius = "671.5 mm"\nrim_radius = "900 mm"\n' + LD,
     "line 3: tyre.rim_radius: RIM_RADIUS 0.9 m is not inside the tyre"),
    ('[tyre]\nwheel_iyy = 1e30\n' + LD, "line 2: tyre.wheel_iyy: 1e+30 kg m^2 is not physical"),
    # pressures within tyrelab.limits (5500 kPa was fitted)
    (LD + 'pressure = "5500 kPa"\n', "line 5: test[1].pressure: pressure 5500 kPa is out of range; "
                                    "allowed: 20 <= pressure <= 1500 kPa"),
    ('[tyre]\npressure = "3 kPa"\n' + LD, "line 2: tyre.pressure: pressure 3 kPa is out of range"),
    # a load case that is none: said so (it asked for "a unit of N, like \"10 mm\"")
    ('[[test]]\nkind = "drop_test"\nfile = "load_deflection.csv"\nload_case = "LC7"\n',
     'line 4: test[1].load_case: unknown load case "LC7"; expected LC1, LC2, LC3'),
    ('[tyre\n', "campaign.toml, line 1: not valid TOML"),
    (LD.replace("load_N_300kPa", "load_N_200kPa"), "load_deflection.csv, line 2: load: column "
                                                   "'load_N_200kPa' is not in the header"),
    ('[[test]]\nkind = "footprint_image"\nfile = "load_deflection.csv"\n', "test[1]: a footprint image "
                                                                          "needs its load or its deflection"),
])
def test_manifest_mistakes_name_file_line_and_key(tmp_path, body, words):
    _campaign(tmp_path, body)
    with pytest.raises(InputError) as err:
        read_campaign(tmp_path)
    assert words in str(err.value)


def test_test_file_mistakes_name_file_and_line(tmp_path):
    p = tmp_path / "press.csv"
    p.write_text("# a comment\ndeflection_mm,load_N\n0,0\n-30,100\n20,300\n")
    with pytest.raises(InputError, match=r"press.csv, line 4: deflection: deflection -0.03 m is negative"):
        read_test("load_deflection", p)
    p.write_text("time_s,z_mm\n" + "".join(f"{i / 100},{600 - i}\n" for i in range(60)) + "0.5,1\n")
    with pytest.raises(InputError, match=r"line 62: time: time 0.5 s does not increase"):
        read_test("drop_test", p)
    p.write_text("deflection_mm,width_mm\n20,-1\n")
    with pytest.raises(InputError, match=r"line 2: width: width -0.001 m must be positive"):
        read_test("contact_patch", p)
    with pytest.raises(InputError, match=r"line 2: load: columns load_N_100kPa, load_N_300kPa, "
                                         r"load_N_550kPa could each be the load"):
        read_test("load_deflection", EXAMPLE / "load_deflection.csv")


def test_tydex_press_and_modal_table(tmp_path):
    from tyrelab.measure.tydex import write_tydex
    from tyrelab.signal import make_signal
    d = np.linspace(0.0, 0.08, 30)
    write_tydex(make_signal({"RUNTIME": np.arange(30) * 0.1, "DEFLECT": d, "FZW": 6.6e5 * d}),
                tmp_path / "press.tdx", units={"FZW": "kN", "DEFLECT": "mm"})
    test = read_test("load_deflection", tmp_path / "press.tdx")
    assert test.deflection == pytest.approx(d) and test.load == pytest.approx(6.6e5 * d)
    modal = read_test("modal", EXAMPLE / "modal.csv").table
    assert len(modal) == 10                       # modes 2-6 at 300 and 550 kPa (mode 1 not measured)
    row = modal[(modal["mode"] == 2) & (modal["pressure"] == 300e3)].iloc[0]
    assert (row.frequency, row.damping) == pytest.approx((22.72, 0.0294))


def test_a_modal_table_numbered_by_frequency_is_refused_on_its_line(tmp_path):
    """An experimental modal analysis numbers modes by ascending frequency; the ring is fitted
    to Table 3-3's numbers (2 vertical/longitudinal, 3 lateral). Table 3-3's own descriptions
    and tyrelab's mode names each name their number; a row whose description names another
    mode is refused on its line, before it could fit the lateral mode as the vertical one."""
    from tyrelab.fit.lab_files import described_mode
    from tyrelab.tyre.ring.modal import MODE_NAMES
    table = (EXAMPLE / "modal.csv").read_text().splitlines()
    rows = [r for r in table if r[:1].isdigit()]
    assert [described_mode(r.split(",")[1]) for r in rows] == [1, 2, 3, 4, 5, 6]
    assert {m: described_mode(name) for m, name in MODE_NAMES.items()} == {m: m for m in MODE_NAMES}
    by_frequency = [table[1], "1,rigid-body movement in lateral direction,16.88,2.33,20.09,2.19",
                    "2,rigid-body movement in longitudinal or vertical direction,22.72,2.94,33.51,2.01"]
    (tmp_path / "modal.csv").write_text("\n".join(by_frequency) + "\n")
    with pytest.raises(InputError, match=r"line 2: .*mode 1 is Table 3-3's in-plane rotation about "
                                         r"the spin axis, but the row describes 'rigid-body movement "
                                         r"in lateral direction', Table 3-3's mode 3"):
        read_test("modal", tmp_path / "modal.csv")


def _plate_as_cleat(tmp_path, deflections):
    """Table 3-2 at 300 kPa written as a 51 x 51 mm lateral cleat press: what a rigid disc gives
    on the cleat (its lowest point rests on the flat top: a disc on a plate)."""
    loads = np.interp(deflections, np.arange(9) / 100, TABLE_3_2_300)
    (tmp_path / "cleat.csv").write_text("deflection_mm,load_N\n" + "".join(
        f"{a * 1e3:g},{b:g}\n" for a, b in zip(deflections, loads)))
    return loads


def _cleat_predictions(result):
    (test, pred), = result.steps["cleats"].data["predictions"]
    rms = {r["parameter"].split(":")[0]: r["held_out"]["cleat.csv"] for r in result.steps["cleats"].rows}
    for model, loads in pred.items():       # the reported error: the RMS of the prediction's misses
        assert rms[model] == pytest.approx(np.sqrt(np.mean((loads - test.load) ** 2)))
    return pred, rms


def test_static_cleats_are_predicted_by_every_analytic_model(tmp_path, xzl):
    """A held-out 51 x 51 mm lateral cleat press whose loads are the plate's (Table 3-2), fitted
    on the plate with the built-in XZL's carcass: the point model reads the road in the wheel
    plane only, a disc blind to the cleat's width, and predicts it to 1 N; the volume and
    enveloping models feel the width and predict less at every deflection (a tyre is softer
    on a cleat than on the plate, thesis 3.3.4)."""
    d = np.arange(1, 9) / 100
    plate = _plate_as_cleat(tmp_path, d)
    write_tir(xzl.tir, tmp_path / "base.tir")
    body = '[tyre]\nbase = "base.tir"\n' + LD + \
        '[[test]]\nkind = "static_cleat"\nfile = "cleat.csv"\ncleat = "51x51"\n'
    pred, rms = _cleat_predictions(fit_campaign(read_campaign(_campaign(tmp_path, body))))
    assert set(rms) == {"point", "volume", "enveloping", "enveloping-edge"}
    assert rms["point"] < 1.0
    for model in ("volume", "enveloping", "enveloping-edge"):
        assert np.all(pred[model] < plate), model


def test_dynamic_cleat_run_is_read_and_drawn(tmp_path):
    """A trailer run over the 50 mm cleat written as TYDEX: read into the campaign (held out,
    drawn in the report; the ring's damping from it is another step's)."""
    import tyrelab
    from tyrelab.measure.tydex import write_tydex
    from tyrelab.report.fit_report import figure_count, report_html
    run = tyrelab.simulate(model="point", road="cleat:50x50", speed=12 / 3.6, duration=2.0,
                           output_rate=200.0, progress=False)
    write_tydex(run[["RUNTIME", "FZW", "FX"]], tmp_path / "cleat12.tdx", units={"FZW": "kN"})
    body = LD + '[[test]]\nkind = "dynamic_cleat"\nfile = "cleat12.tdx"\ncleat = "50x50"\n' \
        'speed = "12 km/h"\nload_case = "LC1"\n'
    campaign = read_campaign(_campaign(tmp_path, body))
    cleat = campaign.tests[1]
    assert cleat.use == "held_out" and cleat.speed == pytest.approx(12 / 3.6)
    assert cleat.signal["FZW"].to_numpy() == pytest.approx(run["FZW"].to_numpy())
    result = fit_campaign(campaign)
    assert figure_count(result) == 2
    assert report_html(result).count("data:image/png;base64,") == 2


def test_held_out_press_is_predicted_not_fitted(tmp_path, xzl):
    """A raw press loop (Table 3-2's curve +-1 kN of hysteresis) held out: the fit stays Table
    3-2's, and the loop is predicted better by the table than by the straight line."""
    t = np.linspace(0.0, 20.0, 801)
    d = 0.04 * (1 - np.cos(2 * np.pi * t / 10.0))
    f = xzl.vertical_law.static_load(d) + 1000.0 * np.sign(np.sin(2 * np.pi * t / 10.0))
    (tmp_path / "loop.csv").write_text("time_s,deflection_m,load_N\n" + "".join(
        f"{a:.6g},{b:.9g},{c:.9g}\n" for a, b, c in zip(t, d, np.maximum(f, 0.0))))
    body = LD + '[[test]]\nkind = "load_deflection"\nfile = "loop.csv"\nuse = "held_out"\n'
    result = fit_campaign(read_campaign(_campaign(tmp_path, body)))
    assert result.tir.table("DEFLECTION_LOAD_CURVE")[:, 1] == pytest.approx(TABLE_3_2_300)
    rows = {r["parameter"]: r for r in result.steps["vertical"].rows}
    table, line = rows["DEFLECTION_LOAD_CURVE"]["held_out"]["loop.csv"], \
        rows["VERTICAL_STIFFNESS"]["held_out"]["loop.csv"]
    assert 900 < table < 1100 < line            # the table misses by the hysteresis only


def test_held_out_drop_at_another_load_is_predicted(tmp_path, xzl):
    """Fitted on the LC1 drop, the LC2 drop (same tyre, 2.66 N s/mm, ballast of Table 3-4) is
    predicted to within its 0.1 mm of noise."""
    from tyrelab.fit.damping import simulated_drop
    t = np.arange(0.0, 3.0, 1e-3)
    z = simulated_drop(xzl, t, "LC2") + np.random.default_rng(4).normal(0.0, 1e-4, t.size)
    (tmp_path / "lc2.csv").write_text("time_s,z_m\n" + "".join(f"{a:.3f},{b:.7f}\n" for a, b in zip(t, z)))
    body = '[tyre]\nunloaded_radius = "671.5 mm"\nwidth = "438 mm"\n' + LD + \
        '[[test]]\nkind = "drop_test"\nfile = "drop_test.csv"\nload_case = "LC1"\n' \
        'columns = { time = "time_s", displacement = "z_mm" }\n' \
        '[[test]]\nkind = "drop_test"\nfile = "lc2.csv"\nload_case = "LC2"\nuse = "held_out"\n'
    result = fit_campaign(read_campaign(_campaign(tmp_path, body, ("load_deflection.csv", "drop_test.csv"))))
    row = result.steps["damping"].rows[0]
    assert row["held_out"]["lc2.csv"] < 1.5e-4
    assert result.tir.number("VERTICAL", "VERTICAL_DAMPING") == pytest.approx(2660.0, rel=0.005)


def test_drop_traces_logged_from_before_the_release_give_the_damper(tmp_path, xzl):
    """Both drops logged from well before the release (the trailer held at rest, 0.1 mm of
    noise): the damper comes back as from traces that start at the release -- the rig fit
    within 0.5 %, the pendulum of eqs. 3.1-3.7 within 3 %, the held-out LC2 drop predicted to
    its noise. Before, the hold was read as the start of the fall."""
    from tyrelab.fit.damping import simulated_drop
    t = np.arange(-1.2, 3.0, 1e-3)
    rng = np.random.default_rng(5)
    for name, case in (("lc1.csv", "LC1"), ("lc2.csv", "LC2")):
        z = simulated_drop(xzl, t, case) + 0.64 + rng.normal(0.0, 1e-4, t.size)
        (tmp_path / name).write_text("time_s,z_m\n" + "".join(f"{a + 7.0:.3f},{b:.7f}\n"
                                                              for a, b in zip(t, z)))
    body = '[tyre]\nunloaded_radius = "671.5 mm"\nwidth = "438 mm"\n' + LD + \
        '[[test]]\nkind = "drop_test"\nfile = "lc1.csv"\nload_case = "LC1"\n' \
        '[[test]]\nkind = "drop_test"\nfile = "lc2.csv"\nload_case = "LC2"\nuse = "held_out"\n'
    result = fit_campaign(read_campaign(_campaign(tmp_path, body)))
    assert result.tir.number("VERTICAL", "VERTICAL_DAMPING") == pytest.approx(2660.0, rel=0.005)
    assert result.tir.number("TYRELAB_FIT", "DAMPING_PENDULUM_NS_PER_M") == pytest.approx(2660.0, rel=0.03)
    assert result.steps["damping"].rows[0]["held_out"]["lc2.csv"] < 1.5e-4


def test_a_press_without_load_is_named_by_its_file(tmp_path):
    """A press whose load never rises (a channel not wired): one line naming the file."""
    (tmp_path / "flat.csv").write_text("deflection_mm,load_N\n0,0\n10,0\n20,0\n30,0\n")
    (tmp_path / "campaign.toml").write_text('[tyre]\nunloaded_radius = "671.5 mm"\nwidth = "438 mm"\n'
                                            '[[test]]\nkind = "load_deflection"\nfile = "flat.csv"\n')
    with pytest.raises(InputError, match="no load above zero") as err:
        fit_campaign(read_campaign(tmp_path), steps=("vertical",))
    assert str(err.value).startswith(str(tmp_path / "flat.csv") + ": ")


def test_a_drop_trace_logged_down_positive_is_named_with_its_fix(tmp_path, xzl):
    """A displacement logged down positive never falls: one line naming the file and the
    manifest key that reads it; with that key, the damper comes back."""
    from tyrelab.fit.damping import simulated_drop
    t = np.arange(0.0, 3.0, 1e-3)
    z = simulated_drop(xzl, t, "LC1")
    (tmp_path / "down.csv").write_text("time_s,z_m\n" + "".join(f"{a:.3f},{-b:.7f}\n" for a, b in zip(t, z)))
    body = '[tyre]\nunloaded_radius = "671.5 mm"\nwidth = "438 mm"\n' + LD + \
        '[[test]]\nkind = "drop_test"\nfile = "down.csv"\nload_case = "LC1"\n'
    with pytest.raises(InputError) as err:
        fit_campaign(read_campaign(_campaign(tmp_path, body)))
    assert str(err.value).startswith(str(tmp_path / "down.csv") + ": ")
    assert 'positive = "down"' in str(err.value) and "\n" not in str(err.value)
    (tmp_path / "campaign.toml").write_text(body + 'positive = "down"\n')
    result = fit_campaign(read_campaign(tmp_path))
    assert result.tir.number("VERTICAL", "VERTICAL_DAMPING") == pytest.approx(2660.0, rel=0.005)


def test_static_cleats_are_predicted_by_the_ring_once_identified(tmp_path, xzl):
    """A base file with a [FLEXIBLE_RING] (the shipped XZL ring): its static cleat press is one
    of the held-out predictions. On the plate's loads written as a cleat press (see above) the
    disc is exact and the ring, which envelops the cleat, predicts less at every deflection."""
    from tyrelab.tyre.ring.parameters import ring_parameters
    d = np.arange(1, 7) / 100
    plate = _plate_as_cleat(tmp_path, d)
    tir = ring_parameters(xzl).to_tir(copy.deepcopy(xzl.tir))
    write_tir(tir, tmp_path / "base.tir", units=tir.units or None)
    body = '[tyre]\nbase = "base.tir"\n' + LD + \
        '[[test]]\nkind = "static_cleat"\nfile = "cleat.csv"\ncleat = "51x51"\n'
    result = fit_campaign(read_campaign(_campaign(tmp_path, body)), skip_missing=True)
    pred, rms = _cleat_predictions(result)
    assert set(rms) == {"point", "volume", "enveloping", "enveloping-edge", "ring"}
    assert rms["point"] < 1.0
    assert np.all(pred["ring"] < plate)


def test_every_unit_example_in_a_message_is_itself_accepted(tmp_path):
    """The manifest's messages show how to write each unit (``UNIT_EXAMPLES``); each example,
    given where that unit is asked for, is read as the SI value it writes."""
    from tyrelab.fit.campaign import UNIT_EXAMPLES, _Manifest

    m = _Manifest(tmp_path / "campaign.toml", "")
    si = {"10 mm": 0.01, "300 kPa": 3e5, "40 kN": 4e4, "154 kg": 154.0, "45 deg": math.pi / 4,
          "12 km/h": 12 / 3.6}
    assert set(UNIT_EXAMPLES.values()) == set(si)
    for unit, example in UNIT_EXAMPLES.items():
        assert m.quantity(example, ("x",), unit) == pytest.approx(si[example], rel=1e-12), example
