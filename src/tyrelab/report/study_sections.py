"""The study report's tables (:mod:`.study_report`): the run matrix, each test
condition's marked metric tables, the summary with the recommended models, the
comparison with the thesis; and the cell formats they share.

Numbers: metric values as the thesis tables print them (:func:`num`), other
cells integers whole and other numbers to 3 significant digits (:func:`g`).
"""

from __future__ import annotations

import html

import numpy as np
import pandas as pd

from .consistency_section import consistency_html
from ..validate.compare import METRICS, THESIS_CLEAT, THESIS_TRACK
from ..validate.tables import _fmt, summary_html, table_html
from .study_figures import load_text, primary_metrics

REPEATABILITY = "measured repeatability"
#: the columns a test condition is
COND = ["test", "speed_kmh", "load"]


def esc(x) -> str:
    return html.escape(str(x))


def num(v) -> str:
    """A metric value as the thesis tables print it (:func:`.tables._fmt`)."""
    try:
        v = float(v)
    except (TypeError, ValueError):
        return esc(v)
    return _fmt(v) if np.isfinite(v) else "&ndash;"


def cell(v) -> str:
    """Any other cell: integers whole, other numbers to 3 significant digits, text escaped."""
    if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, float, np.number)):
        return esc(as_text(v))
    if isinstance(v, (int, np.integer)) or (np.isfinite(v) and float(v).is_integer()):
        return f"{int(v)}"
    return f"{v:.3g}" if np.isfinite(v) else "&ndash;"


def as_text(v) -> str:
    return "" if v is None or (isinstance(v, float) and np.isnan(v)) else str(v)


def frame_html(df: pd.DataFrame, caption: str | None = None) -> str:
    """A plain table: text left, numbers right (:func:`_g`)."""
    out = ["<table>"] + ([f"<caption>{esc(caption)}</caption>"] if caption else [])
    out.append("<tr>" + "".join(f"<th>{esc(c)}</th>" for c in df.columns) + "</tr>")
    for row in df.itertuples(index=False):
        out.append("<tr>" + "".join(f"<td>{cell(v)}</td>" if isinstance(v, (int, float, np.number))
                                    else f"<td class='text'>{cell(v)}</td>" for v in row) + "</tr>")
    return "<div class='scroll'>" + "\n".join(out + ["</table>"]) + "</div>\n"


def _slip_text(run) -> str:
    """``"s = 0.2: "`` or ``"T = 5000 N m: "`` for a soil test's run (the index's ``slip`` or
    ``torque``), else nothing."""
    for name, text in (("slip", "s = {:g}: "), ("torque", "T = {:g} N m: ")):
        value = getattr(run, name, None)
        try:
            if value is not None and np.isfinite(float(value)):
                return text.format(float(value))
        except (TypeError, ValueError):
            pass
    return ""


def run_matrix(index: pd.DataFrame) -> str:
    """Test conditions x models, each cell the runs' status and wall time (for a soil test,
    one line per slip)."""
    if index is None or len(index) == 0:
        return "<section id='runs'><h2>Run matrix</h2><p>The study has no runs.</p></section>\n"
    several = index["tyre"].nunique() > 1
    label = (index["tyre"].astype(str) + " / " + index["model"].astype(str)) if several \
        else index["model"].astype(str)
    cols = list(dict.fromkeys(label))
    out = ["<section id='runs'><h2>Run matrix</h2><table class='run-matrix'><tr><th>test</th>"
           "<th>speed</th><th>load</th>" + "".join(f"<th>{esc(c)}</th>" for c in cols) + "</tr>"]
    # the runs of each condition and column, in the index's order, from one pass over its rows
    # (a filter and a row iteration per cell took 0.4-1.2 s of the built-in campaign's report);
    # like a groupby, a run with a missing condition or label is left out
    cells_of: dict[tuple, list] = {}
    for r, c in zip(index.itertuples(index=False), label):
        key = (*(getattr(r, k) for k in COND), c)
        if not any(pd.isna(k) for k in key):
            cells_of.setdefault(key, []).append(r)
    has_error = "error" in index.columns
    has_warnings = "warnings" in index.columns   # stores written before runs kept them: none
    for test, speed, load in dict.fromkeys(k[:-1] for k in cells_of):
        cells = []
        for c in cols:
            sel = cells_of.get((test, speed, load, c))
            if sel is None:
                cells.append("<td class='text'>&ndash;</td>")
                continue
            warned = {id(r) for r in sel if has_warnings and as_text(r.warnings)}
            parts = [_slip_text(r) + (("&#10003; " + cell(r.wall_time_s) + " s") if r.status == "done"
                                      else "&#10007; " + esc(r.status))
                     + (" &#9888;" if id(r) in warned else "") for r in sel]
            bad = [r for r in sel if r.status != "done"]
            tip = "; ".join([as_text(r.error) for r in bad if has_error and as_text(r.error)]
                            + [as_text(r.warnings) for r in sel if id(r) in warned])
            cls = "failed" if bad else "warned" if warned else "done"
            cells.append(f"<td class='{cls}' title='{esc(tip)}'>" + "<br>".join(parts) + "</td>")
        out.append(f"<tr><th class='text'>{esc(test)}</th><td>{float(speed):g} km/h</td>"
                   f"<td>{esc(load_text(load))}</td>" + "".join(cells) + "</tr>")
    out.append("</table>")
    wall, sim = index["wall_time_s"].sum(), index["simulated_s"].sum()
    out.append(f"<p>Total wall time {cell(wall)} s for {cell(sim)} s simulated.</p>")
    failed = index[index["status"] == "failed"]
    if len(failed):
        out.append(f"<h3>Failed runs ({len(failed)})</h3><table class='failed-runs'><tr><th>key</th>"
                   "<th>tyre</th><th>model</th><th>test</th><th>speed</th><th>load</th>"
                   "<th>error</th></tr>")
        for r in failed.itertuples():
            out.append(f"<tr><td class='text'>{esc(r.key)}</td><td class='text'>{esc(r.tyre)}</td>"
                       f"<td class='text'>{esc(r.model)}</td><td class='text'>{esc(r.test)}</td>"
                       f"<td>{float(r.speed_kmh):g} km/h</td><td>{esc(load_text(r.load))}</td>"
                       f"<td class='text'><pre class='error'>{esc(as_text(getattr(r, 'error', '')))}"
                       "</pre></td></tr>")
        out.append("</table>")
    out.append(_warned_runs(index) if has_warnings else "")
    return "\n".join(out) + "</section>\n"


def _warned_runs(index: pd.DataFrame) -> str:
    """The runs that warned of leaving the models' physics (airborne, rim contact ...), with
    what each said: their results are in the tables, to be read knowing it."""
    warned = index[index["warnings"].map(as_text) != ""]
    if not len(warned):
        return ""
    out = [f"<h3>Runs with warnings ({len(warned)}): &#9888; in the matrix</h3><p>Each is in the "
           "tables below as computed; what it warned of says how far to trust it.</p>"
           "<table class='warned-runs'><tr><th>key</th><th>tyre</th><th>model</th><th>test</th>"
           "<th>speed</th><th>load</th><th>warnings</th></tr>"]
    for r in warned.itertuples():
        out.append(f"<tr><td class='text'>{esc(r.key)}</td><td class='text'>{esc(r.tyre)}</td>"
                   f"<td class='text'>{esc(r.model)}</td><td class='text'>{esc(r.test)}</td>"
                   f"<td>{float(r.speed_kmh):g} km/h</td><td>{esc(load_text(r.load))}</td>"
                   f"<td class='text'><pre class='error'>{esc(as_text(r.warnings))}</pre></td></tr>")
    return "".join(out) + "</table>"


def compared_ok(rows: pd.DataFrame) -> pd.Series:
    """Rows compared without an error."""
    return rows["error"].map(as_text) == "" if "error" in rows.columns else \
        pd.Series(True, index=rows.index)


def _finite_columns(rows: pd.DataFrame, names) -> list[str]:
    return [m for m in names if m in rows.columns and len(rows)
            and np.all(np.isfinite(rows[m].to_numpy(dtype=float)))]


def metric_tables(rows, rep, caption: str) -> str:
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
            cells = "".join(f"<td>{num(getattr(r, c))}</td>" for c in cols)
            text = text.replace("</table>", f"<tr class='repeatability'><th>{REPEATABILITY}</th>"
                                f"{cells}</tr>\n</table>", 1)
        out.append(text)
    units = "; ".join(f"{m}: {METRICS[m][1]} [{METRICS[m][0]}]" for m in primary)
    return "".join(out) + (f"<p class='meta'>{esc(units)}</p>" if units else "")


def near_zero(rows) -> str:
    """Where the near-zero rule touched samples, as a list."""
    items = []
    for r in rows.itertuples():
        n = getattr(r, "near_zero_samples", None)
        if n is not None and not pd.isna(n) and n > 0:
            items.append(f"<li>{esc(r.model)}: the near-zero rule touched {int(n)} of "
                         f"{cell(r.compared_samples)} samples</li>")
    return ("<ul class='near-zero'>" + "".join(items) + "</ul>") if items else ""


def _run_text(run) -> str:
    """A run of the rules' set-aside list: ``{"test": .., "speed_kmh": 18.0}`` as text."""
    if isinstance(run, dict):
        return ", ".join(f"{k} {v:g}" if isinstance(v, float) else f"{k} {v}" for k, v in run.items())
    return as_text(run)


def summary_section(study) -> str:
    """Table 5-15 form, the recommended model per group and its expected error."""
    summary = getattr(study, "summary", None)
    out = ["<section id='summary'><h2>Summary (thesis Table 5-15)</h2>"]
    if summary is None or len(summary) == 0:
        return out[0] + "<p>No summary: no run was compared.</p></section>\n"
    out.append(summary_html(summary))
    metrics = study.metrics
    good = metrics[(metrics["model"] != REPEATABILITY) & compared_ok(metrics)]
    rec = []
    for group, cells in summary.groupby(level=0, sort=False):
        score = {m: ((cells[m].astype(str).str.endswith(", best")).sum(),
                     cells[m].astype(str).str.startswith("comparable").sum()) for m in cells.columns}
        best = max(score, key=lambda m: score[m])
        if score[best][1] == 0:
            rec.append(f"<tr><th class='text'>{esc(group)}</th><td class='text' colspan='2'>no model "
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
        rec.append(f"<tr><th class='text'>{esc(group)}</th><td class='text'>{esc(best)} "
                   f"({esc(verdicts)})</td><td class='text'>{esc('; '.join(errs) or 'no metrics')}"
                   "</td></tr>")
    out.append("<h3>Recommended model per group</h3><table class='recommended'><tr><th>group</th>"
               "<th>model</th><th>expected error (|primary metric|)</th></tr>" + "".join(rec)
               + "</table>")
    left = summary.attrs.get("left_out") or []
    if left:
        out.append("<h3>Left out of the summary (comparison failed)</h3><ul>" + "".join(
            f"<li>{esc(a.get('model'))}: {esc(a.get('test'))}, {esc(a.get('speed_kmh'))} km/h, "
            f"{esc(a.get('load'))}</li>" for a in left) + "</ul>")
    aside = summary.attrs.get("set_aside") or []
    if aside:
        out.append("<h3>Set aside by the rules</h3><ul>" + "".join(
            f"<li>{esc(a.get('obstacle'))} ({esc(_run_text(a.get('run')))}): {esc(a.get('reason'))}</li>"
            for a in aside) + "</ul>")
    out.append(rules_on_thesis_html())
    return "\n".join(out) + "</section>\n"


def rules_on_thesis_html() -> str:
    """The same rules applied to the thesis's own published metrics, cell by cell, with
    each cell they do not reproduce argued (:func:`tyrelab.validate.thesis.rules_on_thesis`)."""
    from ..validate.thesis import rules_on_thesis
    cells = rules_on_thesis()
    rows = "".join(
        f"<tr><td class='text'>{esc(r.group)}</td><td class='text'>{esc(r.obstacle)}</td>"
        f"<td class='text'>{esc(r.model)}</td><td class='text'>{esc(r.rules)}</td>"
        f"<td class='text'>{esc(r.thesis)}</td><td class='text'>{'yes' if r.match else 'no: ' + esc(r.why)}"
        "</td></tr>" for r in cells.itertuples())
    return (f"<h3>These rules on the thesis's own metrics</h3><p>Applied to the metrics the "
            f"thesis published (Tables 5-2 to 5-14), the rules above give {int(cells['match'].sum())} "
            f"of the {len(cells)} cells of its Table 5-15 that those metrics cover; each other "
            "cell is argued below.</p><table class='rules-on-thesis'><tr><th>group</th>"
            "<th>obstacle</th><th>model</th><th>these rules</th><th>thesis Table 5-15</th>"
            f"<th>same?</th></tr>{rows}</table>")


def thesis_section(study) -> str:
    """Our metrics beside the thesis's, and the rank agreement."""
    thesis = getattr(study, "thesis", None)
    if thesis is None or len(thesis) == 0:
        return ""
    t = thesis.reset_index() if any(n is not None for n in thesis.index.names) else thesis
    keys = [c for c in t.columns if not (c.endswith("_ours") or c.endswith("_thesis"))]
    pairs = [c[:-5] for c in t.columns if c.endswith("_ours") and c[:-5] + "_thesis" in t.columns]
    out = ["<section id='thesis'><h2>Against the thesis</h2><div class='scroll'><table class='thesis'><tr>"
           + "".join(f"<th rowspan='2'>{esc(k)}</th>" for k in keys)
           + "".join(f"<th colspan='2'>{esc(m)}</th>" for m in pairs) + "</tr><tr>"
           + "<th>ours</th><th>thesis</th>" * len(pairs) + "</tr>"]
    for _, r in t.iterrows():
        out.append("<tr>" + "".join(f"<td class='text'>{cell(r[k])}</td>" for k in keys)
                   + "".join(f"<td>{num(r[m + '_ours'])}</td><td>{num(r[m + '_thesis'])}</td>"
                             for m in pairs) + "</tr>")
    out.append("</table></div>")
    ra = getattr(study, "rank_agreement", None)
    if ra is not None:
        out.append(f"<p>Rank agreement with the thesis (Spearman's rho of the models' ranks per "
                   f"run and metric, 1 = same order): mean <b>{num(ra.mean)}</b>.</p>")
        out.append(frame_html(ra.per_run, "Rank agreement per run"))
    out.append(consistency_html(getattr(study, "consistency", None)))
    return "\n".join(out) + "</section>\n"
