"""The ring's contact-patch damping fitted to trailer cleat runs (thesis 4.5's
"brute force", recommendation II of 6.2) recovers known damping.

The "measurements" are the ring itself with PATCH_DAMPING x 1.6: the fit,
from the shipped value, finds the factor, and the held-out runs (another
cleat, another speed) improve with it. With 1 % noise on FZW and the
foundation dampers 20 % off the truth (as a modal test might leave them),
the factor still comes back within 10 %.
"""

import numpy as np
import pandas as pd
import pytest

from tyrelab.errors import InputError
from tyrelab.fit.ring_dynamic import CleatRun, fit_ring_damping, scaled_damping, simulate_run
from tyrelab.tyre.ring.parameters import ring_parameters

TIMES = np.arange(0.0, 3.0, 1e-3)


def _measured(tyre, rp, road, kmh, noise=0.0, seed=0, times=TIMES, delay=None):
    """The ring at ``rp`` as a measurement; with ``delay`` [s], logged on a clock of its own (the
    wheel 5 m before the obstacle at ``delay`` on ``times``), else on the simulation's."""
    template = CleatRun(road, kmh / 3.6, "LC1", pd.DataFrame({"RUNTIME": times, "FZW": times * 0 + 1}),
                        delay)
    fzw = simulate_run(tyre, rp, template)
    fzw = fzw + noise * np.abs(fzw).max() * np.random.default_rng(seed).standard_normal(fzw.size)
    return CleatRun(road, kmh / 3.6, "LC1", pd.DataFrame({"RUNTIME": times, "FZW": fzw}))


def test_patch_damping_comes_back_from_one_cleat_run(xzl):
    """The fitted run is logged as a real one is: its logger started 1.2 s before the
    simulation's run-up would have, on a clock reading 100 s. The fit finds that delay
    (within 1 ms) and the factor. Before, it compared the run on the simulation's clock:
    the impact 1.2 s off."""
    rp = ring_parameters(xzl)
    truth = scaled_damping(rp, 1.6, 1.0)
    logged = _measured(xzl, truth, "cleat:50x50", 12, times=100.0 + np.arange(0.0, 4.2, 1e-3),
                       delay=101.2)
    fit = fit_ring_damping(xzl, [logged],
                           held_out=[_measured(xzl, truth, "cleat:76.3x76.3", 12),
                                     _measured(xzl, truth, "cleat:50x50", 42)])
    assert fit.patch == pytest.approx(1.6, rel=0.01)
    assert fit.structure == 1.0
    assert fit.table["shift_s"].tolist() == pytest.approx([101.2, 0.0, 0.0], abs=1e-3)
    assert (fit.table["rms_before_pct"] > 0.5).all()          # the start was visibly off
    fitted = fit.table["set"] == "fit"
    assert (fit.table["rms_after_pct"][fitted] < 0.05).all()  # the fitted run is matched
    # and the held-out runs follow: ten times closer than from the start. Not closer than
    # that: over the 76.3 mm cleat at 12 km/h the ring's FZW jumps by up to 0.19 % of its
    # peak (2.4 kN at one instant) between damping factors 3e-4 apart near the truth, at the
    # internal steps of 1/4 and 1/3 ms alike (an event under the tyre that flips), so a
    # bound below that tests where in its 1 % tolerance the search happened to stop
    held = fit.table[~fitted]
    assert (held["rms_after_pct"] < 0.1 * held["rms_before_pct"]).all()


@pytest.mark.slow
def test_noise_and_wrong_foundation_dampers_degrade_the_fit_gracefully(xzl):
    rp = ring_parameters(xzl)
    truth = scaled_damping(rp, 1.6, 0.8)
    fit = fit_ring_damping(xzl, [_measured(xzl, truth, "cleat:50x50", 12, noise=0.01)],
                           held_out=[_measured(xzl, truth, "cleat:76.3x76.3", 12, noise=0.01, seed=1)])
    assert fit.patch == pytest.approx(1.6, rel=0.10)
    held = fit.table[fit.table["set"] == "held out"].iloc[0]
    assert held["rms_after_pct"] < held["rms_before_pct"]


def test_bad_requests_are_refused_in_one_line(xzl):
    with pytest.raises(InputError, match="at least one run"):
        fit_ring_damping(xzl, [])
    run = CleatRun("cleat:50x50", 12 / 3.6, "LC1", pd.DataFrame({"RUNTIME": TIMES, "FZW": TIMES * 0}))
    with pytest.raises(InputError, match="not all 0"):
        fit_ring_damping(xzl, [run])
    ok = CleatRun("cleat:50x50", 12 / 3.6, "LC1", pd.DataFrame({"RUNTIME": TIMES, "FZW": TIMES + 1}))
    with pytest.raises(InputError, match="free must name"):
        fit_ring_damping(xzl, [ok], free=("tread",))
