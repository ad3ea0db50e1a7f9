"""Benchmark of the models on soil, one core (plain script, prints figures).

The single-wheel tester (the XZL at 23.3 kN, 1 m/s, slip 0.2) on LETE sand, the default
20 mm soil bed: for each model the times faster than real time (simulated / wall), at the
1 ms step and, for the models without their own dynamics, at 2 ms. Compilation, the bed
and the settling are excluded (one warm-up run first; each timed run is 10 s simulated,
its own settling timed apart and subtracted).

    NUMBA_NUM_THREADS=1 python benchmarks/bench_soil.py
"""

from __future__ import annotations

import os
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from tyrelab.rig.single_wheel import single_wheel  # noqa: E402
from tyrelab.tyre.library import load_tyre  # noqa: E402
from tyrelab.tyre.model import TyreModel  # noqa: E402

SOIL, LOAD, SPEED, SLIP, SIMULATED = "lete-sand", 23.3e3, 1.0, 0.2, 10.0


def wall(model, duration, dt):
    t = time.perf_counter()
    single_wheel(model, SOIL, LOAD, SPEED, slip=SLIP, duration=duration, dt=dt, progress=False)
    return time.perf_counter() - t


def main():
    tyre = load_tyre()
    cases = [("rigid", {}, 1e-3), ("rigid", {}, 2e-3), ("point", {}, 1e-3), ("point", {}, 2e-3),
             ("ring", {"n_segments": 100, "n_blocks": 10}, 1e-3), ("ring-tp", {}, 1e-3)]
    print(f"{'model':<10}{'options':<34}{'step':>8}{'x real time':>14}")
    for name, options, dt in cases:
        model = TyreModel(tyre, name, options=options)
        wall(model, 0.05, dt)                               # compile
        setup = wall(model, dt, dt)                         # the bed and the settling alone
        run = wall(model, SIMULATED, dt) - setup
        print(f"{name:<10}{str(options or '-'):<34}{dt * 1e3:>6g}ms{SIMULATED / run:>13.1f}x")


if __name__ == "__main__":
    main()
