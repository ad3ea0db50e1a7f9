"""Validation tables: models x metrics with the best three marked, and summaries.

Models x metrics (thesis Tables 5-2 to 5-4): every metric is an error, so the
smaller absolute value is better; per metric the models are ranked by
``|value|`` (ties share the better rank) and ranks 1, 2, 3 are marked - in
HTML with the thesis's colours (green, orange, red), in Markdown with bold
text and the rank in brackets.

Summary per obstacle group (thesis Table 5-15), by these stated rules:

1. A *run* (one obstacle, speed, load case) **passes** for a model when each
   primary metric satisfies ``|value| <= limit``. Default primary metrics
   and limits (:data:`DEFAULT_LIMITS`): for discrete obstacles m%RE of the
   disturbance and of the response peaks, each <= 20 % - about twice the
   measurement's own scatter at 18 km/h in Table 5-1 (10.4 %, 10.3 %); for
   rough tracks |μ%err| <= 10 % and |σ%err| <= 50 %. Pass your own limits,
   e.g. a factor times the repeatability of the same test.
2. Per obstacle and model, with ``f`` the fraction of its runs that pass:
   ``f >= 2/3`` -> "comparable"; ``1/3 <= f < 2/3`` -> "comparable, under
   certain conditions"; ``f < 1/3`` -> "not representative". (One passing
   run in seven, e.g. at the speed where all models and even two
   measurements disagree alike, does not make a model representative.)
3. Of the models that are comparable (either form) for an obstacle, the one
   with the lowest mean rank over its runs and primary metrics is marked
   ", best" (ties: all tied models).
"""

from __future__ import annotations

import html

import numpy as np
import pandas as pd

from ..errors import InputError

COLOURS = {1: "#7fd17f", 2: "#ffb84d", 3: "#ff7b7b"}  # green, orange, red (thesis 5.2.1)

DEFAULT_LIMITS = {
    "discrete obstacles": {"mRE_disturbance_pct": 20.0, "mRE_response_pct": 20.0},
    "rough tracks": {"mean_error_pct": 10.0, "std_error_pct": 50.0},
}


def metrics_table(rows) -> pd.DataFrame:
    """Models x metrics from ``{model: {metric: value}}`` or a list of records
    with a ``model`` key. Every value must be finite (InputError otherwise)."""
    if isinstance(rows, dict):
        df = pd.DataFrame.from_dict(rows, orient="index")
    else:
        df = pd.DataFrame(list(rows)).set_index("model")
    df.index.name = "model"
    values = df.to_numpy(dtype=float)
    if not np.all(np.isfinite(values)):
        bad = df.columns[~np.all(np.isfinite(values), axis=0)][0]
        raise InputError("a metric is NaN or inf", field=str(bad))
    return df


def rank_models(table: pd.DataFrame) -> pd.DataFrame:
    """Per metric, the rank of each model by |value| (1 = best; ties share)."""
    return table.abs().rank(axis=0, method="min", ascending=True).astype(int)


def _fmt(value: float) -> str:
    """0 decimals from 100 up (and for 0), 1 from 10 up, else 2."""
    a = abs(value)
    if a >= 100 or a == 0:
        return f"{value:.0f}"
    if a >= 10:
        return f"{value:.1f}"
    return f"{value:.2f}"


def table_markdown(table: pd.DataFrame, best: int = 3) -> str:
    """Markdown table; the best ``best`` per metric in bold with their rank."""
    ranks = rank_models(table)
    head = "| model | " + " | ".join(table.columns) + " |"
    lines = [head, "|" + "---|" * (len(table.columns) + 1)]
    for model, row in table.iterrows():
        cells = []
        for col in table.columns:
            text, r = _fmt(row[col]), ranks.at[model, col]
            cells.append(f"**{text}** ({r})" if r <= best else text)
        lines.append(f"| {model} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def table_html(table: pd.DataFrame, best: int = 3, caption: str | None = None) -> str:
    """HTML table; the best three per metric coloured green, orange, red."""
    ranks = rank_models(table)
    out = ["<table class='metrics'>"]
    if caption:
        out.append(f"<caption>{html.escape(caption)}</caption>")
    out.append("<tr><th>model</th>" + "".join(f"<th>{html.escape(str(c))}</th>"
                                             for c in table.columns) + "</tr>")
    for model, row in table.iterrows():
        cells = []
        for col in table.columns:
            r = int(ranks.at[model, col])
            style = f" style='background:{COLOURS[r]}' title='rank {r}'" if r <= min(best, 3) \
                else ""
            cells.append(f"<td{style}>{_fmt(row[col])}</td>")
        out.append(f"<tr><th>{html.escape(str(model))}</th>" + "".join(cells) + "</tr>")
    out.append("</table>")
    return "\n".join(out) + "\n"


def _run_passes(row: pd.Series, limits: dict) -> bool:
    return all(abs(float(row[m])) <= lim for m, lim in limits.items())


def summary_table(results: pd.DataFrame, limits: dict | None = None,
                  run_columns=("speed_kmh", "load_case"),
                  fractions=(2 / 3, 1 / 3)) -> pd.DataFrame:
    """Summary per obstacle group and model by the rules of the module docstring.

    Parameters
    ----------
    results : pandas.DataFrame
        One row per (run, model) with columns ``group``, ``obstacle``,
        ``model`` and the primary metrics of the group; other columns (speed,
        load case) are ignored.
    limits : dict, optional
        ``{group: {metric: limit}}``; default :data:`DEFAULT_LIMITS`.
    run_columns : sequence of str
        Columns that tell the runs of one obstacle apart (models are ranked
        within a run); those absent are ignored.
    fractions : (float, float)
        Pass fractions for "comparable" and "under certain conditions".

    Returns
    -------
    pandas.DataFrame
        Index (group, obstacle), one column per model, text categories.
    """
    limits = DEFAULT_LIMITS if limits is None else limits
    for col in ("group", "obstacle", "model"):
        if col not in results.columns:
            raise InputError("results table needs this column", field=col)
    records = {}
    for (group, obstacle), runs in results.groupby(["group", "obstacle"], sort=False):
        if group not in limits:
            raise InputError(f"no limits for group '{group}'", field="group")
        lim = limits[group]
        missing = [m for m in lim if m not in runs.columns]
        if missing:
            raise InputError(f"results lack the primary metric of group '{group}'",
                             field=missing[0])
        runs = runs.copy()
        keys = [c for c in run_columns if c in runs.columns]
        score = runs[list(lim)].abs()
        ranks = (score.groupby([runs[k] for k in keys], sort=False).rank(method="min")
                 if keys else score.rank(method="min"))
        runs["_rank"] = ranks.mean(axis=1)
        runs["_pass"] = runs.apply(_run_passes, axis=1, limits=lim)
        cats, mean_rank = {}, {}
        for model, r in runs.groupby("model", sort=False):
            f = float(r["_pass"].mean())
            cats[model] = ("comparable" if f >= fractions[0] else
                           "comparable, under certain conditions" if f >= fractions[1] else
                           "not representative")
            mean_rank[model] = float(r["_rank"].mean())
        ok = [m for m in cats if cats[m] != "not representative"]
        if ok:
            top = min(mean_rank[m] for m in ok)
            for m in ok:
                if mean_rank[m] == top:
                    cats[m] += ", best"
        records[(group, obstacle)] = cats
    out = pd.DataFrame.from_dict(records, orient="index")
    out.index = pd.MultiIndex.from_tuples(out.index, names=["group", "obstacle"])
    return out.fillna("not tested")


def summary_markdown(summary: pd.DataFrame) -> str:
    """Markdown form of :func:`summary_table`."""
    lines = ["| group | obstacle | " + " | ".join(summary.columns) + " |",
             "|" + "---|" * (len(summary.columns) + 2)]
    for (group, obstacle), row in summary.iterrows():
        lines.append(f"| {group} | {obstacle} | " + " | ".join(row.astype(str)) + " |")
    return "\n".join(lines) + "\n"


def summary_html(summary: pd.DataFrame) -> str:
    """HTML form of :func:`summary_table`."""
    out = ["<table class='summary'><tr><th>group</th><th>obstacle</th>"
           + "".join(f"<th>{html.escape(str(c))}</th>" for c in summary.columns) + "</tr>"]
    for (group, obstacle), row in summary.iterrows():
        out.append(f"<tr><td>{html.escape(str(group))}</td><td>{html.escape(str(obstacle))}</td>"
                   + "".join(f"<td>{html.escape(str(v))}</td>" for v in row) + "</tr>")
    out.append("</table>")
    return "\n".join(out) + "\n"


def table_markdown_by_metric(table: pd.DataFrame, units: dict | None = None) -> str:
    """Markdown with one row per metric and one column per model (no marking);
    handy for one or two runs, e.g. a model beside the measurement scatter."""
    units = units or {}
    models = [str(m) for m in table.index]
    lines = ["| metric | unit | " + " | ".join(models) + " |",
             "|" + "---|" * (len(models) + 2)]
    for col in table.columns:
        cells = [_fmt(float(v)) for v in table[col]]
        lines.append(f"| {col} | {units.get(col, '')} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"
