"""The thesis's published validation numbers (chapter 5), as package data.

Three tables, copied or transcribed from the thesis into ``validate/data``
(``data/README.md`` gives the text lines) and read through
:mod:`importlib.resources`, so they load from an installed package:

* :func:`thesis_metrics` - the metrics of each model on each run (Tables 5-2
  to 5-5, 5-7 to 5-14), in the long form :func:`.tables.summary_table` and
  :func:`.rank_agreement.rank_agreement` take;
* :func:`thesis_repeatability` - two measurements of one test compared with
  the same metrics (Tables 5-1 and 5-6), the measurement's own scatter;
* :func:`thesis_table_5_15` - the thesis's summary verdicts (Table 5-15), in
  the shape :func:`.tables.summary_table` returns.

Long form: one row per (run, model) with columns ``group`` and ``obstacle``
(the row of Table 5-15: ``"discrete obstacles"``/``"cleats"``, ...),
``test`` (the obstacle or track actually driven, e.g. ``"cleat 76.3x76.3
perpendicular"``), ``speed_kmh``, ``load_case``, ``model``, ``variant`` (the
name the thesis's metric tables use), ``table`` (the thesis table number) and
the metrics of :data:`.compare.THESIS_CLEAT` and :data:`.compare.THESIS_TRACK`
(NaN where a group does not use one). Names are lower case, as
:data:`.tables.DEFAULT_LIMITS` spells the groups.

References
----------
.. [1] Seed thesis "Tyre model verification over off-road terrain", chapter
   5: Tables 5-1 to 5-14 (metrics), Table 5-15 (summary).
"""

from __future__ import annotations

from importlib import resources

import pandas as pd

from ..errors import InputError
from .compare import THESIS_CLEAT, THESIS_TRACK

#: Published variant -> column of Table 5-15: the variants the thesis carried
#: onto the tracks ("only tyre models with nonlinear tyre stiffness" and FTire
#: with its tread pattern, section 5.3), the only ones of Table 5-10 too.
TABLE_5_15_MODELS = {"FTire TP": "FTire", "3D ENV nlk": "3D ENV", "3D VC nlk": "3D VC",
                     "OPC nlk": "OPC"}

#: Test driven -> (group, obstacle) row of Table 5-15.
TABLE_5_15_ROWS = {
    "cleat 50x50 perpendicular": ("discrete obstacles", "cleats"),
    "cleat 50x50 oblique 45deg": ("discrete obstacles", "cleats"),
    "cleat 76.3x76.3 perpendicular": ("discrete obstacles", "cleats"),
    "cleat 100x100 oblique 45deg": ("discrete obstacles", "cleats"),
    "trapezoidal bump 150mm": ("discrete obstacles", "trapezoidal bump"),
    "belgian paving": ("rough tracks", "belgian paving"),
    "fatigue track": ("rough tracks", "fatigue track"),
}

#: Model columns of Table 5-15, in the thesis's order.
TABLE_5_15_COLUMNS = ["FTire", "3D ENV", "3D VC", "OPC"]

_REPEATABILITY = "measured repeatability"
_COLUMNS = ["group", "obstacle", "test", "speed_kmh", "load_case", "model", "variant", "table",
            *THESIS_CLEAT, *THESIS_TRACK]


def _read(name: str) -> pd.DataFrame:
    """One CSV of the package data folder ``validate/data``."""
    with resources.files("tyrelab.validate").joinpath("data", name).open("r",
                                                                        encoding="utf-8") as f:
        return pd.read_csv(f)


def _published() -> pd.DataFrame:
    """Every published row (models and repeatability), long form, all variants."""
    cleat = _read("thesis_cleat_metrics.csv").rename(columns={"obstacle": "test"})
    track = _read("thesis_track_metrics.csv").rename(columns={"track": "test"})
    df = pd.concat([cleat, track], ignore_index=True)
    unknown = sorted(set(df["test"]) - set(TABLE_5_15_ROWS))
    if unknown:
        raise InputError(f"thesis data name a test outside Table 5-15: {unknown[0]}",
                         field="test")
    rows = df["test"].map(TABLE_5_15_ROWS)
    df["group"] = [r[0] for r in rows]
    df["obstacle"] = [r[1] for r in rows]
    df["variant"] = df["model"]
    df["table"] = df["table"].astype(str)
    return df[_COLUMNS]


def thesis_metrics(models: dict | None = TABLE_5_15_MODELS) -> pd.DataFrame:
    """The validation metrics the thesis published per model and run.

    Parameters
    ----------
    models : dict or None, default :data:`TABLE_5_15_MODELS`
        ``{published variant: model name}``: keeps those variants and names
        them by the column of Table 5-15 they stand for (default: FTire TP,
        3D ENV nlk, 3D VC nlk, OPC nlk as FTire, 3D ENV, 3D VC, OPC). None
        keeps every published variant under its own name.

    Returns
    -------
    pandas.DataFrame
        Long form (module docstring), one row per (run, model), from Tables
        5-2 to 5-5 and 5-7 to 5-10 (discrete obstacles: m%RE, 80%RE, RMS of
        the disturbance, m%RE, RMS of the response) and 5-11 to 5-14 (rough
        tracks: μ%err, σ%err); the measurement's repeatability rows are in
        :func:`thesis_repeatability`.
    """
    df = _published()
    df = df[df["model"] != _REPEATABILITY]
    if models is not None:
        df = df[df["variant"].isin(list(models))].copy()
        df["model"] = df["variant"].map(models)
    return df.reset_index(drop=True)


def thesis_repeatability() -> pd.DataFrame:
    """Two measurements of one cleat test compared: the measurement's scatter.

    Returns
    -------
    pandas.DataFrame
        Long form (module docstring), ``model`` = ``"measured
        repeatability"``: thesis Table 5-1 (50 mm cleat at 18, 27, 42 km/h)
        and Table 5-6 (76 mm cleat at 12, 27, 42 km/h), load case LC1. The
        ``scatter`` argument of :func:`.tables.summary_table` takes it.
    """
    df = _published()
    return df[df["model"] == _REPEATABILITY].reset_index(drop=True)


def thesis_table_5_15() -> pd.DataFrame:
    """The thesis's summary of its validation, Table 5-15, cell by cell.

    Returns
    -------
    pandas.DataFrame
        Index (group, obstacle) with the thesis's six rows (cleats,
        trapezoidal bump, Belgian paving, fatigue track, parallel and angled
        corrugations), columns :data:`TABLE_5_15_COLUMNS`, text verdicts in
        :func:`.tables.summary_table`'s spelling (the thesis's wording in
        lower case: ``"comparable, best"``, ``"comparable"``, ``"comparable,
        under certain conditions"``, ``"not representative"``). The verbatim
        wording and the thesis text line of each cell are in
        ``data/thesis_table_5_15.csv``. The two corrugation rows rest on
        figures only; no published metric reproduces them.
    """
    cells = _read("thesis_table_5_15.csv")
    for col in ("group", "obstacle", "verdict"):
        cells[col] = cells[col].str.strip().str.lower()
    out = cells.pivot(index=["group", "obstacle"], columns="model", values="verdict")
    order = list(dict.fromkeys(zip(cells["group"], cells["obstacle"])))
    out = out.loc[order, TABLE_5_15_COLUMNS]
    out.columns.name = None
    return out

_C, _NR = "comparable", "not representative"

#: The Table 5-15 cells the rules of :func:`tyrelab.validate.tables.summary_table` do not
#: reproduce from the thesis's own metrics, each argued:
#: (group, obstacle, model) -> (the rules' verdict, the thesis's, why).
TABLE_5_15_EXCEPTIONS = {
    ("discrete obstacles", "trapezoidal bump", "3D ENV"): (
        _C, _NR,
        "one run (Table 5-10): 3D ENV's disturbance errors, m%RE 8 %, 80%RE 14 %, 2307 N, lie "
        "inside the range of its cleat errors (6-21 %, 11-35 %, 2023-4150 N) where the thesis "
        "calls it comparable, and every model misses the response (26-38 %). A limit that "
        "failed it here (< 8 %) would fail it on 5 of 7 cleat runs too; only a rule relative "
        "to the best model (8 % is twice FTire's and 3D VC's 4 %) separates them, and that "
        "judges a model against its competitors rather than the measurement. The thesis "
        "judged this run from Figure 5-10 (5.2.5: FTire most accurate, 3D VC acceptable)."),
    ("rough tracks", "fatigue track", "3D VC"): (
        _NR, _C,
        "3D VC passes 1 of the 3 runs kept (Tables 5-13, 5-14: σ%err -65 % at LC1 18 km/h, "
        "-26 % at LC2 3 km/h, -6 % at LC2 11 km/h; LC1 3 km/h set aside as unexplained) "
        "against the 25 % limit. The thesis's verdict is qualitative (5.3.2: it 'filtered the "
        "road input in such a way that the statistical behaviour was similar to the measured "
        "results'); the miss at 3 km/h is one point on a value published as an integer. A "
        "limit of 26-27 % would match this cell as well, but nothing measured ties such a "
        "number, so the limit stays at Table 5-1's largest scatter (25.1 %)."),
}


def rules_on_thesis() -> pd.DataFrame:
    """The Table 5-15 rules applied to the thesis's own published metrics, cell by cell.

    One row per cell that published metrics cover: ``group, obstacle, model``,
    ``rules`` (our verdict), ``thesis`` (Table 5-15's), ``match`` and ``why``
    (the argument, :data:`TABLE_5_15_EXCEPTIONS`, where they differ).
    """
    from .tables import summary_table
    ours, theirs = summary_table(thesis_metrics()), thesis_table_5_15()
    rows = []
    for group, obstacle in ours.index:
        for model in TABLE_5_15_COLUMNS:
            a, b = ours.at[(group, obstacle), model], theirs.at[(group, obstacle), model]
            why = "" if a == b else TABLE_5_15_EXCEPTIONS.get((group, obstacle, model), ("", "", "?"))[2]
            rows.append({"group": group, "obstacle": obstacle, "model": model, "rules": a,
                         "thesis": b, "match": a == b, "why": why})
    return pd.DataFrame(rows)
