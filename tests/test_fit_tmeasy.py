"""TMeasy fitted to pure-slip curves (``tyrelab fit tmeasy``): another handling model's, or
measured sweeps.

Round trips recover known parameters: the van's TMeasy file (Chrono's, parameters typed from
it in tests/tmeasy_van.py) sampled under TMeasy itself, and sweeps it "measured" at three
other loads written as TYDEX, each fitted, give its parameters back. MFeval's MF 6.1 example
converted is compared with MFeval's own table, which the fit never saw.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from tyrelab.cli.main import main
from tyrelab.fit.tmeasy import tmeasy_from_handling
from tyrelab.tyre.handling.tmeasy import tmeasy_params
from tyrelab.tyre.library import load_tyre

from tmeasy_van import VAN_NOMINAL, VAN_TRAIL, VAN_X, VAN_Y, fixed_van


def _assert_the_vans_curves(longitudinal, lateral, rel):
    """Each fitted characteristic parameter at both loads is the van file's, to ``rel``."""
    for got, want in ((longitudinal, VAN_X), (lateral, VAN_Y)):
        for level in (0, 1):
            for name in got[level]._fields:
                assert getattr(got[level], name) == pytest.approx(want[name][level], rel=rel), name


def test_a_round_trip_recovers_the_files_parameters(data_dir, tmp_path):
    van = fixed_van(data_dir / "tir", tmp_path)
    fit = tmeasy_from_handling(van, "tmeasy", VAN_NOMINAL)
    _assert_the_vans_curves(fit.longitudinal, fit.lateral, rel=1e-7)
    for level in (0, 1):
        assert fit.trail[level].at_zero == pytest.approx(VAN_TRAIL["at_zero"][level], rel=1e-6)
        assert fit.trail[level].sign_change == pytest.approx(VAN_TRAIL["sign_change"][level], rel=1e-6)
    assert max(fit.rms_pct.values()) < 1e-4


def _sweeps(tyre, loads, speed=1000.0):
    """Pure-slip sweeps of ``tyre`` under TMeasy at ``loads`` as a signal table (ISO slips,
    W-axis; at 1000 m/s TMeasy's 0.01 m/s in its transport speed is 1e-5 of it)."""
    import math

    import pandas as pd

    from tyrelab.tyre.handling.tmeasy import tmeasy_params, tmeasy_wheel_forces

    p = tmeasy_params(tyre)
    rows = []
    for fz in loads:
        for kappa in [k for k in np.linspace(-0.6, 1.5, 85) if k != 0.0]:
            fx, fy, mz, *_ = tmeasy_wheel_forces(p, fz, speed, -kappa * speed, 0.0, 0.0)
            rows.append((fz, kappa, 0.0, fx, fy, mz))
        for alpha in [a for a in np.linspace(-0.8, 0.8, 81) if a != 0.0]:
            fx, fy, mz, *_ = tmeasy_wheel_forces(p, fz, speed, 0.0, math.tan(alpha) * speed, 0.0)
            rows.append((fz, 0.0, alpha, fx, fy, mz))
    return pd.DataFrame(rows, columns=["FZW", "LONGSLIP", "SLIPANGL", "FXW", "FYW", "MZW"])


def test_measured_sweeps_at_other_loads_give_the_parameters_back(data_dir, tmp_path, capsys):
    """Sweeps at 0.8, 1.4 and 2.2 FZ_NOM (none at the two levels), through a TYDEX file and
    the command: the load interpolation is fitted too. Within 1e-4 of the file's values (the
    transport speed's 0.01 m/s, left out of the measured slips, is 1e-5 of the speed)."""
    from tyrelab.measure.tydex import write_tydex
    from tyrelab.signal import make_signal

    van = fixed_van(data_dir / "tir", tmp_path)
    table = _sweeps(van, [0.8 * VAN_NOMINAL, 1.4 * VAN_NOMINAL, 2.2 * VAN_NOMINAL])
    path = tmp_path / "sweeps.tdx"
    write_tydex(make_signal({c: table[c].to_numpy() for c in table.columns}), path)
    out = tmp_path / "fitted.tir"
    assert main(["fit", "tmeasy", str(tmp_path / "van.json"), "--measured", str(path),
                 "--nominal-load", str(VAN_NOMINAL), "-o", str(out)]) == 0
    assert "TMeasy fitted to 1 measured sweep file(s), FZ_NOM 1900 N" in capsys.readouterr().out
    got = tmeasy_params(load_tyre(out))
    _assert_the_vans_curves(got.longitudinal, got.lateral, rel=1e-4)
    for level in (0, 1):
        assert got.trail[level].at_zero == pytest.approx(VAN_TRAIL["at_zero"][level], rel=1e-4)


def test_the_magic_formula_converted(data_dir):
    """The converted tyre against MFeval's own table (independent of the fit's samples), at
    its three loads -- 1.5 FNOMIN never sampled: every pure-slip row's Fx and Fy within 10 %
    of the row set's largest force. MF's braking and driving peaks alone differ by 11 % of
    the larger, which an odd curve must split (measured: Fx within 7.4-8.5 %, Fy 3.7-4.6 %)."""
    import pandas as pd

    from tyrelab.tyre.handling.tmeasy import characteristic, curve_at

    mf61 = load_tyre(data_dir / "mfeval" / "MagicFormula61_Parameters.tir")
    fit = tmeasy_from_handling(mf61, "mf", 6752.0)
    table = pd.read_csv(data_dir / "mfeval" / "MagicFormula61_Parameters.mode111.csv.gz")
    for fz in (3376.0, 6752.0, 10128.0):
        at = table[(table.Fz == fz) & (table.gamma == 0)]
        for rows, slip, force, levels in (
                (at[(at.alpha == 0) & (at.kappa != 0)], lambda r: r.kappa / (1 + r.kappa), "Fx",
                 fit.longitudinal),
                (at[(at.kappa == 0) & (at.alpha != 0)], lambda r: -np.tan(r.alpha), "Fy", fit.lateral)):
            curve = curve_at(levels, fz / 6752.0)
            ours = [np.sign(s) * characteristic(abs(s), *curve) for s in slip(rows)]
            assert len(rows) >= 12
            assert np.abs(ours - rows[force]).max() <= 0.10 * np.abs(rows[force]).max(), (fz, force)
    # TMeasy's curve is odd, MF's not: the fitted maximum lies between MF's braking and
    # driving maxima (MFeval's table at FNOMIN, alpha = gamma = 0: -7388.5 N at kappa = -0.1,
    # 8306.1 N at 0.1; its largest magnitudes on each side)
    assert 7388.5 < fit.longitudinal[0].peak < 8306.1
    # KPUMAX = 1 keeps the samples inside the file's range: TMeasy slip 1 / (1 + 1), on both
    # sides (KPUMIN = -1 reaches lock, where TMeasy's braking slip is endless)
    assert fit.slip_range[0] == (pytest.approx(-0.5), pytest.approx(0.5))


def test_a_tyre_measured_in_braking_only_is_fitted_on_its_braking_side(data_dir):
    """Goodyear's 335/65R22.5 MF-Tyre 5.0 file states KPUMIN = -0.8, KPUMAX = 0: the Magic
    Formula clips the driving side flat at zero force, which the fit sampled as well (to
    TMeasy slip +0.9), so TMeasy's odd curve split the difference: its peak 8.37 kN at
    FZ_NOM where the tyre brakes with 16.65 kN (38 % RMS error). Sampled on the braking
    side only, its peaks are the Magic Formula's braking peaks within the curve's RMS error."""
    import warnings

    from tyrelab.tyre.handling.mf.model import MagicFormula

    source = data_dir / "tir" / "335_65R22_5_G275MSA_40psi.tir"
    fit = tmeasy_from_handling(load_tyre(source), "mf", 16929.0)
    low, high = fit.slip_range[0]
    assert low == pytest.approx(-0.9) and high < 0.0
    kappa = np.linspace(-0.8, 0.0, 80001)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        peaks = [-MagicFormula.from_tir(source).steady_state(fz, kappa, 0.0, 0.0, 10.0)["Fx"].min()
                 for fz in (16929.0, 2 * 16929.0)]
    for curve, peak in zip(fit.longitudinal, peaks):
        assert abs(curve.peak - peak) <= fit.rms_pct["Fx"] / 100.0 * peak


def test_the_command_writes_a_file_tmeasy_runs(data_dir, tmp_path, capsys):
    out = tmp_path / "mf61_tm.tir"
    source = data_dir / "mfeval" / "MagicFormula61_Parameters.tir"
    assert main(["fit", "tmeasy", str(source), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "TMeasy fitted to its mf curves, FZ_NOM 6752 N" in printed
    tyre = load_tyre(out)
    params = tmeasy_params(tyre)
    fit = tmeasy_from_handling(load_tyre(source), "mf", 6752.0)
    assert params.longitudinal[1].peak == pytest.approx(fit.longitudinal[1].peak, rel=1e-9)
    assert tyre.tir.get("TYRELAB_FIT", "TMEASY_SOURCE") == "its mf curves"
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


def test_a_sweep_without_a_channel_or_pure_slip_is_refused(data_dir, tmp_path, capsys):
    from tyrelab.measure.tydex import write_tydex
    from tyrelab.signal import make_signal

    van = fixed_van(data_dir / "tir", tmp_path)
    table = _sweeps(van, [VAN_NOMINAL])
    no_mz = tmp_path / "no_mz.tdx"
    write_tydex(make_signal({c: table[c].to_numpy() for c in table.columns if c != "MZW"}), no_mz)
    combined = tmp_path / "combined.tdx"  # every row slips both ways: no pure slip
    both = table.assign(LONGSLIP=0.05, SLIPANGL=0.05)
    write_tydex(make_signal({c: both[c].to_numpy() for c in both.columns}), combined)
    for path, match in ((no_mz, r"no_mz.tdx: MZW: a slip sweep needs the channels .* missing MZW"),
                        (combined, r"--measured: too few pure longitudinal-slip samples \(0\)")):
        out = tmp_path / "o.tir"
        assert main(["fit", "tmeasy", str(tmp_path / "van.json"), "--measured", str(path),
                     "-o", str(out)]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and re.search(match, err), err
        assert not out.exists()


def test_a_lab_csv_in_its_own_units_through_a_column_map(data_dir, tmp_path, capsys):
    """A logger's CSV (kN, percent, degrees, kN m) read through a column map as ``tyrelab
    validate`` reads one: the same parameters as the SI sweeps, to the same 1e-4."""
    import math

    van = fixed_van(data_dir / "tir", tmp_path)
    table = _sweeps(van, [0.8 * VAN_NOMINAL, 2.2 * VAN_NOMINAL])
    lab = tmp_path / "lab.csv"
    lab.write_text("Fz kN,slip %,angle deg,Fx kN,Fy kN,Mz kNm\n" + "".join(
        f"{r.FZW / 1e3!r},{100 * r.LONGSLIP!r},{math.degrees(r.SLIPANGL)!r},{r.FXW / 1e3!r},"
        f"{r.FYW / 1e3!r},{r.MZW / 1e3!r}\n" for r in table.itertuples()))
    columns = tmp_path / "map.csv"
    columns.write_text("source,channel,unit\nFz kN,FZW,kN\nslip %,LONGSLIP,%\nangle deg,SLIPANGL,deg\n"
                       "Fx kN,FXW,kN\nFy kN,FYW,kN\nMz kNm,MZW,kN m\n")
    out = tmp_path / "fitted.tir"
    assert main(["fit", "tmeasy", str(tmp_path / "van.json"), "--measured", str(lab), "--column-map",
                 str(columns), "--nominal-load", str(VAN_NOMINAL), "-o", str(out)]) == 0
    got = tmeasy_params(load_tyre(out))
    _assert_the_vans_curves(got.longitudinal, got.lateral, rel=1e-4)
