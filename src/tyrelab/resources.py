"""The resources a request may use: its estimated memory and wall time, and a study's workers.

The two limits (:data:`MAX_MEMORY`, :data:`MAX_WALL_TIME`) guard against a request
that would exhaust the machine or run for hours by mistake; an explicit ``force=True``
(``--force`` on the command line) lifts them, where the physical bounds of
:mod:`tyrelab.limits` are hard. A local study cluster starts no more worker processes
than the machine's memory holds.

Estimates are rough (within a factor of about 3): enough to tell a typo
(``--dt 1e-9``, ``--speed 1e-9``) from a long but meant request.
"""

from __future__ import annotations

import math
import os

from .errors import InputError
from .limits import DYNAMIC_INTERNAL_STEP, check_count

#: largest memory one request may need before ``force`` [bytes]: 2 GiB, well inside a
#: workstation's memory, far above any run of the thesis campaign (a 100 m track at
#: 3 km/h at 1 kHz is 0.15 GB of output)
MAX_MEMORY = 2 * 1024 ** 3
#: longest estimated wall time of one request before ``force`` [s]: 10 min (the longest
#: runs of the thesis campaign, the ring on a 100 m track at 3 km/h, take about 2-3 min)
MAX_WALL_TIME = 600.0
#: memory one worker process of a local study cluster holds [bytes]: 0.5 GiB (measured: a
#: process that had imported tyrelab and run the ring, ring-tp and enveloping models held
#: 0.42-0.44 GB); a local cluster starts no more workers than the machine's memory holds
WORKER_MEMORY = 512 * 1024 ** 2
#: most worker processes a study's local cluster may have
MAX_WORKERS = 1024
#: cost of a contact model that states none (``ContactModel.cost``, the registry), analytic /
#: with its own dynamics [s per simulated s at 1 ms on one core]
ANALYTIC_COST, DYNAMIC_COST = 0.015, 1.0
#: columns of a run's output array (the trailer has 31, the quarter vehicle 34), rounded up
OUTPUT_CHANNELS = 36
#: copies of the output table a run holds at once (array, table, file buffers)
OUTPUT_COPIES = 3


def model_cost(model) -> float:
    """Wall time [s] per simulated second at a 1 ms step (rough) of a ``TyreModel`` or a
    registered ``ContactModel``: the cost the model states in the registry, else
    :data:`ANALYTIC_COST` or :data:`DYNAMIC_COST` by its kind."""
    contact = getattr(model, "contact_model", model)
    if contact.cost is not None:
        return contact.cost
    return DYNAMIC_COST if contact.has_state else ANALYTIC_COST


def run_wall_time(models, duration: float, dt: float) -> float:
    """Estimated wall time [s] of a run of ``duration`` [s] at step ``dt`` (rough).

    An analytic model costs the same per step, so its time grows as 1/dt; a model
    with its own dynamics advances in internal steps of about
    :data:`DYNAMIC_INTERNAL_STEP` (the ring's, at 100 segments), so only a rig step
    below that costs more.
    """
    total = 0.0
    for m in models:
        if m.has_state:
            total += model_cost(m) * duration * max(1.0, DYNAMIC_INTERNAL_STEP / dt)
        else:
            total += model_cost(m) * duration * (1e-3 / dt)
    return total


def run_memory(duration: float, dt: float, rate: float, grid_cells: int = 0) -> float:
    """Estimated peak memory [bytes] of a run: its output table and its road grid."""
    out_every = max(1, int(round(1.0 / (rate * dt))))
    n_steps = duration / dt
    samples = n_steps / out_every + 1
    return samples * OUTPUT_CHANNELS * 8 * OUTPUT_COPIES + grid_cells * 8 * 3


def grid_cells(road, spacing=None) -> int:
    """Nodes of ``road``'s grid at ``spacing`` (default its own), without building it."""
    g = getattr(road, "_grid", None)
    if g is not None and (spacing is None or tuple(spacing) == (g.dx, g.dy)):
        return int(g.z.size)
    dx, dy = spacing or road.default_spacing
    xmin, xmax, ymin, ymax = road.extent()
    nx = math.ceil((xmax - xmin) / dx - 1e-9) + 1
    ny = 2 if not road.varies_in_y() else math.ceil((ymax - ymin) / dy - 1e-9) + 1
    return int(nx) * int(ny)


def _size(nbytes: float) -> str:
    for unit, f in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6)):
        if nbytes >= f:
            return f"{nbytes / f:.3g} {unit}"
    return f"{nbytes / 1e3:.3g} kB"


def _time(seconds: float) -> str:
    if seconds >= 86400 * 2:
        return f"{seconds / 86400:.3g} days"
    if seconds >= 5400:
        return f"{seconds / 3600:.3g} h"
    if seconds >= 90:
        return f"{seconds / 60:.3g} min"
    return f"{seconds:.3g} s"


def check_resources(what: str, memory: float = 0.0, wall_time: float = 0.0, force: bool = False,
                    field: str | None = None, hint: str = "") -> None:
    """Refuse a request estimated to need more than MAX_MEMORY or MAX_WALL_TIME, unless ``force``."""
    if force:
        return
    extra = f"; {hint}" if hint else ""
    if memory > MAX_MEMORY:
        raise InputError(f"{what} needs about {_size(memory)} of memory, above the limit of "
                         f"{_size(MAX_MEMORY)}{extra}; pass --force (force=True) to run it anyway",
                         field=field)
    if wall_time > MAX_WALL_TIME:
        raise InputError(f"{what} would take about {_time(wall_time)}, above the limit of "
                         f"{_time(MAX_WALL_TIME)}{extra}; pass --force (force=True) to run it anyway",
                         field=field)


def machine_memory() -> int | None:
    """The machine's physical memory [bytes], None where the system does not say."""
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):  # no sysconf (Windows) or no such name
        return None


def max_local_workers(memory: int | None = None) -> int:
    """Most worker processes a local cluster may start on a machine with ``memory`` bytes
    (default: this machine's): one per :data:`WORKER_MEMORY`, 1 to :data:`MAX_WORKERS`."""
    memory = machine_memory() if memory is None else memory
    if memory is None:
        return MAX_WORKERS
    return max(1, min(MAX_WORKERS, int(memory // WORKER_MEMORY)))


def check_local_workers(n, field: str = "--workers", memory: int | None = None) -> int:
    """``n`` worker processes of a local cluster: a whole number from 1 to what the machine's
    memory holds (:func:`max_local_workers`), or InputError. 1000 workers on a 24 GB machine
    used to start until the machine ran out of memory."""
    n = check_count(n, field, 1, MAX_WORKERS, what="workers")
    memory = machine_memory() if memory is None else memory
    high = max_local_workers(memory)
    if n > high:
        raise InputError(f"{n} worker processes need about {_size(n * WORKER_MEMORY)} of memory "
                         f"({_size(WORKER_MEMORY)} each); this machine has {_size(memory)}: "
                         f"allowed 1 to {high}", field=field)
    return n
