"""The .tir (TeimOrbit) reader and writer."""

import warnings

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.tyre.tir import RepeatedSectionWarning, format_tir, parse_tir, read_tir, write_tir

REAL_FILES = ["335_65R22_5_G275MSA_40psi.tir", "335_65R22_5_G275MSA_95psi.tir", "CityBus_Pac02Tire.tir"]


@pytest.mark.parametrize("name", REAL_FILES)
def test_every_real_file_parses(data_dir, name):
    tir = read_tir(data_dir / "tir" / name)
    # every file states its dimensions and its nominal load
    assert tir.number("DIMENSION", "UNLOADED_RADIUS") > 0.3
    assert tir.number("VERTICAL", "FNOMIN") > 1000


def test_feda_values_in_si(data_dir):
    tir = read_tir(data_dir / "tir" / "335_65R22_5_G275MSA_40psi.tir")
    assert tir.number("DIMENSION", "UNLOADED_RADIUS") == pytest.approx(0.4987)
    assert tir.number("VERTICAL", "VERTICAL_STIFFNESS") == pytest.approx(4.0652e5)
    assert tir.get("MODEL", "PROPERTY_FILE_FORMAT") == "MF_05"
    table = tir.table("DEFLECTION_LOAD_CURVE")
    np.testing.assert_allclose(table, [[0.0, 0.0], [0.05, 17876.049], [0.10, 40051.666]])
    np.testing.assert_allclose(tir.table("SHAPE")[-1], [0.90, 1.00])


def test_units_section_converts_to_si():
    text = """[UNITS]
LENGTH = 'mm'
FORCE = 'kN'
ANGLE = 'degrees'
MASS = 'gram'
TIME = 'millisecond'
[DIMENSION]
UNLOADED_RADIUS = 500   $ mm
[VERTICAL]
VERTICAL_STIFFNESS = 0.4   $ kN/mm = 400 kN/m
VERTICAL_DAMPING = 0.5  $ kN ms/mm = 0.5 N s/mm = 500 N s/m
FNOMIN = 4.5
[OPERATING_CONDITIONS]
INFLPRES = 0.00025   $ kN/mm^2 = 250 kPa
[SLIP_ANGLE_RANGE]
ALPMAX = 15
[INERTIA]
MASS = 9000
[DEFLECTION_LOAD_CURVE]
{pen fz}
0 0
10 3.5
"""
    tir = parse_tir(text, "units.tir")
    assert tir.number("DIMENSION", "UNLOADED_RADIUS") == pytest.approx(0.5)
    assert tir.number("VERTICAL", "VERTICAL_STIFFNESS") == pytest.approx(4.0e5)
    assert tir.number("VERTICAL", "VERTICAL_DAMPING") == pytest.approx(500.0)
    assert tir.number("VERTICAL", "FNOMIN") == pytest.approx(4500.0)
    assert tir.number("OPERATING_CONDITIONS", "INFLPRES") == pytest.approx(250e3)
    assert tir.number("SLIP_ANGLE_RANGE", "ALPMAX") == pytest.approx(np.radians(15))
    assert tir.number("INERTIA", "MASS") == pytest.approx(9.0)
    np.testing.assert_allclose(tir.table("DEFLECTION_LOAD_CURVE"), [[0, 0], [0.01, 3500.0]])


def test_built_in_xzl_file_is_table_3_2(xzl):
    # the built-in file is written in mm; Table 3-2 at 300 kPa, in SI
    np.testing.assert_allclose(xzl.load_deflection[:, 0], np.arange(0, 0.081, 0.01), atol=1e-12)
    np.testing.assert_allclose(xzl.load_deflection[:, 1],
                               [0, 3496, 9445, 15559, 21968, 29011, 37581, 45717, 54191])
    assert xzl.unloaded_radius == pytest.approx(1.343 / 2)
    assert xzl.vertical_damping == pytest.approx(2660.0)       # 2.66 N s/mm
    assert xzl.vertical_stiffness == pytest.approx(659.6e3)    # 659.6 N/mm


def test_repeated_section_later_one_wins_with_warning():
    text = """[UNITS]
LENGTH = 'meter'
[DEFLECTION_LOAD_CURVE]
{pen fz}
0 0
0.05 10000
[VERTICAL]
FNOMIN = 5000
[DEFLECTION_LOAD_CURVE]
{pen fz}
0 0
0.05 20000
0.10 45000
"""
    with pytest.warns(RepeatedSectionWarning, match=r"line 3 and again at line 9"):
        tir = parse_tir(text, "twice.tir")
    np.testing.assert_allclose(tir.table("DEFLECTION_LOAD_CURVE"), [[0, 0], [0.05, 20000], [0.1, 45000]])


@pytest.mark.parametrize("text, line, what", [
    ("[UNITS]\nLENGTH = 'meter'\n[DIMENSION\nWIDTH = 0.3\n", 3, "malformed section header"),
    ("[DIMENSION]\nWIDTH = 0.3x\n", 2, "expected a number"),
    ("[DIMENSION]\nWIDTH = 'abc\n", 2, "unterminated string"),
    ("WIDTH = 0.3\n[DIMENSION]\n", 1, "before the first"),
    ("[SHAPE]\n1.0 0.0\n1.0 0.5 0.3\n", 3, "table row has 3 values"),
    ("[DIMENSION]\nWIDTH = 0.3\n1.0 2.0\n", 3, "row of numbers inside"),
    ("[SHAPE]\n1.0 0.0\nfoo bar\n", 3, "expected 'KEY = value'"),
    ("[UNITS]\nLENGTH = 'furlong'\n[DIMENSION]\nWIDTH = 0.3\n", None, "unknown length unit"),
])
def test_malformed_file_names_line(text, line, what):
    with pytest.raises(InputError) as err:
        parse_tir(text, "bad.tir")
    assert what in str(err.value)
    assert "bad.tir" in str(err.value)
    if line is not None:
        assert err.value.line == line


def test_missing_file_is_clear(tmp_path):
    with pytest.raises(InputError, match="no such tyre property file"):
        read_tir(tmp_path / "nope.tir")


@pytest.mark.parametrize("units", [None, {"LENGTH": "mm", "FORCE": "kN"}])
def test_write_read_round_trip(data_dir, tmp_path, units):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        original = read_tir(data_dir / "tir" / "335_65R22_5_G275MSA_95psi.tir")
    path = tmp_path / "copy.tir"
    write_tir(original, path, units=units)
    again = read_tir(path)
    for name, sec in original.sections.items():
        if name == "UNITS":
            continue
        for key, value in sec.entries.items():
            got = again.get(name, key)
            if isinstance(value, float):
                assert got == pytest.approx(value, rel=1e-12), (name, key)
            else:
                assert got == value, (name, key)
        if sec.table is not None:
            np.testing.assert_allclose(again.table(name), sec.table, rtol=1e-12)
    if units:
        assert "LENGTH = 'mm'" in format_tir(original, units).replace("  ", " ")


def test_a_file_that_states_no_pressure_says_so(data_dir, capsys):
    """The FEDA file gives its pressure only in a vendor section (INFLATION_PRESSURE = 6.5 in
    [GOODYEAR]): the tyre's pressure is unknown, and a pressure asked of it cannot be checked."""
    from tyrelab.cli.main import main

    feda = str(data_dir / "tir" / "335_65R22_5_G275MSA_95psi.tir")
    assert main(["static", "--tyre", feda, "--steps", "3"]) == 0
    header = capsys.readouterr().out.splitlines()[0]
    assert "pressure not stated" in header and "nan" not in header
    assert main(["static", "--tyre", feda, "--steps", "3", "--pressure", "600"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "335_65R22_5_G275MSA_95psi.tir states no inflation pressure" in err[0]
    assert "nan" not in err[0]
