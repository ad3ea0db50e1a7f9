"""The study spec: parsing, validation with file/line/key, the run matrix and run keys.

Nothing here runs a rig: a spec is only read, checked and expanded.
"""

from importlib import resources
from pathlib import Path

import pytest

from tyrelab.errors import InputError
from tyrelab.core.toml_lines import TomlLocator
from tyrelab.study.spec import (GROUPS, ModelSpec, RunSpec, StudySpec, TyreSpec, builtin_spec,
                                example_spec, load_spec, parse_spec, run_key, tyre_digest)

# A small spec; the line numbers below refer to it (line 1 is "[study]").
BASE = """\
[study]
name = "t"
dt = 0.001
output_rate = 1000

[[tyre]]
name = "xzl"
file = "xzl-16.00R20"
pressure_kpa = 300

[[model]]
name = "A"
contact = "point"
stiffness = "linear"

[[model]]
name = "B"
contact = "volume"

[[test]]
name = "cleat"
road = "cleat:50x50"
speeds_kmh = [12, 18]
loads = ["LC1"]
duration = 6.0
reference = { model = "B" }
"""


def edit(line: int, new: str, text: str = BASE) -> str:
    """``text`` with its 1-based ``line`` replaced by ``new`` (which may hold several lines)."""
    lines = text.splitlines()
    lines[line - 1] = new
    return "\n".join(lines) + "\n"


def parse(text: str, folder: Path) -> StudySpec:
    return parse_spec(text, folder / "spec.toml")


def fails(text: str, folder: Path, line: int | None, field: str | None, *words: str) -> str:
    """Parse ``text``; assert one InputError naming the spec, ``line``, ``field`` and ``words``."""
    with pytest.raises(InputError) as info:
        parse(text, folder)
    msg = str(info.value)
    assert "\n" not in msg
    where = f"{folder / 'spec.toml'}" + (f", line {line}" if line is not None else "") + ": "
    assert msg.startswith(where), msg
    if field is not None:
        assert msg.startswith(where + field + ": "), msg
    assert info.value.line == line, msg
    for word in words:
        assert word in msg, msg
    return msg


# ---------------------------------------------------------------------------
# the built-in campaign and the example

def test_builtin_campaign_parses_and_expands(tmp_path):
    spec = builtin_spec(base=tmp_path)
    assert spec.name == "xzl-thesis-campaign"
    assert spec.output == (tmp_path / "results").resolve()
    assert spec.tyres == (TyreSpec("xzl", "xzl-16.00R20", 300e3, True),)
    assert [m.name for m in spec.models] == ["OPC lk", "OPC nlk", "3D VC lk", "3D VC nlk", "3D ENV lk",
                                             "3D ENV nlk", "3D ENV edge lk", "3D ENV edge nlk",
                                             "FTire", "FTire TP"]
    assert [(m.contact, m.stiffness) for m in spec.models] == [
        ("point", "linear"), ("point", "table"), ("volume", "linear"), ("volume", "table"),
        ("enveloping", "linear"), ("enveloping", "table"), ("enveloping-edge", "linear"),
        ("enveloping-edge", "table"), ("ring", None), ("ring-tp", None)]
    runs = spec.runs()
    # conditions (test label, speed, load), counted by hand from the thesis's tables and figures:
    #   cleat 50x50 perpendicular 12/18/42 LC1 (3), cleat 50x50 oblique 12 LC2 (1),
    #   cleat 76.3x76.3 perpendicular 12/27/42 LC1 (3), cleat 100x100 oblique 12 LC1 (1),
    #   trapezoidal bump 3 LC2 (1)                                   -> 9 discrete obstacles
    #   belgian paving 3/18 LC1 + 3/11 LC2 (4), fatigue track the same (4),
    #   parallel corrugations 3 LC1 (1), angled corrugations 3 LC1 + 11 LC2 (2) -> 11 rough tracks
    # 20 conditions x 10 models x 1 tyre = 200 runs (90 + 110)
    assert len(runs) == 200
    assert sum(r.group == "discrete obstacles" for r in runs) == 90
    assert sum(r.group == "rough tracks" for r in runs) == 110
    assert len(set(runs)) == 200
    conditions = {(r.test, round(r.speed_kmh, 9), r.load) for r in runs}
    # every condition of the thesis's Tables 5-2 to 5-14 (the labels of its metrics files)
    thesis = {("cleat 50x50 perpendicular", 12, "LC1"), ("cleat 50x50 perpendicular", 18, "LC1"),
              ("cleat 50x50 perpendicular", 42, "LC1"), ("cleat 50x50 oblique 45deg", 12, "LC2"),
              ("cleat 76.3x76.3 perpendicular", 12, "LC1"), ("cleat 76.3x76.3 perpendicular", 27, "LC1"),
              ("cleat 100x100 oblique 45deg", 12, "LC1"), ("trapezoidal bump 150mm", 3, "LC2"),
              ("belgian paving", 3, "LC1"), ("belgian paving", 18, "LC1"), ("belgian paving", 3, "LC2"),
              ("belgian paving", 11, "LC2"), ("fatigue track", 3, "LC1"), ("fatigue track", 18, "LC1"),
              ("fatigue track", 3, "LC2"), ("fatigue track", 11, "LC2")}
    assert thesis <= conditions
    # beyond them: 76.3 mm at 42 km/h (measured repeatability only, Table 5-6) and the
    # corrugations of Figures 5-17 to 5-21
    assert conditions - thesis == {("cleat 76.3x76.3 perpendicular", 42, "LC1"),
                                   ("parallel corrugations", 3, "LC1"), ("angled corrugations", 3, "LC1"),
                                   ("angled corrugations", 11, "LC2")}
    roads = {r.test: r.road for r in runs}
    assert roads["cleat 50x50 oblique 45deg"] == "cleat:50x50@45"
    assert roads["cleat 100x100 oblique 45deg"] == "cleat:100x100@45"
    assert roads["angled corrugations"] == "corrugations-angled"
    for r in runs:
        assert r.rig == "trailer" and r.dt == 1e-3 and r.output_rate == 1000.0
        assert r.duration == {"discrete obstacles": 14.0 if "bump" in r.test else 6.0,
                              "rough tracks": None}[r.group]
        ref = spec.reference_run(r)
        if r.model.name == "FTire TP":
            assert ref is None
        else:
            assert ref.model.name == "FTire TP" and ref in runs
            assert (ref.test, ref.speed, ref.load, ref.road) == (r.test, r.speed, r.load, r.road)
    assert spec.limits == {"discrete obstacles": {"mRE_disturbance_pct": 20.0, "mRE_response_pct": 20.0},
                           "rough tracks": {"mean_error_pct": 10.0, "std_error_pct": 25.0}}
    # keys: one per run, all different (every run differs in something simulated)
    keys = spec.run_keys()
    assert len(set(keys.values())) == 200
    assert all(len(k) == 16 and int(k, 16) >= 0 for k in keys.values())


def test_builtin_file_is_package_data():
    text = resources.files("tyrelab.study").joinpath("data", "thesis_campaign.toml").read_text()
    assert "[[test]]" in text


def test_example_parses(tmp_path):
    text = example_spec()
    spec = parse(text, tmp_path)
    assert [m.name for m in spec.models] == ["OPC lk", "3D ENV nlk", "rigid wheel", "ring"]
    # second inferred; the third a soil test
    assert [t.group for t in spec.tests] == ["discrete obstacles", "rough tracks", "soil"]
    assert spec.tests[1].loads == (38197.0,)
    assert spec.tests[0].speeds == pytest.approx((12 / 3.6, 18 / 3.6))
    # the rigid-road tests run two models; the soil test three, at three slips each
    assert len(spec.runs()) == (2 + 1) * 2 + 3 * 3
    # the example explains every key of the schema
    for key in ("name", "output", "dt", "output_rate", "file", "pressure_kpa", "contact", "stiffness",
                "handling", "group", "road", "speeds_kmh", "loads", "rig", "duration", "reference",
                "files", "metrics.limits", "models", "terrain", "slips"):
        assert key in text


def test_base_spec_parses(tmp_path):
    spec = parse(BASE, tmp_path)
    runs = spec.runs()
    assert [(r.model.name, round(r.speed_kmh, 9)) for r in runs] == [("A", 12), ("B", 12), ("A", 18),
                                                                     ("B", 18)]
    assert runs[0].speed == 12 / 3.6 and runs[0].load == "LC1" and runs[0].tyre.pressure == 300e3
    assert runs[0].simulate_kwargs() == {
        "tyre": "xzl-16.00R20", "model": "point", "road": "cleat:50x50", "speed": 12 / 3.6, "load": "LC1",
        "pressure": 300e3, "stiffness": "linear", "handling": None, "rig": "trailer", "duration": 6.0,
        "dt": 1e-3, "output_rate": 1000.0, "left_wheel": None, "options": None}
    assert spec.reference_run(runs[0]) == runs[1]
    assert spec.output == (tmp_path / "results").resolve()


def test_a_models_relaxation_reaches_its_runs_and_their_keys(tmp_path):
    """``relaxation`` of a [[model]] is passed to its runs and enters their keys; the runs of
    a model without it keep their keys and arguments (as without the key)."""
    plain = parse(BASE, tmp_path)
    lagged = parse(edit(14, 'stiffness = "linear"\nrelaxation = [0.3, 0.5]'), tmp_path)
    keys = {spec: {(r.model.name, r.speed): k for r, k in spec.run_keys().items()}
            for spec in (plain, lagged)}
    for a, b in zip(plain.runs(), lagged.runs()):
        same = a.model.name != "A"
        assert (keys[plain][a.model.name, a.speed] == keys[lagged][b.model.name, b.speed]) is same
        assert b.simulate_kwargs().get("relaxation") == (None if same else (0.3, 0.5))


def test_a_run_key_says_which_transient_slip_is_simulated(tmp_path):
    """MFeval's MF 5.2 example asks for relaxation (USE_MODE 14): under the default "auto" its
    Magic Formula runs lag, and their keys say so ("file"); with "off" they are steady, and
    their keys are those of a run key made without a transient slip (a store made before it
    existed, when such runs were steady, still serves them; the lagged ones are run again)."""
    from tyrelab.study.keys import run_key, tyre_digest

    mf52 = Path(__file__).parent / "data" / "mfeval" / "MagicFormula52_Parameters.tir"
    text = edit(8, f'file = "{mf52}"', edit(9, "", edit(14, 'stiffness = "linear"\nhandling = "mf"')))
    auto = parse(text, tmp_path)
    off = parse(text.replace('handling = "mf"', 'handling = "mf"\nrelaxation = "off"'), tmp_path)
    run = {spec: next(r for r in spec.runs() if r.model.name == "A") for spec in (auto, off)}
    digest = tyre_digest(run[auto].tyre)
    assert auto.run_keys()[run[auto]] == run_key(run[auto], digest, "file")
    assert off.run_keys()[run[off]] == run_key(run[off], digest)
    assert auto.run_keys()[run[auto]] != off.run_keys()[run[off]]


# ---------------------------------------------------------------------------
# every class of bad spec: one line naming file, line, key, what was expected

BAD = [
    # unknown keys, with the allowed ones listed
    (3, "dtt = 0.001", 3, "study.dtt", "unknown key", "allowed keys: name, output, dt, output_rate"),
    (25, "durration = 6.0", 25, "test[1].durration", "allowed keys: name, group, road, speeds_kmh"),
    (14, "stiffnes = 'linear'", 14, "model[1].stiffnes", "allowed keys: name, contact, stiffness, handling"),
    (26, 'reference = { modell = "B" }', 26, "test[1].reference.modell", "allowed keys: model, files"),
    (1, "[studdy]", 1, "studdy", "allowed keys: study, tyre, model, test, metrics"),
    # wrong types
    (23, 'speeds_kmh = "12"', 23, "test[1].speeds_kmh", "expected an array", 'the string "12"'),
    (23, 'speeds_kmh = [12, "fast"]', 23, "test[1].speeds_kmh[2]", "expected a speed in km/h"),
    (3, "dt = true", 3, "study.dt", "expected a time step > 0 [s], got the boolean true"),
    (13, "contact = 3", 13, "model[1].contact", "expected a contact model name"),
    (6, "[tyre]", 6, "tyre", "expected one or more [[tyre]] tables, got a table"),
    (26, 'reference = "B"', 26, "test[1].reference", "expected a table"),
    # unknown names, with the known ones listed
    (13, 'contact = "magic"', 13, "model[1].contact", "unknown contact model",
     "point, volume, enveloping, enveloping-edge, ring, ring-tp"),
    (14, 'handling = "pacejka"', 14, "model[1].handling", "unknown handling model", "none, pac89, mf"),
    (14, 'handling = "pac89"', 14, "model[1].handling", "tyre 'xzl' has no pac89 coefficients", "A0"),
    (14, 'stiffness = "cubic"', 14, "model[1].stiffness", "unknown stiffness", "table, linear"),
    (14, 'relaxation = "fil"', 14, "model[1].relaxation", "expected one of auto, off, file"),
    (14, 'relaxation = "file"', 14, "model[1].relaxation",
     "tyre 'xzl': 'file': the 'none' handling model has no relaxation lengths"),
    (14, "relaxation = [0.3]", 14, "model[1].relaxation", "expected two lengths in metres"),
    (14, "relaxation = 0.3", 14, "model[1].relaxation", 'expected "auto", "off", "file" or two'),
    (25, 'rig = "sled"', 25, "test[1].rig", "unknown rig", "trailer, quarter-vehicle, rolling"),
    (8, 'file = "michelin"', 8, "tyre[1].file", "unknown tyre", "xzl-16.00R20, hmmwv-pac89"),
    (8, 'file = "nope.tir"', 8, "tyre[1].file", "no such tyre property file"),
    (24, 'loads = ["LC9"]', 24, "test[1].loads[1]", "unknown load case", "LC1, LC2, LC3"),
    (26, 'reference = { model = "FTire" }', 26, "test[1].reference.model", "no model labelled",
     '"A", "B"'),
    # bad roads (the road grammar's own checks)
    (22, 'road = "cleat:50"', 22, "test[1].road", "cannot read sizes '50'"),
    (22, 'road = "cleat:50x50@x"', 22, "test[1].road", "cannot read angle 'x'"),
    (22, 'road = "cleat:50x50@95"', 22, "test[1].road",
     "cleat angle 95 deg is out of range; allowed: -80 <= cleat angle <= 80 deg"),
    (22, 'road = "iso8608:Z"', 22, "test[1].road", "unknown ISO 8608 class 'Z'"),
    (22, 'road = "powerlaw:0,2"', 22, "test[1].road", "expected A,N with A > 0"),
    (22, 'road = "moon-surface"', 22, "test[1].road", "unknown road 'moon-surface'", "belgian-paving"),
    (22, 'road = "missing.crg"', 22, "test[1].road", "no such OpenCRG file"),
    (22, 'road = ""', 22, "test[1].road", "expected a road name"),
    # impossible numbers
    (23, "speeds_kmh = [12, 0]", 23, "test[1].speeds_kmh[2]", "0 < v <= 200", "got 0"),
    (23, "speeds_kmh = [-12]", 23, "test[1].speeds_kmh[1]", "0 < v <= 200"),
    (23, "speeds_kmh = [250]", 23, "test[1].speeds_kmh[1]", "0 < v <= 200", "got 250"),
    (23, "speeds_kmh = [nan]", 23, "test[1].speeds_kmh[1]", "got nan"),
    (23, "speeds_kmh = [12, inf]", 23, "test[1].speeds_kmh[2]", "got inf"),
    (3, "dt = 0", 3, "study.dt", "expected a time step > 0 [s], got 0"),
    (3, "dt = -1e-3", 3, "study.dt", "got -0.001"),
    (4, "output_rate = 5000", 4, "study.output_rate", "faster than the time step", "at most 1000 Hz"),
    (25, "duration = 0.0", 25, "test[1].duration", "expected a duration > 0"),
    (24, "loads = [-5]", 24, "test[1].loads[1]", "wheel load > 0 in N"),
    # an obstacle taller than the tyre's radius, the same
    (22, 'road = "step:800"', 22, "test[1].road", "an edge 0.8 m high", "taller than the tyre's "
     "unloaded radius 0.6715 m", '(tyre "xzl")'),
    # a load the tyre cannot carry: the spec's error, not a failed run of it
    (24, "loads = [1e9]", 24, "test[1].loads[1]", "would press xzl-16.00R20 onto its rim",
     '(tyre "xzl")'),
    (9, "pressure_kpa = 900", 9, "tyre[1].pressure_kpa", "100-550 kPa"),
    (23, "speeds_kmh = []", 23, "test[1].speeds_kmh", "non-empty array"),
    (24, "loads = []", 24, "test[1].loads", "non-empty array"),
    # duplicates
    (17, 'name = "A"', 17, "model[2].name", 'duplicate model label "A" (also model[1])'),
    (23, "speeds_kmh = [12, 12.0]", 23, "test[1].speeds_kmh[2]", "duplicate speed"),
    (24, 'loads = ["LC1", "lc1"]', 24, "test[1].loads[2]", "duplicate load"),
    # missing required keys: the line of their table
    (22, "", 20, "test[1]", "missing key 'road'"),
    (2, "", 1, "study", "missing key 'name'"),
    # references
    (26, 'reference = { model = "B", files = ["a.tdx"] }', 26, "test[1].reference", "exactly one of"),
    (26, 'reference = { files = ["field/a.tdx", "field/b.tdx"] }', 26, "test[1].reference.files[1]",
     "no such reference file", "field/a.tdx"),
    (26, 'reference = { files = ["field/a.tdx"] }', 26, "test[1].reference.files", "1 file(s) for 2"),
    # TOML syntax: the line tomllib reports
    (13, "contact = point", 13, None, "invalid TOML", "column 11"),
]


@pytest.mark.parametrize("case", BAD, ids=[f"{b[0]}:{b[1][:30]}" for b in BAD])
def test_bad_spec_names_line_and_key(tmp_path, case):
    line, new, err_line, field, *words = case
    fails(edit(line, new), tmp_path, err_line, field, *words)


def test_a_model_the_tyre_cannot_run_is_refused_before_any_run(tmp_path):
    """The ring on a tyre file without [FLEXIBLE_RING] (the HMMWV's Pac89 file): refused on the
    model's contact line, naming the tyre and the fix, before any run. Before, the study started
    and every ring run failed in its worker ("1 runs finished, 1 failed", exit 0)."""
    text = edit(13, 'contact = "ring"', edit(9, "", edit(8, 'file = "hmmwv-pac89"')))
    fails(text, tmp_path, 13, "model[1].contact", "tyre 'xzl' cannot run the ring model",
          "[FLEXIBLE_RING]", "tyrelab fit ring CAMPAIGN --into")


def test_arrays_over_lines_and_sub_tables_are_located(tmp_path):
    # an array element on its own line: the element's line
    text = edit(23, "speeds_kmh = [\n    12,  # first\n    -18,\n]")
    fails(text, tmp_path, 25, "test[1].speeds_kmh[2]", "0 < v <= 200")
    # a reference written as a sub-table of the test
    text = edit(26, '[test.reference]\nmodel = "Z"')
    fails(text, tmp_path, 27, "test[1].reference.model", 'no model labelled "Z"')
    # the second of several [[test]] tables
    text = BASE + '\n[[test]]\nname = "bump"\nroad = "bump:100"\nspeeds_kmh = [3]\nloads = [7]\nrig = "x"\n'
    fails(text, tmp_path, 33, "test[2].rig", "unknown rig")


def test_metrics_limits(tmp_path):
    spec = parse(BASE + '\n[metrics.limits."rough tracks"]\nstd_error_pct = 30\n', tmp_path)
    assert spec.limits["rough tracks"] == {"std_error_pct": 30.0}          # the group replaced
    assert spec.limits["discrete obstacles"]["mRE_response_pct"] == 20.0  # the other kept
    fails(BASE + '\n[metrics.limits."smooth roads"]\nx = 1\n', tmp_path, 28,
          'metrics.limits."smooth roads"', "allowed keys: discrete obstacles, rough tracks")
    fails(BASE + '\n[metrics.limits."rough tracks"]\nstd_err = 30\n', tmp_path, 29,
          'metrics.limits."rough tracks".std_err', "allowed keys: mRE_disturbance_pct")
    fails(BASE + '\n[metrics.limits."rough tracks"]\nstd_error_pct = 0\n', tmp_path, 29,
          'metrics.limits."rough tracks".std_error_pct', "a limit > 0")
    fails(BASE + '\n[metrics]\nlimit = 3\n', tmp_path, 29, "metrics.limit", "allowed keys: limits")


def test_a_test_name_may_repeat_for_other_conditions_only(tmp_path):
    more = '\n[[test]]\nname = "cleat"\nroad = "cleat:50x50"\nspeeds_kmh = [42]\nloads = ["LC2"]\n'
    spec = parse(BASE + more, tmp_path)
    assert [(r.test, round(r.speed_kmh), r.load) for r in spec.runs()][-2:] == [("cleat", 42, "LC2")] * 2
    # the same condition twice
    fails(BASE + more.replace("[42]", "[18]").replace("LC2", "LC1"), tmp_path, 31,
          "test[2].speeds_kmh[1]", "at 18 km/h, load LC1 is also in test[1]")
    # the same label for another road
    fails(BASE + more.replace("cleat:50x50", "cleat:76.3x76.3"), tmp_path, 30, "test[2].road",
          "one name, one road and group")


def test_reference_files(tmp_path):
    field = tmp_path / "field"
    field.mkdir()
    for name in ("a.tdx", "b.tdx", "c1.tdx", "c2.tdx"):
        (field / name).write_text("x")
    # one per speed, in order
    spec = parse(edit(26, 'reference = { files = ["field/a.tdx", "field/b.tdx"] }'), tmp_path)
    runs = spec.runs()
    assert spec.reference_files(runs[0]) == ((field / "a.tdx").resolve(),)
    assert spec.reference_files(runs[2]) == ((field / "b.tdx").resolve(),)
    assert spec.reference_run(runs[0]) is None
    # tables naming the condition; two for one condition are repeats
    files = ('reference = { files = [{ file = "field/c1.tdx", speed_kmh = 12, load = "LC1" }, '
             '{ file = "field/c2.tdx", speed_kmh = 12, load = "LC1" }, '
             '{ file = "field/b.tdx", speed_kmh = 18, load = "LC1" }] }')
    spec = parse(edit(26, files), tmp_path)
    assert spec.reference_files(spec.runs()[1]) == ((field / "c1.tdx").resolve(),
                                                    (field / "c2.tdx").resolve())
    # a condition without a file, and a file for a speed the test does not drive
    fails(edit(26, files.replace("speed_kmh = 18", "speed_kmh = 12")), tmp_path, 26,
          "test[1].reference.files", "no reference file for 18 km/h, load LC1")
    fails(edit(26, files.replace("speed_kmh = 18", "speed_kmh = 27")), tmp_path, 26,
          "test[1].reference.files[3].speed_kmh", "27 km/h is not among this test's speeds_kmh")
    # with one condition, plain strings are repeats of it
    one = edit(23, "speeds_kmh = [12]", edit(26, 'reference = { files = ["field/c1.tdx", "field/c2.tdx"] }'))
    spec = parse(one, tmp_path)
    assert len(spec.reference_files(spec.runs()[0])) == 2


def test_paths_are_relative_to_the_spec_folder(tmp_path, monkeypatch):
    folder = tmp_path / "campaign"
    (folder / "field").mkdir(parents=True)
    (folder / "field" / "a.tdx").write_text("x")
    (folder / "field" / "b.tdx").write_text("x")
    tir = resources.files("tyrelab.tyre").joinpath("data", "xzl-16.00R20_300kPa.tir").read_text()
    (folder / "my.tir").write_text(tir)
    text = edit(9, "", edit(8, 'file = "my.tir"',
                            edit(26, 'reference = { files = ["field/a.tdx", "field/b.tdx"] }')))
    (folder / "spec.toml").write_text(text)
    monkeypatch.chdir(tmp_path)  # elsewhere
    spec = load_spec("campaign/spec.toml")
    assert spec.tyres[0] == TyreSpec("xzl", str((folder / "my.tir").resolve()), None, False)
    assert spec.output == (folder / "results").resolve()
    assert spec.tests[0].reference_files[1].path == (folder / "field" / "b.tdx").resolve()
    with pytest.raises(InputError, match="no such study spec file"):
        load_spec("campaign/nope.toml")


def test_a_broken_tir_stops_the_spec(tmp_path):
    (tmp_path / "bad.tir").write_text("[MODEL]\nPROPERTY_FILE_FORMAT = 'X'\n")
    msg = fails(edit(9, "", edit(8, 'file = "bad.tir"')), tmp_path, 8, "tyre[1].file", "cannot use this tyre")
    assert "bad.tir" in msg


# ---------------------------------------------------------------------------
# nothing in a spec is executed

def test_nothing_is_executed(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    evil = "__import__('os').system('touch PWNED')"
    fails(edit(22, f'road = "{evil}"'), tmp_path, 22, "test[1].road", "unknown road")
    fails(edit(13, f'contact = "{evil}"'), tmp_path, 13, "model[1].contact", "unknown contact model")
    fails(edit(24, f'loads = ["{evil}"]'), tmp_path, 24, "test[1].loads[1]", "unknown load case")
    fails(edit(8, f'file = "{evil}"'), tmp_path, 8, "tyre[1].file", "unknown tyre")
    # as a label it is only a label
    spec = parse(edit(12, f'name = "{evil}"', edit(26, "")), tmp_path)
    assert spec.models[0].name == evil
    assert not (tmp_path / "PWNED").exists()


# ---------------------------------------------------------------------------
# run keys

def _keys(spec: StudySpec) -> dict:
    """(model label, speed in km/h) -> key."""
    return {(r.model.name, round(r.speed_kmh, 9)): k for r, k in spec.run_keys().items()}


def test_run_keys_equal_for_equal_runs(tmp_path):
    a, b = parse(BASE, tmp_path), parse(BASE, tmp_path / "elsewhere")
    assert _keys(a) == _keys(b)
    run = a.runs()[0]
    assert run_key(run, tyre_digest(run.tyre)) == run_key(b.runs()[0], tyre_digest(b.runs()[0].tyre))
    # labels are not part of what is simulated
    renamed = parse(BASE.replace('name = "cleat"', 'name = "the cleat"').replace('"xzl"', '"tyre 1"'),
                    tmp_path)
    assert list(_keys(renamed).values()) == list(_keys(a).values())


def test_run_keys_change_with_speed_dt_and_load(tmp_path):
    keys = _keys(parse(BASE, tmp_path))
    assert keys[("A", 12)] != keys[("A", 18)]
    assert len(set(keys.values())) == 4
    finer = _keys(parse(edit(3, "dt = 0.0005"), tmp_path))
    assert all(finer[k] != keys[k] for k in keys)
    heavier = _keys(parse(edit(24, 'loads = ["LC2"]'), tmp_path))
    assert all(heavier[k] != keys[k] for k in keys)
    longer = _keys(parse(edit(25, "duration = 7.0"), tmp_path))
    assert all(longer[k] != keys[k] for k in keys)


def test_run_key_of_a_model_ignores_other_models(tmp_path):
    keys = _keys(parse(BASE, tmp_path))
    other = _keys(parse(edit(18, 'contact = "enveloping"'), tmp_path))
    assert other[("A", 12)] == keys[("A", 12)] and other[("A", 18)] == keys[("A", 18)]
    assert other[("B", 12)] != keys[("B", 12)] and other[("B", 18)] != keys[("B", 18)]
    # and adding a model or a test changes no existing key
    grown = _keys(parse(BASE + '\n[[model]]\nname = "C"\ncontact = "enveloping"\n', tmp_path))
    assert {k: v for k, v in grown.items() if k[0] != "C"} == keys


def test_run_key_changes_with_a_tyre_parameter(tmp_path):
    tir = resources.files("tyrelab.tyre").joinpath("data", "xzl-16.00R20_300kPa.tir").read_text()
    assert "VERTICAL_STIFFNESS = 659.6" in tir
    (tmp_path / "my.tir").write_text(tir)
    text = edit(9, "", edit(8, 'file = "my.tir"'))
    before = _keys(parse(text, tmp_path))
    assert _keys(parse(text, tmp_path)) == before
    (tmp_path / "my.tir").write_text(tir.replace("VERTICAL_STIFFNESS = 659.6", "VERTICAL_STIFFNESS = 700.0"))
    after = _keys(parse(text, tmp_path))
    assert all(after[k] != before[k] for k in before)
    # the built-in tyre at another pressure is another tyre
    p300 = TyreSpec("x", "xzl-16.00R20", 300e3)
    assert tyre_digest(p300) == tyre_digest(TyreSpec("other label", "xzl-16.00R20", 300e3))
    assert tyre_digest(p300) != tyre_digest(TyreSpec("x", "xzl-16.00R20", 400e3))
    run = RunSpec(p300, ModelSpec("m", "point"), "t", GROUPS[0], "flat", 1.0, "LC1", "trailer", None,
                  1e-3, 1000.0)
    assert run_key(run, tyre_digest(p300)) != run_key(run, tyre_digest(TyreSpec("x", "xzl-16.00R20", 550e3)))


# ---------------------------------------------------------------------------
# the line locator (tomllib gives no line numbers)

def test_locator_follows_toml_syntax():
    text = '\n'.join([
        '[a]',                                  # 1
        'doc = """',                            # 2
        '[[test]]',                             # 3  inside a string
        'x = 1 """',                            # 4
        "lit = '''q = [1, 2'''",                # 5
        'list = [',                             # 6
        '  "x]",  # a comment [',               # 7
        "  { k = 1, 'quoted key' = [2] },",     # 8
        ']',                                    # 9
        'dotted . "k\\u0041y" = 2',             # 10
        '[[test]]',                             # 11
        'name = "one"',                         # 12
        '[test.sub]',                           # 13
        'v = 1',                                # 14
        '[[test]]  # second',                   # 15
        'name = "two"',                         # 16
    ]) + '\n'
    loc = TomlLocator(text)
    assert loc.line(("a", "doc")) == 2
    assert loc.line(("a", "lit")) == 5
    assert loc.line(("a", "list", 0)) == 7
    assert loc.line(("a", "list", 1, "quoted key", 0)) == 8
    assert loc.line(("a", "dotted", "kAy")) == 10
    assert loc.line(("test", 0)) == 11
    assert loc.line(("test", 0, "sub", "v")) == 14
    assert loc.line(("test", 1, "name")) == 16
    assert loc.line(("test", 1, "missing")) == 15
    assert loc.line(("nowhere",)) is None


def test_left_wheel_of_the_trailer(tmp_path):
    """[study] left_wheel: a contact model name (checked), used by trailer runs whose test
    wheel is another model, and part of those runs' keys only."""
    plain = parse(BASE, tmp_path)
    spec = parse(edit(4, 'output_rate = 1000\nleft_wheel = "point"'), tmp_path)
    assert spec.left_wheel == "point"
    runs = {r.model.name: r for r in spec.runs()}
    assert runs["A"].left_contact is None           # the point model's left wheel is its own
    assert runs["B"].simulate_kwargs()["left_wheel"] == "point"
    old = {r.model.name: k for r, k in plain.run_keys().items() if r.speed * 3.6 < 15}
    new = {r.model.name: k for r, k in spec.run_keys().items() if r.speed * 3.6 < 15}
    assert old["A"] == new["A"] and old["B"] != new["B"]
    fails(edit(4, 'output_rate = 1000\nleft_wheel = "ring-x"'), tmp_path, 5, "study.left_wheel",
          "ring-x", "point")


def test_run_keys_follow_rdf_roads_and_chrono_tyres(tmp_path):
    """A study takes .rdf/.obj roads and Chrono .json tyres; the run keys follow
    the files' content (a changed file is a new run), not their names."""
    from tyrelab.cli.main import main
    assert main(["road", "export", "cleat:50x50", "-o", str(tmp_path / "plank.rdf")]) == 0
    json_text = (Path(__file__).parent / "data" / "tir" / "HMMWV_Pac89Tire.json").read_text()
    (tmp_path / "hmmwv.json").write_text(json_text)
    text = edit(22, 'road = "plank.rdf"', edit(9, "", edit(8, 'file = "hmmwv.json"')))
    text = text.replace('loads = ["LC1"]', "loads = [15000.0]")
    before = _keys(parse(text, tmp_path))
    assert len(set(before.values())) == 4
    assert _keys(parse(text, tmp_path)) == before
    rdf = (tmp_path / "plank.rdf").read_text()
    (tmp_path / "plank.rdf").write_text(rdf + "$ edited\n")
    road_changed = _keys(parse(text, tmp_path))
    assert all(road_changed[k] != before[k] for k in before)
    (tmp_path / "plank.rdf").write_text(rdf)
    assert _keys(parse(text, tmp_path)) == before
    assert '"Vertical Damping": 3483.932502' in json_text
    (tmp_path / "hmmwv.json").write_text(json_text.replace("3483.932502", "3600.0", 1))
    tyre_changed = _keys(parse(text, tmp_path))
    assert all(tyre_changed[k] != before[k] for k in before)


def test_model_options_reach_the_run_and_its_key(tmp_path):
    """[[model]] options: checked against the contact model's (name and type, file, line and
    key named), handed to tyrelab.simulate, and part of that model's run keys only; a model
    without options keeps the key it had before options existed."""
    plain = parse(BASE, tmp_path)
    spec = parse(edit(18, 'contact = "volume"\noptions = { discs = 4, step = 0.01 }'), tmp_path)
    b = {r.model.name: r for r in spec.runs()}["B"]
    assert b.model.options == (("discs", 4), ("step", 0.01))
    assert b.simulate_kwargs()["options"] == {"discs": 4, "step": 0.01}
    old, new = (dict((r.model.name, k) for r, k in s.run_keys().items() if r.speed * 3.6 < 15)
                for s in (plain, spec))
    assert old["A"] == new["A"] and old["B"] != new["B"]
    fails(edit(18, 'contact = "volume"\noptions = { n_length = 5 }'), tmp_path, 19,
          "model[2].options.n_length", "unknown option(s) n_length of the 'volume' model", "discs, step")
    fails(edit(18, 'contact = "volume"\noptions = { discs = "four" }'), tmp_path, 19,
          "model[2].options.discs", "expected a whole number, got 'four'")
    fails(edit(18, 'contact = "volume"\noptions = 4'), tmp_path, 19, "model[2].options",
          "expected a table")
    fails(edit(18, 'contact = "ring"\noptions = { parameters = 1 }'), tmp_path, 19,
          "model[2].options.parameters", "Python only")
    # an impossible value is the spec's error, not a failed run (it once ran out of memory)
    fails(edit(18, 'contact = "ring"\noptions = { n_segments = 100000 }'), tmp_path, 19,
          "model[2].options.n_segments", "ring segments 100000 is out of range; allowed: 12 to 1000")
    fails(edit(18, 'contact = "enveloping"\noptions = { step = 0.0 }'), tmp_path, 19,
          "model[2].options.step", "sampling step 0 m is out of range")
