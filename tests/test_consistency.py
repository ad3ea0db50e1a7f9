"""Consistency of a campaign referenced to FTire TP with what the thesis measured.

The bound rests on Minkowski's inequality for the RMS error (checked here on random
signals with the metric's own function, and shown *not* to hold for the mean relative
error, which is why that bound is labelled approximate). The bound, the Table 5-15
agreement and Spearman's ρ are then checked on small tables whose answers are worked
by hand from the thesis's published numbers (typed here from Tables 5-2 and 5-15).
"""

import numpy as np
import pandas as pd
import pytest

from tyrelab.validate.consistency import (THESIS_ALIASES, bound_counts, spearman_per_metric,
                                          table_5_15_agreement, triangle_bounds, views_of)
from tyrelab.validate.metrics import mean_relative_error, rms_error
from tyrelab.validate.thesis import thesis_table_5_15

# Table 5-2 (50 mm cleat, 12 km/h, LC1), typed from the thesis
T52 = {"FTire TP": (6, 10, 752, 10, 2256), "OPC lk": (37, 53, 4624, 35, 8410),
       "3D VC lk": (7, 11, 1050, 34, 9279), "3D ENV nlk": (14, 22, 2023, 6, 1584)}
METRICS = ["mRE_disturbance_pct", "RE80_disturbance_pct", "rms_disturbance_N",
           "mRE_response_pct", "rms_response_N"]
RUN = {"test": "cleat 50x50 perpendicular", "speed_kmh": 12.0, "load": "LC1"}


def test_the_rms_bound_is_minkowskis_inequality_and_the_relative_one_is_not():
    rng = np.random.default_rng(7)
    for _ in range(200):
        m, p, r = (rng.normal(2e4, 5e3, 300) for _ in range(3))
        assert rms_error(p, r) <= rms_error(p, m) + rms_error(r, m) + 1e-9
    # a relative error divides by the measurement on one side and by FTire on the other,
    # so the sum need not bound it: p = 2, FTire = 1, measured 1.5 gives 100 % against
    # 33 % + 33 %
    p, r, m = np.array([2.0]), np.array([1.0]), np.array([1.5])
    assert mean_relative_error(p, r) == pytest.approx(100.0)
    assert mean_relative_error(p, m) + mean_relative_error(r, m) == pytest.approx(200.0 / 3)


def ours(values: dict) -> pd.DataFrame:
    return pd.DataFrame([{**RUN, "model": k, **dict(zip(METRICS, v))} for k, v in values.items()])


def test_bounds_by_hand_from_table_5_2():
    theirs = pd.DataFrame([{**RUN, "load_case": "LC1", "model": k, **dict(zip(METRICS, v))}
                           for k, v in T52.items()]).drop(columns="load")
    mine = ours({"OPC lk": (30, 50, 5000, 200, 5000), "3D VC lk": (38, 41, 5365, 20, 5329),
                 "3D ENV edge nlk": (10, 20, 2000, 5, 1000), "FTire TP": (0, 0, 0, 0, 0),
                 "not in the thesis": (1, 1, 1, 1, 1)})
    b = triangle_bounds(mine, theirs, aliases=THESIS_ALIASES)
    cell = b.set_index(["model", "metric"])
    # 3D VC lk, RMS of the disturbance: 1050 + 752 = 1802 N against our 5365 N
    assert cell.loc[("3D VC lk", "rms_disturbance_N"), "bound"] == 1802
    assert not cell.loc[("3D VC lk", "rms_disturbance_N"), "within"]
    assert cell.loc[("3D VC lk", "rms_disturbance_N"), "exact"]
    # OPC lk, m%RE of the response: 35 + 10 = 45 % against 200 %: out, approximate
    assert cell.loc[("OPC lk", "mRE_response_pct"), "bound"] == 45
    assert not cell.loc[("OPC lk", "mRE_response_pct"), "exact"]
    # the edge variant stands for the thesis's 3D ENV nlk: 2023 + 752 = 2775 >= 2000
    assert cell.loc[("3D ENV edge nlk", "rms_disturbance_N"), "bound"] == 2775
    assert cell.loc[("3D ENV edge nlk", "rms_disturbance_N"), "thesis_model"] == "3D ENV nlk"
    # the reference itself and a model the thesis did not run have no cell
    assert set(b["model"]) == {"OPC lk", "3D VC lk", "3D ENV edge nlk"}
    counts = bound_counts(b)
    # by hand, the four counted metrics: OPC 30 <= 43, 5000 <= 5376, 200 > 45, 5000 <= 10666;
    # VC 38 > 13, 5365 > 1802, 20 <= 44, 5329 <= 11535; ENV edge all four within
    assert counts.loc["OPC lk", "all"] == "3/4" and counts.loc["3D VC lk", "all"] == "2/4"
    # 80%RE (shown, not counted): OPC 50 <= 63, VC 41 > 21, ENV edge 20 <= 32
    assert counts.loc["all", "RE80_disturbance_pct"] == "2/3"
    assert (counts.attrs["within"], counts.attrs["cells"]) == (9, 12)


def test_table_5_15_agreement_by_hand():
    thesis = thesis_table_5_15()
    rows = thesis.index
    summary = pd.DataFrame(index=rows, columns=["OPC lk", "OPC nlk", "3D ENV lk", "FTire"], dtype=object)
    summary[:] = "not representative"
    summary.loc[("discrete obstacles", "cleats"), "3D ENV lk"] = "comparable"        # thesis: comparable
    summary.loc[("rough tracks", "belgian paving"), "OPC nlk"] = "comparable, best"  # thesis: not repr.
    summary["FTire"] = "comparable"                                                 # thesis: "..., best"
    a = table_5_15_agreement(summary, thesis).set_index(["obstacle", "model"])
    # OPC: both variants "not representative", as the thesis, except the paving's nlk
    assert a.loc[("belgian paving", "OPC"), "any"] and not a.loc[("belgian paving", "OPC"), "all"]
    assert a.loc[("fatigue track", "OPC"), "all"]
    # the ", best" mark is not compared: FTire matches in every row
    assert a.xs("FTire", level="model")["all"].all()
    # 3D ENV: cleats match (comparable); the other five rows are "not representative" in
    # the thesis too; 3D VC has no variant in this summary: no cell
    assert a.xs("3D ENV", level="model")["any"].sum() == 6
    assert "3D VC" not in a.index.get_level_values("model")
    assert len(a) == 18 and int(a["any"].sum()) == 18 and int(a["all"].sum()) == 17


def test_spearman_per_metric_against_ranks_by_hand():
    theirs = pd.DataFrame([{**RUN, "load_case": "LC1", "model": k, **dict(zip(METRICS, v))}
                           for k, v in T52.items()]).drop(columns="load")
    # ours ranks OPC > VC > ENV on the RMS of the disturbance (thesis: OPC > ENV > VC):
    # ranks (3, 2, 1) against (3, 1, 2): rho = 1 - 6 * (0 + 1 + 1) / (3 * 8) = 0.5
    mine = ours({"OPC lk": (30, 50, 9000, 20, 5000), "3D VC lk": (20, 41, 5000, 10, 5329),
                 "3D ENV nlk": (10, 20, 2000, 5, 1000), "FTire TP": (0, 0, 0, 0, 0)})
    rho = spearman_per_metric(mine, theirs).set_index("metric")
    assert rho.loc["rms_disturbance_N", "rho"] == pytest.approx(0.5)
    assert rho.loc["rms_disturbance_N", "cells"] == 3      # the reference is left out
    # m%RE: thesis 37, 7, 14 ranks (3, 1, 2), ours 30, 20, 10 ranks (3, 2, 1): 0.5 too;
    # m%RE of the response: thesis 35, 34, 6 and ours 20, 10, 5 both rank (3, 2, 1): 1
    assert rho.loc["mRE_disturbance_pct", "rho"] == pytest.approx(0.5)
    assert rho.loc["mRE_response_pct", "rho"] == pytest.approx(1.0)


def test_views_replace_our_enveloping_model_by_the_thesiss_when_it_ran():
    labels = ["OPC lk", "3D ENV lk", "3D ENV nlk", "3D ENV edge lk", "3D ENV edge nlk", "FTire"]
    v = views_of(labels)
    assert v["ours"] == ["OPC lk", "3D ENV lk", "3D ENV nlk", "FTire"]
    assert v["thesis's ENV"] == ["OPC lk", "FTire", "3D ENV edge lk", "3D ENV edge nlk"]
    assert list(views_of(["OPC lk"])) == ["ours"]
