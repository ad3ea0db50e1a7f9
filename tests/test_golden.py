"""Behaviour that a refactor must not change: today's traces against the golden ones.

The files in ``tests/data/golden`` were recorded by ``tools/golden.py record``
before the wheel interface was rebuilt (commit "Golden traces ..."): every
contact model on the trailer over the 50 mm cleat, the oblique cleat, the
first 20 m of Belgian paving and a step at LC1 and LC3, handling models,
the quarter vehicle and the static press. Each channel must agree to 1e-9
of its largest magnitude (``golden.relative_difference``).

The ring's full-length trailer cases (2.5 s, and 6 s of paving, each) run with
the slow studies. By default the ring is guarded by its static press and by
:data:`SHORT_RING`: the same trailer runs cut to their first 2 s (the tyre
reaches the cleats and the step at about 1.4 s, its force peaks at 1.75-1.82 s;
6.7 m of the paving), the ring on the four roads at LC1, ring-tp on the cleat
and the paving at LC3. The short files (``*-2s.npz``) were recorded from the code of the commit
that added them, which is the frozen reference behaviour (every ring file recorded again on
2026-11-26 when the ring's internal step went from 1/6 to 1/4 ms, docs/ring.md "Why
1/4 ms": FZW peaks within 0.42 %, RMS within 0.05 %; and on 2026-11-27, from 1/4 to 1/3 ms,
"Why 1/3 ms": FZW peaks within 0.46 %, RMS within 0.08 %): they are a regression
guard, not a physical check (the ring's physics is tested in test_ring_rig,
test_ring_model and test_ring_integrator). They are also the first 2 s of the
full-length files recorded before them (checked below), so they guard what those
guard. ``python tests/test_golden.py record`` writes them again after a change
whose new behaviour is wanted, as ``tools/golden.py record`` does the others.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import golden  # noqa: E402

CASES = list(golden.all_cases())
#: the ring's short cases: (model, road, load case) -> the first 2 s of that trailer run
SHORT_RING = [*(("ring", road, "LC1") for road in ("cleat", "oblique", "step", "paving")),
              *(("ring-tp", road, "LC3") for road in ("cleat", "paving"))]
SHORT_DURATION = 2.0


def short_cases():
    for model, road, load in SHORT_RING:
        yield (f"trailer-{model}-{road}-{load}-2s", golden.run_case,
               dict(model=model, road=golden.ROADS[road][0], load=load, duration=SHORT_DURATION))


def _marks(name):
    return [pytest.mark.slow] if name.startswith("trailer-ring") else []


@pytest.mark.parametrize("name,fn,args", [pytest.param(*c, id=c[0], marks=_marks(c[0]))
                                          for c in CASES] + [pytest.param(*c, id=c[0])
                                                             for c in short_cases()])
def test_golden_trace(name, fn, args):
    ref = np.load(golden.GOLDEN / f"{name}.npz")
    got = fn(args)
    for channel in ref.files:
        assert golden.relative_difference(got[channel], ref[channel]) <= 1e-9, channel


def test_short_ring_traces_are_the_start_of_the_full_ones():
    """A short file is no new behaviour: its samples are the full-length golden trace's first
    2 s (same run, cut), to the same 1e-9; so the short files guard what the full ones do."""
    for name, _, args in short_cases():
        short = np.load(golden.GOLDEN / f"{name}.npz")
        full = np.load(golden.GOLDEN / f"{name.removesuffix('-2s')}.npz")
        for channel in short.files:
            n = short[channel].size
            assert n == round(SHORT_DURATION * 1000)
            assert golden.relative_difference(full[channel][:n], short[channel]) <= 1e-9, (name, channel)


def test_no_kernel_is_compiled_with_fastmath():
    """The golden traces hold on any x86-64 only if no kernel lets LLVM fuse multiply-adds or
    reassociate sums (numba's ``fastmath``): those results depend on the CPU's floating-point
    features. (The cams' row search had it until 2026-11-26: 5 % faster, 4e-12 off.)"""
    import importlib
    import pkgutil

    from numba.core.dispatcher import Dispatcher

    import tyrelab

    flagged, kernels = [], 0
    for info in pkgutil.walk_packages(tyrelab.__path__, "tyrelab."):
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if isinstance(obj, Dispatcher) and obj.__module__ == info.name:
                kernels += 1
                if obj.targetoptions.get("fastmath"):
                    flagged.append(f"{info.name}.{name}")
    assert kernels > 100, kernels
    assert flagged == []


if __name__ == "__main__":
    if sys.argv[1:] != ["record"]:
        sys.exit("usage: python tests/test_golden.py record   (writes the short ring traces)")
    for name, fn, args in short_cases():
        np.savez_compressed(golden.GOLDEN / f"{name}.npz", **fn(args))
        print("recorded", name, flush=True)
