"""The study report (tyrelab.report.study_report): one self-contained HTML page.

The study is real: a small spec run by ``tyrelab.study.run`` (the Dask runner with one
worker process, the evaluation, the :class:`tyrelab.study.Study` whose summary, thesis
comparison, rank agreement and cost tables the report reads). Four model variants of the
thesis (point lk/nlk, volume nlk, enveloping nlk) on the XZL at 18 km/h, LC1:

* the 50 mm cleat against two *measured* files of the condition (stand-ins written here:
  time, wheel load FZ and wheel-centre path of the enveloping model with a linear vertical
  law, and the same at half the step, so the second file is the measurement's
  repeatability, shown and never ranked; without the load cells' FZ_HUB, FZ is compared);
* the Belgian paving against the enveloping model of the study;
* a road file that cannot be read: every run of that test fails, and the report lists them.

The page is rendered in headless Chromium (``tests/chromium.py``); a missing Chromium fails
the test, it is part of the product's checks. What the page's figures hold is read back in
Python (``figure_embed.unpack_figure``) and checked against the study's signals, and the
browser's decoding against Python's.
"""

from __future__ import annotations

import base64
import gzip
import html
import re
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

import tyrelab
from tyrelab.report.figure_embed import (ERRORS_SCRIPT, LEVELS, SIGNIFICANT, pack_figure, plotly_block,
                                         unpack_figure, value_quantum)
from tyrelab.report.study_figures import MAX_POINTS, decimate_minmax, overlay_figure
from tyrelab.report import study_report
from tyrelab.report.study_report import study_report_html, write_study_report
from tyrelab.validate.compare import THESIS_CLEAT, THESIS_TRACK
from tyrelab.validate.tables import COLOURS

from chromium import find_chromium, parse, render_dom, INSTALL_HINT

SPEED, LOAD = 18.0, "LC1"
#: the model variants, in the spec's order
MODELS = ["OPC lk", "OPC nlk", "3D VC nlk", "3D ENV nlk"]
CLEAT, PAVING, BROKEN = "cleat 50x50 perpendicular", "belgian paving", "unreadable track"
MEASURED = ("cleat_18kmh.parquet", "cleat_18kmh_repeat.parquet")
SPEC = f"""\
[study]
name = "report-test-study"
output = "out"

[[tyre]]
name = "xzl"
file = "xzl-16.00R20"

[[model]]
name = "OPC lk"
contact = "point"
stiffness = "linear"

[[model]]
name = "OPC nlk"
contact = "point"
stiffness = "table"

[[model]]
name = "3D VC nlk"
contact = "volume"
stiffness = "table"

[[model]]
name = "3D ENV nlk"
contact = "enveloping"
stiffness = "table"

[[test]]
name = "{CLEAT}"
road = "cleat:50x50"
speeds_kmh = [{SPEED:g}]
loads = ["{LOAD}"]
duration = 2.5
reference = {{ files = ["{MEASURED[0]}", "{MEASURED[1]}"] }}

[[test]]
name = "{PAVING}"
road = "belgian-paving"
speeds_kmh = [{SPEED:g}]
loads = ["{LOAD}"]
duration = 3.0
reference = {{ model = "3D ENV nlk" }}

[[test]]
name = "{BROKEN}"
road = "broken.crg"
speeds_kmh = [{SPEED:g}]
loads = ["{LOAD}"]
duration = 1.0
reference = {{ model = "3D ENV nlk" }}
"""


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    """The study of the module docstring, run into a temporary folder."""
    from tyrelab import study as studies
    from tyrelab.signal import write_signal
    folder = tmp_path_factory.mktemp("study")
    for name, dt in zip(MEASURED, (1e-3, 5e-4)):
        measured = tyrelab.simulate(model="enveloping", stiffness="linear", road="cleat:50x50",
                                    speed=SPEED / 3.6, load=LOAD, duration=2.5, dt=dt, progress=False)
        # what the trailer's instruments record: time, the wheel load, the wheel centre's path
        write_signal(measured[["RUNTIME", "FZ", "X_WC", "Z_WC"]], folder / name)
    (folder / "broken.crg").write_text("not an OpenCRG file\n")
    (folder / "spec.toml").write_text(SPEC)
    return studies.run(folder / "spec.toml", workers=1, progress=False)


@pytest.fixture(scope="module")
def page(study, tmp_path_factory):
    path = write_study_report(study, tmp_path_factory.mktemp("report") / "report.html")
    return path, path.read_text(encoding="utf-8")


_FIGURE = re.compile(r"<figure class='tyrelab-figure' data-kind='(\w+)'><div id='([\w-]+)'[^>]*></div>"
                     r"<script type='application/octet-stream' class='tyrelab-figure-data' "
                     r"data-figure='\2' data-encoding='gzip\+base64'>([A-Za-z0-9+/=]*)</script>"
                     r"<figcaption>(.*?)</figcaption></figure>", re.S)


def _figures(text):
    """(kind, div id, the figure as the page's loader reads it, caption) of each figure."""
    return [(kind, div, unpack_figure(block), html.unescape(caption))
            for kind, div, block, caption in _FIGURE.findall(text)]


def _overlay_signals(study, caption, traces):
    """{trace name: (time, values)} of an overlay, read from the study: the condition is the
    one the caption starts with, the last trace the reference (``overlay_figure``)."""
    m = study.metrics
    for cond, rows in m[m["model"] != "measured repeatability"].groupby(["test", "speed_kmh", "load"]):
        if caption.startswith(f"{cond[0]}, {float(cond[1]):g} km/h, {cond[2]}:"):
            break
    else:
        raise AssertionError(f"no condition for the caption {caption!r}")
    channel, ref = rows["channel"].iloc[0], rows["reference"].iloc[0]

    def signal(key):
        s = study.signal(key)
        return s["RUNTIME"].to_numpy(dtype=float), s[channel].to_numpy(dtype=float)
    models = {str(r.model): signal(r.key) for r in rows.itertuples()
              if r.key != ref and not r.is_reference}
    assert [t["name"] for t in traces[:-1]] == list(models)
    return {**models, traces[-1]["name"]: signal(ref)}


def _quantum(caption) -> float:
    return float(re.search(r"values rounded to (\S+) N", caption).group(1))


def _size_bound(runs, overlay_traces, distributions, costs=1) -> int:
    """The most bytes a study report may take, from the built-in campaign's page measured on
    2026-11-26 (/work/runs/def1: 200 runs; 20 overlays of 10 traces, 11 distributions, one
    cost figure; 3.86 MB, 35.3 MB before): plotly.js as the page holds it (1.96 MB), 30 kB for
    the page's frame, and per run 2 kB of tables (1.3 kB measured), per overlay trace of at most
    4000 points 10 kB (7.3 kB), per distribution figure 20 kB (16.5 kB), per cost figure 10 kB
    (3 kB)."""
    return (len(plotly_block()) + 30_000 + 2_000 * runs + 10_000 * overlay_traces
            + 20_000 * distributions + 10_000 * costs)


def test_the_study_is_real_and_complete(study):
    """What the report is built from: every run of the readable tests done, every run of the
    unreadable one failed with the reader's error; a model row per model of each compared
    condition, the repeat file's row, the reference compared with itself on the paving."""
    index = study.index
    assert len(index) == 3 * len(MODELS)
    assert set(index.loc[index["test"] != BROKEN, "status"]) == {"done"}
    broken = index[index["test"] == BROKEN]
    assert set(broken["status"]) == {"failed"}
    assert all("OpenCRG" in e for e in broken["error"])
    m = study.metrics
    cleat = m[m["test"] == CLEAT]
    assert sorted(cleat["model"]) == sorted([*MODELS, "measured repeatability"])
    assert set(cleat["reference"]) == {MEASURED[0]}
    assert set(cleat["channel"]) == {"FZ"}                 # the files have no load-cell FZ_HUB
    paving = m[m["test"] == PAVING]
    assert sorted(paving["model"]) == sorted(MODELS) and set(paving["channel"]) == {"FZ_HUB"}
    own = paving[paving["model"] == "3D ENV nlk"]
    assert own["is_reference"].all()                        # the chain's check: every error zero
    assert np.all(own[THESIS_TRACK].to_numpy(dtype=float) == 0.0)
    assert (study.folder / "report.html").is_file()        # study.run writes the report too


def test_the_workers_evaluate_as_this_process_does(study, tmp_path):
    """study.run evaluates each condition on a worker of its cluster: its metrics.parquet is,
    value for value and row for row, what this process computes alone (a failed worker or
    an order that depended on which finished first would show)."""
    from tyrelab.study.evaluate import evaluate_study
    from tyrelab.study.store import Store
    on_workers = pd.read_parquet(study.folder / "metrics.parquet")
    copy = tmp_path / "copy"
    import shutil
    shutil.copytree(study.folder, copy)
    here = evaluate_study(study.spec, Store(copy), progress=False)
    assert len(here) >= 9 and here["error"].eq("").sum() >= 8
    pd.testing.assert_frame_equal(on_workers, here)


def _undated(text):
    return re.sub(r"Generated [^;]*;", "Generated;", text)


def test_the_workers_draw_the_page_this_process_draws(study, page):
    """study.run makes each condition's figures on a worker of its cluster, numbered there as
    a part of the page and renumbered by it (FigureSink.take): its report.html is, byte for
    byte but for the date it was made, the page this process writes alone (the ``page``
    fixture); a numbering restarted per condition, or parts put in the order they finished,
    would show."""
    on_workers = (study.folder / "report.html").read_text(encoding="utf-8")
    assert "tyrelab-fig-<" not in on_workers and "tyrelab-fig-3" in on_workers
    assert _undated(on_workers) == _undated(page[1])


def test_a_client_is_given_every_compared_condition_to_draw(study, page):
    """With a client, each condition that has compared runs goes to a worker (one task each,
    none drawn here: as many as the page drawn alone has overlays, one per such condition), and
    the page is the one this process draws alone: the test above cannot tell the workers' path
    from this process's, this one can. A real Dask client (threads)."""
    from distributed import Client, LocalCluster
    conditions = sum(kind == "overlay" for kind, *_ in _figures(page[1]))
    sent = []
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        submit = client.submit

        def recorded(fn, *args, **kwargs):
            sent.append(fn.__name__)
            return submit(fn, *args, **kwargs)

        client.submit = recorded
        text = study_report_html(study, name=page[0].parent.name, client=client)
    assert conditions >= 2 and sent == ["condition_part"] * conditions
    assert _undated(text) == _undated(page[1])


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
    note = study.reference_note
    for fig in dom.find_all("figure", cls="tyrelab-figure"):
        title = fig.find("text", cls="gtitle")        # drawn in lines: compare without spaces
        assert title is not None and "".join(note.split()) in "".join(title.text().split()), fig.attrs
    kinds = [f.attrs["data-kind"] for f in dom.find_all("figure", cls="tyrelab-figure")]
    assert kinds == ["overlay", "overlay", "distribution", "cost"]
    # the cleat overlay draws its two segments as spans and their four bounds as lines
    shapes = [p for g in dom.find_all("figure", cls="tyrelab-figure")[0].find_all("g", cls="shapelayer")
              for p in g.find_all("path") if "data-index" in p.attrs]
    assert len(shapes) == 6
    assert note in dom.find("div", id="reference-note").text()
    # the browser decoded what Python reads from the page: each trace's extremes, every number
    decoded = {div: spec for _, div, spec, _ in _figures(page[1])}
    assert len(decoded) == declared
    for div in dom.find_all("div", cls="plotly-graph-div"):
        traces = decoded[div.attrs["id"]]["data"]
        extremes = [tuple(float(v) for v in e.split()) for e in div.attrs["data-trace-extremes"].split(";")]
        assert extremes == [(float(np.min(t["y"])), float(np.max(t["y"]))) for t in traces], div.attrs["id"]
        assert int(div.attrs["data-points"]) == sum(len(t["x"]) + len(t["y"]) for t in traces)


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
    """The banner says what each test is compared with (the measured files of the cleat, the
    enveloping model of the study elsewhere, "not a measurement"), and so does every figure."""
    doc = parse(page[1])
    note = study.reference_note
    assert doc.find("div", id="reference-note").text() == note
    assert f"{CLEAT}: reference: measured files {MEASURED[0]}, {MEASURED[1]}" in note
    assert f"{PAVING}: reference: 3D ENV nlk (enveloping model), not a measurement" in note
    figures = doc.find_all("figure", cls="tyrelab-figure")
    assert figures and all(note in f.find("figcaption").text() for f in figures)
    captions = " ".join(f.find("figcaption").text() for f in figures)
    for thesis_number in ("Figures 5-2 to 5-6", "Figure 5-14"):
        assert thesis_number in captions
    assert "Table 5-15" in doc.find("section", id="summary").text()
    assert "Rank agreement" in doc.find("section", id="thesis").text()


def test_best_three_marking_matches_a_hand_ranking(study, page):
    doc = parse(page[1])
    cond = doc.find("section", id="condition-1")
    assert CLEAT in cond.find("h3").text()
    table = cond.find("table", cls="metrics")
    rows = table.find_all("tr")
    header = [th.text() for th in rows[0].find_all("th")][1:]
    assert header == THESIS_CLEAT
    m = study.metrics
    m = m[(m["test"] == CLEAT) & (m["model"] != "measured repeatability")
          & (m["key"] != m["reference"])]                  # not the reference against itself
    assert len(m) == len(MODELS) == 4                      # the fourth is left unmarked
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
            if rank in colour:
                assert cell.attrs.get("style") == f"background:{colour[rank]}", (model, metric)
                seen += 1
            else:
                assert "style" not in cell.attrs, (model, metric)
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
        assert (f"{r.model}: the near-zero rule touched {int(r.near_zero_samples)} of "
                f"{int(r.compared_samples)} samples") in text


def _columns_kept(t, y, td, yd, columns):
    """Each pixel column (the documented rule: column k holds samples k n // c to
    (k + 1) n // c - 1) has its largest and its smallest sample among the kept ones,
    at their own time; returns how many columns were checked."""
    n = len(y)
    for k in range(columns):
        lo, hi = k * n // columns, (k + 1) * n // columns
        inside = (td >= t[lo]) & (td <= t[hi - 1])
        assert yd[inside].max() == y[lo:hi].max() and yd[inside].min() == y[lo:hi].min(), k
        assert t[lo + np.argmax(y[lo:hi])] in td[inside][yd[inside] == y[lo:hi].max()]
        assert t[lo + np.argmin(y[lo:hi])] in td[inside][yd[inside] == y[lo:hi].min()]
    return columns


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
    assert np.all(np.isin(yd, y)) and np.array_equal(y[np.searchsorted(t, td)], yd)   # samples, kept whole
    assert _columns_kept(t, y, td, yd, (1000 - 2) // 2) == 499
    # the default: about the pixel columns of a wide screen, a 6 s cleat run at 1 kHz and a
    # 126 s track run each kept as 4000 points at most
    for m in (6000, 126_557):
        td, yd = decimate_minmax(t[:m], y[:m])
        assert len(td) <= MAX_POINTS == 4000 and len(td) > 3900
        assert _columns_kept(t[:m], y[:m], td, yd, (MAX_POINTS - 2) // 2) == 1999
    short_t, short_y = decimate_minmax(t[:500], y[:500], max_points=1000)
    assert np.array_equal(short_y, y[:500])
    whole_t, whole_y = decimate_minmax(t, y, max_points=None)           # full resolution
    assert np.array_equal(whole_t, t) and np.array_equal(whole_y, y)
    gap = y[:5000].copy()
    gap[1000:1100] = np.nan                                             # a gap is left out
    td, yd = decimate_minmax(t[:5000], gap, max_points=1000)
    assert np.all(np.isfinite(yd)) and yd.max() == np.nanmax(gap) and not np.any((td >= 1.0) & (td < 1.1))


def test_value_rounding_step():
    """The step values are rounded to: 1, 2 or 5 x 10^k, at most LEVELS and at least
    LEVELS / 2.5 steps over the range (4.4 to 4.8 significant digits of it)."""
    for lo, hi in ((0.0, 62_019.5), (4_164.0, 41_187.0), (23_000.0, 23_400.0), (-3e-4, 7e-4), (5.0, 5.0)):
        q = value_quantum(lo, hi)
        mantissa = q / 10.0 ** np.floor(np.log10(q))
        assert min(abs(mantissa - m) for m in (1, 2, 5)) < 1e-9, q
        span = (hi - lo) or abs(hi)
        assert LEVELS / 2.5 <= span / q <= LEVELS, (lo, hi, q)
    assert value_quantum(0.0, 62_019.5) == 1.0 and value_quantum(4_164.0, 41_187.0) == 1.0


def test_figure_data_read_back():
    """What a figure's data block holds, read back as the page's loader reads it: times exact,
    values to the figure's step (packed), short arrays to SIGNIFICANT digits; exact when asked."""
    import plotly.graph_objects as go
    rng = np.random.default_rng(3)
    t = 0.25 + np.arange(5000) * 1e-3
    y = 23_000 + 9_000 * rng.standard_normal(5000)
    t_odd = np.sort(rng.uniform(0.0, 5.0, 3000))                        # not on a grid
    y_gap = rng.standard_normal(3000)
    y_gap[10] = np.nan
    fig = go.Figure([go.Scatter(x=t, y=y, name="grid"), go.Scatter(x=t_odd, y=y_gap, name="odd"),
                     go.Scatter(x=[1.0, 2.0], y=[np.pi, np.e])])
    block, info = pack_figure(fig, packed=True)
    data = unpack_figure(block)["data"]
    q = info["quantum"]
    assert q == value_quantum(min(y.min(), np.nanmin(y_gap)), y.max())
    assert info["points"] == 2 * (5000 + 3000 + 2)
    assert np.abs(data[0]["x"] - t).max() < 1e-12 and np.abs(data[1]["x"] - t_odd).max() == 0
    assert np.abs(data[0]["y"] - y).max() <= q / 2 * (1 + 1e-9)
    assert np.allclose(data[0]["y"] / q, np.round(data[0]["y"] / q), rtol=0, atol=1e-6)
    assert np.array_equal(data[1]["y"], y_gap, equal_nan=True)         # a gap: stored whole
    block, _ = pack_figure(fig, packed=False)
    data = unpack_figure(block)["data"]
    assert data[2]["y"] == [float(f"{np.pi:.{SIGNIFICANT}g}"), float(f"{np.e:.{SIGNIFICANT}g}")]
    assert data[1]["y"][10] is None
    block, info = pack_figure(fig, packed=True, exact=True)
    data = unpack_figure(block)["data"]
    assert info["quantum"] is None and np.array_equal(data[0]["y"], y)
    assert np.abs(data[0]["x"] - t).max() < 1e-12


def test_overlays_keep_every_peak_to_the_stated_rounding(study):
    """The page's overlays against the study's signals, decimated (to 1000 points per trace
    here, so the small study's 2500-3000 samples are): every kept point is a sample at its own
    time, its value rounded to the step the caption states; each trace's largest and smallest
    value and each pixel column's are kept."""
    figures = [f for f in _figures(study_report_html(study, max_points=1000)) if f[0] == "overlay"]
    assert len(figures) == 2
    for _, _, spec, caption in figures:
        q = _quantum(caption)
        assert "the minimum and maximum of each of 499 pixel columns" in caption
        for name, (t, y) in _overlay_signals(study, caption, spec["data"]).items():
            trace = next(tr for tr in spec["data"] if tr["name"] == name)
            x, v = trace["x"], trace["y"]
            assert len(x) <= 1000 < len(t)
            i = np.searchsorted(t, x - 1e-9)
            assert np.abs(t[i] - x).max() < 1e-9                         # original sample times
            assert np.abs(v - y[i]).max() <= q / 2 * (1 + 1e-9)        # rounded to the step
            assert np.abs(v / q - np.round(v / q)).max() < 1e-6
            assert v.max() == pytest.approx(q * np.round(y.max() / q), abs=1e-9 * q)
            assert v.min() == pytest.approx(q * np.round(y.min() / q), abs=1e-9 * q)
            assert y[i].max() == y.max() and y[i].min() == y.min()     # the very samples
            assert _columns_kept(t, y, t[i], y[i], 499) == 499


def test_full_resolution_on_request(study, tmp_path):
    """write_study_report(..., full_resolution=True): every sample of every overlay trace at its
    exact value."""
    text = write_study_report(study, tmp_path / "full.html", full_resolution=True).read_text(
        encoding="utf-8")
    figures = [f for f in _figures(text) if f[0] == "overlay"]
    assert len(figures) == 2 and "id='resolution'" not in text
    for _, _, spec, caption in figures:
        assert "exact values (full resolution)" in caption and "every sample shown" in caption
        for name, (t, y) in _overlay_signals(study, caption, spec["data"]).items():
            trace = next(tr for tr in spec["data"] if tr["name"] == name)
            assert np.array_equal(trace["y"], y) and np.abs(trace["x"] - t).max() < 1e-12


def test_overlay_marks_the_segments_and_zooms_onto_the_disturbance():
    t = np.arange(3000) * 1e-3
    y = 20e3 + 1e4 * np.exp(-((t - 1.0) / 0.05) ** 2)
    seg = {"disturbance": (0.93, 1.03), "response": (1.03, 2.999)}
    fig, n = overlay_figure(("ref", t, y), [("model", t, 1.1 * y, "#d62728")], "FZ", "title", seg)
    assert n == {"samples": 6000, "kept": 6000, "range": (20e3, 1.1 * y.max())}
    rects = sorted((s.x0, s.x1) for s in fig.layout.shapes if s.type == "rect")
    lines = sorted(s.x0 for s in fig.layout.shapes if s.type == "line")
    assert rects == [seg["disturbance"], seg["response"]]
    assert lines == sorted([0.93, 1.03, 1.03, 2.999])
    zoom = fig.layout.updatemenus[0].buttons[0]
    lo, hi = zoom.args[0]["xaxis.range"]
    assert zoom.label == "disturbance" and lo < 0.93 and hi > 1.03 and hi - lo < 0.3


def test_page_is_self_contained(page):
    """Nothing loaded from elsewhere; plotly.js once: the installed package's plotly.min.js,
    byte for byte; one data block per declared figure."""
    from plotly.offline import get_plotlyjs
    text = page[1]
    doc = parse(text)
    for node in doc.iter():
        for attr in ("src", "href"):
            value = node.attrs.get(attr, "")
            assert not re.match(r"\s*(https?:)?//", value), (node.tag, attr, value)
    assert not doc.find_all("link")
    libs = doc.find_all("script", id="tyrelab-plotly")
    assert len(libs) == 1 and text.count("tyrelab-plotly") == 2                # the block, the loader
    js = gzip.decompress(base64.b64decode(libs[0].text())).decode("utf-8")
    assert js == get_plotlyjs() and libs[0].attrs["data-version"] in js[:100]
    declared = int(doc.find("meta", name="tyrelab-figures").attrs["content"])
    assert len(doc.find_all("script", cls="tyrelab-figure-data")) == len(_figures(text)) == declared


def test_report_size(study, page):
    """The page stays within the bound measured on the built-in campaign (_size_bound), and
    that bound for the campaign (200 runs, 20 overlays of 10 traces, 11 distributions) is
    within the 5 MB the issue set."""
    assert _size_bound(200, 200, 11) <= 5_000_000
    figures = _figures(page[1])
    overlay_traces = sum(len(spec["data"]) for kind, _, spec, _ in figures if kind == "overlay")
    distributions = sum(kind == "distribution" for kind, _, _, _ in figures)
    assert (overlay_traces, distributions) == (5 + 4, 1)
    assert len(page[1].encode("utf-8")) <= _size_bound(len(study.index), overlay_traces, distributions)


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
    # the study's tables without a spec, a folder or a store to name it by
    unnamed = SimpleNamespace(spec=None, folder=None, store=None,
                              **{a: getattr(study, a) for a in ("reference_note", "index", "metrics",
                                                                "summary", "thesis", "rank_agreement",
                                                                "cost", "signal")})

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
    bare = SimpleNamespace(spec=None, folder=tmp_path / "all-failed", reference_note=study.reference_note,
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
    from tyrelab.report.study_sections import rules_on_thesis_html
    from tyrelab.validate.thesis import rules_on_thesis
    cells = rules_on_thesis()
    text = rules_on_thesis_html()
    assert f"give {int(cells['match'].sum())} of the {len(cells)} cells" in text
    for why in cells.loc[~cells["match"], "why"]:
        assert why[:60].replace("'", "&#x27;") in text


def test_overlay_on_a_measured_reference(study, page):
    """The cleat's reference is a measured file: the report draws the models over the
    measurement (read through Study.signal), not a 'no figure' note."""
    doc = parse(page[1])
    assert "could not be read" not in page[1]
    cond = doc.find("section", id="condition-1")
    assert MEASURED[0] in cond.text()
    overlay = cond.find("figure", cls="tyrelab-figure")
    assert overlay is not None and overlay.attrs["data-kind"] == "overlay"
    assert "tyrelab-fig-1" in page[1]
