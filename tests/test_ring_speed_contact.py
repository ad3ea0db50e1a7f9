"""The ring's faster contact evaluation changes no result and keeps its speed: facts that could fail.

* :func:`~tyrelab.road.grid.road_penetration`, which the tread strips now
  sample with (the gradient only below the road) and which
  :func:`~tyrelab.road.grid.road_height_gradient` calls, gives the height and
  gradient of an independent bilinear interpolation written here in numpy
  (edge extension: flat beyond the grid), on the Belgian paving and on a
  small rough grid, inside and beyond its edges;
* the ring's force step (:func:`~tyrelab.tyre.ring.kernel.ring_kick`, with
  the tread contact inlined) is compiled without reference counting: no
  ``NRT_incref``/``NRT_decref`` in the code a run executes, read from the
  kernel as the process loaded it (from the compile cache, where numba keeps
  the optimised LLVM module beside the object code; until 2026-11-27 the test
  compiled a second copy for its IR, 6-10 s of every suite run). With them the
  trailer on the Belgian paving took about a quarter longer (docs/ring.md
  "Performance").
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


def _bilinear(road, x, y):
    """Height and gradient of the bilinear surface through the grid nodes, flat beyond it."""
    z = road.z
    u = np.clip((x - road.x0) / road.dx, 0.0, z.shape[0] - 1)
    v = np.clip((y - road.y0) / road.dy, 0.0, z.shape[1] - 1)
    i = np.minimum(np.floor(u).astype(int), z.shape[0] - 2)
    j = np.minimum(np.floor(v).astype(int), z.shape[1] - 2)
    a, b = u - i, v - j
    z00, z10, z01, z11 = z[i, j], z[i + 1, j], z[i, j + 1], z[i + 1, j + 1]
    h = z00 * (1 - a) * (1 - b) + z10 * a * (1 - b) + z01 * (1 - a) * b + z11 * a * b
    gx = ((z10 - z00) * (1 - b) + (z11 - z01) * b) / road.dx
    gy = ((z01 - z00) * (1 - a) + (z11 - z10) * a) / road.dy
    inside_x = ((x - road.x0) / road.dx > 0) & ((x - road.x0) / road.dx < z.shape[0] - 1)
    inside_y = ((y - road.y0) / road.dy > 0) & ((y - road.y0) / road.dy < z.shape[1] - 1)
    return h, np.where(inside_x, gx, 0.0), np.where(inside_y, gy, 0.0)


@pytest.mark.parametrize("which", ["paving", "small"])
def test_road_penetration_is_the_bilinear_surface(which):
    if which == "paving":
        road = road_from_spec("belgian-paving").grid().surface()
        xs = np.random.default_rng(1).uniform(4.0, 106.0, 3000)  # past both ends too
        ys = np.random.default_rng(2).uniform(-2.3, 2.3, 3000)   # and past the sides
    else:
        road = _small_grid()
        xs = np.random.default_rng(3).uniform(-0.5, 0.5, 3000)
        ys = np.random.default_rng(4).uniform(-0.4, 0.7, 3000)
    zq = np.random.default_rng(5).uniform(-0.03, 0.03, xs.size)
    h_ref, gx_ref, gy_ref = _bilinear(road, xs, ys)
    scale = np.abs(road.z).max()
    below = 0
    for x, y, z, h, gx, gy in zip(xs, ys, zq, h_ref, gx_ref, gy_ref):
        p, h2, gx2, gy2 = road_penetration(road, x, y, z)
        assert h2 == pytest.approx(h, abs=1e-12 * scale) and p == h2 - z
        h3, gx3, gy3 = road_height_gradient(road, x, y)    # the gradient everywhere
        assert h3 == h2 and (gx3, gy3) == pytest.approx((gx, gy), abs=1e-12 * scale / road.dx)
        if p > 0.0:
            below += 1
            assert (gx2, gy2) == (gx3, gy3)
        else:
            assert (gx2, gy2) == (0.0, 0.0)
    assert 0.1 * xs.size < below < 0.9 * xs.size      # both branches were tried


def test_ring_kick_is_compiled_without_reference_counting():
    """Read in the code a user's run executes: the kernel's library as this process got it
    (loaded from the compile cache, or compiled here when the cache is cold). Its module
    for linking is the optimised LLVM module the machine code was made from, which numba
    keeps beside the object code in the cache for callers to inline
    (``_get_module_for_linking``: numba-internal, as ``_nrt`` is; the numba range they were
    tested on is pinned, ``test_the_numba_range_pinned_is_the_range_tested_and_installed``)."""
    from tyrelab.road.obstacles import Flat
    from tyrelab.tyre.library import load_tyre
    from tyrelab.tyre.model import TyreModel
    from tyrelab.tyre.ring.kernel import ring_kick
    from tyrelab.tyre.wheel import pose

    model = TyreModel(load_tyre("xzl-16.00R20", 300e3), contact="ring",
                      options={"n_segments": 40, "n_blocks": 2})
    wheel = model.wheel(Flat().grid(), 30e3)
    args = (wheel.contact, wheel.state, wheel.road,
            pose(0.0, 0.0, 0.75, velocity=(3.0, 0.0, 0.0), omega=4.0),
            0.0, 0.0, 0.0, 1e-4, 0.01)
    ring_kick(*args)
    library = ring_kick.overloads[tuple(nb.typeof(a) for a in args)].library
    llvm = str(library._get_module_for_linking())
    bodies = {}
    for f in llvm.split("\ndefine ")[1:]:
        bodies[re.match(r'[^@]*@"?([^"(\s]+)', f).group(1)] = f
    # the function itself, not its Python or C wrappers
    ours = [f for name, f in bodies.items()
            if "ring_kick" in name and "cpython" not in name and not name.startswith("cfunc")]
    assert len(ours) == 1, sorted(bodies)
    assert ours[0].count("@NRT_incref") == 0 and ours[0].count("@NRT_decref") == 0
