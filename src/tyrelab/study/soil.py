"""Evaluate a study's soil tests: each model's steady drawbar pull, torque and sinkage against slip.

A soil test (:attr:`tyrelab.study.records.TestSpec.is_soil_test`: the
single-wheel tester on a terrain, at the test's ``slips`` or under its driving
``torques``) is a slip curve per model, not a signal compared with a reference
over time, so it stays out of
:func:`tyrelab.study.evaluate.evaluate_study` and of every table made from its
metrics (Table 5-15, the thesis's numbers, the rank agreement, the
consistency: those are about the thesis's rigid-road tests).

Per finished run, the means over the last
:data:`~tyrelab.limits.STEADY_FRACTION` of its duration (the samples
with ``RUNTIME >= (1 - STEADY_FRACTION) * duration``, as
:func:`tyrelab.rig.single_wheel.slip_curve` takes them) of

* ``FX`` [N]: the drawbar pull (positive forward),
* ``TORQUE`` [N m]: the driving torque,
* ``SINKAGE`` [m]: the wheel's lowest point below the undisturbed surface,
* ``FZ`` [N]: the load the soil carries (the dead weight, once steady).

A run's ``slip`` is the slip it was driven at, or, under a driving torque (its
``torque`` column, NaN at a prescribed slip), the steady mean of its ``LONGSLIP``:
the soil's answer to that torque.

With a reference model (``reference = { model = ... }``), each run also gets its
difference from the reference's run at the same slip (or the same torque):

* ``FX_diff_pct`` = 100 (FX - FX_ref) / F_ref and ``TORQUE_diff_pct`` =
  100 (TORQUE - TORQUE_ref) / (R0 F_ref), where ``F_ref`` (``force_scale_N``) is
  the reference's largest driving force over the test's slips, max |TORQUE_ref| / R0
  (R0 the tyre's unloaded radius). The pull itself passes through zero near zero
  slip, so it is measured against the traction the reference develops, not
  against its own value;
* ``SINKAGE_diff_pct`` = 100 (SINKAGE - SINKAGE_ref) / SINKAGE_ref.

The reference's own rows give zeros.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..signal import atomic_output
from .records import RunSpec, StudySpec
from .store import DONE, Store

#: the table's file in the study folder
SOIL_FILE = "soil_curves.parquet"
#: the steady means of a run (module notes)
VALUES = ["FX", "TORQUE", "SINKAGE", "FZ"]
LABELS = ["key", "tyre", "test", "soil", "speed_kmh", "load", "model", "contact", "slip", "torque"]
DIFFERENCES = ["reference", "force_scale_N", "FX_diff_pct", "TORQUE_diff_pct", "SINKAGE_diff_pct"]
COLUMNS = [*LABELS, *VALUES, *DIFFERENCES, "wall_time_s"]
#: a soil test's condition: one curve per model
CONDITION = ["tyre", "test", "speed_kmh", "load"]


def steady_means(signal: pd.DataFrame, duration: float, channels=VALUES) -> dict:
    """The means of ``channels`` (:data:`VALUES`) over the last ``STEADY_FRACTION`` of a run of
    ``duration`` [s] (the samples :func:`tyrelab.rig.single_wheel.slip_curve` averages)."""
    from ..limits import STEADY_FRACTION
    steady = signal[signal["RUNTIME"] >= (1.0 - STEADY_FRACTION) * duration]
    return {c: float(steady[c].mean()) for c in channels}


def _soil_name(terrain: str, names: dict) -> str:
    if terrain not in names:
        from ..road.terrain import resolve_terrain
        names[terrain] = resolve_terrain(terrain)[2]
    return names[terrain]


def _radius(run: RunSpec, radii: dict) -> float:
    if run.tyre not in radii:
        from ..tyre.library import load_tyre
        radii[run.tyre] = load_tyre(run.tyre.file, run.tyre.pressure).unloaded_radius
    return radii[run.tyre]


def _differences(df: pd.DataFrame, spec: StudySpec, radius: dict) -> pd.DataFrame:
    """The reference columns of the module notes, per condition with a reference model: the
    reference's run at the same slip, or under the same torque in a test of torques."""
    references = {t.name: (t.reference_model, "torque" if t.torques else "slip")
                  for t in spec.tests if t.is_soil_test}
    for cond, rows in df.groupby(CONDITION, sort=False):
        ref_name, drive = references.get(cond[1], (None, None))
        if ref_name is None:
            continue
        ref = rows[rows["model"] == ref_name].set_index(drive)
        if ref.empty:
            continue
        scale = float(np.max(np.abs(ref["TORQUE"].to_numpy()))) / radius[cond[0]]
        at = rows[drive].map
        df.loc[rows.index, "reference"] = ref_name
        df.loc[rows.index, "force_scale_N"] = scale
        df.loc[rows.index, "FX_diff_pct"] = 100.0 * (rows["FX"] - at(ref["FX"])) / scale
        df.loc[rows.index, "TORQUE_diff_pct"] = (100.0 * (rows["TORQUE"] - at(ref["TORQUE"]))
                                                 / (radius[cond[0]] * scale))
        sink = at(ref["SINKAGE"])
        df.loc[rows.index, "SINKAGE_diff_pct"] = 100.0 * (rows["SINKAGE"] - sink) / sink.where(sink > 0)
    return df


def soil_curves(spec: StudySpec, store: Store, write: bool = True) -> pd.DataFrame:
    """The steady table of every finished run of ``spec``'s soil tests (module notes).

    Returns
    -------
    pandas.DataFrame
        One row per finished run, in the spec's order (condition, model, slip), columns
        :data:`COLUMNS`: labels (``speed_kmh``; ``load`` as the index writes it), the
        steady means in SI (N, N m, m, N), the differences from the reference (NaN
        without one) and the run's wall time [s]. Written atomically to
        ``<store folder>/soil_curves.parquet`` when ``write`` and the spec has soil
        tests (a table left by an earlier version of the spec is removed otherwise).
    """
    keys = spec.run_keys()
    names, radii, rows = {}, {}, []
    for run in spec.runs():
        if not run.is_soil_run:
            continue
        key = keys[run]
        record = store.record(key)
        if record is None or record.get("status") != DONE or not store.is_finished(key):
            continue
        # under a driving torque, the slip is the soil's answer: its steady LONGSLIP
        means = steady_means(store.signal(key), run.duration,
                             VALUES if run.torque is None else (*VALUES, "LONGSLIP"))
        slip = means.pop("LONGSLIP", run.slip)
        radius = _radius(run, radii)
        rows.append({"key": key, "tyre": run.tyre.name, "test": run.test,
                     "soil": _soil_name(run.terrain, names), "speed_kmh": round(run.speed_kmh, 9),
                     "load": str(run.load), "model": run.model.name, "contact": run.model.contact,
                     "slip": float(slip), "torque": np.nan if run.torque is None else float(run.torque),
                     **means, "reference": "", "wall_time_s": float(record.get("wall_time_s", np.nan)),
                     "_radius": radius})
    df = pd.DataFrame(rows, columns=[*COLUMNS, "_radius"])
    for col in (*VALUES, *DIFFERENCES[1:], "slip", "torque", "speed_kmh", "wall_time_s"):
        df[col] = df[col].astype(float)
    df["reference"] = df["reference"].fillna("").astype(str)
    radius = dict(zip(df["tyre"], df["_radius"]))
    df = _differences(df, spec, radius).drop(columns="_radius").reset_index(drop=True)
    if write:
        path = store.folder / SOIL_FILE
        if any(t.is_soil_test for t in spec.tests):
            with atomic_output(path) as tmp:
                df.to_parquet(tmp, index=False)
        else:
            path.unlink(missing_ok=True)
    return df


def empty_table() -> pd.DataFrame:
    """A soil table with no rows (a study without soil tests)."""
    return pd.DataFrame({c: pd.Series(dtype=object if c in ("key", "tyre", "test", "soil", "load",
                                                                "model", "contact", "reference")
                                      else float) for c in COLUMNS})
