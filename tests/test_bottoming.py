"""Bottoming: the load a property file adds to the vertical law once the tyre bottoms out.

References typed from the files: the FEDA 335/65R22.5's ``[BOTTOMING_CURVE]`` (rows
(0, 0), (0.10546 m, 0), (0.30546 m, 563080 N); Project Chrono's ``ChPac02Tire`` adds its
load at the tyre's deflection) and MFeval's MF 6.1 example (R0 0.3943 m, RIM_RADIUS
0.254 m, BOTTOM_OFFST 0.01 m, BOTTOM_STIFF 2e6 N/m: MF-Tyre 6.x bottoms out when the loaded
radius falls below RIM_RADIUS + BOTTOM_OFFST).
"""

from dataclasses import replace

import numpy as np
import pytest

from tyrelab.api import make_tyre_model
from tyrelab.cli.main import main
from tyrelab.errors import InputError
from tyrelab.rig.static_press import static_press
from tyrelab.tyre.library import load_tyre

FEDA_START, FEDA_END, FEDA_LOAD = 0.10546, 0.30546, 563080.0


@pytest.fixture(scope="module")
def feda(data_dir):
    return load_tyre(data_dir / "tir" / "335_65R22_5_G275MSA_95psi.tir")


def _added(tyre, rho):
    """Load [N] the file's bottoming adds at deflections ``rho``: the law with it less without."""
    rho = np.asarray(rho, float)
    return tyre.vertical_law.static_load(rho) - replace(tyre, bottoming=None).vertical_law.static_load(rho)


def test_bottoming_curve_adds_its_load_from_where_it_starts(feda):
    rho = np.array([0.05, 0.105, 0.15, 0.2, 0.3])
    expected = np.maximum(rho - FEDA_START, 0.0) * FEDA_LOAD / (FEDA_END - FEDA_START)
    np.testing.assert_allclose(_added(feda, rho), expected, rtol=1e-12, atol=1e-9)


def test_bottoming_curve_is_continued_with_its_last_slope(feda):
    """Past the curve's last row the rim goes on pressing: the load keeps its last slope (a
    curve held at its last load would let the tyre through the rim for nothing)."""
    expected = FEDA_LOAD * (0.35 - FEDA_START) / (FEDA_END - FEDA_START)
    assert _added(feda, [0.35])[0] == pytest.approx(expected, rel=1e-12)


def test_mf_bottom_stiffness_starts_at_the_rim_plus_its_offset(data_dir):
    tyre = load_tyre(data_dir / "mfeval" / "MagicFormula61_Parameters.tir")
    start = 0.3943 - 0.254 - 0.01
    added = _added(tyre, [start - 0.001, start + 0.005, start + 0.02])
    np.testing.assert_allclose(added, [0.0, 2e6 * 0.005, 2e6 * 0.02], rtol=1e-9, atol=1e-9)


@pytest.mark.filterwarnings("ignore:.*no \\[CONTACT_PATCH\\] value")   # the FEDA's cams are assumed
@pytest.mark.parametrize("model", ["point", "volume", "enveloping"])
def test_plate_press_carries_the_bottoming_load(feda, model):
    """The analytic models press the plate with the law, bottoming included: at 150 mm the
    FEDA carries its curve's 563080 N x 44.54 / 200 on top of its load-deflection table."""
    pressed = static_press(make_tyre_model(feda, model, handling="none"), [0.05, 0.15])["load"].to_numpy()
    bare = replace(feda, bottoming=None).vertical_law.static_load(np.array([0.05, 0.15]))
    np.testing.assert_allclose(pressed - bare, [0.0, FEDA_LOAD * (0.15 - FEDA_START) / 0.2],
                               rtol=1e-9, atol=1e-6)


def test_tyre_without_bottoming_data_does_not_bottom(data_dir):
    assert load_tyre().bottoming is None          # the XZL: no bottoming in its files
    assert load_tyre(data_dir / "tir" / "CityBus_Pac02Tire.tir").bottoming is None   # BOTTOMING_RADIUS 0


def _edited(src, dst, old, new):
    text = src.read_text(encoding="latin-1")
    assert old in text
    dst.write_text(text.replace(old, new, 1), encoding="latin-1")
    return dst


@pytest.mark.parametrize("file, old, new, message", [
    ("tir/335_65R22_5_G275MSA_95psi.tir", "0.10546       0.0", "0.40546       0.0",
     r"line 88.*BOTTOMING_CURVE.*deflection 0.30546 m does not increase"),
    ("tir/335_65R22_5_G275MSA_95psi.tir", "0.10546       0.0", "0.10546       -5.0",
     r"line 87.*BOTTOMING_CURVE.*bottoming load -5 N is negative"),
    ("tir/335_65R22_5_G275MSA_95psi.tir", "FNOMIN                =          29912",
     "BOTTOM_STIFF = 1e6\nFNOMIN                =          29912",
     r"BOTTOM_STIFF.*bottoming twice"),
    ("mfeval/MagicFormula61_Parameters.tir", "BOTTOM_OFFST             =    0.01",
     "BOTTOM_OFFST             =    0.2", r"BOTTOM_OFFST.*bottoming at the unloaded tyre"),
    ("mfeval/MagicFormula61_Parameters.tir", "BOTTOM_STIFF             =    2000000",
     "BOTTOM_STIFF             =    -2000000", r"BOTTOM_STIFF.*-2e\+06 N/m is not physical"),
])
def test_impossible_bottoming_is_refused_naming_the_file(data_dir, tmp_path, file, old, new, message):
    bad = _edited(data_dir / file, tmp_path / "bad.tir", old, new)
    with pytest.raises(InputError, match=message) as info:
        load_tyre(bad)
    assert "bad.tir" in str(info.value)


def test_mf_bottoming_without_a_rim_radius_is_refused_on_the_command_line(data_dir, tmp_path, capsys):
    src = data_dir / "mfeval" / "MagicFormula61_Parameters.tir"
    text = src.read_text(encoding="latin-1")
    lines = [ln for ln in text.splitlines() if not ln.strip().startswith("RIM_RADIUS")]
    bad = tmp_path / "norim.tir"
    bad.write_text("\n".join(lines) + "\n", encoding="latin-1")
    assert main(["static", "--tyre", str(bad), "-o", str(tmp_path / "p.csv")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "norim.tir" in err[0] and "BOTTOM_STIFF needs [DIMENSION] RIM_RADIUS" in err[0]
    assert not (tmp_path / "p.csv").exists()


# --- Chrono's TMeasy: its bottoming spring (ChTMeasyTire::GetNormalStiffnessForce) ----------

def test_tmeasy_default_bottoming_is_chronos(data_dir):
    """HMMWV_TMeasyTire.json sets no bottoming: Chrono's Initialize puts it at the rim radius
    0.2095 m + 10 mm with 5 d1, d1 the load-index guess 1000 x 9.81 / (0.16 (0.4699 - 0.2095))."""
    tyre = load_tyre(data_dir / "tir" / "HMMWV_TMeasyTire.json")
    d1 = 1000 * 9.81 / (0.16 * (0.4699 - 0.2095))
    start = 0.4699 - (0.2095 + 0.01)
    np.testing.assert_allclose(_added(tyre, [start - 0.002, start + 0.004]), [0.0, 5 * d1 * 0.004],
                               rtol=1e-9, atol=1e-9)


def _tmeasy_json(path, vertical):
    import json

    path.write_text(json.dumps({
        "Type": "Tire", "Template": "TMeasyTire",
        "Design": {"Unloaded Radius [m]": 0.5, "Mass [kg]": 40.0, "Inertia [kg.m2]": [4, 7, 4],
                   "Width [m]": 0.3, "Rim Radius [m]": 0.25},
        "Parameters": {"Vertical": {"Nominal Vertical Force [N]": 10000.0,
                                    "Tire Vertical Damping [Ns/m]": 1500.0, **vertical}}}, indent=1))
    return path


def test_tmeasy_bottoming_from_the_file_and_from_a_spring_curve(tmp_path):
    given = load_tyre(_tmeasy_json(tmp_path / "given.json", {
        "Vertical Tire Stiffness [N/m]": 4e5, "Tire Bottoming Radius [m]": 0.27,
        "Tire Bottoming Stiffness [N/m]": 3e6}))
    assert _added(given, [0.229, 0.235])[1] == pytest.approx(3e6 * 0.005, rel=1e-9)   # from 0.5 - 0.27
    assert _added(given, [0.229])[0] == 0.0
    # a spring curve: d1 of the least-squares d1 z + d2 z^2 through (0, 0), (0.02, 5000),
    # (0.05, 14000), by the normal equations: [[S4, -S3], [-S3, S2]] [S1f, S2f] / (S2 S4 - S3^2)
    z, f = np.array([0.0, 0.02, 0.05]), np.array([0.0, 5000.0, 14000.0])
    s2, s3, s4 = (z ** 2).sum(), (z ** 3).sum(), (z ** 4).sum()
    d1 = (s4 * (z * f).sum() - s3 * (z * z * f).sum()) / (s2 * s4 - s3 ** 2)
    curve = load_tyre(_tmeasy_json(tmp_path / "curve.json", {
        "Tire Spring Curve Data": [[0.0, 0.0], [0.02, 5000.0], [0.05, 14000.0]]}))
    start = 0.5 - (0.25 + 0.01)
    assert _added(curve, [start + 0.003])[0] == pytest.approx(5 * d1 * 0.003, rel=1e-9)


def test_tmeasy_bottoming_radius_outside_the_tyre_is_refused(tmp_path):
    path = _tmeasy_json(tmp_path / "inside.json", {"Vertical Tire Stiffness [N/m]": 4e5,
                                                   "Tire Bottoming Radius [m]": 0.2})
    with pytest.raises(InputError) as err:
        load_tyre(path)
    assert err.value.field == "Parameters > Vertical > Tire Bottoming Radius [m]"
    assert "inside.json" in str(err.value) and "between the rim radius 0.25 m" in str(err.value)
