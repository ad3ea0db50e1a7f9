"""``tyrelab mf curves``: the plot and clear messages for bad property files."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tyrelab.cli.main import main
from tyrelab.report.mf_curves import curve_data
from tyrelab.tyre.handling.mf import MagicFormula

DATA = Path(__file__).parent / "data" / "mfeval"


def test_curves_writes_a_png(tmp_path, capsys):
    out = tmp_path / "curves.png"
    assert main(["mf", "curves", str(DATA / "MagicFormula61_Parameters.tir"), "-o", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "6.1" in capsys.readouterr().out


def test_curve_data_has_the_shape_of_real_tyre_curves():
    model = MagicFormula.from_tir(DATA / "CityBus_Pac02Tire.tir")
    d = curve_data(model, load_factors=(0.5, 1.0))
    assert d["Fx"].shape == (2, d["kappa"].size)
    mid = d["kappa"].size // 2
    # ISO-W: driving slip gives a forward force, a positive slip angle a negative side force
    assert np.all(d["Fx"][:, -1] > 0) and np.all(d["Fx"][:, 0] < 0)
    assert np.all(d["Fy"][:, mid + 5] < 0)
    assert np.all(np.abs(d["Fy"][1]).max() > np.abs(d["Fy"][0]).max())  # more load, more force


@pytest.mark.parametrize("text,key", [
    ("[MODEL]\nFITTYP = 61\n[VERTICAL]\nVERTICAL_STIFFNESS = 2e5\n", "FNOMIN"),
    ("[MODEL]\nFITTYP = 99\n[VERTICAL]\nFNOMIN = 4000\n", "FITTYP"),
])
def test_bad_property_file_gives_one_line_naming_file_and_key(tmp_path, capsys, text, key):
    path = tmp_path / "broken.tir"
    path.write_text(text)
    assert main(["mf", "curves", str(path), "-o", str(tmp_path / "x.png")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "broken.tir" in err and key in err
    assert not (tmp_path / "x.png").exists()


def test_missing_output_option_is_an_argument_error(capsys):
    assert main(["mf", "curves", str(DATA / "CityBus_Pac02Tire.tir")]) == 2
    assert "--output" in capsys.readouterr().err
