"""tyrelab.study runner and store on a real Dask LocalCluster with worker processes.

Three short trailer runs (a few seconds each with a warm compile cache) are
computed by 2 worker processes, resumed, and recomputed by 1 worker; the
stored tables must equal an in-process run bit for bit (the simulations are
deterministic, so neither the transport nor the number of workers may
change a value).
"""

from __future__ import annotations

import json

import distributed  # noqa: F401 -- a required dependency: missing, this file fails, never skips
import numpy as np
import pandas as pd
import pytest

import tyrelab
from tyrelab.study.runner import KernelWaves, run_tasks
from tyrelab.study.store import Store


def _task(key, model, road, speed_kmh):
    kwargs = dict(model=model, road=road, speed=speed_kmh / 3.6, load="LC1", duration=1.5)
    return {"key": key, "spec": {"model": model, "road": road, "speed_kmh": speed_kmh},
            "simulate": kwargs, "kernels": model}


TASKS = [_task("a1", "point", "cleat:50x50", 12), _task("b2", "point", "step:30", 18),
         _task("c3", "volume", "cleat:50x50", 12)]


def _same(a: pd.DataFrame, b: pd.DataFrame) -> bool:
    return list(a.columns) == list(b.columns) and all(
        np.array_equal(a[c].to_numpy(), b[c].to_numpy()) for c in a.columns)


@pytest.fixture(scope="module")
def two_workers(tmp_path_factory):
    """The study computed by 2 workers in two goes: the first run, then the rest (every channel
    stored exactly: the tables are compared whole)."""
    store = Store(tmp_path_factory.mktemp("two") / "study", storage="lossless")
    first = run_tasks(TASKS[:1], store, workers=2, progress=False)
    rest = run_tasks(TASKS, store, workers=2, progress=False)
    return store, first, rest


def test_resume_computes_only_the_rest(two_workers):
    store, first, rest = two_workers
    assert first == {"computed": 1, "skipped": 0, "failed": 0}
    assert rest == {"computed": 2, "skipped": 1, "failed": 0}
    index = pd.read_parquet(store.folder / "index.parquet")
    assert sorted(index["key"]) == ["a1", "b2", "c3"]
    assert set(index["status"]) == {"done"}
    assert (index["simulated_s"] > 1.4).all()


def test_stored_tables_equal_an_in_process_run(two_workers):
    store, _, _ = two_workers
    for task in TASKS:
        direct = tyrelab.simulate(**task["simulate"], progress=False)
        assert _same(store.signal(task["key"]), direct), task["key"]


def test_one_worker_gives_identical_results(two_workers, tmp_path):
    store2, _, _ = two_workers
    store1 = Store(tmp_path / "one", storage="lossless")
    assert run_tasks(TASKS, store1, workers=1, progress=False)["computed"] == 3
    for task in TASKS:
        assert _same(store1.signal(task["key"]), store2.signal(task["key"])), task["key"]


def test_failed_run_recorded_and_others_go_on(tmp_path):
    store = Store(tmp_path / "s")
    bad = _task("bad", "point", "cleat:50x50", 12)
    bad["simulate"]["road"] = "no-such-road"
    counts = run_tasks([bad, TASKS[1]], store, workers=2, progress=False)
    assert counts == {"computed": 1, "skipped": 0, "failed": 1}
    rec = store.record("bad")
    assert rec["status"] == "failed" and "no-such-road" in rec["error"]
    assert not store.signal_path("bad").exists()
    # a failed run is tried again on the next run of the study (and fails again here)
    assert run_tasks([bad, TASKS[1]], store, workers=1, progress=False) == \
        {"computed": 0, "skipped": 1, "failed": 1}


def test_a_run_that_leaves_the_models_physics_is_named_kept_and_marked(tmp_path):
    """A 100 x 300 mm cleat at 60 km/h throws the trailer's wheel off the road for 0.8 s: in
    the worker, simulate warns (PhysicsWarning), where no user sees which run it was. The
    warning comes back with the run: issued again here naming the run, kept in its record
    and the index, and marked in the report's run matrix and listed under it."""
    from tyrelab.report.study_sections import run_matrix
    from tyrelab.study.runner import RunWarning
    store = Store(tmp_path / "s")
    hop = {"key": "hop", "spec": {"tyre": "xzl", "model": "OPC lk", "test": "big cleat",
                                  "road": "cleat:100x300", "speed_kmh": 60.0, "load": "LC1"},
           "simulate": dict(model="point", road="cleat:100x300", speed=60 / 3.6, load="LC1",
                            duration=1.5), "kernels": "point"}
    with pytest.warns(RunWarning) as caught:
        counts = run_tasks([hop, TASKS[1]], store, workers=2, progress=False)
    assert counts == {"computed": 2, "skipped": 0, "failed": 0}
    said = [str(w.message) for w in caught]
    assert len(said) == 1, said                         # the step run is within the physics
    assert said[0].startswith("run xzl, OPC lk, big cleat, 60 km/h, LC1: the test wheel left "
                              "the road for ")
    record = store.record("hop")["warnings"]
    assert record == said[0].split(": ", 1)[1] and store.record("b2")["warnings"] == ""
    index = pd.read_parquet(store.folder / "index.parquet")
    assert list(index.loc[index["key"] == "hop", "warnings"]) == [record]
    html = run_matrix(index)
    assert "class='warned'" in html and "&#9888;" in html
    assert "Runs with warnings (1)" in html and "left the road" in html.split("warned-runs")[1]


def test_a_record_without_its_table_is_not_finished(tmp_path):
    """What a killed study can leave -- a record saying done whose table is gone, a stale
    temporary file -- is not a result."""
    store = Store(tmp_path / "s")
    store.record_path("a1").write_text(json.dumps({"key": "a1", "status": "done"}))
    (store.runs / ".tyrelab-abc.part").write_text("half a table")
    assert not store.is_finished("a1")
    store = Store(tmp_path / "s")  # reopening removes the stale temporary file
    assert not list(store.runs.glob("*.part"))


#: a scheduler that has not written its file after this long [s] is stuck (a bound on a hang)
SCHEDULER_START = 300.0


def _scheduler_address(info, proc) -> str:
    """The address in the scheduler file, once the file is complete.

    distributed writes the file in place (``open(.., "w")`` then ``json.dump``), so it can be
    seen empty or half written: it is read until it parses as the scheduler's identity with
    its address, the process still running."""
    import time
    end = time.monotonic() + SCHEDULER_START
    while time.monotonic() < end:
        assert proc.poll() is None, f"the scheduler exited ({proc.returncode}) before writing {info}"
        try:
            ident = json.loads(info.read_text())
        except (FileNotFoundError, json.JSONDecodeError):
            ident = None
        if isinstance(ident, dict) and ident.get("type") == "Scheduler" and \
                str(ident.get("address", "")).startswith("tcp://127.0.0.1:"):
            return ident["address"]
        time.sleep(0.1)
    raise AssertionError(f"no complete scheduler file {info} after {SCHEDULER_START:g} s")


def test_external_scheduler_gives_the_same_tables(two_workers, tmp_path):
    """--scheduler: a separately started Dask scheduler and worker (the commands the README
    gives for a cluster, here on the loopback address) compute the same tables."""
    import subprocess
    import sys

    info = tmp_path / "scheduler.json"
    bindir = [sys.executable, "-m", "distributed.cli.dask_scheduler"]
    sched = subprocess.Popen(bindir + ["--host", "127.0.0.1", "--port", "0", "--dashboard-address", ":0",
                                       "--scheduler-file", str(info)],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    worker = None
    try:
        address = _scheduler_address(info, sched)
        worker = subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address,
                                   "--nworkers", "1", "--nthreads", "1", "--no-dashboard"],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        store = Store(tmp_path / "remote", storage="lossless")
        assert run_tasks(TASKS[:2], store, scheduler=address, progress=False)["computed"] == 2
        reference, _, _ = two_workers
        for task in TASKS[:2]:
            assert _same(store.signal(task["key"]), reference.signal(task["key"])), task["key"]
    finally:
        for proc in (worker, sched):
            if proc is not None:
                proc.terminate()
                proc.wait(timeout=30)


def test_unreachable_scheduler_is_one_clear_error(tmp_path):
    """--scheduler at an address where nothing listens: an InputError naming the address
    and the option, within the connect timeout, and no run recorded."""
    from tyrelab.errors import InputError
    store = Store(tmp_path / "s")
    with pytest.raises(InputError) as info:
        run_tasks(TASKS[:1], store, scheduler="tcp://127.0.0.1:9", progress=False, connect_timeout=3)
    assert "tcp://127.0.0.1:9" in str(info.value) and "--scheduler" in str(info.value)
    assert not list(store.runs.glob("*.json"))


def test_a_spec_given_as_text_is_kept_with_its_results(tmp_path):
    """run() copies the spec into the results folder (spec.toml, study.json) also when it was
    parsed from a string in Python, so Study(folder) reads the same spec back."""
    from tyrelab.study import Study, _keep_spec
    from tyrelab.study.spec import example_spec, parse_spec
    spec = parse_spec(example_spec(), base=tmp_path)
    store = Store(tmp_path / "out")
    _keep_spec(spec, store)
    assert (store.folder / "spec.toml").read_text() == example_spec()
    again = Study(store.folder).spec
    assert again.runs() == spec.runs() and again.run_keys() == spec.run_keys()


def test_a_stop_asked_for_while_no_run_finishes_ends_the_wait(tmp_path):
    """A signal's exception can be swallowed by one of the client's callbacks (it runs in
    the main thread as they do); the handler also records the stop (tyrelab.stop), and the
    runner's wait polls it. Here nothing raises at all: the stop is only recorded, before the
    wait starts -- the wait ends, as on Ctrl-C, instead of waiting for the run, and the store
    holds no finished run. (Recording it first, not from a timer, keeps the outcome free of
    timing: a timer raced a short run on a warm cache and lost.)"""
    from tyrelab import stop

    store = Store(tmp_path / "study")
    stop.request(15)
    try:
        with pytest.raises(KeyboardInterrupt, match="signal 15"):
            run_tasks([_task("long", "point", "flat", 12)], store, workers=1, progress=False)
    finally:
        stop.clear()
    assert not store.is_finished("long")
    assert not list(store.runs.glob("*.json"))


def _play(tasks, slots):
    """A cluster of ``slots`` workers running what :class:`KernelWaves` releases, each task for
    its ``cost`` [s], the highest cost first among those submitted (Dask's priority); returns
    the (start, end, task) of every run and, per kind, how many runs started before the
    first run of the kind ended (each such run compiles the kind's kernels cold)."""
    import heapq
    waves = KernelWaves(tasks, slots)
    queued = list(waves.release())
    running, log, now = [], [], 0.0
    while queued or running:
        queued.sort(key=lambda t: -t["cost"])
        while queued and len(running) < slots:
            task = queued.pop(0)
            heapq.heappush(running, (now + task["cost"], task["key"], task))
            log.append([now, None, task])
        # no worker idles while a task waits for its kind's kernels
        assert len(running) == slots or not waves.waiting
        now, _, task = heapq.heappop(running)
        next(e for e in log if e[2] is task)[1] = now
        queued += waves.release(task)
    cold = {}
    for kind in {t["kernels"] for t in tasks}:
        first_end = min(e[1] for e in log if e[2]["kernels"] == kind)
        cold[kind] = sum(e[0] < first_end for e in log if e[2]["kernels"] == kind)
    return log, cold


def test_a_cold_cache_is_filled_once_per_kind_of_kernel():
    """The thesis campaign's shape (4 kinds, the ring's the longest runs: the ring and ring-tp
    share one kind, the enveloping model and its edge variant another) on 2 and 4 workers:
    every kind's first run ends before another run of its kind starts, every run runs once,
    and (asserted inside) no worker waits while runs do. With one kind and 3 workers the
    workers are not left idle: all three start at once; with as many slots as runs (a running
    scheduler's) nothing waits."""
    costs = {("ring", "ring"): 20.0, ("ring-tp", "ring"): 21.0, ("enveloping", "envelope"): 3.0,
             ("edge", "envelope"): 2.5, ("volume", "volume"): 1.7, ("point", "point"): 0.8}
    tasks = [{"key": f"{model}{i}", "kernels": kind, "cost": cost * (1 + 0.01 * i)}
             for (model, kind), cost in costs.items() for i in range(10)]
    kinds = {kind for _, kind in costs}
    for slots in (2, 4):
        log, cold = _play(tasks, slots)
        assert sorted(e[2]["key"] for e in log) == sorted(t["key"] for t in tasks)
        assert cold == {kind: 1 for kind in kinds}, slots
    log, cold = _play([t for t in tasks if t["kernels"] == "point"], 3)
    assert [e[0] for e in log[:3]] == [0.0, 0.0, 0.0] and cold == {"point": 3}
    # a running scheduler's workers may not share this disk: every run goes at once
    log, _ = _play(tasks, len(tasks))
    assert all(e[0] == 0.0 for e in log)


def test_runs_share_a_kind_exactly_when_their_wheels_compile_alike():
    """``kernel_kind`` labels runs by the compiled code they need. In the thesis campaign (one
    tyre, the trailer, a point left wheel, no soil) two runs get one label exactly when numba
    types their test wheels alike (the type the rig's loop is compiled for), whatever the
    road, speed or load: the ring and ring-tp share one, as do the enveloping model and its
    edge variant; the stiffness law, a value, splits none."""
    import numba

    from tyrelab.road.spec import road_from_spec
    from tyrelab.study import tasks
    from tyrelab.study.spec import builtin_spec
    from tyrelab.tyre.library import load_tyre
    from tyrelab.tyre.model import TyreModel

    labels = {}
    for t in tasks(builtin_spec()):
        labels.setdefault(t["spec"]["contact"], set()).add(t["kernels"])
    assert all(len(v) == 1 for v in labels.values()), labels  # one label per model
    grid = road_from_spec("cleat:50x50").grid()
    tyre = load_tyre("xzl-16.00R20", 300e3)
    types = {c: numba.typeof(TyreModel(tyre, contact=c).wheel(grid, 30e3)) for c in labels}
    assert len(types) == 6
    for a in labels:
        for b in labels:
            assert (labels[a] == labels[b]) == (types[a] == types[b]), (a, b)
    roads = {t["spec"]["road"] for t in tasks(builtin_spec()) if t["spec"]["contact"] == "ring"}
    assert len(roads) > 3  # one kind spans every road it runs on


def _worker_start():
    import os
    import signal
    import sys
    ignored = signal.getsignal(signal.SIGINT) is signal.SIG_IGN
    return os.getppid(), ignored, "tyrelab.study.evaluate" in sys.modules


def test_local_workers_are_forked_from_one_server_with_sigint_ignored():
    """The local cluster's workers are forked from one server process that has imported the
    runner and the evaluation (multiprocessing's forkserver: a process's clusters pay the
    imports once, not each worker of each cluster; a worker started afresh imports the
    evaluation only when it evaluates), and they ignore SIGINT, so that Ctrl-C reaches only
    the study's own process (test_study_cli's Ctrl-C test shows what that process then does)."""
    import os

    from tyrelab.study.runner import _client, _close

    parents = []
    for _ in range(2):  # two clusters one after the other, as a notebook's two studies
        client, cluster = _client(None, 2)
        try:
            starts = client.run(_worker_start)  # on every worker, as it is when it starts
        finally:
            _close(client, cluster, None)
        assert len(starts) == 2
        assert all(ignored and preloaded for _, ignored, preloaded in starts.values())
        parents += [parent for parent, _, _ in starts.values()]
    assert len(set(parents)) == 1 and parents[0] != os.getpid()  # one server, not this process


def test_the_time_left_is_never_shown_negative():
    """The last run's cost sum leaves a rounding residue (-1e-15 s of work): "about 0 s left",
    not "about -0 s left" as the bar said."""
    from tyrelab.study.runner import _minutes
    assert _minutes(-1e-15) == "0 s"
    assert _minutes(89.0) == "89 s" and _minutes(150.0) == "2 min"
