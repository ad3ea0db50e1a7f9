"""Benchmark of the models on soil, one core (plain script, prints figures).

The single-wheel tester (the XZL at 23.3 kN, 1 m/s, slip 0.2) on LETE sand, the default
20 mm soil bed: for each model the times faster than real time (simulated / wall), at the
1 ms step and, for the models without their own dynamics, at 2 ms. Compilation, the bed
and the settling are excluded (one warm-up run first; each timed run is 10 s simulated,
its own settling timed apart and subtracted).

On level ground a straight rut is the same across the wheel, and the soil's pass computes
each distinct node state of a row once (:mod:`tyrelab.road.soil.wheel`); the rows marked
"paving" lay the soil over the Belgian paving instead, where a row's nodes differ from
block to block and the rut follows the blocks.

    NUMBA_NUM_THREADS=1 python benchmarks/bench_soil.py
"""

from __future__ import annotations

import os
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from tyrelab.rig.single_wheel import single_wheel  # noqa: E402
from tyrelab.road.tracks import belgian_paving  # noqa: E402
from tyrelab.tyre.library import load_tyre  # noqa: E402
from tyrelab.tyre.model import TyreModel  # noqa: E402

SOIL, LOAD, SPEED, SLIP, SIMULATED = "lete-sand", 23.3e3, 1.0, 0.2, 10.0


def wall(model, duration, dt, road=None):
    t = time.perf_counter()
    single_wheel(model, SOIL, LOAD, SPEED, slip=SLIP, duration=duration, dt=dt, progress=False,
                 road=road)
    return time.perf_counter() - t


def main():
    tyre = load_tyre()
    paving = belgian_paving()
    cases = [("rigid", {}, 1e-3, None), ("rigid", {}, 2e-3, None), ("point", {}, 1e-3, None),
             ("point", {}, 2e-3, None), ("rigid", {}, 1e-3, paving), ("point", {}, 1e-3, paving),
             ("ring", {"n_segments": 100, "n_blocks": 10}, 1e-3, None), ("ring-tp", {}, 1e-3, None)]
    print(f"{'model':<10}{'options':<38}{'ground':<8}{'step':>8}{'x real time':>14}")
    for name, options, dt, road in cases:
        model = TyreModel(tyre, name, options=options)
        wall(model, 0.05, dt, road)                         # compile
        setup = wall(model, dt, dt, road)                   # the bed and the settling alone
        run = wall(model, SIMULATED, dt, road) - setup
        ground = "paving" if road else "level"
        print(f"{name:<10}{str(options or '-'):<38}{ground:<8}{dt * 1e3:>6g}ms"
              f"{SIMULATED / run:>13.1f}x")


if __name__ == "__main__":
    main()
