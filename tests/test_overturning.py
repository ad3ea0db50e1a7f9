"""The handling model's overturning moment Mx on the rigs.

The Magic Formula gives Mx about the W-axis x at the contact point (QSX1-QSX14: the pressure's
centre shifted across the patch by the lateral force and the camber), as it gives My there.
A rig's wheel carries it besides the moment of its contact force about the wheel centre.
References: MFeval 4.3.1's Mx (tests/data/mfeval, rows without camber: the point model keeps
its contact in the wheel plane and sees no camber) and, with camber, the Magic Formula
kernel's (held to MFeval's tables by tests/test_mf_reference.py) at the loads the volume
model's cambered wheel carries.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from tyrelab.api import make_tyre_model
from tyrelab.road.spec import road_from_spec
from tyrelab.tyre.handling.mf.model import MagicFormula
from tyrelab.tyre.wheel import WheelLoads, loads_table, pose

from mfeval_rows import MF61, mfeval_rows_on_the_wheel

DATA = Path(__file__).parent / "data"


def _about_contact(c, centres):
    """Each row's moment about its contact point (``c`` the :class:`WheelLoads` fields)."""
    r = np.column_stack([c["px"], c["py"], c["pz"]]) - centres
    f = np.column_stack([c["fx"], c["fy"], c["fz"]])
    m = np.column_stack([c["mx"], c["my"], c["mz"]]) - np.cross(r, f)
    return m


def _about_contact_x(loads, centres):
    """``(fields, moments)``: the :class:`WheelLoads` fields of ``loads`` and each row's moment
    about its contact point."""
    c = {name: loads[:, k] for k, name in enumerate(WheelLoads._fields)}
    return c, _about_contact(c, centres)


def test_the_magic_formulas_overturning_moment_is_mfevals_mx():
    """Every MFeval row without camber (507, combined slip to 0.3): the point model's wheel at
    MFeval's deflection, spin and speed carries MFeval's Mx about the W-axis x at its contact
    point (to 1e-6, as its My: tests/test_rolling_resistance.py; Mx up to 96 N m here, where
    the moment of the lateral force about the centre reaches 2.3 kN m)."""
    rows, c, centres = mfeval_rows_on_the_wheel()
    m = _about_contact(c, centres)
    np.testing.assert_allclose(c["fyw"], rows.Fy, rtol=1e-6, atol=1e-6)  # the same state
    assert np.abs(rows.Mx).max() > 90.0
    np.testing.assert_allclose(m[:, 0], rows.Mx, rtol=1e-6, atol=1e-9)


@pytest.mark.parametrize("gamma", [-0.05, 0.03, 0.05])
@pytest.mark.parametrize("alpha", [0.0, 0.04])
def test_a_cambered_wheel_carries_the_kernels_mx(gamma, alpha):
    """The volume model's wheel leaning by ``gamma`` on a flat road (its contact normal the
    road's, so it sees the camber): Mx about the W-axis x at its contact point is the Magic
    Formula kernel's at that wheel's own load, slips and inclination (camber terms QSX2,
    QSX4-QSX11: -70 N m at 0.05 rad and 4 kN with no lateral slip)."""
    model = make_tyre_model(MF61, "volume", handling="mf", relaxation="off")
    r0 = model.tyre.unloaded_radius
    wheel = model.wheel(road_from_spec("flat").grid(), 4000.0)
    axis = (0.0, math.cos(gamma), math.sin(gamma))
    speed, h = 11.0, r0 - 0.012
    at = pose(cz=h, axis=axis, velocity=(speed, speed * math.tan(alpha), 0.0),
              omega=speed / (r0 - 0.008))
    c, m = _about_contact_x(loads_table(wheel, [at]), np.array([[0.0, 0.0, h]]))
    n = np.array([c["nx"][0], c["ny"][0], c["nz"][0]])
    w_x = np.cross(axis, n)
    w_x /= np.linalg.norm(w_x)
    inclination = math.asin(float(np.dot(axis, n)))
    assert inclination == pytest.approx(gamma, abs=1e-12)
    ref = MagicFormula.from_tir(MF61).steady_state(c["fzw"][0], c["kappa"][0], c["alpha"][0],
                                                   inclination, speed)
    assert c["fyw"][0] == pytest.approx(float(ref["Fy"]), rel=1e-9, abs=1e-9)
    assert abs(float(ref["Mx"])) > 5.0  # (the lateral slip's term offsets the camber's part)
    assert float(m[0] @ w_x) == pytest.approx(float(ref["Mx"]), rel=1e-9, abs=1e-9)


def test_chronos_pac89_overturns_by_its_carcass_deflection():
    """Project Chrono's PAC89 (its HMMWV JSON's "Lateral Stiffness": 261065 N/m, typed here):
    the lateral force deflects the carcass by FYW / k_y and the normal force acts there,
    ``Mx = Fz FYW / k_y`` about the W-axis x at the contact point (ChPac89Tire::Advance)."""
    model = make_tyre_model(DATA / "tir" / "HMMWV_Pac89Tire.json", "point", handling="pac89")
    r0 = model.tyre.unloaded_radius
    wheel = model.wheel(road_from_spec("flat").grid(), 15000.0)
    speed, h = 10.0, r0 - 0.045
    poses = [pose(cz=h, velocity=(speed, speed * math.tan(a), 0.0), omega=speed / h)
             for a in (-0.1, -0.02, 0.0, 0.05)]
    c, m = _about_contact_x(loads_table(wheel, poses), np.array([[0.0, 0.0, h]] * len(poses)))
    assert np.abs(c["fyw"]).max() > 5e3
    np.testing.assert_allclose(m[:, 0], c["fzw"] * c["fyw"] / 261065.0, rtol=1e-12, atol=1e-9)
