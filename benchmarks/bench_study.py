"""Benchmark: the built-in thesis campaign (160 runs) on this machine.

    python benchmarks/bench_study.py [--workers N ...] [--subset cleats|all] [--keep FOLDER]

For each worker count, runs the campaign (or only its discrete-obstacle
runs with ``--subset cleats``) into a fresh results folder with a warm
compile cache (a first, untimed pass over one run of each model loads or
compiles every kernel), and prints the wall time, the sum of the runs' own
wall times per model (where the time goes), and the speed-up over the
first worker count given.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import pandas as pd

from tyrelab import study
from tyrelab.study.runner import run_tasks
from tyrelab.study.store import Store


def campaign_tasks(subset: str) -> list[dict]:
    spec = study.builtin_spec()
    tasks = study.tasks(spec)
    if subset == "cleats":
        tasks = [t for t in tasks if t["spec"]["group"] == "discrete obstacles"]
    return tasks


def warm(tasks: list[dict]) -> None:
    """Compile (or load) every model's kernels once in this machine's disk cache."""
    seen, warmup = set(), []
    for t in tasks:
        if t["spec"]["model"] not in seen:
            seen.add(t["spec"]["model"])
            w = {**t, "key": "warm-" + t["key"], "simulate": {**t["simulate"], "duration": 0.2}}
            warmup.append(w)
    with tempfile.TemporaryDirectory() as folder:
        run_tasks(warmup, Store(folder), workers=1, progress=False)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--workers", type=int, nargs="+", default=[2])
    ap.add_argument("--subset", choices=("all", "cleats"), default="all")
    ap.add_argument("--keep", default=None, help="keep the last results folder here")
    args = ap.parse_args()
    tasks = campaign_tasks(args.subset)
    print(f"{len(tasks)} runs ({args.subset})")
    warm(tasks)
    first = None
    for n in args.workers:
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(args.keep) if args.keep else Path(tmp) / "study"
            store = Store(folder)
            t0 = time.perf_counter()
            counts = run_tasks(tasks, store, workers=n, progress=True)
            wall = time.perf_counter() - t0
            index = store.index()
        first = first or wall
        by_model = index.groupby("model")[["wall_time_s", "simulated_s"]].sum()
        by_model["wall_per_simulated_s"] = by_model["wall_time_s"] / by_model["simulated_s"]
        print(f"\nworkers {n}: {wall:.1f} s wall ({wall / 60:.1f} min), {counts}, "
              f"speed-up over the first: {first / wall:.2f}x")
        with pd.option_context("display.width", 120):
            print(by_model.sort_values("wall_time_s", ascending=False).round(3))
        print(f"sum of run wall times {index['wall_time_s'].sum():.0f} s; "
              f"longest run {index['wall_time_s'].max():.0f} s")


if __name__ == "__main__":
    main()
