"""Road memory and compiled query speed (issue: roads, item 7).

Run ``python benchmarks/bench_road.py``. Prints, for 100 m x 4 m roads at
10 mm x 10 mm, the grid size and the peak memory while building it
(tracemalloc, which numpy reports to), then compiled bilinear height queries
per second on one core, for random points over the whole road and for
points walking along it as a contact patch does. Targets: <= 64 MB,
>= 20 million queries/s.
"""

from __future__ import annotations

import gc
import os
import sys
import time
import tracemalloc

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import numba as nb  # noqa: E402
import numpy as np  # noqa: E402

from tyrelab.road.grid import road_height_gradient, road_heights  # noqa: E402
from tyrelab.road.iso8608 import RandomRoad  # noqa: E402
from tyrelab.road.tracks import TRACKS  # noqa: E402

N_QUERIES = 20_000_000


def build(make):
    """(road, grid, peak MB while building) for a road factory."""
    gc.collect()
    tracemalloc.start()
    road = make()
    grid = road.grid()
    peak = tracemalloc.get_traced_memory()[1] / 1e6
    tracemalloc.stop()
    return road, grid, peak


@nb.njit(cache=True)
def _gradient_loop(road, xs, ys):
    acc = 0.0
    for k in range(xs.shape[0]):
        h, gx, gy = road_height_gradient(road, xs[k], ys[k])
        acc += h + gx + gy
    return acc


def rate(func, *args, repeat=3):
    """Best queries per second over ``repeat`` runs (after a warm-up that compiles)."""
    func(*args)
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        func(*args)
        best = min(best, time.perf_counter() - t)
    return N_QUERIES / best


def main() -> int:
    roads = {
        "belgian-paving": TRACKS["belgian-paving"],
        "fatigue-track": TRACKS["fatigue-track"],
        "ISO 8608 class D, 100 x 4 m": lambda: RandomRoad("D", 100.0, 4.0, (0.01, 0.01), seed=1),
        "corrugations-angled": TRACKS["corrugations-angled"],
    }
    print("road                              grid nodes      grid MB   peak MB while built")
    grids = {}
    for name, make in roads.items():
        road, grid, peak = build(make)
        grids[name] = grid
        print(f"{name:32s} {grid.z.shape[0]:6d} x {grid.z.shape[1]:4d} {grid.nbytes / 1e6:9.1f} {peak:12.1f}")

    g = grids["belgian-paving"]
    road, z = g.surface(), g.z
    x1 = g.x0 + g.dx * (z.shape[0] - 1)
    y1 = g.y0 + g.dy * (z.shape[1] - 1)
    rng = np.random.default_rng(0)
    out = np.empty(N_QUERIES)
    rand_x, rand_y = rng.uniform(g.x0, x1, N_QUERIES), rng.uniform(g.y0, y1, N_QUERIES)
    # a 300 mm x 300 mm patch of 10 x 10 points moving 1 mm per step along y = 0
    step = np.repeat(np.arange(N_QUERIES // 100) * 1e-3, 100) % (x1 - g.x0 - 1) + g.x0
    patch_x = step + np.tile(np.repeat(np.linspace(-0.15, 0.15, 10), 10), N_QUERIES // 100)
    patch_y = np.tile(np.tile(np.linspace(-0.15, 0.15, 10), 10), N_QUERIES // 100)
    print(f"\ncompiled queries on one core (numba {nb.__version__}), belgian-paving grid, "
          f"{N_QUERIES / 1e6:.0f} M points:")
    random_rate = rate(road_heights, road, rand_x, rand_y, out)
    patch_rate = rate(road_heights, road, patch_x, patch_y, out)
    gradient_rate = rate(_gradient_loop, road, patch_x, patch_y)
    print(f"  road_heights, random points        {random_rate / 1e6:7.1f} M/s")
    print(f"  road_heights, moving contact patch {patch_rate / 1e6:7.1f} M/s")
    print(f"  road_height_gradient, patch        {gradient_rate / 1e6:7.1f} M/s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
