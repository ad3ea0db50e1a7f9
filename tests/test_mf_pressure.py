"""An MF-Tyre 6.1 property file moved to another inflation pressure.

MFeval's MF 6.1 example (tests/data/mfeval) states NOMPRES = INFLPRES = 260 kPa, a valid range
[INFLATION_PRESSURE_RANGE] 200-400 kPa, and pressure terms typed here from it: PFZ1 0.88241
(vertical stiffness, Besselink et al. 2010 eq. 5), PPX1 -0.8733 and PPX2 0.7035 (longitudinal
slip stiffness, Kxk = Fz (PKX1 + PKX2 dfz) exp(PKX3 dfz) (1 + PPX1 dpi + PPX2 dpi^2) LKX).
At 312 kPa, dpi = 0.2.
"""

import numpy as np
import pytest

from tyrelab.api import make_tyre_model
from tyrelab.cli.main import main
from tyrelab.errors import InputError
from tyrelab.tyre.handling.mf.model import MagicFormula
from tyrelab.tyre.library import load_tyre

from file_edit import edited
from spec_text import study_spec

PFZ1, PPX1, PPX2, DPI = 0.88241, -0.8733, 0.7035, 0.2


@pytest.fixture(scope="module")
def mf61_path(data_dir):
    return data_dir / "mfeval" / "MagicFormula61_Parameters.tir"


def _kxk(tyre, fz):
    mf = MagicFormula.from_tir(tyre.tir)
    return mf.steady_state(fz, 0.0, 0.0, 0.0, 16.7)["Kxk"]


def test_the_vertical_law_and_the_slip_stiffness_follow_the_pressure(mf61_path):
    nominal, moved = load_tyre(mf61_path), load_tyre(mf61_path, 312e3)
    assert moved.pressure == 312e3 and nominal.pressure == 260e3
    rho = np.array([0.01, 0.02, 0.04])
    np.testing.assert_allclose(moved.vertical_law.static_load(rho),
                               (1 + PFZ1 * DPI) * nominal.vertical_law.static_load(rho), rtol=1e-12)
    fz = np.array([3376.0, 6752.0, 10128.0])
    np.testing.assert_allclose(_kxk(moved, fz) / _kxk(nominal, fz), 1 + PPX1 * DPI + PPX2 * DPI ** 2,
                               rtol=1e-12)
    # the rigs' Magic Formula runs at the moved pressure
    assert make_tyre_model(mf61_path, "point", 312e3, handling="mf").handling_params().pressure == 312e3


def test_the_static_press_reports_the_stiffer_tyre(tmp_path, mf61_path):
    """From the command line: the plate press at 312 kPa carries 1 + PFZ1 dpi times the load."""
    loads = {}
    for kpa in (260, 312):
        out = tmp_path / f"plate_{kpa}.csv"
        assert main(["static", "--tyre", str(mf61_path), "--pressure", str(kpa), "--test", "plate",
                     "-o", str(out)]) == 0
        table = np.genfromtxt(out, delimiter=",", names=True)
        loads[kpa] = table["load"][table["deflection"] > 0]
    np.testing.assert_allclose(loads[312], (1 + PFZ1 * DPI) * loads[260], rtol=1e-9)


def test_outside_the_files_range_is_refused(mf61_path):
    with pytest.raises(InputError, match="pressure 150 kPa is outside .* 200-400 kPa"):
        load_tyre(mf61_path, 150e3)


def _replaced(tmp_path, path, old, new):
    return edited(path, tmp_path / "edited.tir", (old, new))


def test_a_file_without_the_pressure_terms_describes_its_own_pressure_only(tmp_path, mf61_path):
    as_52 = _replaced(tmp_path, mf61_path, "FITTYP                   =    61", "FITTYP = 6")
    with pytest.raises(InputError, match="describes 260 kPa only.*MF-Tyre 6.1/6.2 file with pressure"):
        load_tyre(as_52, 312e3)


def test_a_load_deflection_table_pins_the_file_to_its_pressure(tmp_path, mf61_path):
    table = "[DEFLECTION_LOAD_CURVE]\n{pen fz}\n0.0 0.0\n0.02 6000.0\n0.04 13000.0\n"
    with_table = _replaced(tmp_path, mf61_path, "[VERTICAL_FORCE_RANGE]", table + "[VERTICAL_FORCE_RANGE]")
    assert load_tyre(with_table).load_deflection is not None
    with pytest.raises(InputError, match=r"\[DEFLECTION_LOAD_CURVE\] is measured at 260 kPa only"):
        load_tyre(with_table, 312e3)


def test_an_fmu_carries_the_moved_file(tmp_path, mf61_path):
    """Exported at 312 kPa, the FMU's data hold the file at 312 kPa (a copy of the user's file
    would state 260 kPa), and an instance may move it again within the range."""
    from tyrelab.cosim.manifest import DATA, build_stepper, write_data

    tm = make_tyre_model(mf61_path, "point", 312e3, handling="none")
    resources = tmp_path / "resources"
    (resources / DATA).mkdir(parents=True)
    manifest = write_data(resources / DATA, tm, str(mf61_path), "flat", 6752.0, "C-axis", 0.0)
    assert manifest["tyre"]["pressure"] == 312e3
    laws = {}
    for kpa in (312, 360):
        stepper = build_stepper(resources, manifest, kpa * 1e3, 6752.0, 0.0, "C-axis", 0.0, 0.0)
        assert stepper.model.tyre.pressure == kpa * 1e3
        laws[kpa] = stepper.model.tyre.vertical_law.static_load(0.02)
    nominal = load_tyre(mf61_path).vertical_law.static_load(0.02)
    assert laws[312] == pytest.approx((1 + PFZ1 * DPI) * nominal, rel=1e-12)
    assert laws[360] == pytest.approx((1 + PFZ1 * 100 / 260) * nominal, rel=1e-12)


def test_mf_curves_at_another_pressure(tmp_path, mf61_path, capsys):
    """``tyrelab mf curves --pressure``: drawn at the moved pressure, refused outside the file's
    range in one line with exit 2; a file stating no pressure says so (not "nan kPa")."""
    assert main(["mf", "curves", str(mf61_path), "--pressure", "312", "-o", str(tmp_path / "c.png")]) == 0
    assert "Magic Formula 6.1, 312 kPa" in capsys.readouterr().out
    assert main(["mf", "curves", str(mf61_path), "--pressure", "450", "-o", str(tmp_path / "d.png")]) == 2
    assert "outside" in capsys.readouterr().err and not (tmp_path / "d.png").exists()
    mf52 = mf61_path.parent / "MagicFormula52_Parameters.tir"
    assert main(["mf", "curves", str(mf52), "--pressure", "250", "-o", str(tmp_path / "e.png")]) == 2
    text = capsys.readouterr().err
    assert "states no inflation pressure" in text and "nan" not in text


def test_a_study_takes_an_mf_file_at_another_pressure(tmp_path, mf61_path):
    """A study's [[tyre]] may give pressure_kpa for an MF-Tyre 6.x file: its runs take the
    moved tyre (their keys differ by the pressure); a file that cannot move is refused at the
    key, before any run."""
    from tyrelab.study.spec import parse_spec

    spec = parse_spec(study_spec(f'name = "mf61"\nfile = "{mf61_path}"\npressure_kpa = 312'),
                      tmp_path / "spec.toml")
    assert spec.tyres[0].pressure == 312e3
    run = spec.runs()[0]
    assert run.simulate_kwargs()["pressure"] == 312e3
    mf52 = mf61_path.parent / "CityBus_Pac02Tire.tir"
    with pytest.raises(InputError, match=r"line 7: tyre\[1\]\.pressure_kpa: .*describes 800 kPa only") \
            as err:
        parse_spec(study_spec(f'name = "bus"\nfile = "{mf52}"\npressure_kpa = 700'), tmp_path / "spec.toml")
    assert "\n" not in str(err.value)
