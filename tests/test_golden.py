"""Behaviour that a refactor must not change: today's traces against the golden ones.

The files in ``tests/data/golden`` were recorded by ``tools/golden.py record``
before the wheel interface was rebuilt (commit "Golden traces ..."): every
contact model on the trailer over the 50 mm cleat, the oblique cleat, the
first 20 m of Belgian paving and a step at LC1 and LC3, handling models,
the quarter vehicle and the static press. Each channel must agree to 1e-9
of its largest magnitude. The ring's cases take minutes and are ``slow``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import golden  # noqa: E402

CASES = list(golden.all_cases())


def _marks(name):
    return [pytest.mark.slow] if "-ring" in name else []


@pytest.mark.parametrize("name,fn,args", [pytest.param(*c, id=c[0], marks=_marks(c[0]))
                                          for c in CASES])
def test_golden_trace(name, fn, args):
    ref = np.load(golden.GOLDEN / f"{name}.npz")
    got = fn(args)
    for channel in ref.files:
        assert golden.relative_difference(got[channel], ref[channel]) <= 1e-9, channel
