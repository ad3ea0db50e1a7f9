"""The built-in campaign's runs alone, on W plain processes: the floor under ``tyrelab study``.

    python benchmarks/campaign_floor.py [WORKERS] [RESULTS_FOLDER]

Runs every task of the built-in campaign (``tyrelab.study.tasks``) in WORKERS plain worker
processes (default: one per core) without Dask, without a store and without sending the
signals back: each process simulates and keeps only the run's wall time. The tasks go out
as the study sends them -- the most expensive first (the spec's expected cost, the Dask
priority), each to the first process free -- so the pool's wall time is what the study's runs
would take if Dask, the store and the study's own process cost nothing. Each process loads
its kernels from the compile cache at its first run of each model, as a study's worker does
(run the campaign or this script once before, for a warm cache).

Prints the total run time (one core), the pool's wall time, each model's share, and, given
the RESULTS_FOLDER of a finished ``tyrelab study`` of the built-in campaign, each model's run
time there (its ``index.parquet``): the difference is what the runs lose inside a study to
the other work on the same cores (the study's process, which receives and stores every
signal, and the workers' own threads) -- and to the machine's drift, when the two were not
measured within the same few minutes (on this project's machine, 18 % within nine minutes:
docs/benchmarks.md, "The floor under the campaign").
"""

from __future__ import annotations

import multiprocessing
import os
import sys
import time


def _run(task: dict) -> tuple[str, float]:
    """The study worker's own call (:func:`tyrelab.study.runner.execute`); the signal stays here."""
    from tyrelab.study.runner import execute
    status, result, wall, _ = execute(task)
    if status != "done":
        raise RuntimeError(f"run {task['key']} failed: {result}")
    return task["key"], wall


def main(workers: int, folder: str | None) -> None:
    import pandas as pd

    from tyrelab import study

    if folder and not os.path.isfile(os.path.join(folder, "index.parquet")):
        sys.exit(f"{folder}: no index.parquet; expected a finished 'tyrelab study' folder")
    spec = study.builtin_spec()
    tasks = sorted(study.tasks(spec), key=lambda t: -t.get("cost", 0.0))
    model = {t["key"]: t["spec"]["model"] for t in tasks}
    t0 = time.perf_counter()
    with multiprocessing.get_context("spawn").Pool(workers) as pool:
        walls = dict(pool.imap_unordered(_run, tasks, chunksize=1))
    span = time.perf_counter() - t0
    table = pd.DataFrame({"model": [model[k] for k in walls], "plain [s]": list(walls.values())})
    per_model = table.groupby("model")["plain [s]"].sum()
    if folder:
        index = pd.read_parquet(os.path.join(folder, "index.parquet"))
        index = index[index["key"].isin(walls)]
        if len(index) != len(walls):
            sys.exit(f"{folder}: {len(walls) - len(index)} of the campaign's runs are missing")
        per_model = pd.concat([per_model, index.groupby("model")["wall_time_s"].sum()
                               .rename("in the study [s]")], axis=1)
    print(per_model.round(1).to_string())
    work = table["plain [s]"].sum()
    print(f"{len(walls)} runs: {work:.0f} s of run time on one core; {workers} plain processes "
          f"took {span:.1f} s (the work over {workers}: {work / workers:.1f} s)")
    if folder:
        inside = per_model["in the study [s]"].sum()
        print(f"the same runs inside the study: {inside:.0f} s of run time "
              f"({100 * (inside / work - 1):+.0f} %)")


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) > 2 or (args and not args[0].isdigit()):
        sys.exit(__doc__)
    main(int(args[0]) if args else (os.cpu_count() or 1), args[1] if len(args) > 1 else None)
