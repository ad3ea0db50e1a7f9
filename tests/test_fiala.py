"""The Fiala handling model (ADAMS/Tire's brush model; Project Chrono's ChFialaTire).

Expected values are worked here by hand from the brush model's formulas (the module
docstring's, as ADAMS and Chrono write them) with the parameters typed from Chrono's
``tests/data/tir/HMMWV_FialaTire.json``: CSLIP 193929 N, CALPHA 50000 N/rad, UMIN 0.5568,
UMAX 0.9835, width 0.318 m.
"""

import copy
import math

import numpy as np
import pytest

from tyrelab.api import default_handling, simulate
from tyrelab.errors import InputError
from tyrelab.tyre.chrono_json import read_chrono_tyre
from tyrelab.tyre.handling.fiala import fiala_forces, fiala_params, fiala_wheel_forces
from tyrelab.tyre.params import Tyre
from tyrelab.tyre.tir import read_tir, write_tir

from file_edit import edited

CSLIP, CALPHA, UMIN, UMAX, WIDTH = 193929.0, 50000.0, 0.5568, 0.9835, 0.318
#: its X and Y Relaxation Length [m] (2.0 each, as published) and Rolling Resistance [m]
RELAX_X, RELAX_Y, ROLLING = 2.0, 2.0, 0.015


@pytest.fixture(scope="module")
def hmmwv(data_dir):
    return read_chrono_tyre(data_dir / "tir" / "HMMWV_FialaTire.json")


@pytest.fixture(scope="module")
def fp(hmmwv):
    return fiala_params(hmmwv)


def _u(kappa, alpha):
    return UMAX - (UMAX - UMIN) * min(1.0, math.hypot(kappa, math.tan(alpha)))


@pytest.mark.parametrize("fz,kappa", [(4905.0, 0.005), (4905.0, 0.05), (2000.0, -0.3), (9000.0, 1.5)])
def test_longitudinal_force_by_hand(fp, fz, kappa):
    grip = _u(kappa, 0.0) * fz
    critical = grip / (2 * CSLIP)
    want = CSLIP * kappa if abs(kappa) < critical else math.copysign(
        grip - grip ** 2 / (4 * abs(kappa) * CSLIP), kappa)
    assert fiala_forces(fp, fz, kappa, 0.0)[0] == pytest.approx(want, rel=1e-12)


@pytest.mark.parametrize("fz,alpha_deg", [(4905.0, 1.0), (4905.0, -6.0), (2000.0, 12.0), (9000.0, 40.0)])
def test_lateral_force_and_aligning_moment_by_hand(fp, fz, alpha_deg):
    alpha = math.radians(alpha_deg)
    grip = _u(0.0, alpha) * fz
    h = 1 - CALPHA * abs(math.tan(alpha)) / (3 * grip)
    sign = math.copysign(1.0, alpha)
    if h >= 0:
        fy, mz = -grip * (1 - h ** 3) * sign, grip * WIDTH * (1 - h) * h ** 3 * sign
    else:
        fy, mz = -grip * sign, 0.0
    _, got_fy, got_mz = fiala_forces(fp, fz, 0.0, alpha)
    assert (got_fy, got_mz) == pytest.approx((fy, mz), rel=1e-12, abs=1e-12)


def test_the_brush_curves_are_continuous_and_start_at_the_stiffnesses(fp):
    """Slope CSLIP and CALPHA at zero slip; continuous where sliding begins (kappa = U Fz /
    (2 CSLIP), where the force is U Fz / 2; tan alpha = 3 U Fz / CALPHA, where Fy reaches
    -U Fz and Mz returns to zero), and the sliding limit U Fz with U -> UMIN at full slip."""
    fz = 4905.0
    assert fiala_forces(fp, fz, 1e-7, 0.0)[0] / 1e-7 == pytest.approx(CSLIP, rel=1e-5)
    assert -fiala_forces(fp, fz, 0.0, 1e-7)[1] / 1e-7 == pytest.approx(CALPHA, rel=1e-5)
    # the edge of adhesion moves with U, which falls with the slip: find it by bisection
    lo, hi = 1e-6, 0.5
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if mid < _u(mid, 0.0) * fz / (2 * CSLIP):
            lo = mid
        else:
            hi = mid
    for k in (lo * (1 - 1e-9), lo * (1 + 1e-9)):
        assert fiala_forces(fp, fz, k, 0.0)[0] == pytest.approx(_u(lo, 0.0) * fz / 2, rel=1e-6)
    big = fiala_forces(fp, fz, 0.0, math.radians(80.0))
    assert big[1] == pytest.approx(-UMIN * fz, rel=1e-12) and big[2] == 0.0
    assert fiala_forces(fp, fz, 50.0, 0.0)[0] == pytest.approx(UMIN * fz * (1 - UMIN * fz / (200 * CSLIP)))


def test_rolling_backwards_turns_the_aligning_moment_over(fp):
    ahead = fiala_wheel_forces(fp, 4905.0, 10.0, 0.0, 0.5, 0.0)
    back = fiala_wheel_forces(fp, 4905.0, -10.0, 0.0, 0.5, 0.0)
    assert back[1] == pytest.approx(ahead[1], rel=1e-12) and ahead[2] > 0
    assert back[2] == pytest.approx(-ahead[2], rel=1e-12)


def test_the_json_carries_its_fiala_parameters(hmmwv, fp):
    assert fp == (CSLIP, CALPHA, UMIN, UMAX, WIDTH, RELAX_X, RELAX_Y, ROLLING)
    assert default_handling(hmmwv) == "fiala"


def test_a_file_in_degrees_states_calpha_per_degree(hmmwv, tmp_path):
    """ADAMS files may state angles in degrees: CALPHA [N/deg] is then converted."""
    path = tmp_path / "deg.tir"
    write_tir(hmmwv.tir, path, units={"ANGLE": "degree"})
    assert "CALPHA" in path.read_text()
    tir = read_tir(path)
    assert tir.number("PARAMETER", "CALPHA") == pytest.approx(CALPHA, rel=1e-12)
    text = path.read_text()
    per_degree = [line for line in text.splitlines() if line.strip().startswith("CALPHA")][0]
    assert float(per_degree.split("=")[1].split("$")[0]) == pytest.approx(CALPHA * math.pi / 180, rel=1e-9)


@pytest.mark.parametrize("edit,match", [
    (("UMIN", 1.2), r"line \d+: UMIN: expected UMIN <= UMAX"),
    (("CALPHA", -5.0), r"line \d+: CALPHA: expected a positive CALPHA"),
])
def test_impossible_parameters_are_refused_at_their_line(hmmwv, tmp_path, edit, match):
    tir = read_tir_copy(hmmwv, tmp_path, *edit)
    with pytest.raises(InputError, match=match):
        fiala_params(Tyre.from_tir(tir))


def read_tir_copy(tyre, tmp_path, key, value):
    """The tyre's property file with ``[PARAMETER] key = value``, written and read back."""
    tir = copy.deepcopy(tyre.tir)
    tir.sections["PARAMETER"].entries[key] = value
    path = tmp_path / "f.tir"
    write_tir(tir, path)
    return read_tir(path)


def test_a_json_with_only_part_of_the_fiala_parameters_is_refused(data_dir, tmp_path):
    path = edited(data_dir / "tir" / "HMMWV_FialaTire.json", tmp_path / "f.json", ('"UMAX": 0.9835,', ""))
    with pytest.raises(InputError, match=r"Fiala Parameters > UMAX: missing key"):
        read_chrono_tyre(path)


def test_without_fiala_parameters_the_tyre_has_no_handling(data_dir, tmp_path):
    keys = ('"CSLIP": 193929.0,', '"CALPHA": 50000.0,', '"UMIN": 0.5568,', '"UMAX": 0.9835,')
    tyre = read_chrono_tyre(edited(data_dir / "tir" / "HMMWV_FialaTire.json", tmp_path / "f.json",
                                   *((key, "") for key in keys)))
    assert default_handling(tyre) == "none"
    with pytest.raises(InputError, match=r"no Fiala parameter CSLIP in section \[PARAMETER\]"):
        fiala_params(tyre)


def test_a_freely_rolling_wheel_stays_free(hmmwv):
    """Fiala's slip is the contact point's (lever: the loaded radius r = R0 - z), so the rolling
    rig's wheel, its axle free of torque, carries the rolling resistance's drag and no more:
    FXW = -ROLLING Fz / r (tanh(omega) = 1 to 1e-15 at 17 rad/s), from start to end."""
    load = 4900.0
    out = simulate(hmmwv, "point", road="flat", speed=8.0, load=load, handling="fiala",
                   rig="rolling", duration=1.0)
    r = hmmwv.unloaded_radius - hmmwv.static_deflection(load)
    np.testing.assert_allclose(out["FXW"], -ROLLING * load / r, rtol=1e-9)


ADAMS_FIALA = """[MDI_HEADER]
FILE_TYPE = 'tir'
[UNITS]
LENGTH = 'mm'
FORCE = 'newton'
ANGLE = 'degree'
MASS = 'kg'
TIME = 'second'
[MODEL]
PROPERTY_FILE_FORMAT = 'FIALA'
[DIMENSION]
UNLOADED_RADIUS = 326.0
WIDTH = 245.0
[PARAMETER]
VERTICAL_STIFFNESS = {stiffness}
VERTICAL_DAMPING = 3.1
CSLIP = 75000.0
CALPHA = 1000.0
UMIN = 0.8
UMAX = 1.0
RELAX_LENGTH_X = {relax_x}
RELAX_LENGTH_Y = 350.0
"""


def test_an_adams_fiala_file_keeps_its_vertical_law_in_parameter(tmp_path):
    """ADAMS's Fiala layout: the vertical stiffness and damping in [PARAMETER] beside CSLIP
    (here in N/mm, N s/mm and N/deg): read as 310 kN/m, 3.1 kN s/m and 1000 N/deg = 57.3 kN/rad.
    Before, the file was refused for a missing [VERTICAL] VERTICAL_STIFFNESS."""
    from tyrelab.tyre.library import load_tyre

    path = tmp_path / "adams_fiala.tir"
    path.write_text(ADAMS_FIALA.format(stiffness=310.0, relax_x=120.0))
    tyre = load_tyre(path)
    assert (tyre.vertical_stiffness, tyre.vertical_damping) == pytest.approx((310e3, 3.1e3), rel=1e-12)
    assert default_handling(tyre) == "fiala"
    fp = fiala_params(tyre)
    assert fp.cornering_stiffness == pytest.approx(1000.0 * 180.0 / math.pi, rel=1e-12)
    assert (fp.slip_stiffness, fp.width) == pytest.approx((75000.0, 0.245), rel=1e-12)
    assert (fp.relaxation_x, fp.relaxation_y) == pytest.approx((0.12, 0.35), rel=1e-12)
    path.write_text(ADAMS_FIALA.format(stiffness=-5.0, relax_x=120.0))
    with pytest.raises(InputError, match=r"line 15: VERTICAL_STIFFNESS: .* is not physical"):
        load_tyre(path)
    path.write_text(ADAMS_FIALA.format(stiffness=310.0, relax_x=-1.0))
    with pytest.raises(InputError, match=r"line 21: RELAX_LENGTH_X: expected a relaxation length >= 0"):
        fiala_params(load_tyre(path))
