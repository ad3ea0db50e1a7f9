"""The ring's faster contact evaluation changes no result and keeps its speed: facts that could fail.

* :func:`~tyrelab.road.grid.road_penetration`, which the tread strips now
  sample with (the gradient only below the road), gives exactly the height
  and gradient of :func:`~tyrelab.road.grid.road_height_gradient`, on the
  Belgian paving and on a small rough grid, inside and beyond its edges;
* the ring's force step (:func:`~tyrelab.tyre.ring.kernel.ring_kick`, with
  the tread contact inlined) is compiled without reference counting: no
  ``NRT_incref``/``NRT_decref`` in its code (with them the trailer on the
  Belgian paving took about a quarter longer, docs/ring.md "Performance").
"""

import re

import numba as nb
import numpy as np
import pytest

from tyrelab.road.grid import RoadGrid, road_height_gradient, road_penetration
from tyrelab.road.spec import road_from_spec


def _small_grid():
    # odd sizes, 7 mm x 13 mm spacing, rough heights
    rng = np.random.default_rng(4)
    return RoadGrid(-0.3, -0.2, 0.007, 0.013, rng.normal(0.0, 0.01, (77, 41))).surface()


@pytest.mark.parametrize("which", ["paving", "small"])
def test_road_penetration_is_road_height_gradient_exactly(which):
    if which == "paving":
        road = road_from_spec("belgian-paving").grid().surface()
        xs = np.random.default_rng(1).uniform(4.0, 106.0, 3000)  # past both ends too
        ys = np.random.default_rng(2).uniform(-2.3, 2.3, 3000)   # and past the sides
    else:
        road = _small_grid()
        xs = np.random.default_rng(3).uniform(-0.5, 0.5, 3000)
        ys = np.random.default_rng(4).uniform(-0.4, 0.7, 3000)
    zq = np.random.default_rng(5).uniform(-0.03, 0.03, xs.size)
    below = 0
    for x, y, z in zip(xs, ys, zq):
        h, gx, gy = road_height_gradient(road, x, y)
        p, h2, gx2, gy2 = road_penetration(road, x, y, z)
        assert h2 == h and p == h - z
        if p > 0.0:
            below += 1
            assert (gx2, gy2) == (gx, gy)
        else:
            assert (gx2, gy2) == (0.0, 0.0)
    assert 0.1 * xs.size < below < 0.9 * xs.size      # both branches were tried


def test_ring_kick_is_compiled_without_reference_counting():
    from tyrelab.road.obstacles import Flat
    from tyrelab.tyre.library import load_tyre
    from tyrelab.tyre.model import TyreModel
    from tyrelab.tyre.ring.kernel import ring_kick
    from tyrelab.tyre.wheel import pose

    model = TyreModel(load_tyre("xzl-16.00R20", 300e3), contact="ring",
                      options={"n_segments": 40, "n_blocks": 2})
    wheel = model.wheel(Flat().grid(), 30e3)
    # a fresh compile of the same function with the same options (a cached one has no IR)
    options = {k: v for k, v in ring_kick.targetoptions.items() if k != "nopython"}
    fresh = nb.njit(**options)(ring_kick.py_func)
    fresh(wheel.contact, wheel.state, wheel.road,
          pose(0.0, 0.0, 0.75, velocity=(3.0, 0.0, 0.0), omega=4.0),
          0.0, 0.0, 0.0, 0.0, 1e-4, 0.01)
    llvm = fresh.inspect_llvm(fresh.signatures[0])
    bodies = {}
    for f in llvm.split("\ndefine ")[1:]:
        bodies[re.match(r'[^@]*@"?([^"(\s]+)', f).group(1)] = f
    # the function itself, not its Python or C wrappers
    ours = [f for name, f in bodies.items()
            if "ring_kick" in name and "cpython" not in name and not name.startswith("cfunc")]
    assert len(ours) == 1, sorted(bodies)
    assert ours[0].count("@NRT_incref") == 0 and ours[0].count("@NRT_decref") == 0
