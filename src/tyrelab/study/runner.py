"""Running a study's simulations on Dask: one run per task, results into the store.

A *task* is a plain dict: ``key`` (the run's store key), ``spec`` (the
columns its record and the index carry) and ``simulate`` (the keyword
arguments of :func:`tyrelab.simulate`, SI units). Workers compute the
signal table and send it back; only this process writes the store, so a
cluster whose workers do not share its disk works as well as a local one.
After the runs, a study's evaluation and its report's figures read the store on the
workers of its local cluster (``then``: they share its disk); with a running scheduler
they are made in this process.

Execution: a :class:`distributed.LocalCluster` of worker *processes*, one
thread each (numba kernels hold the GIL-free core for themselves), as many
as cores by default; or a running scheduler (``tcp://HOST:8786``). Each
worker compiles (or loads from the disk cache, :mod:`tyrelab.core.jit_cache`)
a model's kernels at its first run of that model and keeps them for the
rest; :class:`KernelWaves` orders the submissions so that each kind of kernel is
compiled by one worker while the others run other kinds. A run that raises
is recorded with its error; a worker that dies is recorded the same way
(Dask's ``KilledWorker``); the other runs go on. The warnings a run raises in its
worker (a :class:`~tyrelab.guards.PhysicsWarning`: airborne, rim contact ...) are
sent back with it, kept in its record (``warnings``, one per line) and issued again
here as a :class:`RunWarning` naming the run, so a user sees which run left the
models' physics (a worker's own stderr would show them without the run).
Ctrl-C cancels the runs in flight and stops the cluster; finished runs
stay in the store. The simulations are deterministic, so the results do
not depend on the number of workers or the order in which runs finish.
"""

from __future__ import annotations

import logging
import multiprocessing
import os
import signal
import threading
import time
import warnings
from contextlib import contextmanager

from .. import resources, stop
from ..errors import InputError
from .store import Store


class RunWarning(UserWarning):
    """A warning one of a study's runs raised in its worker, issued again where the study runs,
    with the run it came from."""


def execute(task: dict):
    """Run one task in a worker; returns ``("done", signal, wall time, warnings)`` or
    ``("failed", one-line error, wall time, warnings)``, ``warnings`` the messages of the
    warnings the run raised (each once, on one line)."""
    from ..api import simulate
    t0 = time.perf_counter()
    with kept_warnings() as caught:
        try:
            signal = simulate(**task["simulate"], progress=False)
        except Exception as exc:  # recorded, not raised: the other runs go on
            text = " ".join(str(exc).split()) or type(exc).__name__
            return "failed", f"{type(exc).__name__}: {text}", time.perf_counter() - t0, \
                warning_messages(caught)
    return "done", signal, time.perf_counter() - t0, warning_messages(caught)


@contextmanager
def kept_warnings():
    """Within it, every user warning is recorded, not shown, into the list it yields (a
    worker's: the run or row keeps them, :func:`warning_messages`)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", UserWarning)
        yield caught


def warning_messages(caught) -> list[str]:
    """The recorded user warnings' messages, each once, on one line."""
    return list(dict.fromkeys(" ".join(str(w.message).split()) for w in caught
                              if issubclass(w.category, UserWarning)))


def run_label(spec: dict) -> str:
    """A run in words, from its record: ``"run xzl, OPC lk, cleat 50x50, 12 km/h, LC1"`` (tyre,
    model, test, speed, load; a soil test's slip or driving torque)."""
    parts = [str(spec[k]) for k in ("tyre", "model", "test") if spec.get(k) not in (None, "")]
    if spec.get("test") in (None, "") and spec.get("road"):
        parts.append(str(spec["road"]))
    if spec.get("speed_kmh") is not None:
        parts.append(f"{float(spec['speed_kmh']):g} km/h")
    if spec.get("load") not in (None, ""):
        parts.append(str(spec["load"]))
    if spec.get("slip") is not None:
        parts.append(f"s = {float(spec['slip']):g}")
    if spec.get("torque") is not None:
        parts.append(f"T = {float(spec['torque']):g} N m")
    return "run " + ", ".join(parts)


def _client(scheduler: str | None, workers: int | None, connect_timeout: float = 30.0):
    """A Dask client and the cluster it owns (None for an external scheduler)."""
    from distributed import Client, LocalCluster
    if scheduler:
        try:
            return Client(scheduler, timeout=connect_timeout), None
        except (OSError, TimeoutError, ValueError) as exc:
            raise InputError(f"cannot reach a Dask scheduler at '{scheduler}' within "
                             f"{connect_timeout:g} s ({type(exc).__name__}); expected the address a "
                             "running 'dask scheduler' prints, e.g. tcp://host:8786",
                             field="--scheduler") from None
    # one per core by default, and never more than the machine's memory holds (limits)
    n = (resources.check_local_workers(workers) if workers is not None
         else min(os.cpu_count() or 1, resources.max_local_workers()))
    # the worker processes start with SIGINT ignored (an ignored signal stays ignored across
    # exec, and Python then installs no KeyboardInterrupt handler): Ctrl-C in a terminal
    # reaches the whole process group, and only this process should answer it, by
    # cancelling the runs and closing the cluster, not every worker with a traceback
    main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main_thread else None
    try:
        # silence_logs: the workers' own log lines stay off the terminal; at ERROR a worker
        # whose scheduler closes under it (a study stopped by SIGTERM or Ctrl-C) printed a
        # heartbeat traceback (CommClosedError) before "tyrelab: terminated". A run's own
        # failure reaches the study through its future, and is recorded
        with _forked_workers():
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                   dashboard_address=":0", silence_logs=logging.CRITICAL)  # any port
    finally:
        if main_thread:
            signal.signal(signal.SIGINT, previous)
    return Client(cluster), cluster


#: what the server that forks the local workers imports once (:func:`_forked_workers`): the
#: runner, whose tasks the workers run, and the evaluation they run after the runs
WORKER_PRELOAD = ["distributed", __name__, "tyrelab.study.evaluate"]


def _forked_workers():
    """A Dask configuration under which a local cluster's worker processes are forked from one
    server process that has imported :data:`WORKER_PRELOAD` once (multiprocessing's
    ``forkserver`` start method), not each started as a new interpreter (``spawn``, Dask's
    default), where it exists (not on Windows).

    Why: a new interpreter imports distributed, pandas, numba and tyrelab before its first run,
    1.2-1.5 s of one core per worker; a forked one starts in milliseconds. Measured on 2 cores,
    a cluster of 2 workers started, ran a task that imports tyrelab and closed in 1.7-2.3 s
    spawned, and in 0.15 s forked once the server was up (the server's own start, once per
    process: 2.1 s). So a study's start costs about the same, and a process that runs several
    studies (a notebook, the tests) pays the imports once. The workers start from the same
    modules as before, in a fresh process each (their kernels are loaded from the disk cache
    at their first run, as before); only this process's working folder, ``sys.path`` and
    main module reach them (multiprocessing's preparation data), not environment variables
    changed after the server started: tyrelab reads none in a worker but the cache folder's,
    and a worker that used the first one's still loads and saves the same kernels.

    A worker is still started with SIGINT ignored (:func:`_client`): the server inherits the
    disposition when the first cluster starts it, and gives it to every process it forks
    (``multiprocessing.forkserver`` restores its own start's signal handlers in each child).
    So a process whose first cluster starts outside its main thread, where :func:`_client`
    leaves SIGINT alone, has workers that take SIGINT for the rest of its life."""
    import dask

    if "forkserver" not in multiprocessing.get_all_start_methods():
        return dask.config.set({})
    config = dask.config.set({"distributed.worker.multiprocessing-method": "forkserver"})
    from distributed.utils import get_mp_context

    # distributed sets its own preload list at its first call (the packages it uses); ours
    # replaces it, until the server starts (it starts once, at the first worker)
    get_mp_context().set_forkserver_preload(WORKER_PRELOAD)
    return config


def _minutes(seconds: float) -> str:
    if not seconds == seconds:  # NaN: nothing finished yet
        return "?"
    seconds = max(seconds, 0.0)   # the last run's rounding leaves -1e-15 of cost: not "-0 s"
    return f"{seconds / 60:.0f} min" if seconds >= 90 else f"{seconds:.0f} s"


#: a finished study of at most this many tasks calls ``then`` (its evaluation) in this
#: process: starting a cluster for it costs more than the work
SMALL_STUDY = 40


def run_tasks(tasks: list[dict], store: Store, workers: int | None = None,
              scheduler: str | None = None, progress: bool = True,
              connect_timeout: float = 30.0, then=None) -> dict:
    """Compute every task whose run is not finished in ``store``; then, with ``then``, call
    ``then(client)`` on the same cluster before it closes (the study's evaluation: the
    client of a local cluster, None for a running scheduler, whose workers may not share
    this process's disk). With every run finished already, a cluster is started for
    ``then`` only when there are more than :data:`SMALL_STUDY` tasks (else None).

    Parameters
    ----------
    tasks : list of dict
        As in the module docstring; keys must be unique.
    store : Store
    workers : int, optional
        Worker processes of the local cluster (default: one per core).
    scheduler : str, optional
        Address of a running Dask scheduler; ``workers`` is then ignored.
    progress : bool
        A progress bar over runs (on stderr), with the estimated time left.
    connect_timeout : float
        Seconds to wait for an external scheduler (InputError when it does not answer).

    Returns
    -------
    dict
        ``{"computed": n, "skipped": n, "failed": n}``.
    """
    todo = [t for t in tasks if not store.is_finished(t["key"])]
    counts = {"computed": 0, "skipped": len(tasks) - len(todo), "failed": 0}
    if not todo:
        if then is not None:
            if scheduler or len(tasks) <= SMALL_STUDY:
                then(None)
            else:
                _on_cluster(then, workers)
        return counts
    from distributed import as_completed
    from tqdm import tqdm
    client, cluster = _client(scheduler, workers, connect_timeout)
    futures = {}
    interrupted = False
    # the time left is estimated from the runs' expected costs, not from their count: the
    # longest runs go first, so a count-based estimate would start far too high
    total_cost = sum(t.get("cost", 0.0) for t in todo) or 1.0
    done_cost = 0.0
    t_start = time.perf_counter()
    bar = tqdm(total=len(todo), unit="run", disable=not progress, desc="study",
               bar_format="{desc}: {percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} runs "
                          "[{elapsed}{postfix}]")
    try:
        # the longest runs first (Dask runs higher priorities first), so that no long run
        # starts last and leaves the other workers idle; pure=False: a rerun of a study
        # computes again what the store lacks
        waves = KernelWaves(todo, _slots(cluster, todo))

        def submit(batch):
            return {client.submit(execute, t, key=f"tyrelab-run-{t['key']}", pure=False,
                                  priority=t.get("cost", 0.0)): t for t in batch}

        futures = submit(waves.release())
        finished = as_completed(futures)
        for future in completed(finished):
            task = futures[future]
            more = submit(waves.release(task))
            futures.update(more)
            for f in more:
                finished.add(f)
            key = task["key"]
            try:
                status, result, wall, notes = future.result()
            except Exception as exc:  # the worker died (KilledWorker) or the task was lost
                status, result, wall, notes = "failed", f"{type(exc).__name__}: {exc}", 0.0, []
            if status == "done":
                store.save(key, task["spec"], result, wall, notes)
                counts["computed"] += 1
            else:
                store.save_failure(key, task["spec"], result, wall, notes)
                counts["failed"] += 1
            for note in notes:
                warnings.warn(f"{run_label(task['spec'])}: {note}", RunWarning, stacklevel=2)
            done_cost += task.get("cost", 0.0)
            elapsed = time.perf_counter() - t_start
            left = elapsed * (total_cost - done_cost) / done_cost if done_cost > 0 else float("nan")
            bar.set_postfix_str(f"about {_minutes(left)} left, {counts['failed']} failed", refresh=False)
            bar.update(1)
            future.release()
        bar.close()
        if then is not None:
            then(client if cluster is not None else None)
    except KeyboardInterrupt:
        interrupted = True
        for f in futures:
            f.cancel()
        raise
    finally:
        bar.close()
        _close(client, cluster, CLOSE_TIMEOUT if interrupted else None)
        store.write_index()
    return counts


def _slots(cluster, todo: list[dict]) -> int:
    """How many runs :class:`KernelWaves` keeps in flight: the local cluster's worker threads;
    with a running scheduler every run at once (its workers may sit on other machines,
    whose compile caches are not this one's, and may join later)."""
    if cluster is None:
        return max(len(todo), 1)
    return sum(w.nthreads for w in cluster.workers.values()) or 1


class KernelWaves:
    """When each task goes to the cluster, so that a cold compile cache is filled once per
    kernel, not once per worker.

    A run compiles its model's kernels at its first use in a worker process, or loads them
    from the disk cache (:mod:`tyrelab.core.jit_cache`) if another process has saved them:
    a ring on soil compiles for about 40 s, a trailer loop for 4-16 s. Submitted all at once,
    the longest runs first, every worker of a fresh install started on the same model and
    compiled the same kernels at the same time (the docs' example study on 2 workers compiled
    the ring on soil twice, 50 s each). So the first run of each *kind* (``task["kernels"]``:
    runs of one kind share their compiled code) goes first; the other runs of a kind wait
    until one of its runs has finished (its kernels are then in the disk cache) -- unless a
    worker would otherwise sit idle, when the costliest waiting run goes at once (it then waits
    on the kernel's compile lock, :mod:`tyrelab.core.jit_cache`, and loads the code instead of
    compiling it a second time). With a warm cache this only reorders runs while every worker
    is busy. Tasks without a kind never wait; with ``slots`` as many as the tasks (a running
    scheduler, :func:`_slots`) none does.
    """

    def __init__(self, tasks: list[dict], slots: int):
        self.slots = slots
        self.in_flight = 0
        self.waiting = sorted(tasks, key=lambda t: -t.get("cost", 0.0))  # costliest first
        self.started: set = set()   # kinds with a run submitted
        self.compiled: set = set()  # kinds with a run finished

    def release(self, finished: dict | None = None) -> list[dict]:
        """The tasks to submit now: at the start (``finished`` None), or after ``finished``."""
        if finished is not None:
            self.in_flight -= 1
            self.compiled.add(finished.get("kernels"))
        out, held = [], []
        for task in self.waiting:
            kind = task.get("kernels")
            if kind is None or kind in self.compiled or kind not in self.started:
                self.started.add(kind)
                out.append(task)
            else:
                held.append(task)
        while held and self.in_flight + len(out) < self.slots:  # no worker idle
            out.append(held.pop(0))
        self.waiting = held
        self.in_flight += len(out)
        return out


def _on_cluster(then, workers: int | None) -> None:
    """``then(client)`` on a local cluster of its own, closed after (stopped: promptly)."""
    client, cluster = _client(None, workers)
    interrupted = False
    try:
        then(client)
    except KeyboardInterrupt:
        interrupted = True
        raise
    finally:
        _close(client, cluster, CLOSE_TIMEOUT if interrupted else None)


def completed(finished, poll: float = 0.2):
    """The futures of ``finished`` (a distributed ``as_completed``) as they finish, checking
    between them for a stop a signal asked for (:func:`tyrelab.stop.check`): the exception the
    signal raised may have been swallowed by a callback of the client's (tyrelab.stop)."""
    while True:
        stop.check()
        batch = finished.next_batch(block=False)
        if batch:
            yield from batch
        elif finished.is_empty():
            return
        else:
            time.sleep(poll)


#: how long a stopped study waits for the cluster to close [s]: a worker may be inside a
#: compiled loop that cannot be interrupted (a ring run on a track, half a minute and more on a
#: busy machine); its process is a daemon, ended when this one exits
CLOSE_TIMEOUT = 10.0


def _close(client, cluster, timeout: float | None) -> None:
    """Close the client and the local cluster; stopped (``timeout`` given), do not wait longer,
    and keep what the scheduler logs while it closes under its client off the terminal (the
    cluster restores the log level it silenced as it closes, and a scheduler whose client
    has gone logs a traceback: "... already closed")."""
    quiet = _Quiet() if timeout is not None else None
    try:
        if timeout is None:
            client.close()
            if cluster is not None:
                cluster.close()
        else:
            client.close(timeout=timeout)
            if cluster is not None:
                cluster.close(timeout=timeout)
    except (TimeoutError, OSError):
        if timeout is None:
            raise
    finally:
        if quiet is not None:
            quiet.restore()


class _Quiet:
    """Drops every record reaching the handlers of the ``distributed`` and root loggers
    until :meth:`restore`."""

    def __init__(self):
        self.handlers = [*logging.getLogger("distributed").handlers, *logging.getLogger().handlers]
        for h in self.handlers:
            h.addFilter(self._drop)

    @staticmethod
    def _drop(record) -> bool:
        return False

    def restore(self) -> None:
        for h in self.handlers:
            h.removeFilter(self._drop)
