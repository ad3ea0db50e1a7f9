"""Validation tables: models x metrics with the best three marked, and summaries.

Models x metrics (thesis Tables 5-2 to 5-4): every metric is an error, so the
smaller absolute value is better; per metric the models are ranked by
``|value|`` (ties share the better rank) and ranks 1, 2, 3 are marked - in
HTML with the thesis's colours (green, orange, red), in Markdown with bold
text and the rank in brackets.

Summary per obstacle group (thesis Table 5-15), by these stated rules. A
*run* is one obstacle or track driven at one speed and load case.

1. **Limits.** A run passes for a model when each primary metric satisfies
   ``|value| <= limit`` (:data:`DEFAULT_LIMITS`). Discrete obstacles: m%RE of
   the disturbance and of the response peaks, each <= 20 %, about twice the
   scatter between two measurements of the best-controlled tests (Table 5-1,
   18 km/h: 10.4 %, 10.3 %; Table 5-6, 12 km/h: 8 %, 7 %). Rough tracks:
   |σ%err| <= 25 %, the largest scatter between two measurements of one test
   the thesis published (25.1 %, Table 5-1 at 27 km/h; it published none for
   the tracks), and |μ%err| <= 10 %, a guard against lost ground contact (the
   mean is otherwise the static load, section 5.3). Given the measurement's
   own scatter per run (``scatter``, e.g. :func:`.thesis.thesis_repeatability`),
   a limit is raised to that run's scatter: no model is asked to agree with a
   measurement better than two measurements agree with each other.
2. **Shared errors.** Some metrics hold errors of the rest of the simulation,
   common to every tyre model: the response after an obstacle is the
   trailer's free oscillation, whose period the thesis's trailer model (its
   hitch) missed for all tyres alike (section 5.2). When no model meets the
   limit of such a metric (:data:`SHARED_METRICS`) in a run, that metric is
   set aside for that run instead of failing every model.
3. **Unexplained runs.** When even the best model misses a remaining limit by
   more than ``unexplained`` (default 2) times, the run says more about the
   test than about the models and is set aside (e.g. the fatigue track at
   3 km/h, LC1: σ%err of 273 % to 1708 %, which the thesis could not explain,
   5.3.2). Set-aside metrics and runs are listed in
   ``summary.attrs["set_aside"]``.
4. **Verdict.** With ``f`` the fraction of a model's remaining runs that pass:
   ``f >= 2/3`` (it passes at least twice as often as it fails) ->
   "comparable"; ``1/2 <= f < 2/3`` (at least as often) -> "comparable,
   under certain conditions"; ``f < 1/2`` (it fails more often than it
   passes) -> "not representative". A model all of whose runs were set aside
   gets "set aside"; one without runs, "not tested".
5. **Best.** Of the models in the highest verdict reached (other than "not
   representative"), the one with the lowest mean rank over the remaining
   runs and all the group's published metrics (:data:`RANK_METRICS`, the
   thesis's colour-coded ranking) is marked ", best" (ties: all tied models).

Applied to the thesis's own metrics (:func:`.thesis.thesis_metrics`) these
rules reproduce 14 of the 16 cells of Table 5-15 that published metrics
cover; ``tests/test_verdict.py`` lists the two exceptions with their reasons.

:func:`~tyrelab.validate.rank_agreement.rank_agreement` compares two long-form metric
tables (e.g. ours beside the thesis's) run by run with Spearman's rank correlation.
"""

from __future__ import annotations

import html

import numpy as np
import pandas as pd

from ..errors import InputError
from .compare import THESIS_CLEAT, THESIS_TRACK

COLOURS = {1: "#7fd17f", 2: "#ffb84d", 3: "#ff7b7b"}  # green, orange, red (thesis 5.2.1)

#: ``{group: {primary metric: limit}}`` (rule 1 of the module docstring).
DEFAULT_LIMITS = {
    "discrete obstacles": {"mRE_disturbance_pct": 20.0, "mRE_response_pct": 20.0},
    "rough tracks": {"mean_error_pct": 10.0, "std_error_pct": 25.0},
}

#: Metrics holding errors common to every tyre model: the response after an
#: obstacle is the trailer's free oscillation (rule 2).
SHARED_METRICS = ("mRE_response_pct", "rms_response_N")

#: ``{group: metrics}`` ranked to find the best model (rule 5): all the thesis
#: published for the group. Other groups rank their primary metrics.
RANK_METRICS = {"discrete obstacles": tuple(THESIS_CLEAT), "rough tracks": tuple(THESIS_TRACK)}

COMPARABLE = "comparable"
CONDITIONAL = "comparable, under certain conditions"
NOT_REPRESENTATIVE = "not representative"
SET_ASIDE = "set aside"
NOT_TESTED = "not tested"


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


def _run_limits(lim: dict, scatter: pd.DataFrame | None, match: dict) -> dict:
    """The limits of one run: ``lim``, each raised to the run's own measured
    scatter where ``scatter`` holds a row of that run (rule 1)."""
    out = dict(lim)
    if scatter is None:
        return out
    sel = np.ones(len(scatter), dtype=bool)
    for col, value in match.items():
        sel &= (scatter[col] == value).to_numpy()
    rows = scatter[sel]
    for m in out:
        if m in rows.columns:
            s = rows[m].abs().max()
            if np.isfinite(s):
                out[m] = max(out[m], float(s))
    return out


def _check_scatter(scatter: pd.DataFrame | None, keys: list) -> None:
    if scatter is None:
        return
    for col in ("obstacle", *keys):
        if col not in scatter.columns:
            raise InputError("the scatter table lacks a column that tells runs apart",
                             field=col)


def summary_table(results: pd.DataFrame, limits: dict | None = None,
                  run_columns=("test", "speed_kmh", "load_case"),
                  fractions=(2 / 3, 1 / 2), *, shared=SHARED_METRICS,
                  unexplained: float | None = 2.0, scatter: pd.DataFrame | None = None,
                  rank_metrics: dict | None = None) -> pd.DataFrame:
    """Summary per obstacle group and model by the rules of the module docstring.

    Parameters
    ----------
    results : pandas.DataFrame
        One row per (run, model) with columns ``group``, ``obstacle``,
        ``model`` and the primary metrics of the group (finite); the run
        columns tell the runs of one obstacle apart; other columns are
        ignored (e.g. :func:`.thesis.thesis_metrics`).
    limits : dict, optional
        ``{group: {metric: limit}}``; default :data:`DEFAULT_LIMITS`.
    run_columns : sequence of str
        Columns that tell the runs of one obstacle apart (models are ranked
        within a run); those absent are ignored.
    fractions : (float, float)
        Pass fractions for "comparable" and "under certain conditions"
        (rule 4).
    shared : sequence of str
        Metrics set aside in a run no model meets them in (rule 2); ``()``
        for none.
    unexplained : float or None
        A run whose best model misses a limit by more than this factor is set
        aside (rule 3); None keeps every run.
    scatter : pandas.DataFrame, optional
        The measurement's own scatter per run, same long form (columns
        ``obstacle``, the run columns present in ``results`` and metrics),
        e.g. :func:`.thesis.thesis_repeatability`; a run's limits are raised
        to its scatter (rule 1).
    rank_metrics : dict, optional
        ``{group: metrics}`` ranked for "best" (rule 5); default
        :data:`RANK_METRICS`, then the group's primary metrics. Metrics
        absent or not finite in a group are skipped.

    Returns
    -------
    pandas.DataFrame
        Index (group, obstacle), one column per model, text verdicts;
        ``attrs["set_aside"]`` lists the metrics and runs set aside (dicts
        with ``group``, ``obstacle``, ``run``, ``metric`` (None: the whole
        run) and ``reason``).
    """
    limits = DEFAULT_LIMITS if limits is None else limits
    rank_metrics = RANK_METRICS if rank_metrics is None else rank_metrics
    for col in ("group", "obstacle", "model"):
        if col not in results.columns:
            raise InputError("results table needs this column", field=col)
    keys = [c for c in run_columns if c in results.columns]
    _check_scatter(scatter, keys)
    records, set_aside = {}, []
    for (group, obstacle), runs in results.groupby(["group", "obstacle"], sort=False):
        if group not in limits:
            raise InputError(f"no limits for group '{group}'", field="group")
        lim = limits[group]
        for m in lim:
            if m not in runs.columns:
                raise InputError(f"results lack the primary metric of group '{group}'",
                                 field=m)
            if not np.all(np.isfinite(runs[m].to_numpy(dtype=float))):
                raise InputError(f"a primary metric of group '{group}' is NaN or inf", field=m)
        ranked = [m for m in rank_metrics.get(group, lim) if m in runs.columns
                  and np.all(np.isfinite(runs[m].to_numpy(dtype=float)))] or list(lim)
        passed = {m: [] for m in runs["model"].unique()}
        run_ranks = {m: [] for m in passed}
        by = [runs[k] for k in keys]
        for key, run in (runs.groupby(by, sort=False, dropna=False) if keys else [((), runs)]):
            key = key if isinstance(key, tuple) else (key,)
            run_id = {k: (v.item() if isinstance(v, np.generic) else v) for k, v in zip(keys, key)}
            where = {"group": group, "obstacle": obstacle, "run": run_id}
            run_lim = _run_limits(lim, scatter, {"obstacle": obstacle, **run_id})
            err = run[list(run_lim)].abs()
            best = err.min()
            active = []
            for m, limit in run_lim.items():
                if m in shared and best[m] > limit:
                    set_aside.append({**where, "metric": m,
                                      "reason": f"no model meets {m} <= {limit:g}: an error "
                                                "common to all models"})
                else:
                    active.append(m)
            worst = [m for m in active
                     if unexplained is not None and best[m] > unexplained * run_lim[m]]
            if worst or not active:
                m = worst[0] if worst else None
                reason = (f"the best model's |{m}| = {best[m]:g} exceeds {unexplained:g} x "
                          f"{run_lim[m]:g}: unexplained run" if worst else
                          "every primary metric set aside")
                set_aside.append({**where, "metric": None, "reason": reason})
                continue
            ok = np.all(err[active].to_numpy() <= np.array([run_lim[m] for m in active]), axis=1)
            ranks = run[ranked].abs().rank(method="min").mean(axis=1).to_numpy()
            for model, p, r in zip(run["model"], ok, ranks):
                passed[model].append(bool(p))
                run_ranks[model].append(float(r))
        cats, mean_rank = {}, {}
        for model, p in passed.items():
            if not p:
                cats[model] = SET_ASIDE
                continue
            f = float(np.mean(p))
            cats[model] = (COMPARABLE if f >= fractions[0] else
                           CONDITIONAL if f >= fractions[1] else NOT_REPRESENTATIVE)
            mean_rank[model] = float(np.mean(run_ranks[model]))
        for verdict in (COMPARABLE, CONDITIONAL):
            top = [m for m in mean_rank if cats[m] == verdict]
            if top:
                lowest = min(mean_rank[m] for m in top)
                for m in top:
                    if mean_rank[m] == lowest:
                        cats[m] += ", best"
                break
        records[(group, obstacle)] = cats
    out = pd.DataFrame.from_dict(records, orient="index")
    out.index = pd.MultiIndex.from_tuples(out.index, names=["group", "obstacle"])
    out = out.fillna(NOT_TESTED)
    out.attrs["set_aside"] = set_aside
    return out


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
