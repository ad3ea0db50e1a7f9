"""Choosing the enveloping model's cam count from a cam-count study's table
(:mod:`tyrelab.fit.cams`): accuracy against cost (:func:`recommend`).

Per pair, error and cost are averaged over the roads and speeds. The best
pair is the one of least mean error; a pair qualifies when its mean error
is at most ``best + max(rel_tol * best, abs_tol)`` (default 10 % of the
best's error or 0.5 percentage points, whichever is larger); the
recommended pair is the one of fewest cams (then fewest along the length)
among the qualifying pairs whose mean cost (``cost`` column) is within
``cost_tol`` (default 25 %) of the least mean cost of a qualifying pair:
a run of the XZL over a cleat takes about 10 ms (1-2 ms per simulated
second, about 1 ms of it fixed: grid, parameters, output table), and its
fastest of 5 timings still varies by 10-20 % on a shared machine, more
than the cams change it on a road that does not vary across (see below),
so costs that close count as equal.

On a road uniform across (cleats, steps, 2D profiles) every row of cams
sees the same road (``EnvelopingParams.profile_road``), so ``n_width``
changes neither the error (to rounding) nor, measurably, the cost; only a
road that varies across (an oblique cleat, a random road) shows it.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from ..errors import InputError

#: default tolerance of the recommendation: relative to the best error, and absolute [percentage points]
REL_TOL, ABS_TOL = 0.10, 0.5
#: costs within this fraction of the least qualifying cost count as equal (noise of a timing)
COST_TOL = 0.25


def rule_text(rel_tol: float = REL_TOL, abs_tol: float = ABS_TOL, cost: str = "wall_s_per_sim_s",
              cost_tol: float = COST_TOL) -> str:
    """The recommendation rule in words (its arguments checked)."""
    if cost not in ("wall_s_per_sim_s", "cams"):
        raise InputError(f"cost must be 'wall_s_per_sim_s' or 'cams', got '{cost}'", field="cost")
    for name, v in (("rel_tol", rel_tol), ("abs_tol", abs_tol), ("cost_tol", cost_tol)):
        if not (math.isfinite(v) and v >= 0):
            raise InputError(f"{name} must be finite and >= 0, got {v}", field=name)
    return (f"among pairs whose mean error is within max({rel_tol * 100:g} % of the best's, "
            f"{abs_tol:g} points) of the best pair's, those whose mean {cost} is within "
            f"{cost_tol * 100:g} % of the cheapest such pair's; of these the fewest cams "
            "(then fewest along the length)")


def summarise(table: pd.DataFrame, rel_tol: float = REL_TOL, abs_tol: float = ABS_TOL) -> pd.DataFrame:
    """Per pair: mean error and cost over the conditions, and whether it qualifies."""
    need = {"n_length", "n_width", "error_pct", "wall_s_per_sim_s"}
    missing = need - set(table.columns)
    if missing:
        raise InputError(f"cam-study table lacks column(s) {', '.join(sorted(missing))}", field="table")
    if table.empty:
        raise InputError("cam-study table has no rows", field="table")
    if not (rel_tol >= 0 and abs_tol >= 0 and math.isfinite(rel_tol) and math.isfinite(abs_tol)):
        raise InputError(f"tolerances must be finite and >= 0, got {rel_tol}, {abs_tol}", field="tolerance")
    s = (table.groupby(["n_length", "n_width"], as_index=False)
         .agg(error_pct=("error_pct", "mean"), wall_s_per_sim_s=("wall_s_per_sim_s", "mean")))
    s["cams"] = s["n_length"] * s["n_width"]
    if not np.all(np.isfinite(s["error_pct"])):
        raise InputError("cam-study table has a non-finite error", field="error_pct")
    best = float(s["error_pct"].min())
    s["qualifies"] = s["error_pct"] <= best + max(rel_tol * best, abs_tol)
    return s


def recommend(table: pd.DataFrame, rel_tol: float = REL_TOL, abs_tol: float = ABS_TOL,
              cost: str = "wall_s_per_sim_s", cost_tol: float = COST_TOL) -> tuple[int, int]:
    """The recommended ``(n_length, n_width)`` of a study table (the rule of the module docstring).

    Per pair (mean over the table's conditions): ``best`` = least error; a
    pair qualifies when its error <= ``best + max(rel_tol * best, abs_tol)``;
    of the qualifying pairs whose ``cost`` <= ``(1 + cost_tol)`` x the least
    qualifying cost, the one of fewest cams, then fewest along the length.
    ``cost``: ``"wall_s_per_sim_s"`` (measured) or ``"cams"`` (the count, a
    deterministic proxy).
    """
    rule_text(rel_tol, abs_tol, cost, cost_tol)
    s = summarise(table, rel_tol, abs_tol)
    ok = s[s["qualifies"]]
    cheap = ok[ok[cost] <= (1.0 + cost_tol) * float(ok[cost].min())]
    row = cheap.sort_values(["cams", "n_length", cost], kind="stable").iloc[0]
    return int(row["n_length"]), int(row["n_width"])
