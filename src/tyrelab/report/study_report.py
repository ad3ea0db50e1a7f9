"""The study report: one self-contained HTML page of a whole study (opens offline).

:func:`write_study_report` takes a study's results object (``tyrelab.study``)
and writes one HTML file, atomically (temporary name, then rename). The page
carries plotly.js once (inline, in the first figure), so every figure can be
zoomed - e.g. into a cleat impact - with no network.

Sections, in order:

1. **Header**: study name, date, package version, and the reference note in a
   banner (what every model is compared with: a measurement or another model).
2. **Run matrix**: test conditions x models, each cell a run's status and wall
   time; the failed runs with their error.
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

4. **Summary** in the form of thesis Table 5-15
   (:func:`tyrelab.validate.tables.summary_html`), the recommended model per
   group with its expected error (mean and worst |primary metric| over the
   group's runs), and what the rules set aside.
5. **Against the thesis**: our metrics beside the thesis's and the rank
   agreement (Spearman's rho per run), when the study has thesis rows; and,
   when the reference is the thesis's FTire TP stand-in, the consistency with
   what the thesis measured (:mod:`.consistency_section`).
6. **Accuracy against cost**: each model's wall time per simulated second
   against its mean error (a scatter), and the parameterization it needs.

Long signals are decimated for the overlays (at most ``max_points`` points
per trace, the minimum and maximum of each bucket kept, so no peak is lost;
:func:`tyrelab.report.study_figures.decimate_minmax`); each overlay's caption
states how many samples were kept.

Checks: a tiny script at the top of the page records script errors, failed
resource loads, unhandled promise rejections and ``console.error`` calls in
``<pre id="tyrelab-errors">``; one at the bottom sets the body's
``data-figures-rendered`` to the number of plotly figures drawn (divs
``.js-plotly-plot`` holding an ``svg.main-svg``), to be compared with the
count the page declares in ``<meta name="tyrelab-figures">``.
"""

from __future__ import annotations

import datetime
import html
import os
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd

from .._version import __version__
from .consistency_section import consistency_html
from ..io_atomic import atomic_output
from ..validate.compare import METRICS, THESIS_CLEAT, THESIS_TRACK
from ..validate.tables import _fmt, summary_html, table_html
from .study_figures import (ERRORS_SCRIPT, MAX_POINTS, PALETTE, RENDERED_SCRIPT, FigureSink,
                            condition_figures, condition_text, cost_figure, cost_points, load_text,
                            primary_metrics, title_text)

REPEATABILITY = "measured repeatability"
_COND = ["test", "speed_kmh", "load"]
#: columns of ``study.index`` and ``study.metrics`` the report reads
INDEX_COLUMNS = ["key", "tyre", "model", "contact", "stiffness", "test", "group", "road",
                 "speed_kmh", "load", "rig", "dt", "status", "wall_time_s", "simulated_s", "error"]
METRIC_COLUMNS = ["key", "reference", "tyre", "model", "contact", "test", "group", "road",
                  "speed_kmh", "load", "channel", "near_zero_samples", "compared_samples",
                  "disturbance_start_s", "disturbance_end_s", "response_start_s", "response_end_s",
                  "error"]
_ATTRIBUTES = ("spec", "folder", "store", "reference_note", "summary", "thesis", "rank_agreement",
               "consistency", "cost", "signal")

_STYLE = """body{font-family:system-ui,sans-serif;max-width:75em;margin:auto;padding:0 1em;color:#222}
.reference-note{background:#fff3cd;border:2px solid #e0a800;padding:.6em 1em;font-weight:bold;margin:1em 0}
table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #aaa;padding:2px 7px;text-align:right}
th{background:#f2f2f2}caption{caption-side:top;text-align:left;font-style:italic;padding:.3em 0}
td.failed{background:#ffb3b3}td.done{background:#e6f5e6}td.text,th.text{text-align:left}
tr.repeatability th,tr.repeatability td{background:#eef3ff;font-style:italic}
pre.error{white-space:pre-wrap;margin:0;text-align:left}.scroll{overflow-x:auto}figure{margin:1em 0}
figcaption{font-size:.9em;color:#444}.meta{color:#555}
"""


def _e(x) -> str:
    return html.escape(str(x))


def _num(v) -> str:
    """A metric value as the thesis tables print it (:func:`.tables._fmt`)."""
    try:
        v = float(v)
    except (TypeError, ValueError):
        return _e(v)
    return _fmt(v) if np.isfinite(v) else "&ndash;"


def _g(v) -> str:
    """Any other cell: integers whole, other numbers to 3 significant digits, text escaped."""
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, float, np.number)):
        return _e(_text(v))
    if isinstance(v, (int, np.integer)) or (np.isfinite(v) and float(v).is_integer()):
        return f"{int(v)}"
    return f"{v:.3g}" if np.isfinite(v) else "&ndash;"


def _text(v) -> str:
    return "" if v is None or (isinstance(v, float) and np.isnan(v)) else str(v)


def _frame_html(df: pd.DataFrame, caption: str | None = None) -> str:
    """A plain table: text left, numbers right (:func:`_g`)."""
    out = ["<table>"] + ([f"<caption>{_e(caption)}</caption>"] if caption else [])
    out.append("<tr>" + "".join(f"<th>{_e(c)}</th>" for c in df.columns) + "</tr>")
    for row in df.itertuples(index=False):
        out.append("<tr>" + "".join(f"<td>{_g(v)}</td>" if isinstance(v, (int, float, np.number))
                                    else f"<td class='text'>{_g(v)}</td>" for v in row) + "</tr>")
    return "<div class='scroll'>" + "\n".join(out + ["</table>"]) + "</div>\n"


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
    return (f"<header><h1>Study report: {_e(name)}</h1>"
            f"<p class='meta'>Generated {_e(when)} by tyrelab {_e(__version__)}; {len(idx)} runs: "
            f"{done} done, {failed} failed.</p>"
            f"<div class='reference-note' id='reference-note' role='note'>{_e(note)}</div>"
            "</header>\n")


def _run_matrix(index: pd.DataFrame) -> str:
    """Test conditions x models, each cell the runs' status and wall time."""
    if index is None or len(index) == 0:
        return "<section id='runs'><h2>Run matrix</h2><p>The study has no runs.</p></section>\n"
    several = index["tyre"].nunique() > 1
    label = (index["tyre"].astype(str) + " / " + index["model"].astype(str)) if several \
        else index["model"].astype(str)
    cols = list(dict.fromkeys(label))
    out = ["<section id='runs'><h2>Run matrix</h2><table class='run-matrix'><tr><th>test</th>"
           "<th>speed</th><th>load</th>" + "".join(f"<th>{_e(c)}</th>" for c in cols) + "</tr>"]
    for (test, speed, load), runs in index.assign(_label=label).groupby(_COND, sort=False):
        cells = []
        for c in cols:
            sel = runs[runs["_label"] == c]
            if sel.empty:
                cells.append("<td class='text'>&ndash;</td>")
                continue
            bad = sel["status"] != "done"
            parts = [("&#10003; " + _g(r.wall_time_s) + " s") if r.status == "done"
                     else "&#10007; " + _e(r.status) for r in sel.itertuples()]
            tip = "; ".join(_text(e) for e in sel.loc[bad].get("error", []) if _text(e))
            cls = "failed" if bad.any() else "done"
            cells.append(f"<td class='{cls}' title='{_e(tip)}'>" + "<br>".join(parts) + "</td>")
        out.append(f"<tr><th class='text'>{_e(test)}</th><td>{float(speed):g} km/h</td>"
                   f"<td>{_e(load_text(load))}</td>" + "".join(cells) + "</tr>")
    out.append("</table>")
    wall, sim = index["wall_time_s"].sum(), index["simulated_s"].sum()
    out.append(f"<p>Total wall time {_g(wall)} s for {_g(sim)} s simulated.</p>")
    failed = index[index["status"] == "failed"]
    if len(failed):
        out.append(f"<h3>Failed runs ({len(failed)})</h3><table class='failed-runs'><tr><th>key</th>"
                   "<th>tyre</th><th>model</th><th>test</th><th>speed</th><th>load</th>"
                   "<th>error</th></tr>")
        for r in failed.itertuples():
            out.append(f"<tr><td class='text'>{_e(r.key)}</td><td class='text'>{_e(r.tyre)}</td>"
                       f"<td class='text'>{_e(r.model)}</td><td class='text'>{_e(r.test)}</td>"
                       f"<td>{float(r.speed_kmh):g} km/h</td><td>{_e(load_text(r.load))}</td>"
                       f"<td class='text'><pre class='error'>{_e(_text(getattr(r, 'error', '')))}"
                       "</pre></td></tr>")
        out.append("</table>")
    return "\n".join(out) + "</section>\n"


def _ok(rows: pd.DataFrame) -> pd.Series:
    return rows["error"].map(_text) == "" if "error" in rows.columns else \
        pd.Series(True, index=rows.index)


def _finite_columns(rows: pd.DataFrame, names) -> list[str]:
    return [m for m in names if m in rows.columns and len(rows)
            and np.all(np.isfinite(rows[m].to_numpy(dtype=float)))]


def _metric_tables(rows, rep, caption: str) -> str:
    """The marked models x metrics tables of one condition, repeatability below."""
    is_cleat = np.isfinite(rows["disturbance_start_s"].to_numpy(dtype=float)).any()
    primary = _finite_columns(rows, THESIS_CLEAT if is_cleat else THESIS_TRACK)
    further = _finite_columns(rows, [m for m in METRICS if m not in THESIS_CLEAT + THESIS_TRACK])
    labels = rows["model"].astype(str)
    if labels.duplicated().any():
        labels = rows["tyre"].astype(str) + " / " + labels
    out = []
    for cols, what in ((primary, caption), (further, "Further metrics: " + caption)):
        if not cols:
            continue
        table = pd.DataFrame(rows[cols].to_numpy(dtype=float), index=list(labels), columns=cols)
        text = table_html(table, caption=what)
        for r in rep.itertuples():
            cells = "".join(f"<td>{_num(getattr(r, c))}</td>" for c in cols)
            text = text.replace("</table>", f"<tr class='repeatability'><th>{REPEATABILITY}</th>"
                                f"{cells}</tr>\n</table>", 1)
        out.append(text)
    units = "; ".join(f"{m}: {METRICS[m][1]} [{METRICS[m][0]}]" for m in primary)
    return "".join(out) + (f"<p class='meta'>{_e(units)}</p>" if units else "")


def _near_zero(rows) -> str:
    items = []
    for r in rows.itertuples():
        n = getattr(r, "near_zero_samples", None)
        if n is not None and not pd.isna(n) and n > 0:
            items.append(f"<li>{_e(r.model)}: the near-zero rule touched {int(n)} of "
                         f"{_g(r.compared_samples)} samples</li>")
    return ("<ul class='near-zero'>" + "".join(items) + "</ul>") if items else ""


def _conditions(study, note, figs, colours, max_points) -> str:
    metrics = study.metrics
    out = ["<section id='conditions'><h2>Per test condition</h2>"]
    if metrics is None or len(metrics) == 0:
        return out[0] + "<p>No run was compared.</p></section>\n"
    index = study.index
    refs = {k: f"{m} (reference)" for k, m in zip(index["key"], index["model"])}
    rep_mask = metrics["model"] == REPEATABILITY
    for n, (cond, rows) in enumerate(metrics[~rep_mask].groupby(_COND, sort=False), start=1):
        rep = metrics[rep_mask]
        for col, value in zip(_COND, cond):
            rep = rep[rep[col] == value]
        ok = _ok(rows)
        good = rows[ok]
        ref_names = sorted({refs.get(k, str(k)) for k in rows["reference"]})
        group = str(rows["group"].iloc[0])
        out.append(f"<section class='condition' id='condition-{n}'><h3>{_e(condition_text(*cond))}"
                   f" <small>({_e(group)})</small></h3>")
        if len(good):
            caption = (f"{condition_text(*cond)}: models against {', '.join(ref_names)}; best three per "
                       f"metric green, orange, red (as thesis Tables 5-2 to 5-14). {note}")
            out.append(_metric_tables(good, rep[_ok(rep)], caption))
            out.append(_near_zero(pd.concat([good, rep[_ok(rep)]])))
        own = study.self_checks
        for col, value in zip(_COND, cond):
            own = own[own[col] == value]
        if len(own):
            worst = np.nanmax(np.abs(own[[m for m in METRICS if m in own]].to_numpy(dtype=float)),
                              initial=0.0)
            out.append(f"<p class='meta'>The reference compared with itself (a check of the chain): "
                       f"largest |metric| {_num(worst)}.</p>")
        for r in rows[~ok].itertuples():
            out.append(f"<p class='compare-error'>{_e(r.model)} could not be compared: "
                       f"{_e(r.error)}</p>")
        if len(good):
            out.append(condition_figures(study, cond, good, refs, note, figs, colours, max_points))
        out.append("</section>")
    return "\n".join(out) + "</section>\n"


def _run_text(run) -> str:
    """A run of the rules' set-aside list: ``{"test": .., "speed_kmh": 18.0}`` as text."""
    if isinstance(run, dict):
        return ", ".join(f"{k} {v:g}" if isinstance(v, float) else f"{k} {v}" for k, v in run.items())
    return _text(run)


def _summary(study) -> str:
    """Table 5-15 form, the recommended model per group and its expected error."""
    summary = getattr(study, "summary", None)
    out = ["<section id='summary'><h2>Summary (thesis Table 5-15)</h2>"]
    if summary is None or len(summary) == 0:
        return out[0] + "<p>No summary: no run was compared.</p></section>\n"
    out.append(summary_html(summary))
    metrics = study.metrics
    good = metrics[(metrics["model"] != REPEATABILITY) & _ok(metrics)]
    rec = []
    for group, cells in summary.groupby(level=0, sort=False):
        score = {m: ((cells[m].astype(str).str.endswith(", best")).sum(),
                     cells[m].astype(str).str.startswith("comparable").sum()) for m in cells.columns}
        best = max(score, key=lambda m: score[m])
        if score[best][1] == 0:
            rec.append(f"<tr><th class='text'>{_e(group)}</th><td class='text' colspan='2'>no model "
                       "is comparable</td></tr>")
            continue
        rows = good[(good["group"] == group) & (good["model"] == best)]
        errs = []
        for m in primary_metrics(group, rows):
            v = rows[m].abs().dropna()
            if len(v):
                errs.append(f"{m}: {_fmt(v.mean())} mean, {_fmt(v.max())} worst "
                            f"[{METRICS[m][0]}] over {len(v)} run{'s' if len(v) > 1 else ''}")
        verdicts = ", ".join(sorted(set(cells[best].astype(str))))
        rec.append(f"<tr><th class='text'>{_e(group)}</th><td class='text'>{_e(best)} "
                   f"({_e(verdicts)})</td><td class='text'>{_e('; '.join(errs) or 'no metrics')}"
                   "</td></tr>")
    out.append("<h3>Recommended model per group</h3><table class='recommended'><tr><th>group</th>"
               "<th>model</th><th>expected error (|primary metric|)</th></tr>" + "".join(rec)
               + "</table>")
    left = summary.attrs.get("left_out") or []
    if left:
        out.append("<h3>Left out of the summary (comparison failed)</h3><ul>" + "".join(
            f"<li>{_e(a.get('model'))}: {_e(a.get('test'))}, {_e(a.get('speed_kmh'))} km/h, "
            f"{_e(a.get('load'))}</li>" for a in left) + "</ul>")
    aside = summary.attrs.get("set_aside") or []
    if aside:
        out.append("<h3>Set aside by the rules</h3><ul>" + "".join(
            f"<li>{_e(a.get('obstacle'))} ({_e(_run_text(a.get('run')))}): {_e(a.get('reason'))}</li>"
            for a in aside) + "</ul>")
    out.append(_rules_on_thesis())
    return "\n".join(out) + "</section>\n"


def _rules_on_thesis() -> str:
    """The same rules applied to the thesis's own published metrics, cell by cell, with
    each cell they do not reproduce argued (:func:`tyrelab.validate.thesis.rules_on_thesis`)."""
    from ..validate.thesis import rules_on_thesis
    cells = rules_on_thesis()
    rows = "".join(
        f"<tr><td class='text'>{_e(r.group)}</td><td class='text'>{_e(r.obstacle)}</td>"
        f"<td class='text'>{_e(r.model)}</td><td class='text'>{_e(r.rules)}</td>"
        f"<td class='text'>{_e(r.thesis)}</td><td class='text'>{'yes' if r.match else 'no: ' + _e(r.why)}"
        "</td></tr>" for r in cells.itertuples())
    return (f"<h3>These rules on the thesis's own metrics</h3><p>Applied to the metrics the "
            f"thesis published (Tables 5-2 to 5-14), the rules above give {int(cells['match'].sum())} "
            f"of the {len(cells)} cells of its Table 5-15 that those metrics cover; each other "
            "cell is argued below.</p><table class='rules-on-thesis'><tr><th>group</th>"
            "<th>obstacle</th><th>model</th><th>these rules</th><th>thesis Table 5-15</th>"
            f"<th>same?</th></tr>{rows}</table>")


def _thesis(study) -> str:
    """Our metrics beside the thesis's, and the rank agreement."""
    thesis = getattr(study, "thesis", None)
    if thesis is None or len(thesis) == 0:
        return ""
    t = thesis.reset_index() if any(n is not None for n in thesis.index.names) else thesis
    keys = [c for c in t.columns if not (c.endswith("_ours") or c.endswith("_thesis"))]
    pairs = [c[:-5] for c in t.columns if c.endswith("_ours") and c[:-5] + "_thesis" in t.columns]
    out = ["<section id='thesis'><h2>Against the thesis</h2><div class='scroll'><table class='thesis'><tr>"
           + "".join(f"<th rowspan='2'>{_e(k)}</th>" for k in keys)
           + "".join(f"<th colspan='2'>{_e(m)}</th>" for m in pairs) + "</tr><tr>"
           + "<th>ours</th><th>thesis</th>" * len(pairs) + "</tr>"]
    for _, r in t.iterrows():
        out.append("<tr>" + "".join(f"<td class='text'>{_g(r[k])}</td>" for k in keys)
                   + "".join(f"<td>{_num(r[m + '_ours'])}</td><td>{_num(r[m + '_thesis'])}</td>"
                             for m in pairs) + "</tr>")
    out.append("</table></div>")
    ra = getattr(study, "rank_agreement", None)
    if ra is not None:
        out.append(f"<p>Rank agreement with the thesis (Spearman's rho of the models' ranks per "
                   f"run and metric, 1 = same order): mean <b>{_num(ra.mean)}</b>.</p>")
        out.append(_frame_html(ra.per_run, "Rank agreement per run"))
    out.append(consistency_html(getattr(study, "consistency", None)))
    return "\n".join(out) + "</section>\n"


def _cost(study, note, figs, colours) -> str:
    """Accuracy against cost: scatter and the parameterization table."""
    cost = getattr(study, "cost", None)
    if cost is None or len(cost) == 0:
        return ""
    metrics = study.metrics
    good = metrics[(metrics["model"] != REPEATABILITY) & _ok(metrics)]
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
    out.append(_frame_html(table, "Cost and the parameterization data each model needs"))
    return "\n".join(out) + "</section>\n"


def _normalised(study) -> SimpleNamespace:
    """The attributes the report reads; an index or metrics table that is None or has
    no columns (nothing run, nothing compared) becomes an empty table of the
    interface's columns. Rows comparing the reference with itself (``key ==
    reference``, or ``is_reference`` where the table has it) are moved out of
    the metrics into ``self_checks``: they are no model and are never ranked."""
    def frame(df, columns):
        return pd.DataFrame(columns=columns) if df is None or len(df.columns) == 0 else df
    out = SimpleNamespace(**{a: getattr(study, a, None) for a in _ATTRIBUTES})
    out.index = frame(getattr(study, "index", None), INDEX_COLUMNS)
    metrics = frame(getattr(study, "metrics", None), METRIC_COLUMNS + list(METRICS))
    own = (metrics["key"].astype(str) == metrics["reference"].astype(str)).to_numpy()
    if "is_reference" in metrics.columns:
        own = own | metrics["is_reference"].fillna(False).astype(bool).to_numpy()
    out.metrics, out.self_checks = metrics[~own], metrics[own]
    return out


def study_report_html(study, *, name: str | None = None, max_points: int = MAX_POINTS) -> str:
    """The whole page as text (see the module docstring); ``name`` if the study has none."""
    study = _normalised(study)
    note = str(getattr(study, "reference_note", "") or "reference: not stated")
    name = _study_name(study, name)
    models = list(dict.fromkeys([*study.index["model"].astype(str),
                                 *study.metrics["model"].astype(str)]))
    colours = {m: PALETTE[i % len(PALETTE)] for i, m in enumerate(models)}
    figs = FigureSink()
    body = [_header(study, name, note),
            "<nav><a href='#runs'>runs</a> &middot; <a href='#conditions'>per condition</a> &middot; "
            "<a href='#summary'>summary</a> &middot; <a href='#thesis'>thesis</a> &middot; "
            "<a href='#cost'>cost</a></nav>",
            _run_matrix(study.index), _conditions(study, note, figs, colours, max_points),
            _summary(study), _thesis(study), _cost(study, note, figs, colours)]
    return ("<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>\n" + ERRORS_SCRIPT
            + f"\n<title>Study report: {_e(name)}</title>\n"
            f"<meta name='tyrelab-figures' content='{figs.count}'>\n"
            "<meta name='viewport' content='width=device-width, initial-scale=1'>\n"
            f"<style>{_STYLE}</style></head>\n<body>\n<pre id='tyrelab-errors' hidden></pre>\n"
            + "\n".join(body) + "\n" + RENDERED_SCRIPT + "\n</body></html>\n")


def write_study_report(study, path, *, max_points: int = MAX_POINTS) -> Path:
    """Write the study report to ``path`` (HTML) and return the path.

    The page is built completely first, then written to a temporary sibling
    and renamed over ``path``, so an interrupted write never leaves a page
    that looks finished. Without ``study.spec`` the study is named after its
    folder (``study.folder`` or ``study.store.folder``), else after the
    folder ``path`` is in.
    """
    path = Path(path)
    text = study_report_html(study, name=path.resolve().parent.name, max_points=max_points)
    with atomic_output(path) as tmp:
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.chmod(tmp, 0o644)            # a page to share (the temporary file is private)
    return path
