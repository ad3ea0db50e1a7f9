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

import importlib
import json
from pathlib import Path
from typing import TYPE_CHECKING

from .records import expected_cost, kernel_kind
from .spec import RunSpec, StudySpec, builtin_spec, example_spec, load_spec
from .store import Store

if TYPE_CHECKING:
    from .results import Study

#: names of this package loaded at their first use, not with it: the evaluation imports
#: scipy.signal and scipy.stats (0.5-0.9 s of one core), which ``tyrelab study --example``,
#: a spec's check or the runner's tasks never use (PEP 562)
_LAZY = {"evaluate_study": ".evaluate", "soil_curves": ".soil", "Study": ".results"}


def __getattr__(name):
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(_LAZY[name], __name__), name)
    globals()[name] = value
    return value


#: the HTML report's name in a study folder
REPORT = "report.html"


def run_record(run: RunSpec) -> dict:
    """The columns a run's record and the study index carry (labels in the spec's words,
    speed in km/h as the thesis tables give it, the rest SI)."""
    return {"tyre": run.tyre.name, "model": run.model.name, "contact": run.model.contact,
            "stiffness": run.model.stiffness or "", "test": run.test, "group": run.group,
            "road": run.road, "speed_kmh": round(run.speed_kmh, 9), "load": str(run.load),
            "rig": run.rig, "left_wheel": run.left_contact or run.model.contact
            if run.rig in ("trailer", "drop") else "", "dt": run.dt,
            "terrain": run.terrain or "", "slip": run.slip, "torque": run.torque}


def tasks(spec: StudySpec) -> list[dict]:
    """The runner's tasks of ``spec``, one per distinct run key, in the spec's order, each
    with its ``cost`` estimate (:func:`expected_cost`)."""
    out, seen = [], set()
    for run, key in spec.run_keys().items():
        if key not in seen:  # two labels with identical settings are one simulation
            seen.add(key)
            out.append({"key": key, "spec": run_record(run), "simulate": run.simulate_kwargs(),
                        "cost": expected_cost(run), "kernels": kernel_kind(run)})
    return out


def _keep_spec(spec: StudySpec, store: Store) -> None:
    """Copy the spec's text into the study folder (``spec.toml``) with where its relative
    paths point (``study.json``), so ``tyrelab.study.open`` can read the study alone."""
    store.write_text("spec.toml", spec.text)
    store.write_text("study.json", json.dumps({"name": spec.name, "spec_source": str(spec.source),
                                               "base": str(spec.base)}, indent=1))


def run(spec: StudySpec | str | Path | None = None, workers: int | None = None,
        scheduler: str | None = None, output: str | Path | None = None,
        progress: bool = True) -> Study:
    """Run a study (the built-in thesis campaign when ``spec`` is None), evaluate it
    against its references (the soil tests' slip curves: :func:`tyrelab.study.soil.soil_curves`)
    and write its HTML report (``report.html`` in the results
    folder); returns the :class:`Study` (index, metrics, summary, ...).

    ``output`` overrides the spec's results folder; ``workers`` and
    ``scheduler`` as in :func:`tyrelab.study.runner.run_tasks`.
    """
    from .evaluate import evaluate_study
    from .results import Study
    from .runner import run_tasks
    from .soil import soil_curves

    if spec is None:
        spec = builtin_spec()
    elif not isinstance(spec, StudySpec):
        spec = load_spec(spec)
    if workers is not None and not scheduler:
        from ..resources import check_local_workers

        check_local_workers(workers)  # before the results folder is made
    store = Store(output if output is not None else spec.output, storage=spec.store)
    _keep_spec(spec, store)

    def then(client):
        # metrics.parquet, rewritten every time, and the report's figures: on the study's
        # local cluster (its workers share this disk), in this process with a running
        # scheduler's (client None) or for a small finished study
        from ..report.study_report import write_study_report
        evaluate_study(spec, store, progress=progress, client=client)
        soil_curves(spec, store)                    # soil_curves.parquet, in this process
        write_study_report(Study(store.folder), store.folder / REPORT, client=client)

    run_tasks(tasks(spec), store, workers=workers, scheduler=scheduler, progress=progress,
              then=then)
    return Study(store.folder)


def open(folder: str | Path) -> Study:  # noqa: A001 - the name the issue asks for
    """A finished (or partly finished) study folder as a :class:`Study`: ``.index``,
    ``.metrics``, ``.summary``, ``.thesis``, ``.rank_agreement``, ``.cost``, ``.soil_curves``,
    ``.signal(key)``."""
    from .results import Study

    return Study(folder)


__all__ = ["run", "open", "tasks", "run_record", "load_spec", "builtin_spec", "example_spec",
           "evaluate_study", "soil_curves", "Study", "StudySpec", "RunSpec", "Store"]
