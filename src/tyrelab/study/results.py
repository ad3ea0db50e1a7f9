"""A finished study as one object to slice: ``Study(folder)`` (``tyrelab.study.open``).

>>> s = Study("results")                  # doctest: +SKIP
>>> s.metrics                             # one row per compared run (metrics.parquet)
>>> s.summary                             # thesis Table 5-15 form
>>> s.thesis                              # our metrics beside the thesis's published ones
>>> s.rank_agreement.mean                 # do we rank the models as the thesis did?
>>> s.consistency.views                  # within the bound the thesis's numbers impose?
>>> s.cost                                # wall time per simulated second, data each model needs
>>> s.soil_curves                         # soil tests: steady pull, torque, sinkage against slip
>>> s.to_xarray()                         # metrics as a Dataset, dims model x condition

The folder holds what the runner wrote: ``runs/`` and ``index.parquet``
(:mod:`.store`), ``spec.toml`` with ``study.json`` (the folder its relative
paths start from) and, once evaluated, ``metrics.parquet``
(:mod:`.evaluate`) and, with soil tests, ``soil_curves.parquet`` (:mod:`.soil`).
Without ``spec.toml`` the spec is None and everything
that needs it (computing missing metrics, the spec's limits) falls back to
what the folder holds (the metrics' own ``is_reference`` column, the
default limits).
"""

from __future__ import annotations

import functools
import json
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import InputError
from ..validate.compare import METRICS, THESIS_CLEAT, THESIS_TRACK
from ..validate.rank_agreement import RankAgreement, rank_agreement
from ..validate.tables import DEFAULT_LIMITS, summary_table
from .evaluate import METRICS_FILE, REPEATABILITY, evaluate_study
from .soil import SOIL_FILE, empty_table, soil_curves
from .spec import StudySpec, parse_spec
from .store import DONE, Store

RUN_COLUMNS = ("tyre", "test", "speed_kmh", "load")
THESIS_METRICS = [*THESIS_CLEAT, *THESIS_TRACK]


def _parameterization(contact: str) -> str:
    """What a contact model must be given, measured (the registry's text; "" if unknown)."""
    from ..tyre.registry import contact_models
    model = contact_models().get(contact)
    return model.parameterization if model is not None else ""


class Study:
    """A study folder: its spec, index, metrics and the tables made from them."""

    def __init__(self, folder):
        self.folder = Path(folder)
        if not self.folder.is_dir():
            raise InputError("no such study folder", source=str(self.folder))
        self.store = Store(self.folder)

    def __repr__(self) -> str:
        return f"Study({str(self.folder)!r})"

    def __getstate__(self) -> dict:
        """Pickled as its folder: the tables are read again where it is unpickled (a study's
        worker, which shares the folder, draws the report's figures from the signals)."""
        return {"folder": self.folder, "store": self.store}

    # -- what the folder holds ------------------------------------------------------
    @functools.cached_property
    def spec(self) -> StudySpec | None:
        """The spec (``spec.toml``; relative paths from ``study.json``'s base), or None."""
        path = self.folder / "spec.toml"
        if not path.is_file():
            return None
        base = self.folder
        info = self.folder / "study.json"
        if info.is_file():
            base = Path(json.loads(info.read_text(encoding="utf-8")).get("base") or base)
        return parse_spec(path.read_text(encoding="utf-8"), path, base=base)

    @property
    def index(self) -> pd.DataFrame:
        """One row per run record (spec columns, status, wall time, error): the runs of the
        study's spec (records of runs an earlier version of the spec made stay in the folder,
        reused if the spec comes back to them, but are not this study's)."""
        index = self.store.index()
        if self.spec is not None and len(index):
            order = {key: i for i, key in enumerate(dict.fromkeys(self.spec.run_keys().values()))}
            index = index[index["key"].isin(order.keys())]  # in the spec's order
            index = index.sort_values("key", key=lambda k: k.map(order), kind="stable")
        return index.reset_index(drop=True)

    @functools.cached_property
    def metrics(self) -> pd.DataFrame:
        """``metrics.parquet``, or computed (and written) when missing and the spec is there."""
        path = self.folder / METRICS_FILE
        if path.is_file():
            return pd.read_parquet(path)
        if self.spec is None:
            raise InputError("the study has no metrics.parquet and no spec.toml to compute it",
                             source=str(self.folder))
        return evaluate_study(self.spec, self.store, progress=False)

    @functools.cached_property
    def soil_curves(self) -> pd.DataFrame:
        """The soil tests' steady drawbar pull ``FX`` [N], driving torque ``TORQUE`` [N m],
        sinkage ``SINKAGE`` [m] and load ``FZ`` [N] per test, model and slip, with each
        model's difference from the test's reference model
        (:func:`tyrelab.study.soil.soil_curves`): ``soil_curves.parquet``, or computed (and
        written) when missing and the spec has soil tests; no rows when the study has none."""
        path = self.folder / SOIL_FILE
        if path.is_file():
            return pd.read_parquet(path)
        if self.spec is not None and any(t.is_soil_test for t in self.spec.tests):
            return soil_curves(self.spec, self.store)
        return empty_table()

    def signal(self, key: str, columns=None) -> pd.DataFrame:
        """The signal table of the finished run ``key``, or of the spec's measured
        reference file of that name (the ``reference`` column of :attr:`metrics`); only
        ``columns``, if given."""
        measured = self._measured_file(key)
        if measured is None:
            return self.store.signal(key, columns)
        from ..measure import read_run
        run = read_run(measured.path, column_map=measured.column_map)
        if columns is None:
            return run
        missing = [c for c in columns if c not in run.columns]
        if missing:  # one line, as read_signal gives for a stored run
            raise InputError(f"no channel {', '.join(missing)} in this measured run",
                             source=str(measured.path))
        return run[list(columns)]

    def _measured_file(self, key: str):
        """The spec's measured reference file named ``key`` when no finished run has that
        key, else None."""
        if self.store.is_finished(key) or self.spec is None:
            return None
        return next((f for test in self.spec.tests for f in test.reference_files
                     if f.path.name == key), None)

    # -- rows -----------------------------------------------------------------------
    def _reference_models(self) -> set:
        if self.spec is not None:
            return {t.reference_model for t in self.spec.tests if t.reference_model}
        m = self.metrics
        return set(m.loc[m["is_reference"].astype(bool), "model"]) if "is_reference" in m else set()

    def _model_rows(self) -> pd.DataFrame:
        """Model rows compared without error, the reference model's own and the measured
        repeatability rows left out."""
        m = self.metrics
        keep = ~m["model"].isin(self._reference_models() | {REPEATABILITY})
        if "is_reference" in m:
            keep &= ~m["is_reference"].astype(bool)
        if "error" in m:
            keep &= m["error"].fillna("").astype(str) == ""
        return m[keep]

    def _limits(self) -> dict:
        return self.spec.limits if self.spec is not None else DEFAULT_LIMITS

    # -- tables ---------------------------------------------------------------------
    @property
    def summary(self) -> pd.DataFrame:
        """Table 5-15 form (:func:`~tyrelab.validate.tables.summary_table`) over the model
        rows, with the spec's limits; measured repeatability rows, if any, raise a run's
        limits (``scatter``). Rows whose primary metrics are not finite (a failed
        comparison) are left out and listed in ``attrs["left_out"]``."""
        limits = self._limits()
        rows = self._model_rows()
        ok = np.ones(len(rows), dtype=bool)
        for group, lim in limits.items():
            in_group = (rows["group"] == group).to_numpy()
            for metric in lim:
                if in_group.any() and metric in rows:  # a missing metric: summary_table says
                    ok &= ~in_group | np.isfinite(rows[metric].to_numpy(dtype=float))
        m = self.metrics
        scatter = m[m["model"] == REPEATABILITY]
        out = summary_table(rows[ok], limits, run_columns=RUN_COLUMNS,
                            scatter=scatter if len(scatter) else None)
        out.attrs["left_out"] = rows[~ok][["key", *RUN_COLUMNS, "model"]].to_dict("records")
        return out

    @property
    def thesis(self) -> pd.DataFrame:
        """Our metrics beside the thesis's published ones, joined on test label, speed,
        load case and model label (the thesis's variant labels, e.g. "3D VC nlk"; measured
        repeatability with Tables 5-1 and 5-6): ``<metric>_ours``, ``<metric>_thesis``."""
        from ..validate.thesis import thesis_metrics, thesis_repeatability
        theirs = pd.concat([thesis_metrics(models=None), thesis_repeatability()],
                           ignore_index=True)
        theirs = theirs[["test", "speed_kmh", "load_case", "model", "table", *THESIS_METRICS]].copy()
        m = self.metrics
        # the models and the measured scatter; not the reference compared with itself (all zeros)
        keep = ~m["is_reference"].astype(bool) if "is_reference" in m else m["key"] != m["reference"]
        ours = m[keep].rename(columns={"load": "load_case"})
        ours = ours[["key", "tyre", "test", "speed_kmh", "load_case", "model", *THESIS_METRICS]].copy()
        for df in (ours, theirs):
            df["speed_kmh"] = df["speed_kmh"].astype(float).round(6)
        out = ours.merge(theirs, on=["test", "speed_kmh", "load_case", "model"],
                         suffixes=("_ours", "_thesis"), how="inner")
        cols = [c for m in THESIS_METRICS for c in (f"{m}_ours", f"{m}_thesis")]
        return out[["key", "tyre", "test", "speed_kmh", "load_case", "model", "table", *cols]]

    @property
    def rank_agreement(self) -> RankAgreement:
        """Spearman's ρ between our ranking of the models and the thesis's, per run
        (test, speed, load case) and the mean (:func:`~tyrelab.validate.rank_agreement.rank_agreement`);
        the reference model's own rows are left out. With several tyres, the first."""
        from ..validate.thesis import thesis_metrics
        ours = self._model_rows().rename(columns={"load": "load_case"})
        if len(ours):
            ours = ours[ours["tyre"] == ours["tyre"].iloc[0]].copy()
        theirs = thesis_metrics(models=None)
        for df in (ours, theirs):
            df["speed_kmh"] = df["speed_kmh"].astype(float).round(6)
        keys = ["test", "speed_kmh", "load_case"]
        runs = set(map(tuple, ours[keys].itertuples(index=False, name=None)))
        theirs = theirs[[tuple(r) in runs for r in theirs[keys].itertuples(index=False, name=None)]]
        if theirs.empty:
            empty = pd.DataFrame(columns=[*keys, "n_models", *THESIS_METRICS, "rho"])
            return RankAgreement(empty, float("nan"))
        return rank_agreement(ours, theirs, by=keys, metrics=THESIS_METRICS)

    @property
    def consistency(self):
        """Our campaign against what the thesis measured
        (:class:`~tyrelab.validate.consistency.Consistency`: the triangle bound per cell,
        its counts, the agreement with Table 5-15 and Spearman's ρ per metric), over the
        tests whose reference is the thesis's FTire TP (a model of that label); None when
        no test has it."""
        from ..validate.consistency import REFERENCE, consistency
        m = self.metrics
        if "is_reference" not in m:
            return None
        own = m[m["is_reference"].astype(bool) & (m["model"] == REFERENCE)]
        if own.empty:
            return None
        rows = self._model_rows()
        rows = rows[rows["test"].isin(set(own["test"]))]
        if rows.empty:
            return None
        return consistency(rows, self.summary)

    @property
    def reference_note(self) -> str:
        """What the models were compared with, e.g. "reference: FTire TP (ring-tp model),
        not a measurement"; per test when the tests differ."""
        notes = {}
        if self.spec is not None:
            for test in self.spec.tests:
                if test.reference_model:
                    contact = self.spec.model(test.reference_model).contact
                    notes[test.name] = (f"reference: {test.reference_model} ({contact} model), "
                                        "not a measurement")
                elif test.reference_files:
                    names = ", ".join(dict.fromkeys(f.path.name for f in test.reference_files))
                    notes[test.name] = f"reference: measured files {names}"
                else:
                    notes[test.name] = "no reference"
        else:
            m = self.metrics
            for test, rows in m.groupby("test", sort=False):
                own = rows[rows["is_reference"].astype(bool)] if "is_reference" in rows else rows[:0]
                if len(own):
                    notes[test] = (f"reference: {own['model'].iloc[0]} ({own['contact'].iloc[0]} "
                                   "model), not a measurement")
                else:
                    names = ", ".join(dict.fromkeys(rows["reference"].astype(str)))
                    notes[test] = f"reference: measured files {names}"
        texts = list(dict.fromkeys(notes.values()))
        if len(texts) <= 1:
            return texts[0] if texts else "no reference"
        return "; ".join(f"{test}: {text}" for test, text in notes.items())

    @property
    def cost(self) -> pd.DataFrame:
        """Per model: finished runs, median wall time per simulated second (from the index)
        and the parameterization data the model needs; over the runs compared with a reference
        in time (the soil tests' runs, at a prescribed slip, are left out: their wall times are
        in :attr:`soil_curves`)."""
        idx = self.index
        cols = ["model", "contact", "runs", "wall_per_simulated_s", "parameterization"]
        if idx.empty or "status" not in idx:
            return pd.DataFrame(columns=cols)
        done = idx[(idx["status"] == DONE) & (idx["simulated_s"] > 0)]
        for drive in ("slip", "torque"):
            if drive in done:
                done = done[done[drive].isna()]
        rows = []
        for model, g in done.groupby("model", sort=False):
            contact = str(g["contact"].iloc[0]) if "contact" in g else ""
            rows.append({"model": model, "contact": contact, "runs": len(g),
                         "wall_per_simulated_s": float((g["wall_time_s"] / g["simulated_s"]).median()),
                         "parameterization": _parameterization(contact)})
        out = pd.DataFrame(rows, columns=cols)
        if self.spec is not None:
            order = {m.name: i for i, m in enumerate(self.spec.models)}
            out = out.sort_values("model", key=lambda s: s.map(order).fillna(len(order)),
                                  kind="stable")
        return out.reset_index(drop=True)

    def to_xarray(self):
        """The metrics as an :class:`xarray.Dataset`: dims ``model`` x ``condition`` (one
        label per tyre, test, speed, load), one variable per metric; NaN where a model was
        not compared. Repeated rows of one cell (several repeat files) keep the first."""
        try:
            import xarray  # noqa: F401 - from_dataframe needs it
        except ModuleNotFoundError:
            raise InputError("to_xarray needs the xarray package (pip install xarray)") from None
        m = self.metrics.copy()
        several = m["tyre"].nunique() > 1
        m["condition"] = [(f"{ty} | " if several else "") + f"{te} | {sp:g} km/h | {lo}"
                          for ty, te, sp, lo in zip(m["tyre"], m["test"], m["speed_kmh"], m["load"])]
        m = m.drop_duplicates(["model", "condition"])
        variables = [c for c in METRICS if c in m.columns]
        ds = m.set_index(["model", "condition"])[variables].to_xarray()
        ds = ds.reindex(model=list(dict.fromkeys(m["model"])),
                        condition=list(dict.fromkeys(m["condition"])))  # the study's order
        info = m.drop_duplicates("condition").set_index("condition")
        for col in ("tyre", "test", "group", "speed_kmh", "load"):
            ds = ds.assign_coords({col: ("condition", info.loc[ds["condition"].values, col].to_numpy())})
        for name in variables:
            ds[name].attrs.update(units=METRICS[name][0], description=METRICS[name][1])
        ds.attrs["reference"] = self.reference_note
        return ds
