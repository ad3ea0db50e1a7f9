"""Benchmark of the flexible ring model on one core (plain script, prints figures).

The towed trailer over the 50 mm cleat at 12 km/h (thesis 5.2) and over
100 m of Belgian paving at 18 km/h, rig step 1 ms, for several numbers of
belt segments and tread blocks per segment, with the ring on both wheels
and with the point model (same vertical law) on the left wheel (as the study
campaign runs every model: one ring per trailer, so that column is the cost
of one ring). Prints the
internal step, the wall time per simulated second (wall / simulated: < 1 is
faster than real time, 0.2 is five times faster) and the wall time per
internal step and segment, which says how the cost grows with the
discretisation. Compilation and the rigs' equilibrium search are excluded
(one warm-up run first).

    NUMBA_NUM_THREADS=1 python benchmarks/bench_ring.py [--quick]
"""

from __future__ import annotations

import os
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from tyrelab.rig.trailer import Trailer  # noqa: E402
from tyrelab.road.obstacles import Flat  # noqa: E402
from tyrelab.tyre.library import load_tyre  # noqa: E402
from tyrelab.tyre.model import TyreModel  # noqa: E402

#: (road, speed [m/s], simulated time [s]): the cleat is reached after 1.5 s
CLEAT = ("cleat:50x50", 12 / 3.6, 3.0)
PAVING = ("belgian-paving", 18 / 3.6, 100.0 / (18 / 3.6))


def run(n_segments, n_blocks, case=CLEAT, contact="ring", left=None, pressure=300e3):
    """Wall time [s] of one run, the internal step [s] and the signal table."""
    road, speed, duration = case
    tyre = load_tyre("xzl-16.00R20", pressure)
    model = TyreModel(tyre, contact=contact,
                      options={"n_segments": n_segments, "n_blocks": n_blocks})
    left_model = None if left is None else TyreModel(tyre, contact=left)
    trailer = Trailer(model, "LC1", left=left_model)
    trailer.run(road, speed, 0.01, progress=False)  # warm-up: compilation, equilibrium
    t0 = time.perf_counter()
    table = trailer.run(road, speed, duration, progress=False)
    wall = time.perf_counter() - t0
    return wall, model.contact_params(Flat().grid()).max_step, table


def main(argv=None):
    quick = "--quick" in (argv or sys.argv[1:])
    grid = [(100, 10)] if quick else [(50, 10), (100, 5), (100, 10), (100, 20), (150, 10),
                                       (200, 10)]
    print("trailer, LC1, rig step 1 ms, one core; RT = wall / simulated")
    print(f"{'segments':>8} {'blocks':>6} {'step_us':>7} {'cleat_RT':>8} {'paving_RT':>9} "
          f"{'cleat_RT_left_point':>19} {'paving_RT_left_point':>20} {'us_per_step_segment':>19}")
    for n, nb in grid:
        wall_c, step, _ = run(n, nb, CLEAT)
        wall_p, _, _ = run(n, nb, PAVING)
        wall_l, _, _ = run(n, nb, CLEAT, left="point")
        wall_pl, _, _ = run(n, nb, PAVING, left="point")  # one ring, as the campaign runs it
        steps = CLEAT[2] / step
        # both wheels carry a ring: two rings' internal steps per simulated step
        per = wall_c / steps / (2 * n) * 1e6
        print(f"{n:8d} {nb:6d} {step * 1e6:7.1f} {wall_c / CLEAT[2]:8.3f} {wall_p / PAVING[2]:9.3f} "
              f"{wall_l / CLEAT[2]:19.3f} {wall_pl / PAVING[2]:20.3f} {per:19.4f}")
    wall, step, _ = run(100, 10, CLEAT, contact="ring-tp")
    print(f"ring-tp 100 x 10 over the cleat: step {step * 1e6:.1f} us, RT {wall / CLEAT[2]:.3f}")
    wall, step, _ = run(100, 10, PAVING, contact="ring-tp", left="point")
    print(f"ring-tp 100 x 10 over the paving, point model on the left wheel: RT "
          f"{wall / PAVING[2]:.3f}")


if __name__ == "__main__":
    main()
