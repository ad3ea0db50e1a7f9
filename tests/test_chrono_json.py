"""Project Chrono's JSON tyre files read directly (tyrelab.tyre.chrono_json).

The Chrono files in tests/data/tir are unchanged copies (SOURCES.md there).
Expected numbers are read off the files' text by hand, not computed by the
reader under test.
"""

import json
import math
import re

import numpy as np
import pytest

from tyrelab.api import default_handling
from tyrelab.cli.main import main
from tyrelab.errors import InputError
from tyrelab.rig.static_press import static_press
from tyrelab.signal import read_signal
from tyrelab.tyre.chrono_json import SUPPORTED_TEMPLATES, read_chrono_json, read_chrono_tyre
from tyrelab.tyre.handling.mf import MagicFormula
from tyrelab.tyre.handling.pac89 import pac89_forces, pac89_params
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.tir import read_tir


@pytest.fixture(scope="module")
def tir_dir(data_dir):
    return data_dir / "tir"


@pytest.fixture(scope="module")
def pac89_pair(tir_dir):
    """(read from Chrono's JSON, the shipped built-in .tir)."""
    return read_chrono_tyre(tir_dir / "HMMWV_Pac89Tire.json"), load_tyre("hmmwv-pac89")


def _strip(text):
    return json.loads(re.sub(r'("(?:\\.|[^"\\])*")|//[^\n]*', lambda m: m.group(1) or "", text))


# --- Pac89: the JSON's numbers, typed here from tests/data/tir/HMMWV_Pac89Tire.json ----------

#: (JSON key path -> value), copied by hand from HMMWV_Pac89Tire.json
PAC89_JSON = {
    ("Mass",): 37.6,
    ("Inertia", 1): 6.69,                                   # [3.84, 6.69, 3.84]: the spin axis
    ("Design Parameters", "Unloaded Radius"): 0.464,
    ("Design Parameters", "Width"): 0.318,
    ("Design Parameters", "Vertical Stiffness"): 326332.4234,
    ("Design Parameters", "Vertical Damping"): 3483.932502,
}
#: "Vertical Curve Data", every row
PAC89_CURVE = [[0.0, 0.0], [0.01, 2830.0], [0.02, 6212.0], [0.03, 10146.0], [0.04, 14632.0],
               [0.05, 19670.0], [0.06, 25260.0], [0.07, 31402.0], [0.08, 38096.0], [0.09, 45342.0],
               [0.10, 53140.0]]
#: the non-zero handling coefficients; every other one of a0-a13, b0-b10, c0-c17 is 0.0
PAC89_LATERAL = {"a0": 1.49975356208205, "a1": -4.84987524731462, "a2": 812.449795340733,
                 "a3": 2613.92367840654, "a4": 48.857910109076, "a6": -0.00879541881020228,
                 "a7": 0.376999015041155}
PAC89_LONGITUDINAL = {"b0": 1.50018802672136, "b1": -15.7761466722458, "b2": 1022.11238546683,
                      "b3": -2.55317715303733, "b4": 208.777316195246, "b5": 0.0073134908964823,
                      "b6": -0.00376410345674027, "b7": 0.156330736057758, "b8": -1.15310023217878}
PAC89_ALIGNING = {"c0": 2.34, "c1": 0.990427, "c2": 2.96848, "c3": -0.277098, "c4": -0.944859,
                  "c6": 0.0027699, "c7": -0.0001151, "c8": 0.10, "c9": -1.3329}


def _coefficients(typed: dict, letter: str, count: int) -> np.ndarray:
    return np.array([typed.get(f"{letter}{i}", 0.0) for i in range(count)])


def test_pac89_json_gives_the_files_numbers(pac89_pair):
    """The tyre read from the JSON carries the numbers typed above from the file."""
    js, _ = pac89_pair
    assert js.wheel_mass == PAC89_JSON[("Mass",)]
    assert js.wheel_spin_inertia == PAC89_JSON[("Inertia", 1)]
    assert js.unloaded_radius == PAC89_JSON[("Design Parameters", "Unloaded Radius")]
    assert js.width == PAC89_JSON[("Design Parameters", "Width")]
    assert js.vertical_stiffness == PAC89_JSON[("Design Parameters", "Vertical Stiffness")]
    assert js.vertical_damping == PAC89_JSON[("Design Parameters", "Vertical Damping")]
    np.testing.assert_array_equal(js.load_deflection, PAC89_CURVE)
    assert js.stiffness == "table"  # the curve has precedence over the linear stiffness, as in Chrono
    assert js.shape is None and math.isnan(js.pressure)  # the JSON has neither
    assert default_handling(js) == "pac89"
    hp = pac89_params(js)
    np.testing.assert_array_equal(hp.lateral, _coefficients(PAC89_LATERAL, "a", 14))
    np.testing.assert_array_equal(hp.longitudinal, _coefficients(PAC89_LONGITUDINAL, "b", 11))
    np.testing.assert_array_equal(hp.aligning, _coefficients(PAC89_ALIGNING, "c", 18))
    # Chrono's PAC89 additions: "Lateral Stiffness": 261065.0, "Rolling Resistance": 0.015
    assert (hp.lateral_stiffness, hp.rolling_resistance) == (261065.0, 0.015)
    # the vertical law from those numbers: the curve's last row, and k x 10 mm when linear
    assert js.vertical_law.static_load(0.1) == pytest.approx(53140.0, rel=1e-12)
    assert js.with_stiffness("linear").vertical_law.static_load(0.01) == pytest.approx(3263.324234)


def test_the_shipped_tyre_is_the_json_read_now(pac89_pair):
    """Consistency, not a reference: the built-in hmmwv-pac89.tir was written from this JSON
    by the reader, so this checks only that the shipped file is still what the reader makes
    of the JSON (the numbers themselves are checked above against the file's text)."""
    js, shipped = pac89_pair
    for name in ("unloaded_radius", "width", "vertical_stiffness", "vertical_damping", "stiffness",
                 "wheel_mass", "wheel_spin_inertia", "damping_ramp"):
        assert getattr(js, name) == getattr(shipped, name), name
    assert set(js.tir.sections) == set(shipped.tir.sections)
    for name in js.tir.sections:
        a, b = js.tir.sections[name], shipped.tir.sections[name]
        assert a.entries == b.entries, name
        assert (a.table is None) == (b.table is None), name
        if a.table is not None:
            np.testing.assert_array_equal(a.table, b.table, err_msg=name)


def _mf(x, b, c, d, e):
    """Bakker, Nyborg & Pacejka (1989), eq. 1: D sin(C atan(B x - E (B x - atan(B x))))."""
    return d * math.sin(c * math.atan(b * x - e * (b * x - math.atan(b * x))))


def _pac89_by_hand(fz_n, kappa, alpha_deg, gamma_deg):
    """Fx, Fy, Mz in the PAC89 axes from the typed coefficients (Fz in kN, slip in % and degrees;
    the coefficients' zero shifts dropped: a8-a13, b9-b10, c10-c17 are 0 in the file)."""
    fz = fz_n * 1e-3
    a, b, c = PAC89_LATERAL, PAC89_LONGITUDINAL, PAC89_ALIGNING
    dx = (b["b1"] * fz + b["b2"]) * fz
    bcd_x = (b["b3"] * fz ** 2 + b["b4"] * fz) * math.exp(-b["b5"] * fz)
    ex = b["b6"] * fz ** 2 + b["b7"] * fz + b["b8"]
    fx = _mf(100 * kappa, bcd_x / (b["b0"] * dx), b["b0"], dx, ex)
    dy = (a["a1"] * fz + a["a2"]) * fz
    bcd_y = a["a3"] * math.sin(2 * math.atan(fz / a["a4"]))           # a5 = 0: no camber term
    fy = _mf(alpha_deg, bcd_y / (a["a0"] * dy), a["a0"], dy, a["a6"] * fz + a["a7"])
    dz = c["c1"] * fz ** 2 + c["c2"] * fz
    bcd_z = (c["c3"] * fz ** 2 + c["c4"] * fz) * (1 - c["c6"] * abs(gamma_deg))   # c5 = 0
    ez = c["c7"] * fz ** 2 + c["c8"] * fz + c["c9"]
    mz = _mf(alpha_deg, bcd_z / (c["c0"] * dz), c["c0"], dz, ez)
    return fx, fy, mz


@pytest.mark.parametrize("fz, kappa, alpha_deg, gamma_deg", [
    (2e3, 0.05, -12.0, 0.0), (8e3, -0.02, 2.0, 0.0), (15e3, 0.4, 8.0, 3.0), (30e3, -0.3, -1.0, 3.0)])
def test_pac89_json_forces_by_hand(pac89_pair, fz, kappa, alpha_deg, gamma_deg):
    """The forces of the tyre read from the JSON, against the formula evaluated here from the
    typed coefficients, and turned to the W-axis as the module documents (Fy, Mz change sign)."""
    js, _ = pac89_pair
    fx, fy, mz = _pac89_by_hand(fz, kappa, alpha_deg, gamma_deg)
    got = pac89_forces(pac89_params(js), fz, kappa, math.radians(alpha_deg), math.radians(gamma_deg))
    assert got == pytest.approx((fx, -fy, -mz), rel=1e-12)
    assert abs(fx) > 100.0 and abs(fy) > 100.0 and abs(mz) > 1.0  # none of them trivially zero


def test_json_keys_carry_their_lines(tir_dir):
    tir = read_chrono_json(tir_dir / "HMMWV_Pac89Tire.json")
    lines = (tir_dir / "HMMWV_Pac89Tire.json").read_text().splitlines()
    line = tir.sections["VERTICAL"].lines["VERTICAL_STIFFNESS"]
    assert '"Vertical Stiffness"' in lines[line - 1]
    line = tir.sections["LATERAL_COEFFICIENTS"].lines["A3"]
    assert '"a3"' in lines[line - 1]


# --- Fiala and TMeasy from Chrono's repository ----------------------------------------

def test_fiala_numbers_are_the_files(tir_dir):
    tyre = read_chrono_tyre(tir_dir / "HMMWV_FialaTire.json")
    # HMMWV_FialaTire.json: "Unloaded Radius": 0.47, "Width": 0.318, "Vertical Damping": 7500,
    # "Vertical Stiffness": 326332, 17 curve rows from [0.000, 0] to [0.080, 21699]
    assert tyre.unloaded_radius == 0.47
    assert tyre.width == 0.318
    assert tyre.vertical_stiffness == 326332.0
    assert tyre.vertical_damping == 7500.0
    assert tyre.load_deflection.shape == (17, 2)
    assert tuple(tyre.load_deflection[8]) == (0.040, 9027.0)
    assert tuple(tyre.load_deflection[-1]) == (0.080, 21699.0)
    assert tyre.stiffness == "table"  # the curve has precedence, as in Chrono
    assert tyre.wheel_mass == 37.6 and tyre.wheel_spin_inertia == 6.69
    assert default_handling(tyre) == "fiala"  # its CSLIP, CALPHA, UMIN, UMAX: tests/test_fiala.py
    # and the independent parse of the text agrees on every row
    js = _strip((tir_dir / "HMMWV_FialaTire.json").read_text())
    np.testing.assert_array_equal(tyre.load_deflection, js["Fiala Parameters"]["Vertical Curve Data"])


def test_fiala_static_press_with_the_point_model(tir_dir):
    """On the plate the point model carries the file's load at the file's deflections
    (the spline passes through the curve's points) and k x deflection when linear."""
    tyre = read_chrono_tyre(tir_dir / "HMMWV_FialaTire.json")
    table = static_press(TyreModel(tyre, contact="point"), [0.02, 0.04, 0.06], "plate")
    np.testing.assert_allclose(table["load"], [3477.0, 9027.0, 15368.0], rtol=1e-9)
    linear = static_press(TyreModel(tyre.with_stiffness("linear"), contact="point"), [0.03], "plate")
    assert linear["load"].iloc[0] == pytest.approx(326332.0 * 0.03, rel=1e-9)  # 9789.96 N


def test_tmeasy_by_load_index_is_chronos_guess(tir_dir):
    tyre = read_chrono_tyre(tir_dir / "HMMWV_TMeasyTire.json")
    # HMMWV_TMeasyTire.json: R0 0.4699 m, width 0.3175 m, rim radius 0.2095 m, 37.6 kg,
    # load index 108 = 1000 kg: k = 1000 x 9.81 / (0.16 x (0.4699 - 0.2095)) = 235455.07 N/m,
    # c = 2 x 0.5 x sqrt(k x 37.6) = 2975.42 N s/m
    assert tyre.unloaded_radius == 0.4699 and tyre.width == 0.3175
    assert tyre.tir.number("DIMENSION", "RIM_RADIUS") == 0.2095
    assert tyre.vertical_stiffness == pytest.approx(235455.07, abs=0.01)
    assert tyre.vertical_damping == pytest.approx(2975.42, abs=0.01)
    assert tyre.stiffness == "linear" and tyre.wheel_spin_inertia == 6.69
    assert any("GUESSED" in line for line in tyre.tir.header)


def test_tmeasy_with_explicit_vertical_parameters(tmp_path):
    path = tmp_path / "explicit.json"
    path.write_text(json.dumps({
        "Type": "Tire", "Template": "TMeasyTire",
        "Design": {"Unloaded Radius [m]": 0.5, "Mass [kg]": 40.0, "Inertia [kg.m2]": [4, 7, 4],
                   "Width [m]": 0.3, "Rim Radius [m]": 0.25},
        "Load Index": 108,  # the full parameterisation takes precedence, as in Chrono
        "Parameters": {"Vertical": {"Nominal Vertical Force [N]": 10000.0,
                                    "Tire Spring Curve Data": [[0.0, 0.0], [0.02, 5000.0], [0.05, 14000.0]],
                                    "Tire Vertical Damping [Ns/m]": 1500.0}}}))
    tyre = read_chrono_tyre(path)
    assert tyre.stiffness == "table" and tyre.vertical_damping == 1500.0
    assert tyre.vertical_law.static_load(0.02) == pytest.approx(5000.0)


# --- Pac02: a JSON naming a .tir --------------------------------------------------------

def test_pac02_json_reads_the_tir_it_names(tir_dir):
    tyre = load_tyre(tir_dir / "CityBus_Pac02Tire.json")
    plain = load_tyre(tir_dir / "CityBus_Pac02Tire.tir")
    # the .tir's values (UNLOADED_RADIUS 0.548, VERTICAL_STIFFNESS 1e6, VERTICAL_DAMPING 5000, IP 800 kPa)
    assert (tyre.unloaded_radius, tyre.vertical_stiffness, tyre.vertical_damping) == (0.548, 1e6, 5000.0)
    assert tyre.pressure == 800e3
    # the .tir has no [INERTIA]: the JSON's "Mass" 68.6 and "Inertia" [6.104, 11.144, 6.104] fill it
    assert plain.wheel_mass == 0.0 and tyre.wheel_mass == 68.6 and tyre.wheel_spin_inertia == 11.144
    assert tyre.name == "CityBus_Pac02Tire" and tyre.tir.source.endswith("CityBus_Pac02Tire.tir")
    assert default_handling(tyre) == "mf"
    np.testing.assert_array_equal(MagicFormula.from_tir(tyre.tir).coefficients,
                                  MagicFormula.from_tir(plain.tir).coefficients)


def test_pac02_missing_tir_names_the_key_and_path(tmp_path):
    path = tmp_path / "bus.json"
    path.write_text('{\n  "Type": "Tire",\n  "Template": "Pac02Tire",\n  "Mass": 68.6,\n'
                    '  "Inertia": [6.1, 11.1, 6.1],\n  "TIR Specification File": "bus/tire/Nowhere.tir"\n}\n')
    with pytest.raises(InputError) as err:
        read_chrono_tyre(path)
    assert err.value.field == "TIR Specification File" and err.value.line == 6
    assert "Nowhere.tir" in str(err.value) and str(tmp_path) in str(err.value)


def test_pac02_embedded_coefficients(tmp_path, tir_dir):
    """Chrono's embedded Pac02 keys land in the ADAMS sections: built here from the CityBus .tir."""
    tir = read_tir(tir_dir / "CityBus_Pac02Tire.tir")
    sections = {"Scaling Factors": "SCALING_COEFFICIENTS",
                "Longitudinal Coefficients": "LONGITUDINAL_COEFFICIENTS",
                "Lateral Coefficients": "LATERAL_COEFFICIENTS",
                "Aligning Coefficients": "ALIGNING_COEFFICIENTS",
                "Overturning Coefficients": "OVERTURNING_COEFFICIENTS",
                "Rolling Coefficients": "ROLLING_COEFFICIENTS"}
    doc = {"Type": "Tire", "Template": "Pac02Tire", "Mass": 68.6, "Inertia": [6.104, 11.144, 6.104],
           "Coefficient of Friction": 0.8,
           "Dimension": {"Unloaded Radius": 0.548, "Width": 0.318, "Rim Radius": 0.28},
           "Vertical": {"Vertical Stiffness": 1e6, "Vertical Damping": 5000, "Nominal Wheel Load": 35000,
                        "DREFF": 0.5, "BREFF": 3.5, "FREFF": -0.005},
           "Tire Conditions": {"Inflation Pressure": 8e5, "Nominal Inflation Pressure": 8e5}}
    for obj, section in sections.items():
        doc[obj] = {k: v for k, v in tir.sections[section].entries.items() if isinstance(v, (int, float))}
    path = tmp_path / "embedded.json"
    path.write_text(json.dumps(doc, indent=1))
    tyre = read_chrono_tyre(path)
    for obj, section in sections.items():
        assert tyre.tir.sections[section].entries == doc[obj], section
        assert len(doc[obj]) > 0
    assert tyre.tir.number("VERTICAL", "FNOMIN") == 35000.0 and tyre.pressure == 8e5
    assert (tyre.unloaded_radius, tyre.width, tyre.vertical_stiffness) == (0.548, 0.318, 1e6)
    assert default_handling(tyre) == "mf"
    theirs, ours = MagicFormula.from_tir(tir), MagicFormula.from_tir(tyre.tir)
    assert ours.version == theirs.version == "5.2"
    for name in ("PCY1", "PDX1", "QBZ1", "LMUY", "FNOMIN", "UNLOADED_RADIUS"):
        assert ours.coefficient(name) == theirs.coefficient(name), name


def test_mftire_json_is_the_mfeval_property_file(tir_dir, data_dir):
    """Chrono's MFTire JSON embeds the property file MFeval ships as MagicFormula52_Parameters.tir."""
    tyre = read_chrono_tyre(tir_dir / "MagicFormula52_Parameters.json")
    # the JSON's "UNLOADED_RADIUS": 0.4, "VERTICAL_STIFFNESS": 463000, "MASS": 17.451, "IYY": 0.7
    assert (tyre.unloaded_radius, tyre.vertical_stiffness) == (0.4, 463000.0)
    assert (tyre.wheel_mass, tyre.wheel_spin_inertia) == (17.451, 0.7)
    assert default_handling(tyre) == "mf"
    ours = MagicFormula.from_tir(tyre.tir)
    theirs = MagicFormula.from_tir(data_dir / "mfeval" / "MagicFormula52_Parameters.tir")
    assert ours.version == theirs.version == "5.2"
    np.testing.assert_array_equal(ours.coefficients, theirs.coefficients)


def test_mftire_embedded_units_apply(tmp_path):
    path = tmp_path / "mm.json"
    path.write_text(json.dumps({"Type": "Tire", "Template": "MFTire", "Mass": 10.0, "Inertia": [1, 2, 1],
                                "UNITS": {"LENGTH": "mm", "FORCE": "newton"},
                                "MODEL": {"FITTYP": 6},
                                "DIMENSION": {"UNLOADED_RADIUS": 400, "WIDTH": 250},
                                "VERTICAL": {"FNOMIN": 5000, "VERTICAL_STIFFNESS": 300}}))
    tyre = read_chrono_tyre(path)
    assert (tyre.unloaded_radius, tyre.width) == (0.4, 0.25)
    assert tyre.vertical_stiffness == pytest.approx(300e3)  # N/mm -> N/m
    assert (tyre.wheel_mass, tyre.wheel_spin_inertia) == (10.0, 2.0)  # from "Mass", "Inertia"
    path.write_text(path.read_text().replace('"mm"', '"furlong"'))
    with pytest.raises(InputError, match="unknown length unit") as err:
        read_chrono_tyre(path)
    assert err.value.field == "UNITS > LENGTH"


# --- bad input: one InputError naming file, line and key --------------------------------

def _write(tmp_path, text, name="tyre.json"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_malformed_json_gives_its_line(tmp_path):
    path = _write(tmp_path, '{\n  /* a block\n     comment */\n  "Type": "Tire",\n'
                            '  "Template": "FialaTire"\n  "Mass": 37.6\n}\n')
    with pytest.raises(InputError) as err:
        read_chrono_tyre(path)
    assert err.value.line == 6 and err.value.source == str(path)
    assert "malformed JSON" in str(err.value) and f"{path}, line 6" in str(err.value)


def test_missing_key_is_named(tmp_path, tir_dir):
    text = (tir_dir / "HMMWV_Pac89Tire.json").read_text()
    text = re.sub(r'\n\s*"Unloaded Radius": 0.464,', "", text)
    with pytest.raises(InputError) as err:
        read_chrono_tyre(_write(tmp_path, text))
    assert err.value.field == "Design Parameters > Unloaded Radius"
    assert "missing key 'Unloaded Radius'" in str(err.value)
    assert err.value.line == 12  # the object that lacks it
    text = (tir_dir / "HMMWV_Pac89Tire.json").read_text().replace('"c17" : 0.0', '"c71" : 0.0')
    with pytest.raises(InputError, match="missing key 'c17'"):
        read_chrono_tyre(_write(tmp_path, text))


def test_unknown_template_lists_the_supported_ones(tmp_path):
    path = _write(tmp_path, '{"Type": "Tire",\n "Template": "BananaTire"}')
    with pytest.raises(InputError) as err:
        read_chrono_tyre(path)
    assert err.value.field == "Template" and err.value.line == 2
    for name in SUPPORTED_TEMPLATES:
        assert name in str(err.value)
    with pytest.raises(InputError, match="finite-element"):
        read_chrono_tyre(_write(tmp_path, '{"Type": "Tire", "Template": "ANCFTire", "Tire Radius": 0.47}'))


@pytest.mark.parametrize("bad", ["NaN", "Infinity", "-Infinity", "1e999"])
def test_non_finite_value(tmp_path, tir_dir, bad):
    text = (tir_dir / "HMMWV_FialaTire.json").read_text().replace('"Vertical Damping": 7500',
                                                                   f'"Vertical Damping": {bad}')
    with pytest.raises(InputError) as err:
        read_chrono_tyre(_write(tmp_path, text))
    assert err.value.field == "Fiala Parameters > Vertical Damping" and err.value.line == 15
    assert "finite" in str(err.value)


@pytest.mark.parametrize("old,new,match", [
    ('"Width": 0.318,\n        "Vertical Damping"', '"Width": -0.318,\n        "Vertical Damping"',
     "positive"),
    ("[ 0.040,  9027 ]", "[ 0.030,  9027 ]", "increase strictly"),
    ("[ 0.040,  9027 ]", '[ 0.040,  "9027" ]', "expected a number"),
    ('"Template": "FialaTire"', '"Template": 3', "non-empty string"),
    ('"Type": "Tire"', '"Type": "Wheel"', "Chrono tyre file"),
])
def test_values_out_of_range(tmp_path, tir_dir, old, new, match):
    text = (tir_dir / "HMMWV_FialaTire.json").read_text()
    assert old in text
    with pytest.raises(InputError, match=match):
        read_chrono_tyre(_write(tmp_path, text.replace(old, new)))


def test_library_dispatches_json_and_keeps_its_errors(tmp_path, tir_dir):
    assert load_tyre(str(tir_dir / "HMMWV_FialaTire.json")).name == "HMMWV_FialaTire"
    with pytest.raises(InputError, match="no such Chrono tyre file"):
        load_tyre(tmp_path / "absent.json")
    with pytest.raises(InputError, match="states no inflation pressure"):  # as for a .tir
        load_tyre(tir_dir / "HMMWV_FialaTire.json", pressure=200e3)
    stated = tmp_path / "stated.json"
    stated.write_text(json.dumps({
        "Type": "Tire", "Template": "TMeasyTire", "Load Index": 108, "Vehicle Type": "Truck",
        "Inflation Pressure Use [Pa]": 250e3,
        "Design": {"Unloaded Radius [m]": 0.5, "Mass [kg]": 40.0, "Inertia [kg.m2]": [4, 7, 4],
                   "Width [m]": 0.3, "Rim Radius [m]": 0.25}}))
    assert load_tyre(stated, pressure=250e3).pressure == 250e3
    with pytest.raises(InputError, match="describes 250 kPa only; a single property file cannot be moved"):
        load_tyre(stated, pressure=200e3)


# --- the command line -------------------------------------------------------------------

def test_cli_simulates_a_chrono_json_tyre(tmp_path, tir_dir, capsys):
    out = tmp_path / "hmmwv.parquet"
    code = main(["simulate", "--tyre", str(tir_dir / "HMMWV_Pac89Tire.json"), "--model", "point",
                 "--road", "cleat:50x50", "--speed", "36", "--load", "15000", "--duration", "0.7",
                 "-o", str(out)])
    assert code == 0, capsys.readouterr().err
    run = read_signal(out)
    assert run["DISTANCE"].iloc[-1] > 5.3  # over the cleat (it starts at x = 5 m)
    assert run["FZW"].max() > 1.2 * run["FZW"].iloc[:100].mean()
    assert run["FZW"].iloc[:100].mean() == pytest.approx(15000.0, rel=0.01)
    code = main(["simulate", "--tyre", str(tmp_path / "absent.json"), "-o", str(tmp_path / "x.parquet")])
    assert code == 2 and "absent.json" in capsys.readouterr().err
