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
