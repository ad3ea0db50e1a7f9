"""Handling forces on a rig: slip from the wheel's spin drives the spin to free rolling."""

import numpy as np
import pytest

from tyrelab.api import default_handling, make_tyre_model
from tyrelab.rig.trailer import Trailer
from tyrelab.tyre.library import load_tyre


def test_file_format_picks_the_handling_model(data_dir):
    assert default_handling(load_tyre(data_dir / "mfeval" / "MagicFormula61_Parameters.tir")) == "mf"
    assert default_handling(load_tyre()) == "none"
    with pytest.warns(UserWarning, match="FITTYP"):   # MF-Tyre 5.0 (FITTYP 5) is not supported
        assert default_handling(load_tyre(data_dir / "tir" / "335_65R22_5_G275MSA_40psi.tir")) == "none"


def test_magic_formula_wheel_settles_at_free_rolling(data_dir):
    """With no drive torque the spin must settle where the Magic Formula's Fx vanishes
    (I dw/dt = -r Fx); a slip sign opposite to MF's would make the spin run away."""
    from scipy.optimize import brentq

    from tyrelab.tyre.handling.mf import MagicFormula

    path = data_dir / "mfeval" / "MagicFormula61_Parameters.tir"
    model = make_tyre_model(path, handling="mf")
    fz0 = 4000.0
    run = Trailer(model, fz0).run("flat", 10.0, duration=3.0)
    mf = MagicFormula.from_tir(path)
    kappa0 = brentq(lambda k: float(mf.steady_state(fz0, k, 0.0, 0.0, 10.0)["Fx"]), -0.05, 0.05)
    tail = run.iloc[-500:]
    assert np.abs(tail["FXW"]).max() < 1e-3 * fz0
    assert tail["LONGSLIP"].mean() == pytest.approx(kappa0, abs=1e-4)
    assert np.all(np.isfinite(run["ROTSPEED"])) and run["ROTSPEED"].std() < 0.01 * run["ROTSPEED"].mean()
