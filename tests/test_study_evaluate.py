"""Evaluating a study (tyrelab.study.evaluate) and slicing it (tyrelab.study.results.Study).

One tiny study: three analytic models (the thesis's labels) over the 50 mm cleat at
18 km/h, LC1, 2.5 s, the enveloping model as reference; its runs are simulated in
process and saved with Store.save (no Dask). Variants of its store (a scaled copy,
zeros in the reference, a missing reference, measured files) test the rules.
"""

from __future__ import annotations

import json
import math
import shutil

import numpy as np
import pandas as pd
import pytest

import tyrelab
from tyrelab.errors import InputError
from tyrelab.rig.trailer import load_case_wheel_load
from tyrelab.signal import write_signal
from tyrelab.study import tasks
from tyrelab.study.evaluate import COLUMNS, REPEATABILITY, evaluate_study
from tyrelab.study.results import Study
from tyrelab.study.spec import parse_spec
from tyrelab.study.store import Store
from tyrelab.tyre.library import load_tyre
from tyrelab.validate.compare import METRICS, THESIS_CLEAT, THESIS_TRACK
from tyrelab.validate.segments import (segments_from_contact, segments_from_contour,
                                       segments_from_geometry)

TEST = "cleat 50x50 perpendicular"
MODELS = {"OPC nlk": "point", "3D VC nlk": "volume", "3D ENV nlk": "enveloping"}
REF = "3D ENV nlk"


def spec_text(reference: str = f'{{ model = "{REF}" }}') -> str:
    models = "".join(f'[[model]]\nname = "{n}"\ncontact = "{c}"\nstiffness = "table"\n'
                     f'handling = "none"\n\n' for n, c in MODELS.items())
    return f"""[study]
name = "tiny"

[[tyre]]
name = "xzl"
file = "xzl-16.00R20"
pressure_kpa = 300

{models}[[test]]
name = "{TEST}"
group = "discrete obstacles"
road = "cleat:50x50"
speeds_kmh = [18]
loads = ["LC1"]
duration = 2.5
reference = {reference}
"""


def keep_spec(folder, text):
    """What the runner leaves beside the runs: the spec text and where its paths start."""
    (folder / "spec.toml").write_text(text, encoding="utf-8")
    (folder / "study.json").write_text(json.dumps({"base": str(folder)}), encoding="utf-8")


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    folder = tmp_path_factory.mktemp("tiny") / "results"
    store = Store(folder)
    text = spec_text()
    spec = parse_spec(text, base=folder)
    for task in tasks(spec):
        store.save(task["key"], task["spec"], tyrelab.simulate(**task["simulate"], progress=False),
                   wall_time=0.5)
    store.write_index()
    keep_spec(folder, text)
    keys = {run.model.name: key for run, key in spec.run_keys().items()}
    return spec, store, keys, evaluate_study(spec, store, progress=False)


def copy_store(tiny, tmp_path, name="copy"):
    spec, store, keys, _ = tiny
    folder = tmp_path / name
    shutil.copytree(store.folder, folder)
    (folder / "metrics.parquet").unlink(missing_ok=True)
    return Store(folder)


def row(metrics, model):
    sel = metrics[metrics["model"] == model]
    assert len(sel) == 1, model
    return sel.iloc[0]


def test_one_row_per_run_written_to_the_folder(tiny):
    spec, store, keys, m = tiny
    assert list(m.columns) == COLUMNS
    assert sorted(m["model"]) == sorted(MODELS)
    assert (m["error"] == "").all() and (m["channel"] == "FZ_HUB").all()
    assert (m["reference"] == keys[REF]).all()
    assert m["is_reference"].tolist() == [mo == REF for mo in m["model"]]
    # cleats: the segmented metrics and the others; the track metrics do not apply
    assert m[THESIS_CLEAT + ["SG_C", "psd_lsd_dB", "damage_ratio_log10"]].notna().all().all()
    assert m[THESIS_TRACK].isna().all().all()
    stored = pd.read_parquet(store.folder / "metrics.parquet")
    pd.testing.assert_frame_equal(stored, m, check_dtype=False)


def test_reference_compared_with_itself_has_no_error(tiny):
    r = row(tiny[3], REF)
    assert r["key"] == r["reference"] and r["is_reference"]
    for metric in METRICS:
        if metric not in THESIS_TRACK:
            assert r[metric] == pytest.approx(0.0, abs=1e-9), metric
    assert r["near_zero_samples"] == 0 and r["compared_samples"] > 50


def test_segments_bracket_the_force_peak_and_lie_inside_the_run(tiny):
    spec, store, keys, m = tiny
    ref = store.signal(keys[REF])
    t, x, f = (ref[c].to_numpy() for c in ("RUNTIME", "X_WC", "FZ_HUB"))
    r = row(m, "OPC nlk")
    t0, t1 = r["disturbance_start_s"], r["disturbance_end_s"]
    assert r["segment_method"] == "contact"
    assert t[0] < t0 < t1 < t[-1]
    assert r["response_start_s"] == t1 and r["response_end_s"] == t[-1]
    # every model of the condition has the same segments (the reference's contact)
    assert m["disturbance_start_s"].nunique() == 1 and m["disturbance_end_s"].nunique() == 1
    near = (x > 5.0 - 0.7) & (x < 5.05 + 0.7)  # the cleat at x = 5.00-5.05 m, R0 = 0.67 m
    t_peak = t[near][np.argmax(f[near])]
    assert t0 < t_peak < t1
    # the tyre touches the cleat before the centre reaches it and leaves it after, within
    # the static free circle's reach sqrt(R0^2 - (h_c - h)^2) on either side
    x0, x1 = np.interp([t0, t1], t, x)
    tyre = load_tyre("xzl-16.00R20", 300e3)
    r0 = tyre.unloaded_radius
    hc = r0 - tyre.static_deflection(load_case_wheel_load("LC1"))
    reach = math.sqrt(r0 ** 2 - (hc - 0.05) ** 2)
    assert 5.0 - reach - 0.01 < x0 < 5.0 and 5.05 < x1 < 5.05 + reach


def test_contour_on_a_level_path_is_the_free_circle_cut():
    """A centre at constant height over a 50 mm cleat: the contour touches its top corners
    exactly where the free circle of segments_from_geometry does; a centre that rises by
    3 cm after the cleat leaves it sooner."""
    t = np.arange(0.0, 4.0, 0.001)
    x = 5.0 * t
    seg = segments_from_contour(t, x, np.full(t.size, 0.63), (10.0, 10.0, 10.05, 10.05),
                                (0.0, 0.05, 0.05, 0.0), 0.67)
    old = segments_from_geometry(t, x, 10.0, 10.05, 0.05, 0.67, 0.63)
    assert seg.disturbance == pytest.approx(old.disturbance, abs=1.5e-3)
    rising = np.where(x > 10.05, 0.66, 0.63)
    later = segments_from_contour(t, x, rising, (10.0, 10.0, 10.05, 10.05),
                                  (0.0, 0.05, 0.05, 0.0), 0.67)
    reach = math.sqrt(0.67 ** 2 - 0.61 ** 2)
    assert later.disturbance[1] == pytest.approx((10.05 + reach) / 5.0, abs=1.5e-3)
    assert later.disturbance[1] < old.disturbance[1] - 0.01


def test_contact_from_the_contact_point_height():
    t = np.arange(100) * 0.01
    z = np.where((t > 0.3) & (t < 0.6), 0.03, 0.0)
    z[45] = 0.0004  # below 1 % of 50 mm: not a gap, the span runs first to last
    seg = segments_from_contact(t, z, 0.05)
    assert seg.disturbance == pytest.approx((0.31, 0.59)) and seg.method == "contact"
    with pytest.raises(Exception, match="fewer than two"):
        segments_from_contact(t, z, 0.05, x_cp=t, x_range=(2.0, 3.0))


def _save(store, key, signal):
    rec = store.record(key)
    store.save(key, {k: v for k, v in rec.items() if k not in ("key", "status", "error")},
               signal, rec["wall_time_s"])


def test_a_copy_scaled_by_1_1_has_ten_percent_relative_error(tiny, tmp_path):
    """p = 1.1 m gives |p - m| / max(|m|, floor) = 0.1 |m| / |m| = 10 % at every sample whose
    measured value is above the near-zero floor, and the reference never comes near zero in
    the disturbance: m%RE = 80%RE = 10 % exactly; the peak load is 10 % high; the matched
    response peaks are the same samples scaled, 10 % each."""
    spec, _, keys, _ = tiny
    store = copy_store(tiny, tmp_path)
    scaled = store.signal(keys[REF]).copy()
    scaled[["FZ", "FZ_HUB"]] *= 1.1
    _save(store, keys["OPC nlk"], scaled)
    r = row(evaluate_study(spec, store, progress=False), "OPC nlk")
    assert r["near_zero_samples"] == 0
    for metric in ("mRE_disturbance_pct", "RE80_disturbance_pct", "max_error_pct",
                   "mRE_response_pct"):
        assert r[metric] == pytest.approx(10.0, abs=1e-9), metric


def test_near_zero_samples_count_the_zeros_of_the_reference(tiny, tmp_path):
    spec, _, keys, m = tiny
    store = copy_store(tiny, tmp_path)
    ref = store.signal(keys[REF]).copy()
    t0, t1 = row(m, REF)[["disturbance_start_s", "disturbance_end_s"]]
    inside = np.flatnonzero((ref["RUNTIME"] > t0) & (ref["RUNTIME"] < t1))
    k = 7
    zeros = inside[len(inside) // 2: len(inside) // 2 + k]
    ref.loc[zeros, "FZ_HUB"] = 0.0
    _save(store, keys[REF], ref)
    m2 = evaluate_study(spec, store, progress=False)
    for model in MODELS:
        r = row(m2, model)
        assert r["near_zero_samples"] == k, model
        n_dist = int(np.sum((ref["RUNTIME"] >= t0) & (ref["RUNTIME"] <= t1)))
        assert r["compared_samples"] == n_dist + r["n_response_peaks"]
    # the rule: each zero counts |p - 0| / floor, the floor 1 % of the disturbance's peak
    base = row(m, "OPC nlk")
    assert row(m2, "OPC nlk")["mRE_disturbance_pct"] > base["mRE_disturbance_pct"] + 50


def test_a_missing_reference_gives_an_error_row(tiny, tmp_path):
    spec, _, keys, _ = tiny
    store = copy_store(tiny, tmp_path)
    store.signal_path(keys[REF]).unlink()
    m = evaluate_study(spec, store, progress=False)
    assert sorted(m["model"]) == ["3D VC nlk", "OPC nlk"]  # the reference itself is not finished
    assert m["error"].str.contains("not finished").all()
    assert m[THESIS_CLEAT].isna().all().all()


def test_measured_reference_files_and_their_repeatability(tiny, tmp_path):
    spec, store, keys, _ = tiny
    folder = tmp_path / "measured"
    shutil.copytree(store.folder, folder)
    (folder / "metrics.parquet").unlink()
    meas = store.signal(keys[REF])
    write_signal(meas, folder / "m1.parquet")
    repeat = meas.copy()
    repeat["FZ_HUB"] *= 1.05
    write_signal(repeat, folder / "m2.parquet")
    files = ('[{ file = "m1.parquet", speed_kmh = 18, load = "LC1" }, '
             '{ file = "m2.parquet", speed_kmh = 18, load = "LC1" }]')
    text = spec_text(f"{{ files = {files} }}")
    keep_spec(folder, text)
    study = Study(folder)
    m = study.metrics
    assert (folder / "metrics.parquet").is_file()
    rep = row(m, REPEATABILITY)
    assert rep["key"] == "m2.parquet" and rep["reference"] == "m1.parquet"
    assert rep["mRE_disturbance_pct"] == pytest.approx(5.0, abs=1e-6)
    assert (m["reference"] == "m1.parquet").all() and not m["is_reference"].any()
    env = row(m, REF)  # the file is the enveloping run itself: found at shift 0
    assert env["shift_s"] == pytest.approx(0.0, abs=1e-9)
    assert env["mRE_disturbance_pct"] == pytest.approx(0.0, abs=1e-9)
    assert study.reference_note == "reference: measured files m1.parquet, m2.parquet"
    # the report's overlays read the measured reference through Study.signal
    got = study.signal("m1.parquet")
    assert np.array_equal(got["FZ_HUB"].to_numpy(), meas["FZ_HUB"].to_numpy())
    part = study.signal("m1.parquet", ("RUNTIME", "FZ_HUB"))     # what an overlay reads
    assert list(part.columns) == ["RUNTIME", "FZ_HUB"]
    assert np.array_equal(part.to_numpy(), meas[["RUNTIME", "FZ_HUB"]].to_numpy())
    with pytest.raises(InputError, match="no channel FX in this measured run"):
        study.signal("m1.parquet", ("RUNTIME", "FX"))


def test_study_opens_the_folder(tiny):
    spec, store, keys, m = tiny
    study = Study(store.folder)
    assert study.spec is not None and study.spec.name == "tiny"
    assert sorted(study.index["key"]) == sorted(keys.values())
    pd.testing.assert_frame_equal(study.metrics, pd.read_parquet(store.folder / "metrics.parquet"))
    assert study.reference_note == "reference: 3D ENV nlk (enveloping model), not a measurement"
    pd.testing.assert_frame_equal(study.signal(keys[REF]), store.signal(keys[REF]))
    cost = study.cost
    assert cost["model"].tolist() == list(MODELS)
    assert cost["contact"].tolist() == list(MODELS.values())
    assert cost["wall_per_simulated_s"].to_numpy() == pytest.approx(0.5 / 2.499, rel=1e-3)
    assert "cam" in cost.iloc[2]["parameterization"]
    ra = study.rank_agreement  # two models besides the reference: too few for Spearman
    assert ra.per_run["n_models"].tolist() == [2] and math.isnan(ra.mean)
    summary = study.summary
    assert REF not in summary.columns and set(summary.columns) == {"OPC nlk", "3D VC nlk"}


def test_study_thesis_joins_the_published_row(tiny):
    spec, store, keys, m = tiny
    th = Study(store.folder).thesis
    # every model but the reference (compared with itself it has no error to set beside the thesis's)
    assert sorted(th["model"]) == sorted(set(MODELS) - {REF})
    vc = th[th["model"] == "3D VC nlk"].iloc[0]
    # thesis Table 5-3 (50 mm cleat, 18 km/h, LC1), 3D VC nlk: 13, 23, 2023, 31, 7464
    assert vc["table"] == "5-3"
    assert vc["mRE_disturbance_pct_thesis"] == 13 and vc["rms_disturbance_N_thesis"] == 2023
    assert vc["mRE_disturbance_pct_ours"] == row(m, "3D VC nlk")["mRE_disturbance_pct"]
    assert vc["key"] == keys["3D VC nlk"]


def test_to_xarray(tiny):
    import xarray  # noqa: F401 -- a required dependency: missing, this test fails, never skips
    ds = Study(tiny[1].folder).to_xarray()
    assert dict(ds.sizes) == {"model": 3, "condition": 1}
    assert set(ds.data_vars) == set(METRICS)
    assert ds["condition"].item() == f"{TEST} | 18 km/h | LC1"
    assert float(ds["mRE_disturbance_pct"].sel(model="3D VC nlk").item()) == \
        row(tiny[3], "3D VC nlk")["mRE_disturbance_pct"]


def test_summary_of_a_hand_made_metrics_table(tmp_path):
    """Limits 20 % on both m%RE (no spec: the defaults). Passes per run (12, 18, 42 km/h):
    P fail, fail, pass (1/3: not representative); V pass, pass, fail and E pass, fail, pass
    (2/3: comparable). Mean rank over the two metrics: V (2 + 1.5 + 3)/3 = 2.17, E (1.5 +
    2.5 + 1.5)/3 = 1.83: E is best. R, the reference (all zeros), is left out -- it would
    be best."""
    values = {12: {"P": (30, 10), "V": (10, 15), "E": (15, 5), "R": (0, 0)},
              18: {"P": (25, 10), "V": (12, 18), "E": (19, 25), "R": (0, 0)},
              42: {"P": (15, 10), "V": (18, 30), "E": (10, 12), "R": (0, 0)}}
    rows = [{"key": f"{model}{speed}", "reference": f"R{speed}", "is_reference": model == "R",
             "tyre": "xzl", "model": model, "contact": "point", "test": "cleat A",
             "obstacle": "cleats", "group": "discrete obstacles", "speed_kmh": float(speed),
             "load": "LC1", "mRE_disturbance_pct": float(d), "mRE_response_pct": float(r),
             "error": ""}
            for speed, models in values.items() for model, (d, r) in models.items()]
    pd.DataFrame(rows).to_parquet(tmp_path / "metrics.parquet", index=False)
    study = Study(tmp_path)
    assert study.spec is None
    summary = study.summary
    assert summary.loc[("discrete obstacles", "cleats")].to_dict() == {
        "P": "not representative", "V": "comparable", "E": "comparable, best"}
    assert summary.attrs["set_aside"] == [] and summary.attrs["left_out"] == []
    assert study.reference_note == "reference: R (point model), not a measurement"


def test_measured_csv_reference_with_a_column_map(tiny, tmp_path):
    """A logger's CSV (its own column names, ms and kN) as the reference, read through the
    spec's column_map: the enveloping run compared with its own signal so exported gives
    errors at the CSV's rounding (9 significant digits), i.e. zero to 1e-4 %."""
    spec, store, keys, _ = tiny
    folder = tmp_path / "csv"
    shutil.copytree(store.folder, folder)
    (folder / "metrics.parquet").unlink()
    meas = store.signal(keys[REF])
    pd.DataFrame({"time [ms]": meas["RUNTIME"] * 1e3, "hub load (kN)": meas["FZ_HUB"] / 1e3}).to_csv(
        folder / "logger.csv", index=False, float_format="%.9g")
    (folder / "map.csv").write_text("source,channel,unit\ntime [ms],RUNTIME,ms\nhub load (kN),FZ_HUB,kN\n")
    text = spec_text('{ files = ["logger.csv"], column_map = "map.csv" }')
    keep_spec(folder, text)
    m = Study(folder).metrics
    env = row(m, REF)
    assert env["error"] == "" and env["channel"] == "FZ_HUB"
    assert env["mRE_disturbance_pct"] == pytest.approx(0.0, abs=1e-4)
    assert row(m, "OPC nlk")["mRE_disturbance_pct"] > 1.0  # another model is not the reference
    # a column map without files is refused with its key
    with pytest.raises(InputError, match="column_map"):
        parse_spec(spec_text('{ model = "3D ENV nlk", column_map = "map.csv" }'), base=folder)


def test_a_logger_on_the_opposite_axis_is_warned_once_and_read_with_a_minus(tiny, tmp_path):
    """The same logger's load cell on an axis pointing down: every model's comparison warns of
    the opposite sign (in the workers, where no one sees it); the study issues it once, naming
    the file, and keeps it in each row. Its column map's '-FZ_HUB' reads it back to the run
    exactly (the metrics of the plain logger, to 1e-4 %)."""
    from tyrelab.study.runner import RunWarning
    spec, store, keys, _ = tiny
    folder = tmp_path / "down"
    shutil.copytree(store.folder, folder)
    (folder / "metrics.parquet").unlink()
    meas = store.signal(keys[REF])
    pd.DataFrame({"t_ms": meas["RUNTIME"] * 1e3, "fz_kN": -meas["FZ_HUB"] / 1e3}).to_csv(
        folder / "logger.csv", index=False, float_format="%.9g")
    (folder / "map.csv").write_text("t_ms,RUNTIME,ms\nfz_kN,FZ_HUB,kN\n")
    keep_spec(folder, spec_text('{ files = ["logger.csv"], column_map = "map.csv" }'))
    with pytest.warns(RunWarning) as caught:
        m = Study(folder).metrics
    assert len(caught) == 1, [str(w.message) for w in caught]
    assert "logger.csv: the measured FZ_HUB has on average the opposite sign to the simulated one " \
        "(negative against positive)" in str(caught[0].message)
    assert (m["warnings"].str.contains("'-FZ_HUB' in the column map")).all()
    (folder / "map.csv").write_text("t_ms,RUNTIME,ms\nfz_kN,-FZ_HUB,kN\n")
    (folder / "metrics.parquet").unlink()
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error", RunWarning)
        m = Study(folder).metrics
    assert (m["warnings"] == "").all()
    assert row(m, REF)["mRE_disturbance_pct"] == pytest.approx(0.0, abs=1e-4)
