"""Benchmark of the flexible ring model on one core (plain script, prints figures).

The towed trailer with the ring model on both wheels over the 50 mm cleat at
12 km/h (thesis 5.2), rig step 1 ms, for several numbers of belt segments
and tread blocks per segment. Prints the internal (sub-)step, the wall time
per simulated second and the real-time factor (wall / simulated; < 1 is
faster than real time). Compilation is excluded (one warm-up run first).

    NUMBA_NUM_THREADS=1 python benchmarks/bench_ring.py [--quick]
"""

from __future__ import annotations

import os
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from tyrelab.rig.trailer import Trailer  # noqa: E402
from tyrelab.tyre.model import TyreModel  # noqa: E402
from tyrelab.road.obstacles import Flat  # noqa: E402
from tyrelab.tyre.library import load_tyre  # noqa: E402

SPEED = 12 / 3.6
ROAD = "cleat:50x50"
# the wheel reaches the cleat (x = 5 m) after 1.5 s; simulate across it
DURATION = 3.0


def run(n_segments, n_blocks, contact="ring", duration=DURATION, pressure=300e3):
    tyre = load_tyre("xzl-16.00R20", pressure)
    model = TyreModel(tyre, contact=contact,
                      options={"n_segments": n_segments, "n_blocks": n_blocks})
    trailer = Trailer(model, "LC1")
    trailer.run(ROAD, SPEED, 0.01)  # warm-up: compilation, initial state
    t0 = time.perf_counter()
    table = trailer.run(ROAD, SPEED, duration)
    wall = time.perf_counter() - t0
    return wall, model.contact_params(Flat().grid()).max_step, table


def main(argv=None):
    quick = "--quick" in (argv or sys.argv[1:])
    cases = [(100, 10)] if quick else [(50, 10), (100, 5), (100, 10), (100, 20), (150, 10),
                                        (200, 10)]
    print(f"trailer, {ROAD}, {SPEED * 3.6:.0f} km/h, rig step 1 ms, {DURATION:.1f} s simulated, "
          "ring model on both wheels, one core")
    print(f"{'segments':>8} {'blocks':>6} {'substep_us':>10} {'wall_s':>7} {'RT_factor':>9} "
          f"{'FZW_max_kN':>10}")
    for n, nb in cases:
        wall, step, table = run(n, nb)
        print(f"{n:8d} {nb:6d} {step * 1e6:10.1f} {wall:7.2f} {wall / DURATION:9.3f} "
              f"{table['FZW'].max() / 1e3:10.1f}")
    wall, step, table = run(100, 10, contact="ring-tp")
    print(f"ring-tp  100 x 10: substep {step * 1e6:.1f} us, RT factor {wall / DURATION:.3f}")


if __name__ == "__main__":
    main()
