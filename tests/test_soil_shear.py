"""A soil node's shear under sliding (:func:`tyrelab.road.soil.scm.mobilized_shear`).

Three facts with their own references: sliding one way, the shear follows Janosi &
Hanamoto's curve ``1 - exp(-j / K)`` (1961); sliding back, Dahl's law ``dm = (dj - m |dj|) / K``
(1968), solved by hand from the turn, puts the shear's reversal at ``K ln(1 + m)``; and a
cycle of sliding forth and back costs work (the loop's area), where an elastic reading of
Janosi's curve, ``sign(j)(1 - exp(-|j| / K))``, gives it all back.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tyrelab.road.soil.scm import mobilized_shear

K = 0.0115          # LETE sand's Janosi modulus [m]


def _slide(m, steps):
    """The mobilized shear after sliding by each ``(dc, da)`` of ``steps`` in turn, and every
    state on the way."""
    path = [m]
    for dc, da in steps:
        m = mobilized_shear(m[0], m[1], dc, da, K)
        path.append(m)
    return np.array(path)


@pytest.mark.parametrize("direction", [(1.0, 0.0), (-1.0, 0.0), (0.6, -0.8)])
def test_sliding_one_way_is_janosi_and_hanamotos_curve(direction):
    """5 cm slid in 500 unequal steps along one direction: |m| = 1 - exp(-j / K) at every step,
    to 1e-12, pointing along the sliding."""
    rng = np.random.default_rng(3)
    lengths = rng.uniform(0.0, 2e-4, 500)
    e = np.array(direction)
    path = _slide((0.0, 0.0), [tuple(e * d) for d in lengths])
    j = np.r_[0.0, np.cumsum(lengths)]
    np.testing.assert_allclose(path, np.outer(1.0 - np.exp(-j / K), e), rtol=0, atol=1e-12)


@pytest.mark.parametrize("first", [0.2 * K, K, 5.0 * K])
def test_sliding_back_the_shear_reverses_after_k_ln_1_plus_m(first):
    """Slid forwards by ``first``, then back in small steps: the shear passes through zero
    after ``K ln(1 + m)`` of sliding back (m its value at the turn), Dahl's law solved by
    hand, to the step; the elastic reading would need all of ``first``."""
    m_turn = 1.0 - math.exp(-first / K)
    step = 1e-6
    path = _slide(_slide((0.0, 0.0), [(first, 0.0)])[-1], [(-step, 0.0)] * int(2 * first / step))
    back = step * int(np.argmax(path[:, 0] <= 0.0))
    assert back == pytest.approx(K * math.log(1.0 + m_turn), abs=step)
    assert back < first
    assert np.all(np.abs(path[:, 0]) < 1.0) and not path[:, 1].any()


def test_a_cycle_of_sliding_costs_work_that_the_elastic_reading_gives_back():
    """Forth by 2 K and back to the start, along a ring of directions too: the work of the
    shear stress on the node, sum(m . dj) (per unit strength), is positive over the cycle (by
    hand for the 1-D loop, Masing-like: from m* = 1 - exp(-2) the way back ends at
    m = -1 + (1 + m*) exp(-2)); the elastic reading's is zero, to rounding."""
    n = 4000
    d = 2.0 * K / n
    steps = [(d, 0.0)] * n + [(-d, 0.0)] * n
    path = _slide((0.0, 0.0), steps)
    mid = 0.5 * (path[:-1] + path[1:])                     # the midpoint rule on each step
    work = float(np.sum(mid[:, 0] * np.array(steps)[:, 0]))
    j = np.r_[np.arange(n + 1), np.arange(n - 1, -1, -1)] * d
    elastic = 1.0 - np.exp(-j / K)
    elastic_work = float(np.sum(0.5 * (elastic[:-1] + elastic[1:]) * np.diff(j)))
    assert abs(elastic_work) < 1e-12
    m_star = 1.0 - math.exp(-2.0)
    assert path[-1, 0] == pytest.approx(-1.0 + (1.0 + m_star) * math.exp(-2.0), abs=1e-12)
    # by hand: forth, K (2 - m*); back, -K [(1 + m*)(1 - exp(-2)) - 2]
    by_hand = K * (2.0 - m_star) - K * ((1.0 + m_star) * (1.0 - math.exp(-2.0)) - 2.0)
    assert work == pytest.approx(by_hand, rel=1e-6) and work > 0.1 * K
    # in the plane: round a square of side K, back where it started
    side = [(K / 500, 0.0)] * 500 + [(0.0, K / 500)] * 500 + [(-K / 500, 0.0)] * 500 + [(0.0, -K / 500)] * 500
    path = _slide((0.0, 0.0), side)
    mid = 0.5 * (path[:-1] + path[1:])
    assert float(np.sum(mid * np.array(side))) > 0.1 * K
    assert np.all(np.hypot(path[:, 0], path[:, 1]) < 1.0)


def _bed():
    from tyrelab.road.grid import RoadGrid
    from tyrelab.road.soil import load_soil
    from tyrelab.road.soil.scm import soil_bed
    return soil_bed(load_soil("lete-sand")[0], RoadGrid(-1.0, -1.0, 0.02, 0.02, np.zeros((11, 11))))


def test_a_tread_block_on_soil_shears_in_series_with_it():
    """A tread block on the soil (:func:`~tyrelab.road.soil.terrain.soil_shear`), pressed with
    4 kN over 0.002 m^2 (2 MPa): a block far stiffer than the soil, slid 3 cm one way, has
    Janosi & Hanamoto's force ``A (c + sigma tan phi)(1 - exp(-j / K))`` against the sliding,
    to 1e-9; a block of 5e7 Pa/m takes its first 1 um at the series stiffness
    ``A / (K / tau_max + 1 / k)``, to 1e-4; and a block whose own friction bounds it below
    the soil's strength is held at that bound once slid far (50 cm)."""
    from tyrelab.road.soil.terrain import soil_shear
    bed = _bed()
    soil = bed.soil
    fn, area = 4000.0, 0.002
    tau_max = soil.cohesion + fn / area * math.tan(soil.friction_angle)
    m, j = (0.0, 0.0), 0.0
    for d in np.full(300, 1e-4):
        own, f1, f2, *m = soil_shear(bed, 0.0, 0.0, fn, area, m[0], m[1], d, 0.0, 1e30, 1e30)
        j += d
        assert own and f2 == 0.0
        assert f1 == pytest.approx(-area * tau_max * (1.0 - math.exp(-j / soil.janosi_k)), rel=1e-9)
    k = 5e7
    _, f1, _, _, _ = soil_shear(bed, 0.0, 0.0, fn, area, 0.0, 0.0, 1e-6, 0.0, k, 1e30)
    assert -f1 / 1e-6 == pytest.approx(area / (soil.janosi_k / tau_max + 1.0 / k), rel=1e-4)
    limit = 0.3 * area * tau_max
    _, f1, f2, _, _ = soil_shear(bed, 0.0, 0.0, fn, area, 0.0, 0.0, 0.3, -0.4, k, limit)
    assert math.hypot(f1, f2) == pytest.approx(limit, rel=1e-6) and f2 / f1 == pytest.approx(-4 / 3)
