"""Soil tests in study specs: the spec keys, the run matrix, the slip-curve table, the report.

A real study (the Dask runner, one worker) of the XZL on LETE sand at 23.3 kN and 3.6 km/h,
slips 0, 0.2 and 0.4, with the rigid wheel and the point model as a flexible wheel, beside a
rigid-road cleat test of two point-model variants. Its soil table must be what
``tyrelab.rig.single_wheel.slip_curve`` gives when run directly with the same arguments,
the same with two workers, and stay out of the chapter-5 tables; its report's "On soil"
section must render in headless Chromium with no script error.
"""

from __future__ import annotations

import dataclasses
import html
import re

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.study.spec import parse_spec

from chromium import INSTALL_HINT, find_chromium, parse, render_dom

LOAD, SPEED_KMH, SLIPS, DURATION = 23300.0, 3.6, (0.0, 0.2, 0.4), 2.0
#: the soil test's model variants: label -> (contact, stiffness, handling)
SOIL_MODELS = {"rigid wheel": ("rigid", None, None), "OPC lk": ("point", "linear", "none")}

HEAD = """\
[study]
name = "soil-study"
output = "out"

[[tyre]]
name = "xzl"
file = "xzl-16.00R20"

[[model]]
name = "rigid wheel"
contact = "rigid"

[[model]]
name = "OPC lk"
contact = "point"
stiffness = "linear"
handling = "none"
"""
SOIL_TEST = f"""
[[test]]
name = "sand"
rig = "single-wheel"
terrain = "lete-sand"
slips = [0, 0.2, 0.4]
speeds_kmh = [{SPEED_KMH}]
loads = [{LOAD:g}]
duration = {DURATION}
models = ["rigid wheel", "OPC lk"]
reference = {{ model = "rigid wheel" }}
"""
SPEC = HEAD + """
[[model]]
name = "OPC nlk"
contact = "point"
stiffness = "table"
handling = "none"

[[test]]
name = "cleat"
road = "cleat:50x50"
speeds_kmh = [12]
loads = ["LC1"]
duration = 2.5
models = ["OPC lk", "OPC nlk"]
reference = { model = "OPC nlk" }
""" + SOIL_TEST


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    """The study of the module docstring, one worker."""
    from tyrelab import study as studies
    folder = tmp_path_factory.mktemp("soil_study")
    (folder / "spec.toml").write_text(SPEC)
    return studies.run(folder / "spec.toml", workers=1, progress=False)


@pytest.fixture(scope="module")
def direct():
    """``slip_curve`` run directly for each model of the soil test: {label: table}."""
    from tyrelab.api import make_tyre_model
    from tyrelab.rig.single_wheel import slip_curve
    return {label: slip_curve(make_tyre_model("xzl-16.00R20", contact, stiffness=stiffness,
                                              handling=handling),
                              "lete-sand", LOAD, SPEED_KMH / 3.6, SLIPS, duration=DURATION)
            for label, (contact, stiffness, handling) in SOIL_MODELS.items()}


def _curve(table, model):
    return table[table["model"] == model].sort_values("slip")


# ---------------------------------------------------------------------------
# the table


def test_the_soil_table_is_the_slip_curve_run_directly(study, direct):
    """Through the spec, the runner, the compact store and the evaluation, each model's steady
    pull, torque, sinkage and load per slip are those of ``slip_curve`` called directly, to
    round-off (the compact store keeps these channels in float64)."""
    table = study.soil_curves
    assert list(table["model"]) == [m for m in SOIL_MODELS for _ in SLIPS]  # the test's order
    assert set(table["soil"]) == {"LETE sand"} and set(table["test"]) == {"sand"}
    for model, expected in direct.items():
        ours = _curve(table, model)
        assert list(ours["slip"]) == list(expected["slip"]) == list(SLIPS)
        for col in ("FX", "TORQUE", "SINKAGE", "FZ"):
            np.testing.assert_allclose(ours[col].to_numpy(), expected[col].to_numpy(), rtol=1e-12,
                                       atol=0, err_msg=f"{model} {col}")


def test_pull_rises_with_slip_and_the_soil_carries_the_dead_weight(study):
    """Physics of the table: the drawbar pull and the torque rise with slip for every model
    (rigid wheel 0.97 -> 11.4 -> 12.4 kN); once steady the soil carries the 23.3 kN dead
    weight (within 0.1 %); the rigid wheel sinks deeper than the flexible tyre, which
    flattens and spreads the load (23.8 mm against 8.2 mm at zero slip)."""
    table = study.soil_curves
    for model in SOIL_MODELS:
        curve = _curve(table, model)
        assert np.all(np.diff(curve["FX"].to_numpy()) > 0), (model, list(curve["FX"]))
        assert np.all(np.diff(curve["TORQUE"].to_numpy()) > 0), (model, list(curve["TORQUE"]))
        np.testing.assert_allclose(curve["FZ"].to_numpy(), LOAD, rtol=1e-3)
        assert np.all(curve["SINKAGE"].to_numpy() > 0)
    rigid = _curve(table, "rigid wheel")["SINKAGE"].to_numpy()
    flexible = _curve(table, "OPC lk")["SINKAGE"].to_numpy()
    assert np.all(rigid > 2 * flexible), (rigid, flexible)


def test_differences_from_the_reference_model(study):
    """With reference = rigid wheel: the reference's own rows are zero; each other row's pull
    and torque differ by 100 dX / F_ref with F_ref = max |torque_ref| / R0 (R0 the XZL's
    unloaded radius), its sinkage by 100 ds / s_ref, recomputed here from the table's own
    means."""
    from tyrelab.tyre.library import load_tyre
    table = study.soil_curves
    r0 = load_tyre("xzl-16.00R20").unloaded_radius
    ref = _curve(table, "rigid wheel")
    assert set(table["reference"]) == {"rigid wheel"}
    assert np.all(ref[["FX_diff_pct", "TORQUE_diff_pct", "SINKAGE_diff_pct"]].to_numpy() == 0.0)
    f_ref = np.max(np.abs(ref["TORQUE"].to_numpy())) / r0
    assert 10e3 < f_ref < 20e3                       # the torque at s = 0.4 over 0.67 m
    other = _curve(table, "OPC lk")
    np.testing.assert_allclose(other["force_scale_N"], f_ref, rtol=1e-12)
    np.testing.assert_allclose(other["FX_diff_pct"],
                               100 * (other["FX"].to_numpy() - ref["FX"].to_numpy()) / f_ref, rtol=1e-12)
    np.testing.assert_allclose(other["TORQUE_diff_pct"], 100 * (other["TORQUE"].to_numpy()
                               - ref["TORQUE"].to_numpy()) / (r0 * f_ref), rtol=1e-12)
    np.testing.assert_allclose(other["SINKAGE_diff_pct"], 100 * (other["SINKAGE"].to_numpy()
                               / ref["SINKAGE"].to_numpy() - 1), rtol=1e-12)


def test_the_command_prints_the_soil_table(study, capsys):
    """``tyrelab study`` on the finished study (every run kept: nothing is computed again)
    prints each model's pull, torque and sinkage per slip, the table's values to the digits
    shown."""
    from tyrelab.cli.main import main
    folder = study.folder
    assert main(["study", str(folder / "spec.toml"), "--workers", "1", "-o", str(folder)]) == 0
    out = capsys.readouterr().out
    for row in study.soil_curves.itertuples():
        line = next(ln for ln in out.splitlines()
                    if ln.strip().startswith(row.model) and f"s = {row.slip:g}:" in ln)
        assert f"pull {row.FX / 1e3:7.2f} kN" in line and f"sinkage {row.SINKAGE * 1e3:6.1f} mm" in line


def test_two_workers_give_the_same_table(study, tmp_path):
    """The soil test alone, in another folder, on two worker processes: the same run keys (a
    key does not depend on the other tests) and bit for bit the same steady values."""
    from tyrelab import study as studies
    (tmp_path / "spec.toml").write_text(HEAD + SOIL_TEST)
    two = studies.run(tmp_path / "spec.toml", workers=2, progress=False)
    a, b = study.soil_curves, two.soil_curves
    assert list(a["key"]) == list(b["key"])
    cols = ["FX", "TORQUE", "SINKAGE", "FZ", "FX_diff_pct", "TORQUE_diff_pct", "SINKAGE_diff_pct"]
    assert np.array_equal(a[cols].to_numpy(), b[cols].to_numpy())


def test_soil_runs_stay_out_of_the_thesis_tables(study):
    """The chapter-5 metrics, the Table 5-15 summary and the cost table hold the cleat test
    only: no metric row of the soil test although it names a reference model, and the cost
    counts OPC lk's one cleat run, not its three soil runs."""
    assert len(study.index) == 2 + 2 * 3 and set(study.index["status"]) == {"done"}
    m = study.metrics
    assert set(m["test"]) == {"cleat"} and len(m) == 2
    assert set(study.summary.index.get_level_values(1)) == {"cleat"}
    cost = study.cost.set_index("model")
    assert cost.loc["OPC lk", "runs"] == 1 and "rigid wheel" not in cost.index
    assert (study.folder / "soil_curves.parquet").is_file()


# ---------------------------------------------------------------------------
# the report


def test_the_on_soil_section_renders_in_chromium(study, tmp_path):
    """The report's "On soil" section: one figure of three stacked panels (pull [kN], torque
    [kN m], sinkage [mm] against slip, a trace per model and panel) drawn with no script error,
    every figure of the page drawn; the traces hold the table's values (to the page's five
    significant digits); the table lists the six runs."""
    from tyrelab.report.figure_embed import unpack_figure
    from tyrelab.report.study_report import write_study_report
    if find_chromium() is None:
        pytest.fail("Chromium is needed to check the study report renders: " + INSTALL_HINT)
    path = write_study_report(study, tmp_path / "report.html")
    text = path.read_text(encoding="utf-8")
    dom = parse(render_dom(path))
    errors = dom.find("pre", id="tyrelab-errors")
    assert errors is not None and errors.text().strip() == "", errors and errors.text()
    declared = int(dom.find("meta", name="tyrelab-figures").attrs["content"])
    assert dom.find("body").attrs.get("data-figures-rendered") == str(declared)
    assert dom.find("body").attrs.get("data-figures-done") == "yes"
    section = dom.find("section", id="soil")
    assert section is not None
    figures = section.find_all("figure", cls="tyrelab-figure")
    assert [f.attrs["data-kind"] for f in figures] == ["soil"]
    drawn = figures[0].find("div", cls="js-plotly-plot")
    assert drawn is not None and drawn.find("svg", cls="main-svg") is not None
    axis_titles = [t.text() for t in drawn.find_all("text")
                   if any(re.fullmatch(r"y\d*title", c) for c in t.classes)]
    assert axis_titles == ["drawbar pull [kN]", "driving torque [kN m]", "sinkage [mm]"]
    block = re.search(r"data-kind='soil'>.*?data-encoding='gzip\+base64'>([A-Za-z0-9+/=]*)</script>",
                      text, re.S).group(1)
    traces = unpack_figure(html.unescape(block))["data"]
    table = study.soil_curves
    assert len(traces) == 3 * len(SOIL_MODELS)
    for trace, (model, (column, factor)) in zip(traces, [(m, p) for m in SOIL_MODELS for p in (
            ("FX", 1e-3), ("TORQUE", 1e-3), ("SINKAGE", 1e3))]):
        assert trace["name"] == model
        curve = _curve(table, model)
        assert list(trace["x"]) == list(SLIPS)
        np.testing.assert_allclose(trace["y"], curve[column].to_numpy() * factor, rtol=1e-4)
    rows = section.find("table").find_all("tr")
    assert len(rows) == 1 + len(SOIL_MODELS) * len(SLIPS)


# ---------------------------------------------------------------------------
# the spec


def _spec_error(tmp_path, text) -> str:
    (tmp_path / "spec.toml").write_text(text)
    with pytest.raises(InputError) as info:
        parse_spec(text, tmp_path / "spec.toml")
    message = str(info.value)
    assert "\n" not in message
    return message


def _line_of(text, needle, start=0) -> int:
    """The 1-based line of the first ``needle`` in ``text`` after character ``start``."""
    return text[:text.index(needle, start)].count("\n") + 1


def _soil_test(**keys) -> str:
    """The soil test above with ``keys`` replaced (None: removed), as TOML."""
    base = {"name": '"sand"', "rig": '"single-wheel"', "terrain": '"lete-sand"',
            "slips": "[0, 0.2, 0.4]", "speeds_kmh": "[3.6]", "loads": "[23300]"}
    base.update(keys)
    return "\n[[test]]\n" + "".join(f"{k} = {v}\n" for k, v in base.items() if v is not None)


BAD = [
    # (what, test keys, the key the error names, the text its line holds, words in the message)
    ("unknown soil", {"terrain": '"beach"'}, "test[1].terrain", "terrain =",
     ("unknown soil", "beach", "lete-sand", "dry-sand", "FILE.toml")),
    ("no soil file", {"terrain": '"soils/none.toml"'}, "test[1].terrain", "terrain =",
     ("no such soil file",)),
    ("terrain on a rigid-only rig", {"rig": '"rolling"', "slips": None, "road": '"flat"'},
     "test[1].terrain", "terrain =", ("rolling rig runs on the rigid road only", "single-wheel")),
    ("terrain on the trailer", {"rig": '"trailer"', "slips": None, "road": '"flat"'},
     "test[1].terrain", "terrain =", ("rigid road only", "single-wheel", "simulate(terrain=...)")),
    ("slips on the trailer", {"rig": '"trailer"', "terrain": None, "road": '"flat"'},
     "test[1].slips", "slips =", ("trailer rig takes no slip", "single-wheel")),
    ("no terrain", {"terrain": None}, "test[1]", "[[test]]", ("missing key 'terrain'", "lete-sand")),
    ("no slips", {"slips": None}, "test[1]", "[[test]]", ("missing key 'slips'",)),
    ("slip 1", {"slips": "[0, 1.0]"}, "test[1].slips[2]", "slips =", ("[-1, 1)", "1.0")),
    ("skid beyond locked", {"slips": "[-1.1]"}, "test[1].slips[1]", "slips =", ("[-1, 1)", "-1.1")),
    ("slip as text", {"slips": '["0.2"]'}, "test[1].slips[1]", "slips =", ("the string",)),
    ("empty slips", {"slips": "[]"}, "test[1].slips", "slips =", ("non-empty array",)),
    ("duplicate slip", {"slips": "[0.2, 0.2]"}, "test[1].slips[2]", "slips =", ("duplicate slip",)),
    ("slips and torques", {"torques": "[4000]"}, "test[1].torques", "torques =",
     ("slips or under driving torques, not both",)),
    ("torques on the trailer", {"rig": '"trailer"', "terrain": None, "road": '"flat"', "slips": None,
                                "torques": "[4000]"}, "test[1].torques", "torques =",
     ("trailer rig takes no driving torque", "single-wheel")),
    ("torque as text", {"slips": None, "torques": '["4 kN m"]'}, "test[1].torques[1]", "torques =",
     ("a driving torque in N m", "the string")),
    ("empty torques", {"slips": None, "torques": "[]"}, "test[1].torques", "torques =",
     ("non-empty array of driving torques",)),
    ("duplicate torque", {"slips": None, "torques": "[4000, 4000.0]"}, "test[1].torques[2]",
     "torques =", ("duplicate torque",)),
    ("group on a soil test", {"group": '"rough tracks"'}, "test[1].group", "group =",
     ("group 'soil'",)),
    ("measured reference", {"reference": '{ files = ["a.tdx"] }'}, "test[1].reference.files",
     "reference =", ("reference model", "rigid-road tests")),
    ("reference not run", {"models": '["OPC lk"]', "reference": '{ model = "rigid wheel" }'},
     "test[1].reference.model", "reference =", ("not among this test's models",)),
    ("unknown model label", {"models": '["OPC lk", "FTire"]'}, "test[1].models[2]", "models =",
     ("no model labelled", "FTire")),
    ("duplicate model", {"models": '["OPC lk", "OPC lk"]'}, "test[1].models[2]", "models =",
     ("duplicate model",)),
]


@pytest.mark.parametrize("what, keys, field, line_text, words", BAD, ids=[b[0] for b in BAD])
def test_bad_soil_keys_are_one_named_line(tmp_path, what, keys, field, line_text, words):
    text = HEAD + _soil_test(**keys)
    message = _spec_error(tmp_path, text)
    line = _line_of(text, line_text, text.index("[[test]]"))
    assert message.startswith(f"{tmp_path / 'spec.toml'}, line {line}: {field}: "), message
    for word in words:
        assert word in message, message


def test_a_rigid_road_test_refuses_the_rigid_wheel(tmp_path):
    """Every model of a test must run on its ground: the rigid wheel (soil only) in a cleat test
    that names no models is refused at the test, with the hint to list its models."""
    text = HEAD + '\n[[test]]\nname = "cleat"\nroad = "cleat:50x50"\nspeeds_kmh = [12]\nloads = ["LC1"]\n'
    message = _spec_error(tmp_path, text)
    line = _line_of(text, "[[test]]")
    assert message.startswith(f"{tmp_path / 'spec.toml'}, line {line}: test[1]: "), message
    assert '"rigid wheel" (rigid) does not run on the rigid road' in message
    assert "models list" in message


def test_a_model_that_does_not_run_on_soil_is_refused(tmp_path, monkeypatch):
    """A contact model whose registry entry lists only the rigid road, in a soil test's
    models: refused at its place in the list."""
    from tyrelab.tyre import registry
    road_only = dataclasses.replace(registry.contact_model("point"), name="road-only",
                                    terrains=("rigid",))
    monkeypatch.setitem(registry._CONTACT, "road-only", road_only)
    text = (HEAD + '\n[[model]]\nname = "road model"\ncontact = "road-only"\n'
            + _soil_test(models='["OPC lk", "road model"]'))
    message = _spec_error(tmp_path, text)
    line = _line_of(text, "models =", text.index("[[test]]"))
    assert message.startswith(f"{tmp_path / 'spec.toml'}, line {line}: test[1].models[2]: "), message
    assert '"road model" (road-only) does not run on soil (it runs on: rigid)' in message


def test_a_bad_soil_file_names_the_spec_and_the_soil_file(tmp_path):
    """A soil file with a friction angle of 70 deg: one line naming the spec's terrain key and,
    inside, the soil file's own line and key."""
    (tmp_path / "soils").mkdir()
    soil = tmp_path / "soils" / "bad.toml"
    soil.write_text("[soil]\nn = 1.0\nkc = 1e3\nkphi = 1e6\ncohesion = 1e3\nfriction_angle = 70\n"
                    "janosi_k = 0.02\n")
    text = HEAD + _soil_test(terrain='"soils/bad.toml"')
    message = _spec_error(tmp_path, text)
    line = _line_of(text, "terrain =", text.index("[[test]]"))
    assert message.startswith(f"{tmp_path / 'spec.toml'}, line {line}: test[1].terrain: "), message
    assert f"{soil}, line 6: soil.friction_angle" in message and "[0, 60)" in message


def test_a_soil_file_is_read_from_the_spec_folder_and_its_content_keys_its_runs(tmp_path):
    """``terrain`` = a soil file relative to the spec's folder: resolved there, given to the
    runs, with a default duration of 3 s and the group "soil"; changing one number in the file
    changes the key of every run on it and of no other run (the cleat's), and putting it back
    gives the keys back; each slip is its own run."""
    from tyrelab.road.soil import load_soil
    folder = tmp_path / "campaign"
    (folder / "soils").mkdir(parents=True)
    soil = folder / "soils" / "wet.toml"
    original = ("[soil]\nname = \"wet loam\"\nn = 0.7\nkc = 5.27e3\nkphi = 1515.04e3\ncohesion = 1.72e3\n"
                "friction_angle = 29\njanosi_k = 0.025\n")
    soil.write_text(original)
    cleat = '\n[[test]]\nname = "cleat"\nroad = "cleat:50x50"\nspeeds_kmh = [12]\nloads = ["LC1"]\n' \
            'models = ["OPC lk"]\n'
    text = HEAD + cleat + _soil_test(terrain='"soils/wet.toml"', duration=None)
    spec = parse_spec(text, folder / "spec.toml")
    test = spec.tests[1]
    assert test.terrain == str(soil.resolve()) and test.duration == 3.0 and test.group == "soil"
    runs = [r for r in spec.runs() if r.test == "sand"]
    assert [(r.model.name, r.slip) for r in runs] == [(m, s) for m in ("rigid wheel", "OPC lk")
                                                        for s in SLIPS]
    assert runs[0].simulate_kwargs()["terrain"] == str(soil.resolve())
    assert runs[1].simulate_kwargs()["rig_options"] == {"slip": 0.2}
    assert load_soil(runs[0].simulate_kwargs()["terrain"])[1] == "wet loam"
    before = spec.run_keys()
    assert len(set(before.values())) == len(before) == 1 + 6
    soil.write_text(original.replace("kphi = 1515.04e3", "kphi = 1600e3"))
    after = parse_spec(text, folder / "spec.toml").run_keys()
    for run, key in before.items():
        assert (after[run] != key) == (run.test == "sand"), run
    soil.write_text(original)
    assert parse_spec(text, folder / "spec.toml").run_keys() == before


# ---------------------------------------------------------------------------
# driving torques instead of slips

TORQUE = 8000.0   # N m: the rigid wheel on LETE sand settles at s = 0.15 within 1.2 s


def test_a_torque_test_is_a_soil_test_run_per_torque(tmp_path):
    text = HEAD + _soil_test(slips=None, torques=f"[0, {TORQUE:g}]")
    (tmp_path / "spec.toml").write_text(text)
    from tyrelab.study.spec import load_spec
    spec = load_spec(tmp_path / "spec.toml")
    runs = spec.runs()
    assert [(r.model.name, r.slip, r.torque) for r in runs] == [
        (m, None, t) for m in ("rigid wheel", "OPC lk") for t in (0.0, TORQUE)]
    assert spec.tests[0].is_soil_test and spec.tests[0].group == "soil"
    assert runs[1].simulate_kwargs()["rig_options"] == {"torque": TORQUE}
    keys = spec.run_keys()
    assert len({keys[r] for r in runs}) == 4
    slip_spec = parse_spec(HEAD + _soil_test(slips="[0]"), tmp_path / "s.toml")
    assert keys[runs[0]] != slip_spec.run_keys()[slip_spec.runs()[0]]   # s = 0 is not T = 0


def test_a_torque_run_gives_the_slip_at_which_that_torque_drives_the_wheel(tmp_path):
    """Round trip through both drives: the study runs the rigid wheel under 8 kN m; its table's
    slip is the one the soil settled it at. Prescribing that slip must then take the same
    torque (the steady torque balances the soil's moment whichever way the spin is set)."""
    import tyrelab
    from tyrelab import study as studies
    text = HEAD + _soil_test(slips=None, torques=f"[{TORQUE:g}]", models='["rigid wheel", "OPC lk"]',
                             duration="3.0", reference='{ model = "rigid wheel" }')
    (tmp_path / "spec.toml").write_text(text)
    table = studies.run(tmp_path / "spec.toml", workers=1, progress=False).soil_curves
    # the point model settles at another slip under the same torque: it is compared with the
    # reference at that torque (at its own slip the reference has no run)
    (row,) = _curve(table, "rigid wheel").itertuples()
    (other,) = _curve(table, "OPC lk").itertuples()
    assert other.slip != row.slip and other.TORQUE_diff_pct == 0.0
    assert other.FX_diff_pct == pytest.approx(100 * (other.FX - row.FX) / other.force_scale_N, rel=1e-12)
    assert row.torque == TORQUE and row.TORQUE == pytest.approx(TORQUE, rel=1e-12)
    assert 0.1 < row.slip < 0.2
    back = tyrelab.simulate(model="rigid", rig="single-wheel", terrain="lete-sand", load=LOAD,
                            speed=SPEED_KMH / 3.6, duration=3.0, rig_options={"slip": row.slip},
                            progress=False)
    steady = back[back["RUNTIME"] >= 1.5]
    assert steady["TORQUE"].mean() == pytest.approx(TORQUE, rel=0.01)
    assert steady["FX"].mean() == pytest.approx(row.FX, rel=0.01)
