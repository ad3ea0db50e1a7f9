"""The study report: one self-contained HTML page of a whole study (opens offline).

:func:`write_study_report` takes a study's results object (``tyrelab.study``)
and writes one HTML file, atomically (temporary name, then rename). The page
carries plotly.js once (compressed, inline), so every figure can be zoomed -
e.g. into a cleat impact - with no network. This module assembles the page;
the tables come from :mod:`.study_sections`, the figures from
:mod:`.study_figures`, and :mod:`.figure_embed` puts plotly.js and the
figures' data into the page.

Sections, in order:

1. **Header**: study name, date, package version, and the reference note in a
   banner (what every model is compared with: a measurement or another model).
2. **Run matrix**: test conditions x models, each cell a run's status and wall
   time; the failed runs with their error; the runs that warned of leaving the
   models' physics (airborne, rim contact ...), marked and listed with their warnings.
3. **Per test condition** (test, speed, load):

   * the models x metrics table with the best three per metric green, orange
     and red (thesis Tables 5-2 to 5-5 and 5-7 to 5-10 for obstacles, 5-11 to
     5-14 for tracks; :func:`tyrelab.validate.tables.table_html`), further
     metrics in a second table, the measured repeatability below the models
     when the study has it (thesis Tables 5-1 and 5-6; not ranked), and
     "the near-zero rule touched N of M samples" wherever it did;
   * an overlay of every model's compared channel on the reference over time,
     disturbance and response shaded with their bounds as vertical lines,
     zoomable (thesis Figures 5-2 to 5-6; Figure 5-11 for a track);
   * for a track (no disturbance segment), the force distributions of every
     model and the reference with normal fits (thesis Figure 5-14).

4. **On soil** (only when the study has soil tests): each soil test's drawbar
   pull, driving torque and sinkage against slip, one trace per model, in three
   stacked zoomable panels, and their table (:mod:`.soil_section`).
5. **Summary** in the form of thesis Table 5-15
   (:func:`tyrelab.validate.tables.summary_html`), the recommended model per
   group with its expected error (mean and worst |primary metric| over the
   group's runs), and what the rules set aside.
6. **Against the thesis**: our metrics beside the thesis's and the rank
   agreement (Spearman's rho per run), when the study has thesis rows; and,
   when the reference is the thesis's FTire TP stand-in, the consistency with
   what the thesis measured (:mod:`.consistency_section`).
7. **Accuracy against cost**: each model's wall time per simulated second
   against its mean error (a scatter), and the parameterization it needs.

Size: the page holds plotly.js once and each figure's data compressed
(:mod:`.figure_embed`), the overlays' traces decimated to what a screen shows:
at most ``max_points`` (4000) points per trace, the minimum and maximum of
each of 1999 pixel columns, so no peak is lost
(:func:`tyrelab.report.study_figures.decimate_minmax`), their values rounded to
the figure's quantum (0.2 N to 2 N for a wheel load); each overlay's caption
says how many samples it shows and how they were rounded. The built-in
campaign's page (200 runs, 32 figures) is 3.9 MB (35 MB before decimation to
a screen and compression). ``full_resolution=True`` writes every sample with
its exact value instead (for zooming into a single impact at the sample
rate; a page of about 70 MB for that campaign).

Where it is made: in this process, or, given a Dask ``client`` whose workers share the
study's folder (``tyrelab.study.run`` passes its local cluster's), each condition's figures
on a worker (:func:`condition_part`), numbered as a part of the page and renumbered here in
the page's order, so the page is the same byte for byte.

Checks: a tiny script at the top of the page records script errors, failed
resource loads, unhandled promise rejections and ``console.error`` calls in
``<pre id="tyrelab-errors">``; one at the bottom sets the body's
``data-figures-rendered`` to the number of plotly figures drawn (divs
``.js-plotly-plot`` holding an ``svg.main-svg``), to be compared with the
count the page declares in ``<meta name="tyrelab-figures">``
(:mod:`.figure_embed`).
"""

from __future__ import annotations

import datetime
import os
from pathlib import Path

import numpy as np
import pandas as pd

from .._version import __version__
from ..io_atomic import atomic_output
from ..validate.compare import METRICS
from .figure_embed import ERRORS_SCRIPT, RENDERED_SCRIPT, FigureSink
from .soil_section import soil_section
from .study_figures import (MAX_POINTS, PALETTE, condition_figures, condition_text, cost_figure,
                            cost_points, title_text)
from .study_sections import (COND, REPEATABILITY, compared_ok, esc, frame_html, metric_tables,
                             near_zero, num, run_matrix, summary_section, thesis_section)

#: columns of ``study.index`` and ``study.metrics`` the report reads
INDEX_COLUMNS = ["key", "tyre", "model", "contact", "stiffness", "test", "group", "road",
                 "speed_kmh", "load", "rig", "dt", "status", "wall_time_s", "simulated_s", "error",
                 "warnings"]
METRIC_COLUMNS = ["key", "reference", "tyre", "model", "contact", "test", "group", "road",
                  "speed_kmh", "load", "channel", "near_zero_samples", "compared_samples",
                  "disturbance_start_s", "disturbance_end_s", "response_start_s", "response_end_s",
                  "error"]
_ATTRIBUTES = ("spec", "folder", "store", "reference_note", "summary", "thesis", "rank_agreement",
               "consistency", "cost", "signal", "soil_curves")

_STYLE = """body{font-family:system-ui,sans-serif;max-width:75em;margin:auto;padding:0 1em;color:#222}
.reference-note{background:#fff3cd;border:2px solid #e0a800;padding:.6em 1em;font-weight:bold;margin:1em 0}
table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #aaa;padding:2px 7px;text-align:right}
th{background:#f2f2f2}caption{caption-side:top;text-align:left;font-style:italic;padding:.3em 0}
td.failed{background:#ffb3b3}td.done{background:#e6f5e6}td.warned{background:#fff0b3}td.text,th.text{text-align:left}
table.run-matrix td{white-space:nowrap}
tr.repeatability th,tr.repeatability td{background:#eef3ff;font-style:italic}
pre.error{white-space:pre-wrap;margin:0;text-align:left}.scroll{overflow-x:auto}figure{margin:1em 0}
figcaption{font-size:.9em;color:#444}.meta{color:#555}
"""


def _study_name(study, fallback: str | None) -> str:
    spec = getattr(study, "spec", None)
    if spec is not None and getattr(spec, "name", None):
        return str(spec.name)
    for folder in (getattr(study, "folder", None),
                   getattr(getattr(study, "store", None), "folder", None)):
        if folder:
            return Path(folder).name
    return fallback or "study"


def _header(study, name: str, note: str) -> str:
    idx = study.index
    done = int((idx["status"] == "done").sum()) if len(idx) else 0
    failed = int((idx["status"] == "failed").sum()) if len(idx) else 0
    when = datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    return (f"<header><h1>Study report: {esc(name)}</h1>"
            f"<p class='meta'>Generated {esc(when)} by tyrelab {esc(__version__)}; {len(idx)} runs: "
            f"{done} done, {failed} failed.</p>"
            f"<div class='reference-note' id='reference-note' role='note'>{esc(note)}</div>"
            "</header>\n")


def condition_part(study, cond, rows, refs, note, colours, max_points, exact):
    """One condition's figures made on a study's worker, which shares the study's folder:
    ``(html, count)``, the figures numbered for the page to number them in turn
    (:meth:`.figure_embed.FigureSink.take`); the arguments as :func:`condition_figures`'s."""
    figs = FigureSink(exact=exact, deferred=True)
    return condition_figures(study, cond, rows, refs, note, figs, colours, max_points), figs.count


def _conditions(study, note, figs, colours, max_points, client=None) -> str:
    """Each test condition: its tables, the reference's self-check, its figures (with a Dask
    ``client`` whose workers share the study's folder, made there, one condition per task)."""
    metrics = study.metrics
    out = ["<section id='conditions'><h2>Per test condition</h2>"]
    if metrics is None or len(metrics) == 0:
        return out[0] + "<p>No run was compared.</p></section>\n"
    if max_points is not None:
        out.append("<p class='meta' id='resolution'>The overlays show what a screen resolves: long "
                   "traces as the minimum and maximum of each pixel column (every peak kept), values "
                   "rounded as each caption says. Every sample at its exact value: <code>"
                   "tyrelab.report.study_report.write_study_report(tyrelab.study.open(folder), path, "
                   "full_resolution=True)</code>.</p>")
    index = study.index
    refs = {k: f"{m} (reference)" for k, m in zip(index["key"], index["model"])}
    remote = client is not None and getattr(study, "folder", None) is not None
    parts = {}  # position in out -> (condition, rows, future) of figures made on a worker
    rep_mask = metrics["model"] == REPEATABILITY
    for n, (cond, rows) in enumerate(metrics[~rep_mask].groupby(COND, sort=False), start=1):
        rep = metrics[rep_mask]
        for col, value in zip(COND, cond):
            rep = rep[rep[col] == value]
        ok = compared_ok(rows)
        good = rows[ok]
        ref_names = sorted({refs.get(k, str(k)) for k in rows["reference"]})
        group = str(rows["group"].iloc[0])
        out.append(f"<section class='condition' id='condition-{n}'><h3>{esc(condition_text(*cond))}"
                   f" <small>({esc(group)})</small></h3>")
        if len(good):
            caption = (f"{condition_text(*cond)}: models against {', '.join(ref_names)}; best three per "
                       f"metric green, orange, red (as thesis Tables 5-2 to 5-14). {note}")
            out.append(metric_tables(good, rep[compared_ok(rep)], caption))
            out.append(near_zero(pd.concat([good, rep[compared_ok(rep)]])))
        own = study.self_checks
        for col, value in zip(COND, cond):
            own = own[own[col] == value]
        if len(own):
            worst = np.nanmax(np.abs(own[[m for m in METRICS if m in own]].to_numpy(dtype=float)),
                              initial=0.0)
            out.append(f"<p class='meta'>The reference compared with itself (a check of the chain): "
                       f"largest |metric| {num(worst)}.</p>")
        for r in rows[~ok].itertuples():
            out.append(f"<p class='compare-error'>{esc(r.model)} could not be compared: "
                       f"{esc(r.error)}</p>")
        if len(good) and remote:
            parts[len(out)] = (cond, good, client.submit(
                condition_part, study.source, cond, good, refs, note, colours, max_points,
                figs.exact, pure=False))
            out.append("")
        elif len(good):
            out.append(condition_figures(study, cond, good, refs, note, figs, colours, max_points))
        out.append("</section>")
    for at, (cond, good, future) in parts.items():  # numbered in the page's order
        try:
            text, count = future.result()
        except Exception:  # the worker died: made here
            text, count = condition_part(study, cond, good, refs, note, colours, max_points,
                                         figs.exact)
        out[at] = figs.take(text, count)
    return "\n".join(out) + "</section>\n"


def _cost(study, note, figs, colours) -> str:
    """Accuracy against cost: scatter and the parameterization table."""
    cost = getattr(study, "cost", None)
    if cost is None or len(cost) == 0:
        return ""
    metrics = study.metrics
    good = metrics[(metrics["model"] != REPEATABILITY) & compared_ok(metrics)]
    pts = cost_points(good, cost)
    table = cost[[c for c in ("model", "contact", "runs", "wall_per_simulated_s", "parameterization")
                  if c in cost.columns]].rename(
        columns={"wall_per_simulated_s": "wall time per simulated second [s/s]"})
    for group, rows in pts.groupby("group", sort=False):
        errors = dict(zip(rows["model"], rows["mean_error_pct"]))
        table[f"mean error, {group} [%]"] = [errors.get(m, np.nan) for m in table["model"]]
    out = ["<section id='cost'><h2>Accuracy against cost</h2>"]
    if len(pts):
        title = title_text("Accuracy against cost: mean error vs wall time per simulated second", note)
        caption = ("Each model's wall time per simulated second against its mean error: per group, "
                   "the mean over the compared runs of the mean |primary metric| (obstacles: m%RE "
                   "of disturbance and response; tracks: mu%err and sigma%err). " + note)
        out.append(figs.add(cost_figure(pts, title, colours), "cost", caption))
    out.append(frame_html(table, "Cost and the parameterization data each model needs"))
    return "\n".join(out) + "</section>\n"


class _Normalised:
    """The attributes the report reads; an index or metrics table that is None or has
    no columns (nothing run, nothing compared) becomes an empty table of the
    interface's columns. Rows comparing the reference with itself (``key ==
    reference``, or ``is_reference`` where the table has it) are moved out of
    the metrics into ``self_checks``: they are no model and are never ranked.
    The others (:data:`_ATTRIBUTES`; None where the study has none) are read at their
    first use, so a study's workers draw its figures while the tables are made."""

    def __init__(self, study):
        def frame(df, columns):
            return pd.DataFrame(columns=columns) if df is None or len(df.columns) == 0 else df
        self.source = study  # what a worker is sent to read the runs' signals (_conditions)
        self.index = frame(getattr(study, "index", None), INDEX_COLUMNS)
        metrics = frame(getattr(study, "metrics", None), METRIC_COLUMNS + list(METRICS))
        own = (metrics["key"].astype(str) == metrics["reference"].astype(str)).to_numpy()
        if "is_reference" in metrics.columns:
            own = own | metrics["is_reference"].fillna(False).astype(bool).to_numpy()
        self.metrics, self.self_checks = metrics[~own], metrics[own]

    def __getattr__(self, name):  # only for what __init__ did not set
        if name not in _ATTRIBUTES:
            raise AttributeError(name)
        value = getattr(self.source, name, None)
        setattr(self, name, value)
        return value


def study_report_html(study, *, name: str | None = None, max_points: int = MAX_POINTS,
                      full_resolution: bool = False, client=None) -> str:
    """The whole page as text (see the module docstring); ``name`` if the study has none;
    ``client``: a Dask client whose workers share the study's folder (the study's local
    cluster) makes the conditions' figures, one condition per task (the same page)."""
    study = _Normalised(study)
    note = str(getattr(study, "reference_note", "") or "reference: not stated")
    name = _study_name(study, name)
    models = list(dict.fromkeys([*study.index["model"].astype(str),
                                 *study.metrics["model"].astype(str)]))
    colours = {m: PALETTE[i % len(PALETTE)] for i, m in enumerate(models)}
    figs = FigureSink(exact=full_resolution)
    conditions = _conditions(study, note, figs, colours, None if full_resolution else max_points,
                             client)
    soil = soil_section(study, figs, colours)
    body = [_header(study, name, note),
            "<nav><a href='#runs'>runs</a> &middot; <a href='#conditions'>per condition</a> &middot; "
            + ("<a href='#soil'>on soil</a> &middot; " if soil else "")
            + "<a href='#summary'>summary</a> &middot; <a href='#thesis'>thesis</a> &middot; "
            "<a href='#cost'>cost</a></nav>",
            run_matrix(study.index), conditions, soil,
            summary_section(study), thesis_section(study), _cost(study, note, figs, colours)]
    return ("<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>\n" + ERRORS_SCRIPT
            + f"\n<title>Study report: {esc(name)}</title>\n"
            f"<meta name='tyrelab-figures' content='{figs.count}'>\n"
            "<meta name='viewport' content='width=device-width, initial-scale=1'>\n"
            f"<style>{_STYLE}</style></head>\n<body>\n<pre id='tyrelab-errors' hidden></pre>\n"
            + "\n".join(body) + "\n" + figs.page_scripts() + "\n" + RENDERED_SCRIPT
            + "\n</body></html>\n")


def write_study_report(study, path, *, max_points: int = MAX_POINTS,
                       full_resolution: bool = False, client=None) -> Path:
    """Write the study report to ``path`` (HTML) and return the path.

    ``max_points``: most points per overlay trace (the min/max envelope of
    ``(max_points - 2) // 2`` pixel columns); ``full_resolution=True``: every
    sample of every overlay trace and every number exact (a much larger page).

    The page is built completely first, then written to a temporary sibling
    and renamed over ``path``, so an interrupted write never leaves a page
    that looks finished. Without ``study.spec`` the study is named after its
    folder (``study.folder`` or ``study.store.folder``), else after the
    folder ``path`` is in. ``client``: as :func:`study_report_html`'s.
    """
    path = Path(path)
    text = study_report_html(study, name=path.resolve().parent.name, max_points=max_points,
                             full_resolution=full_resolution, client=client)
    with atomic_output(path) as tmp:
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.chmod(tmp, 0o644)            # a page to share (the temporary file is private)
    return path
