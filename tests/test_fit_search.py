"""The coarse-to-fine least-squares search (tyrelab.fit.search) finds a known minimum to the
resolution asked, evaluating a bounded number of points per pass."""

import numpy as np
import pytest

from tyrelab.fit.search import POINTS, refine_minimum


def test_a_known_minimum_to_the_resolution_asked():
    calls = []

    def sse(x):
        calls.append(x.size)
        return (x - 0.3137) ** 2 + 0.1 * np.abs(x - 0.3137) ** 3
    assert refine_minimum(sse, 0.0, 1.0, 1e-7) == pytest.approx(0.3137, abs=1e-7)
    assert max(calls) == POINTS and len(calls) <= 8        # 201 points a pass, a handful of passes


def test_a_minimum_at_the_range_end_and_an_empty_range():
    assert refine_minimum(lambda x: x, 2.0, 3.0, 1e-6) == pytest.approx(2.0, abs=1e-6)
    assert refine_minimum(lambda x: -x, 2.0, 3.0, 1e-6) == pytest.approx(3.0, abs=1e-6)
    assert refine_minimum(lambda x: x, 5.0, 5.0, 1e-6) == 5.0
