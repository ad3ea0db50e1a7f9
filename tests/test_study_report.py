"""The study report (tyrelab.report.study_report): one self-contained HTML page.

The study is a stand-in for ``tyrelab.study``'s results object with exactly
the attributes the report reads, filled from real short simulations (the
point and volume models against the enveloping model as the reference, on
the 50 mm cleat and the Belgian paving at 18 km/h) and metrics computed by
``tyrelab.validate.compare.compare_runs``, so every number and figure is
real. The page is rendered in headless Chromium (``tests/chromium.py``); a
missing Chromium fails the test, it is part of the product's checks.
"""

from __future__ import annotations

import re
import time
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

import tyrelab
from tyrelab.errors import InputError
from tyrelab.report.study_figures import ERRORS_SCRIPT, decimate_minmax, overlay_figure
from tyrelab.report import study_report
from tyrelab.report.study_report import write_study_report
from tyrelab.validate.compare import METRICS, THESIS_CLEAT, compare_runs
from tyrelab.validate.segments import segments_from_signal
from tyrelab.validate.tables import COLOURS, rank_agreement, summary_table
from tyrelab.validate.thesis import thesis_metrics

from chromium import find_chromium, parse, render_dom, INSTALL_HINT

NOTE = "reference: 3D ENV nlk (enveloping model), not a measurement"
SPEED, LOAD = 18.0, "LC1"
#: label -> (contact model, stiffness)
MODELS = {"OPC lk": ("point", "linear"), "OPC nlk": ("point", "table"),
          "3D VC nlk": ("volume", "table")}
REFERENCE = ("3D ENV nlk", "enveloping", "table")
#: test -> (group, road, duration [s], models run)
TESTS = {"cleat 50x50 perpendicular": ("discrete obstacles", "cleat:50x50", 2.5, list(MODELS)),
         "belgian paving": ("rough tracks", "belgian-paving", 3.0, ["OPC nlk", "3D VC nlk"])}
FAILED = ("FTire", "ftire")      # a model label and a contact model that does not exist


def _record(key, label, contact, stiffness, test, status, wall, simulated, error=""):
    group, road = TESTS[test][:2]
    return {"key": key, "tyre": "xzl", "model": label, "contact": contact, "stiffness": stiffness,
            "test": test, "group": group, "road": road, "speed_kmh": SPEED, "load": LOAD,
            "rig": "trailer", "dt": 1e-3, "status": status, "wall_time_s": wall,
            "simulated_s": simulated, "error": error}


def _metric_row(key, ref_key, label, test, sim, ref, seg):
    res = compare_runs(sim, ref, "FZ", segments=seg)
    m = ref["FZ"].to_numpy()
    near = int(np.sum(np.abs(m) < 0.01 * np.max(np.abs(m))))
    row = {"key": key, "reference": ref_key, "tyre": "xzl", "model": label, "contact": "",
           "test": test, "group": TESTS[test][0], "road": TESTS[test][1], "speed_kmh": SPEED,
           "load": LOAD, "channel": "FZ", "near_zero_samples": near, "compared_samples": len(m),
           "error": ""}
    row.update({k: res.get(k, np.nan) for k in METRICS})
    for name in ("disturbance", "response"):
        span = getattr(seg, name) if seg is not None else (np.nan, np.nan)
        row[f"{name}_start_s"], row[f"{name}_end_s"] = span
    return row


def build_study(folder=None, spec_name="report-test-study"):
    """The stand-in study (see the module docstring)."""
    signals, index, metrics = {}, [], []

    def run(label, contact, stiffness, test, **kw):
        key = f"{test.split()[0]}-{label.replace(' ', '-').lower()}"
        group, road, duration, _ = TESTS[test]
        t0 = time.perf_counter()
        sim = tyrelab.simulate(model=contact, stiffness=stiffness, road=road, speed=SPEED / 3.6,
                               load=LOAD, duration=duration, progress=False, **kw)
        signals[key] = sim
        index.append(_record(key, label, contact, stiffness, test, "done",
                             time.perf_counter() - t0, float(sim["RUNTIME"].iloc[-1])))
        return key, sim

    for test, (group, road, duration, labels) in TESTS.items():
        ref_key, ref = run(*REFERENCE, test)
        seg = (segments_from_signal(ref["RUNTIME"].to_numpy(), ref["FZ"].to_numpy())
               if group == "discrete obstacles" else None)
        for label in labels:
            key, sim = run(label, *MODELS[label], test)
            metrics.append(_metric_row(key, ref_key, label, test, sim, ref, seg))
        own = _metric_row(ref_key, ref_key, REFERENCE[0], test, ref, ref, seg)
        metrics.append({**own, "is_reference": True})     # the chain's check: every error zero
        if seg is not None:   # the "measurement's scatter": the reference again at half the step
            again = tyrelab.simulate(model=REFERENCE[1], stiffness=REFERENCE[2], road=road,
                                     speed=SPEED / 3.6, load=LOAD, duration=duration, dt=5e-4,
                                     progress=False)
            rep = _metric_row("repeat", ref_key, "measured repeatability", test, again, ref, seg)
            metrics.append(rep)
    test = "cleat 50x50 perpendicular"
    with pytest.raises(InputError) as err:
        tyrelab.simulate(model=FAILED[1], road=TESTS[test][1], speed=SPEED / 3.6, duration=0.1)
    index.append(_record("cleat-ftire", FAILED[0], FAILED[1], "table", test, "failed", 0.01, 0.0,
                         f"InputError: {err.value}"))
    index, metrics = pd.DataFrame(index), pd.DataFrame(metrics)
    metrics["is_reference"] = metrics["is_reference"].fillna(False).astype(bool)
    metrics["near_zero_samples"] = metrics["near_zero_samples"].astype("Int64")

    models = metrics[(metrics["model"] != "measured repeatability") & ~metrics["is_reference"]]
    results = models.assign(obstacle=models["test"], load_case=models["load"])
    summary = summary_table(results)
    cleat = results[results["test"] == test]
    theirs = thesis_metrics(None)
    theirs = theirs[(theirs["test"] == test) & (theirs["speed_kmh"] == SPEED)
                    & theirs["model"].isin(list(cleat["model"]))]
    ra = rank_agreement(cleat, theirs, by=("test", "speed_kmh", "load_case"))
    thesis = cleat[["test", "speed_kmh", "load", "model", *THESIS_CLEAT]].merge(
        theirs[["model", *THESIS_CLEAT]], on="model", suffixes=("_ours", "_thesis"))
    done = index[index["status"] == "done"].groupby("model")[["wall_time_s", "simulated_s"]].sum()
    cost = pd.DataFrame({"model": list(done.index),
                         "wall_per_simulated_s": (done["wall_time_s"] / done["simulated_s"]).to_numpy(),
                         "parameterization": "load-deflection table, free radius, damping"})
    return SimpleNamespace(
        spec=SimpleNamespace(name=spec_name) if spec_name else None, folder=folder,
        reference_note=NOTE, index=index, metrics=metrics, summary=summary, thesis=thesis,
        rank_agreement=ra, cost=cost, signal=lambda key: signals[key])


@pytest.fixture(scope="module")
def study():
    return build_study()


@pytest.fixture(scope="module")
def page(study, tmp_path_factory):
    path = write_study_report(study, tmp_path_factory.mktemp("report") / "report.html")
    return path, path.read_text(encoding="utf-8")


def _expected_figures(study):
    """One overlay per compared condition, a distribution per track, one cost scatter."""
    m = study.metrics[study.metrics["model"] != "measured repeatability"]
    conds = m.groupby(["test", "speed_kmh", "load"])["disturbance_start_s"].apply(
        lambda s: bool(np.isfinite(s).any()))
    return len(conds) + int((~conds).sum()) + 1


def test_page_renders_in_chromium_without_script_errors(study, page):
    if find_chromium() is None:
        pytest.fail("Chromium is needed to check the study report renders: " + INSTALL_HINT)
    dom = parse(render_dom(page[0]))
    errors = dom.find("pre", id="tyrelab-errors")
    assert errors is not None and errors.text().strip() == "", errors and errors.text()
    declared = int(dom.find("meta", name="tyrelab-figures").attrs["content"])
    assert declared == _expected_figures(study) == 4
    drawn = [d for d in dom.find_all("div", cls="js-plotly-plot") if d.find("svg", cls="main-svg")]
    assert len(drawn) == declared
    body = dom.find("body")
    assert body.attrs.get("data-figures-rendered") == str(declared)
    assert body.attrs.get("data-figures-done") == "yes"
    # every figure compares with the reference: its drawn title carries the note
    for fig in dom.find_all("figure", cls="tyrelab-figure"):
        title = fig.find("text", cls="gtitle")
        assert title is not None and NOTE in title.text(), fig.attrs
    kinds = [f.attrs["data-kind"] for f in dom.find_all("figure", cls="tyrelab-figure")]
    assert kinds == ["overlay", "overlay", "distribution", "cost"]
    # the cleat overlay draws its two segments as spans and their four bounds as lines
    shapes = [p for g in dom.find_all("figure", cls="tyrelab-figure")[0].find_all("g", cls="shapelayer")
              for p in g.find_all("path") if "data-index" in p.attrs]
    assert len(shapes) == 6
    assert NOTE in dom.find("div", id="reference-note").text()


def test_the_error_recorder_catches_what_it_claims(tmp_path):
    """The checks above mean something: the page's recorder does record errors."""
    if find_chromium() is None:
        pytest.fail("Chromium is needed to check the study report renders: " + INSTALL_HINT)
    page = tmp_path / "broken.html"
    page.write_text("<!DOCTYPE html><html><head><meta charset='utf-8'>" + ERRORS_SCRIPT
                    + "</head><body><pre id='tyrelab-errors' hidden></pre>"
                    "<img src='missing-figure.png'>"
                    "<script>Promise.reject(new Error('rejected-x'));</script>"
                    "<script>console.error('plotly-said-x');</script>"
                    "<script>throw new Error('thrown-x');</script></body></html>")
    dom = parse(render_dom(page, budget_ms=2000))
    recorded = dom.find("pre", id="tyrelab-errors").text()
    for needle in ("thrown-x", "rejected-x", "plotly-said-x", "failed to load", "missing-figure.png"):
        assert needle in recorded, recorded


def test_reference_note_and_thesis_numbers_in_the_page(study, page):
    doc = parse(page[1])
    assert doc.find("div", id="reference-note").text() == NOTE
    figures = doc.find_all("figure", cls="tyrelab-figure")
    assert figures and all(NOTE in f.find("figcaption").text() for f in figures)
    captions = " ".join(f.find("figcaption").text() for f in figures)
    for thesis_number in ("Figures 5-2 to 5-6", "Figure 5-14"):
        assert thesis_number in captions
    assert "Table 5-15" in doc.find("section", id="summary").text()
    assert "Rank agreement" in doc.find("section", id="thesis").text()


def test_best_three_marking_matches_a_hand_ranking(study, page):
    doc = parse(page[1])
    cond = doc.find("section", id="condition-1")
    assert "cleat 50x50 perpendicular" in cond.find("h3").text()
    table = cond.find("table", cls="metrics")
    rows = table.find_all("tr")
    header = [th.text() for th in rows[0].find_all("th")][1:]
    assert header == THESIS_CLEAT
    m = study.metrics
    m = m[(m["test"] == "cleat 50x50 perpendicular") & (m["model"] != "measured repeatability")
          & (m["key"] != m["reference"])]                  # not the reference against itself
    colour = {1: COLOURS[1], 2: COLOURS[2], 3: COLOURS[3]}
    seen = 0
    for row in rows[1:]:
        model = row.find("th").text()
        cells = row.find_all("td")
        if model == "measured repeatability":
            assert all("style" not in c.attrs for c in cells)     # shown, never ranked
            continue
        for metric, cell in zip(header, cells):
            values = sorted(abs(v) for v in m[metric])
            mine = abs(float(m.loc[m["model"] == model, metric].iloc[0]))
            rank = 1 + values.index(mine)                       # hand ranking by |value|
            assert cell.attrs.get("style") == f"background:{colour[rank]}", (model, metric)
            seen += 1
    assert seen == 3 * len(THESIS_CLEAT)
    assert [r.find("th").text() for r in rows[1:]] == [*MODELS, "measured repeatability"]
    assert "measured repeatability" in table.text()


def test_near_zero_rule_is_reported(study, page):
    doc = parse(page[1])
    text = " ".join(ul.text() for ul in doc.find_all("ul", cls="near-zero"))
    m = study.metrics
    touched = m[(m["near_zero_samples"] > 0) & (m["key"] != m["reference"])]
    assert len(touched)
    for r in touched.itertuples():
        assert (f"{r.model}: the near-zero rule touched {r.near_zero_samples} of "
                f"{r.compared_samples} samples") in text


def test_decimation_keeps_every_extreme_exactly():
    rng = np.random.default_rng(7)
    n = 200_001
    t = np.arange(n) * 1e-3
    y = 25_000 + 500 * rng.standard_normal(n)
    y[123_457] = 61_109.094417003   # a one-sample impact peak, at an odd place
    y[77_777] = -3.25               # and a trough
    td, yd = decimate_minmax(t, y, max_points=1000)
    assert len(td) <= 1000 and np.all(np.diff(td) > 0)
    assert yd.max() == y.max() and td[np.argmax(yd)] == t[123_457]
    assert yd.min() == y.min() and td[np.argmin(yd)] == t[77_777]
    assert td[0] == t[0] and td[-1] == t[-1]
    assert np.all(np.isin(yd, y))                                 # only original samples
    short_t, short_y = decimate_minmax(t[:500], y[:500], max_points=1000)
    assert np.array_equal(short_y, y[:500])


def test_overlay_marks_the_segments_and_zooms_onto_the_disturbance():
    t = np.arange(3000) * 1e-3
    y = 20e3 + 1e4 * np.exp(-((t - 1.0) / 0.05) ** 2)
    seg = {"disturbance": (0.93, 1.03), "response": (1.03, 2.999)}
    fig, n = overlay_figure(("ref", t, y), [("model", t, 1.1 * y, "#d62728")], "FZ", "title", seg)
    assert n == {"samples": 6000, "kept": 6000}
    rects = sorted((s.x0, s.x1) for s in fig.layout.shapes if s.type == "rect")
    lines = sorted(s.x0 for s in fig.layout.shapes if s.type == "line")
    assert rects == [seg["disturbance"], seg["response"]]
    assert lines == sorted([0.93, 1.03, 1.03, 2.999])
    zoom = fig.layout.updatemenus[0].buttons[0]
    lo, hi = zoom.args[0]["xaxis.range"]
    assert zoom.label == "disturbance" and lo < 0.93 and hi > 1.03 and hi - lo < 0.3


def test_page_is_self_contained(page):
    text = page[1]
    doc = parse(text)
    for node in doc.iter():
        for attr in ("src", "href"):
            value = node.attrs.get(attr, "")
            assert not re.match(r"\s*(https?:)?//", value), (node.tag, attr, value)
    assert not doc.find_all("link")
    assert len(re.findall(r"\* plotly\.js v\d", text)) == 1            # the library, once
    assert text.count("Plotly.newPlot(") == int(doc.find("meta", name="tyrelab-figures")
                                                 .attrs["content"])
    assert len(text) < 6_000_000


def test_failed_runs_listed_with_their_error(study, page):
    doc = parse(page[1])
    failed = study.index[study.index["status"] == "failed"]
    table = doc.find("table", cls="failed-runs")
    assert table is not None
    for r in failed.itertuples():
        assert r.error and r.error in table.text()
    cells = doc.find("table", cls="run-matrix").find_all("td", cls="failed")
    assert len(cells) == len(failed) and failed["error"].iloc[0] in cells[0].attrs["title"]


def test_written_atomically_and_named_after_the_folder(study, tmp_path, monkeypatch):
    folder = tmp_path / "my-campaign"
    folder.mkdir()
    target = folder / "report.html"
    target.write_text("old page")
    unnamed = SimpleNamespace(**{**vars(study), "spec": None, "folder": None})

    def interrupted(src, dst):
        raise OSError("disk full")

    monkeypatch.setattr(study_report.os, "replace", interrupted)
    with pytest.raises(OSError, match="disk full"):
        write_study_report(unnamed, target)
    assert target.read_text() == "old page"                 # the old page stands, no leftover
    assert sorted(p.name for p in folder.iterdir()) == ["report.html"]
    monkeypatch.undo()
    assert write_study_report(unnamed, target) == target
    assert "<h1>Study report: my-campaign</h1>" in target.read_text()
    assert sorted(p.name for p in folder.iterdir()) == ["report.html"]


def test_a_study_where_every_run_failed_still_reports(study, tmp_path):
    index = study.index.assign(status="failed", error="InputError: the road file is gone")
    bare = SimpleNamespace(spec=None, folder=tmp_path / "all-failed", reference_note=NOTE,
                           index=index, metrics=None, summary=pd.DataFrame(),
                           thesis=pd.DataFrame(), rank_agreement=None, cost=None,
                           signal=study.signal)
    doc = parse(write_study_report(bare, tmp_path / "r.html").read_text(encoding="utf-8"))
    assert doc.find("h1").text() == "Study report: all-failed"
    assert doc.find("meta", name="tyrelab-figures").attrs["content"] == "0"
    assert len(doc.find("table", cls="failed-runs").find_all("tr")) == len(index) + 1
    assert "No run was compared" in doc.find("section", id="conditions").text()


def test_report_argues_the_table_5_15_cells_the_rules_miss(tmp_path):
    """The verdict rules' own check on the thesis's numbers is in every report: the count of
    matched cells and, for each miss, its argument."""
    from tyrelab.report.study_report import _rules_on_thesis
    from tyrelab.validate.thesis import rules_on_thesis
    cells = rules_on_thesis()
    html = _rules_on_thesis()
    assert f"give {int(cells['match'].sum())} of the {len(cells)} cells" in html
    for why in cells.loc[~cells["match"], "why"]:
        assert why[:60].replace("'", "&#x27;") in html


def test_overlay_on_a_measured_reference(tmp_path):
    """A study whose reference is a measured file: the report draws the models over the
    measurement (read through Study.signal), not a 'no figure' note."""

    from tyrelab.report.study_report import study_report_html
    from tyrelab.signal import write_signal
    from tyrelab.study import Study, tasks
    from tyrelab.study.spec import parse_spec
    from tyrelab.study.store import Store
    text_models = ('[[model]]\nname = "OPC nlk"\ncontact = "point"\n\n'
                   '[[model]]\nname = "3D VC nlk"\ncontact = "volume"\n\n')
    folder = tmp_path / "s"
    store = Store(folder)
    head = ('[study]\nname = "measured"\n\n[[tyre]]\nname = "xzl"\nfile = "xzl-16.00R20"\n\n'
            + text_models + '[[test]]\nname = "cleat 50x50 perpendicular"\nroad = "cleat:50x50"\n'
            'speeds_kmh = [18]\nloads = ["LC1"]\nduration = 2.5\n')
    measured = tyrelab.simulate(model="enveloping", road="cleat:50x50", speed=5.0, load="LC1",
                                duration=2.5, progress=False)
    write_signal(measured, folder / "field.parquet")
    text = head + 'reference = { files = [{ file = "field.parquet", speed_kmh = 18, load = "LC1" }] }\n'
    spec = parse_spec(text, folder / "spec.toml")
    for task in tasks(spec):
        store.save(task["key"], task["spec"], tyrelab.simulate(**task["simulate"], progress=False), 0.1)
    store.write_text("spec.toml", text)
    html = study_report_html(Study(folder))
    assert "could not be read" not in html
    assert "field.parquet" in html and "tyrelab-fig-1" in html
