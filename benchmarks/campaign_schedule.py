"""How the built-in campaign scales with workers, from its measured run costs and the schedule.

    python benchmarks/campaign_schedule.py RESULTS_FOLDER

RESULTS_FOLDER is a finished ``tyrelab study -o RESULTS_FOLDER`` of the built-in campaign
(its ``index.parquet`` holds each run's wall time on the worker that ran it). Where no
machine with many cores is at hand, the scaling is shown from these costs:

* the runs are laid on W workers as the study's scheduler lays them -- the most expensive
  first (by the spec's expected cost, the Dask priority), each to the first worker free
  (a list schedule) -- for W = 1, 2, 4, 8, 16;
* the evaluation runs on the workers after the last run, one task per condition (the
  runs that share a reference), the longest first: each condition's evaluation is timed
  here, in this process, and laid on the W workers the same way;
* then the report: each condition's figures on the workers, one task per condition, in
  the page's order (timed here, each call of ``condition_figures``, and laid on the W
  workers), the rest of the page (its tables) in the study's own process, as the soil
  curves: timed here and added;
* it prints the predicted wall time for each W, the speed-up of 16 workers over 4, and
  whether every single run and every serial step is at most a sixteenth of the total work
  (the condition for 16 workers to be kept busy).

Assumes a run costs on each of W workers what it cost here (a machine whose memory
bandwidth or clock falls with load does worse); the cluster's start (1-2 s) and each
worker's first compile (loaded from the disk cache) are left out.
"""

from __future__ import annotations

import heapq
import sys
import time
from pathlib import Path


def makespan(costs: list[float], workers: int) -> float:
    """The finish time of a list schedule: each cost, in the order given, to the first free
    worker."""
    free = [0.0] * workers
    for c in costs:
        start = heapq.heappop(free)
        heapq.heappush(free, start + c)
    return max(free)


def main(folder: str) -> None:
    from tyrelab import study
    from tyrelab.report import study_report
    from tyrelab.report.study_report import write_study_report
    from tyrelab.study.soil import soil_curves
    from tyrelab.study.store import Store

    spec = study.builtin_spec()
    store = Store(folder)
    index = store.index()
    index = index[index["status"] == "done"]
    priority = {t["key"]: t.get("cost", 0.0) for t in study.tasks(spec)}
    missing = set(priority) - set(index["key"])
    if missing:
        sys.exit(f"{folder}: {len(missing)} of the campaign's {len(priority)} runs are not finished")
    index = index.assign(priority=index["key"].map(priority))
    ordered = index.sort_values("priority", ascending=False)["wall_time_s"].tolist()
    from tyrelab.study import expected_cost
    from tyrelab.study.evaluate import condition_rows, conditions
    groups = conditions([r for r in spec.runs() if r.slip is None])
    timed = []                              # (priority, evaluation time) of each condition
    for g in groups:
        t0 = time.perf_counter()
        condition_rows(spec, store, g)
        timed.append((sum(expected_cost(r) for r in g), time.perf_counter() - t0))
    evaluation = [c for _, c in sorted(timed, key=lambda pc: -pc[0])]
    serial = {}
    t0 = time.perf_counter()
    soil_curves(spec, store)
    serial["soil curves"] = time.perf_counter() - t0
    figures = []                            # each condition's figures, as a worker makes them
    draw = study_report.condition_figures

    def timed_figures(*args, **kwargs):
        t = time.perf_counter()
        html = draw(*args, **kwargs)
        figures.append(time.perf_counter() - t)
        return html

    study_report.condition_figures = timed_figures
    try:
        t0 = time.perf_counter()
        result = study.open(folder)
        _ = (result.summary, result.thesis, result.rank_agreement, result.cost)
        write_study_report(result, Path(folder) / "report-schedule-check.html")
        serial["report's tables"] = time.perf_counter() - t0 - sum(figures)
    finally:
        study_report.condition_figures = draw
    (Path(folder) / "report-schedule-check.html").unlink()

    runs = sum(ordered)
    work = runs + sum(evaluation) + sum(figures) + sum(serial.values())
    print(f"{len(ordered)} runs: {runs:.0f} s of run time (longest {max(ordered):.1f} s); "
          f"on the workers after them: evaluation {sum(evaluation):.1f} s in {len(evaluation)} "
          f"conditions (longest {max(evaluation):.1f} s), the report's figures {sum(figures):.1f} s "
          f"(longest {max(figures):.1f} s); in the study's process: "
          + ", ".join(f"{k} {v:.1f} s" for k, v in serial.items()))
    print(f"{'workers':>8}{'runs [s]':>11}{'evaluation [s]':>16}{'figures [s]':>13}"
          f"{'command [s]':>13}{'speed-up':>10}")
    times = {}
    for w in (1, 2, 4, 8, 16):
        span, ev, fig = makespan(ordered, w), makespan(evaluation, w), makespan(figures, w)
        # the page's tables are made while the workers draw: the longer of the two
        times[w] = span + ev + max(fig, serial["report's tables"]) + serial["soil curves"]
        print(f"{w:>8}{span:>11.1f}{ev:>16.1f}{fig:>13.1f}{times[w]:>13.1f}"
              f"{times[1] / times[w]:>9.2f}x")
    print(f"16 workers over 4: {times[4] / times[16]:.2f}x (target >= 3x)")
    sixteenth = work / 16
    largest = {"longest run": max(ordered), "longest condition's evaluation": max(evaluation),
               "longest condition's figures": max(figures), **serial}
    for what, cost in largest.items():
        verdict = "within" if cost <= sixteenth else "ABOVE"
        print(f"  {what}: {cost:.1f} s, {verdict} a sixteenth of the total work ({sixteenth:.1f} s)")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
