"""Running a compiled rig loop in chunks, with a progress bar, into a signal table."""

from __future__ import annotations

import sys
import time

import numpy as np

from ..road.grid import RoadGrid
from ..signal import signal_from_array

#: runs expected to take longer than this [s] show a progress bar by default
PROGRESS_AFTER = 2.0


def run_chunks(advance, n_steps: int, out_every: int, n_channels: int, dt: float,
               progress: bool | None = None, chunk_time: float = 0.5) -> np.ndarray:
    """Call ``advance(n, out, row) -> row`` until ``n_steps`` steps are done.

    The compiled loop runs in chunks of ``chunk_time`` simulated seconds so a
    progress bar (tqdm, on stderr) can follow long runs; no Python code runs
    per time step. Returns the filled output array.
    """
    n_out = (n_steps - 1) // out_every + 1 if n_steps > 0 else 0
    out = np.zeros((n_out, n_channels))
    per_chunk = max(out_every, int(round(chunk_time / dt)) // out_every * out_every)
    bar = None
    done = 0
    row = 0
    started = time.perf_counter()
    try:
        while done < n_steps:
            n = min(per_chunk, n_steps - done)
            row = advance(n, out, row)
            done += n
            if bar is None and progress is not False and done < n_steps:
                elapsed = time.perf_counter() - started
                expected = elapsed * n_steps / done
                if progress or (expected > PROGRESS_AFTER and sys.stderr.isatty()):
                    from tqdm import tqdm
                    bar = tqdm(total=n_steps * dt, unit="s sim", desc="simulating", file=sys.stderr,
                               bar_format="{l_bar}{bar}| {n:.1f}/{total:.1f} s simulated "
                                          "[{elapsed}<{remaining}]")
                    bar.update(done * dt)
            elif bar is not None:
                bar.update(n * dt)
    finally:  # an interrupt too: the bar's line is left, not redrawn after the message
        if bar is not None:
            bar.close()
    return out[:row]


def levelled_grid(road, x0: float, y0: float = 0.0):
    """The road's grid shifted in height so the run starts at height zero.

    A rig stands on level ground at z = 0 (the trailer's hitch and left
    wheel, the quarter vehicle's start); measured roads (OpenCRG) carry
    absolute heights, so the road under test is levelled to its height at
    the start of the run.
    """
    grid = road.grid()
    offset = float(grid.height(x0, y0))
    if offset == 0.0:
        return grid
    return RoadGrid(grid.x0, grid.y0, grid.dx, grid.dy, grid.z - offset)


def drop_road(road, lift: float, duration: float):
    """The road of a drop test, after checking its ``lift`` [m] and ``duration`` [s]."""
    from ..errors import InputError
    from ..road.spec import road_from_spec
    if not (np.isfinite(lift) and lift >= 0):
        raise InputError(f"lift must be a number of metres >= 0, got {lift}", field="lift")
    if not (np.isfinite(duration) and duration > 0):
        raise InputError(f"duration must be a positive number of seconds, got {duration}",
                         field="duration")
    return road_from_spec(road)


class SimulationError(RuntimeError):
    """A run produced a non-finite value, a negative normal force or one no tyre carries."""


#: a normal force beyond this many times the static wheel load is no tyre's: the run diverged.
#: (The XZL 16.00R20 reaches its rim at 15.7 times its LC1 load; a stiff soil's or tyre's
#: explicit step that is too long threw the single wheel 330 m up in 1 ms after a
#: 7.9e8 kN push, and it flew on with finite numbers.)
DIVERGED_LOAD_FACTOR = 100.0
#: ... times the static load, or this one [N] when that is lighter: a tyre barely touching
#: the road (the ring with tread blocks under a 1 N load) rings to some hundred newtons
#: while it settles, a hundred times 1 N and no divergence
DIVERGED_LOAD_FLOOR = 1e3


def to_signal(data: np.ndarray, channels, metadata: dict):
    """Wrap a rig's output array as a signal table, refusing NaN or tension.

    A model must never hand out a NaN or a negative normal force; if one
    does, this stops the run with an error instead of writing it.
    """
    if not np.all(np.isfinite(data)):
        bad = [c for k, c in enumerate(channels) if not np.all(np.isfinite(data[:, k]))]
        raise SimulationError(f"the simulation diverged (non-finite {', '.join(bad)}); "
                              "try a smaller time step")
    load = float(metadata.get("static_wheel_load_N") or 0.0)
    for name in ("FZW", "FZ_LEFT"):
        if name not in channels or not len(data):
            continue
        fz = data[:, list(channels).index(name)]
        if np.any(fz < 0):
            raise SimulationError(f"negative normal force in {name}")
        k = int(np.argmax(fz))
        if load > 0 and fz[k] > DIVERGED_LOAD_FACTOR * max(load, DIVERGED_LOAD_FLOOR):
            t = data[k, list(channels).index("RUNTIME")] if "RUNTIME" in channels else float("nan")
            raise SimulationError(f"the simulation diverged (normal force {name} {fz[k] / 1e3:.4g} kN "
                                  f"at t = {t:.4g} s, {fz[k] / load:.3g} times the static wheel load "
                                  f"{load / 1e3:.4g} kN; no tyre carries more than "
                                  f"{DIVERGED_LOAD_FACTOR:g} times)")
    return signal_from_array(data, channels, metadata)
