"""``tyrelab study``: a validation campaign in one call.

>>> from tyrelab import study
>>> index = study.run("spec.toml")          # doctest: +SKIP  (or study.run() for the thesis campaign)
>>> index = study.open("results")           # doctest: +SKIP

A study spec (:mod:`tyrelab.study.spec`) expands into runs; each run is one
Dask task (:mod:`tyrelab.study.runner`) whose signal table lands in the
results store under a key derived from its complete specification
(:mod:`tyrelab.study.store`), so a rerun computes only what is missing or
what changed.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from .spec import RunSpec, StudySpec, builtin_spec, example_spec, load_spec
from .store import Store


def run_record(run: RunSpec) -> dict:
    """The columns a run's record and the study index carry (labels in the spec's words,
    speed in km/h as the thesis tables give it, the rest SI)."""
    return {"tyre": run.tyre.name, "model": run.model.name, "contact": run.model.contact,
            "stiffness": run.model.stiffness or "", "test": run.test, "group": run.group,
            "road": run.road, "speed_kmh": round(run.speed_kmh, 9), "load": str(run.load),
            "rig": run.rig, "dt": run.dt}


def tasks(spec: StudySpec) -> list[dict]:
    """The runner's tasks of ``spec``, one per distinct run key, in the spec's order."""
    out, seen = [], set()
    for run, key in spec.run_keys().items():
        if key not in seen:  # two labels with identical settings are one simulation
            seen.add(key)
            out.append({"key": key, "spec": run_record(run), "simulate": run.simulate_kwargs()})
    return out


def run(spec: StudySpec | str | Path | None = None, workers: int | None = None,
        scheduler: str | None = None, output: str | Path | None = None,
        progress: bool = True) -> pd.DataFrame:
    """Run a study (the built-in thesis campaign when ``spec`` is None); returns its index.

    ``output`` overrides the spec's results folder; ``workers`` and
    ``scheduler`` as in :func:`tyrelab.study.runner.run_tasks`.
    """
    from .runner import run_tasks
    if spec is None:
        spec = builtin_spec()
    elif not isinstance(spec, StudySpec):
        spec = load_spec(spec)
    store = Store(output if output is not None else spec.output)
    run_tasks(tasks(spec), store, workers=workers, scheduler=scheduler, progress=progress)
    return store.index()


def open(folder: str | Path) -> pd.DataFrame:  # noqa: A001 - the name the issue asks for
    """The index of a study folder: one row per run (spec columns, status, wall time, error)."""
    return Store(folder).index()


__all__ = ["run", "open", "tasks", "run_record", "load_spec", "builtin_spec", "example_spec",
           "StudySpec", "RunSpec", "Store"]
