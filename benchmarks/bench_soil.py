"""Benchmark of the models on soil, one core (plain script, prints figures).

The single-wheel tester (the XZL at 23.3 kN, 1 m/s, slip 0.2) on LETE sand, the default
20 mm soil bed: for each model the times faster than real time (simulated / wall), at the
1 ms step and, for the models without their own dynamics, at 2 ms. Compilation, the bed
and the settling are excluded (one warm-up run first; each timed run is 10 s simulated,
its own settling timed apart and subtracted).

On level ground a straight rut is the same across the wheel, and the soil's pass computes
each distinct node state of a row once (:mod:`tyrelab.road.soil.wheel`); the rows marked
"paving" lay the soil over the Belgian paving instead, where a row's nodes differ from
block to block and the rut follows the blocks; "dozing": LETE sand that bulldozes (angle
of repose 55 deg, Chrono's demo values otherwise).

    NUMBA_NUM_THREADS=1 python benchmarks/bench_soil.py
"""

from __future__ import annotations

import os
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from tyrelab.rig.single_wheel import single_wheel  # noqa: E402
from tyrelab.road.soil import load_soil  # noqa: E402
from tyrelab.road.soil.params import bulldozing_from_table  # noqa: E402
from tyrelab.road.tracks import belgian_paving  # noqa: E402
from tyrelab.tyre.library import load_tyre  # noqa: E402
from tyrelab.tyre.model import TyreModel  # noqa: E402

SOIL, LOAD, SPEED, SLIP, SIMULATED = "lete-sand", 23.3e3, 1.0, 0.2, 10.0


def wall(model, duration, dt, road=None, soil=SOIL):
    t = time.perf_counter()
    single_wheel(model, soil, LOAD, SPEED, slip=SLIP, duration=duration, dt=dt, progress=False,
                 road=road)
    return time.perf_counter() - t


def main():
    tyre = load_tyre()
    paving = belgian_paving()
    dozing = bulldozing_from_table(load_soil(SOIL)[0], {"erosion_angle": 55.0})
    cases = [("rigid", {}, 1e-3, None, SOIL), ("rigid", {}, 2e-3, None, SOIL),
             ("point", {}, 1e-3, None, SOIL), ("point", {}, 2e-3, None, SOIL),
             ("rigid", {}, 1e-3, paving, SOIL), ("point", {}, 1e-3, paving, SOIL),
             ("rigid", {}, 1e-3, None, dozing), ("point", {}, 1e-3, None, dozing),
             ("ring", {"n_segments": 100, "n_blocks": 10}, 1e-3, None, SOIL),
             ("ring-tp", {}, 1e-3, None, SOIL)]
    print(f"{'model':<10}{'options':<38}{'ground':<12}{'step':>8}{'x real time':>14}")
    for name, options, dt, road, soil in cases:
        model = TyreModel(tyre, name, options=options)
        wall(model, 0.05, dt, road, soil)                   # compile
        setup = wall(model, dt, dt, road, soil)             # the bed and the settling alone
        run = wall(model, SIMULATED, dt, road, soil) - setup
        ground = ("paving" if road else "level") + (" dozing" if soil is dozing else "")
        print(f"{name:<10}{str(options or '-'):<38}{ground:<12}{dt * 1e3:>6g}ms"
              f"{SIMULATED / run:>13.1f}x")


if __name__ == "__main__":
    main()
