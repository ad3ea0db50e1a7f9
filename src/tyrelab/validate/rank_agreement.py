"""Do two metric tables rank the models alike? Spearman's rank correlation, run by run
(:func:`rank_agreement`): our study's ranking against the thesis's tables (Tables 5-2 to
5-14), the measure of :mod:`tyrelab.validate.consistency` and the study report.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import pandas as pd
from scipy import stats

from ..errors import InputError
from .compare import METRICS


class RankAgreement(NamedTuple):
    """Result of :func:`rank_agreement`."""

    per_run: pd.DataFrame   #: run columns, ``n_models``, ρ per metric, ``rho`` (their mean)
    mean: float             #: mean of ``rho`` over the runs where it is defined


def rank_agreement(ours: pd.DataFrame, theirs: pd.DataFrame,
                   by=("obstacle", "test", "speed_kmh", "load_case"), metrics=None,
                   min_models: int = 3) -> RankAgreement:
    """Do two metric tables rank the models alike? Spearman's ρ run by run.

    For each run (the ``by`` columns present in both tables) and each metric,
    the models both tables hold are ranked by ``|value|`` (every metric is an
    error) and the two rankings are compared with Spearman's rank
    correlation (:func:`scipy.stats.spearmanr`): 1 = the same order, -1 =
    reversed, 0 = unrelated.

    Parameters
    ----------
    ours, theirs : pandas.DataFrame
        Long form, one row per (run, model), e.g. our study's metrics and
        :func:`.thesis.thesis_metrics`.
    by : sequence of str
        Columns that identify a run; those absent from either table are
        ignored (at least one must remain).
    metrics : sequence of str, optional
        Metrics compared; default every metric of :data:`.compare.METRICS`
        present in both tables.
    min_models : int
        Fewest shared models with finite values for ρ to be computed
        (otherwise NaN; so is ρ when either side ranks all models equal).

    Returns
    -------
    RankAgreement
        ``per_run``: one row per run of ``theirs``, with the run columns,
        ``n_models`` (shared), ρ per metric and ``rho``, the mean over the
        metrics; ``mean``: the mean of ``rho`` over the runs (NaN if none).
    """
    for name, table in (("ours", ours), ("theirs", theirs)):
        if "model" not in table.columns:
            raise InputError(f"{name}: the metric table needs a 'model' column", field="model")
    keys = [c for c in by if c in ours.columns and c in theirs.columns]
    if not keys:
        raise InputError("the tables share none of the columns that identify a run",
                         field=",".join(by))
    if metrics is None:
        metrics = [m for m in METRICS if m in ours.columns and m in theirs.columns]
    for m in metrics:
        if m not in ours.columns or m not in theirs.columns:
            raise InputError("both tables need the metric compared", field=m)
    if not metrics:
        raise InputError("the tables share no metric", field="metrics")
    for name, table in (("ours", ours), ("theirs", theirs)):
        if table.duplicated([*keys, "model"]).any():
            raise InputError(f"{name}: a model appears twice in one run", field="model")
    mine = ours.set_index([*keys, "model"])
    rows = []
    for key, run in theirs.groupby(keys, sort=False, dropna=False):
        key = key if isinstance(key, tuple) else (key,)
        row = dict(zip(keys, key))
        idx = [(*key, m) for m in run["model"] if (*key, m) in mine.index]
        row["n_models"] = len(idx)
        rhos = []
        # the shared models' |values|, every metric at once (model by model in idx's order)
        xs = (mine.loc[idx, metrics].abs().to_numpy(dtype=float) if idx
              else np.empty((0, len(metrics))))
        ys = run.set_index("model").loc[[i[-1] for i in idx], metrics].abs().to_numpy(dtype=float)
        for j, m in enumerate(metrics):
            x, y = xs[:, j], ys[:, j]
            ok = np.isfinite(x) & np.isfinite(y)
            x, y = x[ok], y[ok]
            rho = np.nan
            if x.size >= max(min_models, 2) and np.ptp(x) > 0 and np.ptp(y) > 0:
                rho = float(stats.spearmanr(x, y).statistic)
            row[m] = rho
            rhos.append(rho)
        finite = [r for r in rhos if np.isfinite(r)]
        row["rho"] = float(np.mean(finite)) if finite else np.nan
        rows.append(row)
    per_run = pd.DataFrame(rows, columns=[*keys, "n_models", *metrics, "rho"])
    defined = per_run["rho"].dropna()
    return RankAgreement(per_run, float(defined.mean()) if len(defined) else float("nan"))
