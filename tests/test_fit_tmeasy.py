"""TMeasy fitted to another handling model's curves (``tyrelab fit tmeasy``).

A round trip recovers known parameters: the van's TMeasy file (Chrono's, parameters typed
from it in tests/test_tmeasy.py) sampled under TMeasy itself and fitted gives its own
parameters back. MFeval's MF 6.1 example converted: TMeasy carries its forces to 0.4-0.7 %
RMS of their peaks (measured: 0.38 % Fx, 0.71-0.74 % Fy) and its aligning moment, where the
tyre grips, to 8 % (TMeasy has no residual moment).
"""

from __future__ import annotations

import re

import pytest

from tyrelab.cli.main import main
from tyrelab.fit.tmeasy import tmeasy_from_handling
from tyrelab.tyre.handling.tmeasy import tmeasy_params
from tyrelab.tyre.library import load_tyre

from tmeasy_van import VAN_NOMINAL, VAN_TRAIL, VAN_X, VAN_Y, fixed_van


def test_a_round_trip_recovers_the_files_parameters(data_dir, tmp_path):
    van = fixed_van(data_dir / "tir", tmp_path)
    fit = tmeasy_from_handling(van, "tmeasy", VAN_NOMINAL)
    for got, want in ((fit.longitudinal, VAN_X), (fit.lateral, VAN_Y)):
        for level in (0, 1):
            for name in got[level]._fields:
                assert getattr(got[level], name) == pytest.approx(want[name][level], rel=1e-7), name
    for level in (0, 1):
        assert fit.trail[level].at_zero == pytest.approx(VAN_TRAIL["at_zero"][level], rel=1e-6)
        assert fit.trail[level].sign_change == pytest.approx(VAN_TRAIL["sign_change"][level], rel=1e-6)
    assert max(fit.rms_pct.values()) < 1e-4


def test_the_magic_formula_converted(data_dir):
    mf61 = load_tyre(data_dir / "mfeval" / "MagicFormula61_Parameters.tir")
    fit = tmeasy_from_handling(mf61, "mf", 6752.0)
    for key in ("Fx1", "Fx2", "Fy1", "Fy2"):
        assert fit.rms_pct[key] < 0.8, key
    for key in ("Mz1", "Mz2"):
        assert fit.rms_pct[key] < 9.0, key
    # TMeasy's curve is odd, MF's not: the fitted maximum lies between MF's braking and
    # driving maxima (MFeval's table at FNOMIN, alpha = gamma = 0: -7388.5 N at kappa = -0.1,
    # 8306.1 N at 0.1; its largest magnitudes on each side)
    assert 7388.5 < fit.longitudinal[0].peak < 8306.1
    # KPUMAX = 1 keeps the samples inside the file's range: TMeasy slip 1 / (1 + 1)
    assert fit.slip_range[0] == pytest.approx(0.5)


def test_the_command_writes_a_file_tmeasy_runs(data_dir, tmp_path, capsys):
    out = tmp_path / "mf61_tm.tir"
    source = data_dir / "mfeval" / "MagicFormula61_Parameters.tir"
    assert main(["fit", "tmeasy", str(source), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "TMeasy fitted to mf at 6752 N and 13504 N" in printed
    tyre = load_tyre(out)
    params = tmeasy_params(tyre)
    fit = tmeasy_from_handling(load_tyre(source), "mf", 6752.0)
    assert params.longitudinal[1].peak == pytest.approx(fit.longitudinal[1].peak, rel=1e-9)
    assert tyre.tir.get("TYRELAB_FIT", "TMEASY_SOURCE") == "mf"
    assert main(["curves", str(out), str(out), "--handling", "mf", "--handling", "tmeasy",
                 "-o", str(tmp_path / "c.png")]) == 0


@pytest.mark.parametrize("argv,match", [
    (["fit", "tmeasy", "xzl-16.00R20", "-o", "{out}"], r"no handling model to fit TMeasy to"),
    (["fit", "tmeasy", "hmmwv-pac89", "-o", "{out}"], r"--nominal-load: the file names no nominal load"),
    (["curves", "hmmwv-pac89", "xzl-16.00R20", "xzl-16.00R20", "--handling", "pac89", "--handling",
      "mf", "--loads", "4000", "-o", "{png}"], r"--handling: give --handling once \(every tyre\) or once "
                                               r"per tyre \(3\), got 2"),
])
def test_bad_requests_get_one_line_and_exit_2(tmp_path, capsys, argv, match):
    argv = [a.format(out=tmp_path / "o.tir", png=tmp_path / "c.png") for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and re.search(match, err), err
    assert not (tmp_path / "o.tir").exists() and not (tmp_path / "c.png").exists()
