"""Speed of the contact models on the towed trailer (plain script, prints figures).

    python benchmarks/bench_contact.py [point volume enveloping]

For each contact model: the XZL 16.00R20 at 300 kPa, load case LC1, towed at
12 km/h over the 50 mm cleat and over the 100 m Belgian paving track, one
core. Reported: simulated seconds per wall-clock second ("x real time"),
after a warm-up run that compiles (or loads from cache) the kernels. The
road grid is built before timing. Targets (issue): >= 100x for volume
contact, >= 50x for enveloping contact with 10 x 15 cams.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from tyrelab.rig.trailer import Trailer
from tyrelab.road.base import Road
from tyrelab.road.grid import RoadGrid
from tyrelab.road.obstacles import Cleat
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.library import load_tyre

SPEED = 12 / 3.6


class _Gridded(Road):
    """A road whose grid is built once (so timing sees only the simulation)."""

    def __init__(self, road):
        self._road = road
        self._grid = road.grid()
        self.name = road.name

    def height(self, x, y):
        return self._road.height(x, y)

    def extent(self):
        return self._road.extent()

    def varies_in_y(self):
        return self._road.varies_in_y()

    def grid(self, spacing=None) -> RoadGrid:
        return self._grid


def belgian_paving():
    try:
        from tyrelab.road.tracks import TRACKS
        return TRACKS["belgian-paving"]()
    except (ImportError, KeyError):  # fallback: a seeded random block road
        rng = np.random.default_rng(1)

        class Blocks(Road):
            name = "random blocks (fallback)"
            default_spacing = (0.01, 0.01)
            tops = rng.normal(0.0, 0.01, (800, 40))

            def height(self, x, y):
                i = np.clip(((np.asarray(x) - 5.0) / 0.134).astype(int), 0, 799)
                j = np.clip(((np.asarray(y) + 2.0) / 0.1).astype(int), 0, 39)
                return self.tops[i, j]

            def extent(self):
                return (4.5, 112.0, -2.0, 2.0)

        return Blocks()


def run(model, road, duration):
    tyre = load_tyre("xzl-16.00R20", 300e3)
    trailer = Trailer(TyreModel(tyre, model), "LC1")
    trailer.run(road, SPEED, 0.2)  # compile / load the cached kernels
    t0 = time.perf_counter()
    df = trailer.run(road, SPEED, duration)
    wall = time.perf_counter() - t0
    return duration / wall, df


def main(models):
    roads = [("cleat 50x50 mm", _Gridded(Cleat(0.05, 0.05)), 10.0),
             ("Belgian paving 100 m", _Gridded(belgian_paving()), 105.0 / SPEED)]
    print(f"{'model':<12} {'road':<22} {'x real time':>12} {'peak FZW [kN]':>14}")
    for model in models:
        for name, road, duration in roads:
            rate, df = run(model, road, duration)
            print(f"{model:<12} {name:<22} {rate:12.1f} {df['FZW'].max() / 1e3:14.2f}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or ["point", "volume", "enveloping"])
