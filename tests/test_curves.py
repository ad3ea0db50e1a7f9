"""``tyrelab curves``: any handling model's pure-slip curves, tyres side by side.

The sweep's slips are the ISO slips every model reports; checked against the Fiala brush
model worked by hand (parameters typed from Chrono's HMMWV_FialaTire.json) and the Magic
Formula's file-stated nominal load.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from tyrelab.cli.main import main
from tyrelab.report.handling_curves import curve_set
from tyrelab.tyre.chrono_json import read_chrono_tyre

DATA = Path(__file__).parent / "data"
#: HMMWV_FialaTire.json: CSLIP [N], UMIN, UMAX
CSLIP, UMIN, UMAX = 193929.0, 0.5568, 0.9835


def test_the_sweep_is_at_the_iso_slips():
    """Fiala at 4905 N, 10 m/s: at kappa = 0.3 (sliding: 0.3 > U Fz / (2 CSLIP)) the force is
    U Fz - (U Fz)^2 / (4 kappa CSLIP), U = UMAX - (UMAX - UMIN) 0.3; at alpha = -0.3 rad (past
    atan(3 U Fz / CALPHA) = 0.28 rad) FYW = +U Fz with U at |tan 0.3|; the sweep ends there."""
    tyre = read_chrono_tyre(DATA / "tir" / "HMMWV_FialaTire.json")
    s = curve_set(tyre, "fiala", [4905.0], 10.0, "hmmwv")
    assert (s.kappa[-1], s.alpha[0]) == (0.3, -0.3)
    grip = (UMAX - (UMAX - UMIN) * 0.3) * 4905.0
    assert s.fx[0, -1] == pytest.approx(grip - grip ** 2 / (4 * 0.3 * CSLIP), rel=1e-12)
    grip = (UMAX - (UMAX - UMIN) * math.tan(0.3)) * 4905.0
    assert s.fy[0, 0] == pytest.approx(grip, rel=1e-12) and s.mz[0, 0] == 0.0
    assert s.fx[0, 60] == 0.0 and s.fy[0, 60] == 0.0  # the middle of the sweep: no slip


def test_three_parameterisations_of_one_tyre_in_one_figure(tmp_path, capsys):
    out = tmp_path / "hmmwv.png"
    argv = ["curves", "hmmwv-pac89", str(DATA / "tir" / "HMMWV_TMeasyTire.json"),
            str(DATA / "tir" / "HMMWV_FialaTire.json"), "--loads", "2500,4900", "-o", str(out)]
    assert main(argv) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "hmmwv-pac89: pac89, HMMWV_TMeasyTire: tmeasy, HMMWV_FialaTire: fiala" in capsys.readouterr().out


def test_default_loads_come_from_the_files_nominal_load():
    """MFeval's 6.1 example states FNOMIN = 6752 N; the HMMWV TMeasy guess FZ_NOM = half the
    1000 kg of load index 108 (4905 N); PAC89 names none (the command then asks for --loads)."""
    from tyrelab.report.handling_curves import nominal_load
    from tyrelab.tyre.library import load_tyre

    assert nominal_load(load_tyre(DATA / "mfeval" / "MagicFormula61_Parameters.tir")) == 6752.0
    assert nominal_load(read_chrono_tyre(DATA / "tir" / "HMMWV_TMeasyTire.json")) == pytest.approx(4905.0)
    assert nominal_load(load_tyre("hmmwv-pac89")) is None


@pytest.mark.parametrize("argv,match", [
    (["hmmwv-pac89"], r"hmmwv-pac89: --loads: the file names no nominal load \(FNOMIN, FZ_NOM\)"),
    (["xzl-16.00R20"], r"--handling: this tyre's file describes no handling model"),
    (["hmmwv-pac89", "--handling", "none"], r"--handling: 'none' has no forces to draw"),
    (["hmmwv-pac89", "--handling", "brush"], r"unknown handling model 'brush'"),
    (["hmmwv-pac89", "--loads", "4900,abc"], r"--loads: expected 1 to 6 wheel loads in N"),
    (["hmmwv-pac89", "--loads", "0.5"], r"--loads: expected 1 to 6 wheel loads in N \(each at least 1\)"),
])
def test_bad_requests_get_one_line_and_exit_2(tmp_path, capsys, argv, match):
    out = tmp_path / "c.png"
    assert main(["curves", *argv, "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and __import__("re").search(match, err), err
    assert not out.exists()
