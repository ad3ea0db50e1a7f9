"""Reading Magic Formula property files: version, defaults, units, bad input."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.tyre.handling.mf import MagicFormula
from tyrelab.tyre.tir import parse_tir

DATA = Path(__file__).parent / "data" / "mfeval"
MF61 = (DATA / "MagicFormula61_Parameters.tir").read_text()


def minimal_tir(model="FITTYP = 61", vertical="FNOMIN = 4000\nVERTICAL_STIFFNESS = 200000",
                extra="") -> str:
    """A small property file: everything not given takes MFeval's defaults."""
    return f"""[UNITS]
LENGTH = 'meter'
FORCE = 'newton'
ANGLE = 'radians'
MASS = 'kg'
TIME = 'second'
[MODEL]
{model}
[DIMENSION]
UNLOADED_RADIUS = 0.3
WIDTH = 0.2
[VERTICAL]
{vertical}
{extra}
"""


def model_of(text, source="test.tir"):
    return MagicFormula.from_tir(parse_tir(text, source=source))


@pytest.mark.parametrize("model,version", [
    ("FITTYP = 5", "5.2"), ("FITTYP = 6", "5.2"), ("FITTYP = 21", "5.2"), ("FITTYP = 61", "6.1"),
    ("FITTYP = 62", "6.2"),
    ("PROPERTY_FILE_FORMAT = 'PAC2002'", "5.2"), ("PROPERTY_FILE_FORMAT = 'MF_61'", "6.1"),
    ("PROPERTY_FILE_FORMAT = 'USER'\nFITTYP = 62", "6.2"),
    ("PROPERTY_FILE_FORMAT = 'USER'\nFILE_VERSION = 6.1", "6.1"),
])
def test_version_from_fittyp_or_property_file_format(model, version):
    assert model_of(minimal_tir(model)).version == version


def test_citybus_without_fittyp_is_read_as_pac2002():
    assert MagicFormula.from_tir(DATA / "CityBus_Pac02Tire.tir").version == "5.2"


def test_unknown_fittyp_names_file_and_key():
    with pytest.raises(InputError) as info:
        model_of(minimal_tir("FITTYP = 4"), source="old_pac94.tir")
    text = str(info.value)
    assert "old_pac94.tir" in text and "FITTYP" in text and "line 8" in text


def test_missing_version_names_file_and_key():
    with pytest.raises(InputError, match=r"nover\.tir.*FITTYP"):
        model_of(minimal_tir("LONGVL = 16.7"), source="nover.tir")


def test_pac89_file_is_refused():
    with pytest.raises(InputError, match=r"PROPERTY_FILE_FORMAT.*PAC89"):
        model_of(minimal_tir("PROPERTY_FILE_FORMAT = 'PAC89'"))


def test_missing_fnomin_names_file_and_key():
    with pytest.raises(InputError) as info:
        model_of(minimal_tir(vertical="VERTICAL_STIFFNESS = 200000"), source="nofnomin.tir")
    assert "nofnomin.tir" in str(info.value) and "FNOMIN" in str(info.value)
    assert info.value.field == "FNOMIN"


def test_non_numeric_coefficient_names_key():
    with pytest.raises(InputError, match="PCX1"):
        model_of(minimal_tir(extra="[LONGITUDINAL_COEFFICIENTS]\nPCX1 = 'abc'"))


def test_mfeval_defaults_for_missing_coefficients():
    m = model_of(minimal_tir())
    assert m.coefficient("PKY4") == 2.0
    assert m.coefficient("QSX4") == 5.0
    assert m.coefficient("Q_FZ2") == 1e-4
    assert m.coefficient("LONGVL") == 16.7
    assert m.coefficient("INFLPRES") == 220000.0
    assert m.coefficients.dtype == np.float64 and m.coefficients.ndim == 1


def test_hand_computed_pure_forces_and_rolling_resistance():
    """Defaults only: Fy = D sin(C atan(B alpha)), Fx likewise, My = -R0 Fz0 (QSY1+QSY3+QSY4)."""
    m = model_of(minimal_tir())
    fz0, alpha, kappa = 4000.0, 0.05, 0.1
    lat = m.steady_state(fz0, 0.0, alpha, 0.0, 16.7, use_mode=111)
    kya = -20.0 * fz0 * math.sin(2.0 * math.atan(1.0))       # PKY1, PKY2 = 1, PKY4 = 2
    dy = 1.1 * fz0                                           # PDY1
    fy = dy * math.sin(1.3 * math.atan(kya / (1.3 * dy) * alpha))  # PCY1
    assert lat["Fy"] == pytest.approx(fy, rel=1e-9)
    assert lat["Kya"] == pytest.approx(kya, rel=1e-12)
    lon = m.steady_state(fz0, kappa, 0.0, 0.0, 16.7, use_mode=111)
    dx = 1.3 * fz0                                           # PDX1
    fx = dx * math.sin(1.65 * math.atan(20.0 * fz0 / (1.65 * dx) * kappa))  # PKX1, PCX1
    assert lon["Fx"] == pytest.approx(fx, rel=1e-9)
    free = m.steady_state(fz0, 0.0, 0.0, 0.0, 16.7, use_mode=111)
    assert free["My"] == pytest.approx(-0.3 * fz0 * (0.01 + 4e-4 + 4e-5), rel=1e-12)


def _to_millimetres(text: str) -> str:
    """The 6.1 example file rewritten in millimetres (lengths, speeds, stiffnesses, pressures)."""
    factors = {"UNLOADED_RADIUS": 1e3, "WIDTH": 1e3, "RIM_RADIUS": 1e3, "RIM_WIDTH": 1e3,
               "BOTTOM_OFFST": 1e3, "LONGVL": 1e3, "VXLOW": 1e3, "VERTICAL_STIFFNESS": 1e-3,
               "LONGITUDINAL_STIFFNESS": 1e-3, "LATERAL_STIFFNESS": 1e-3,
               "INFLPRES": 1e-6, "NOMPRES": 1e-6, "PRESMIN": 1e-6, "PRESMAX": 1e-6}
    out = []
    for line in text.splitlines():
        m = re.match(r"^(\w+)(\s*=\s*)([-+0-9.eE]+)(.*)$", line)
        if m and m.group(1) in factors:
            line = f"{m.group(1)}{m.group(2)}{float(m.group(3)) * factors[m.group(1)]!r}{m.group(4)}"
        elif line.startswith("LENGTH"):
            line = "LENGTH = 'mm'"
        out.append(line)
    return "\n".join(out)


def test_non_si_file_gives_the_same_model():
    si = model_of(MF61)
    mm = model_of(_to_millimetres(MF61))
    assert mm.coefficient("PRESMIN") == pytest.approx(200000.0, rel=1e-12)
    assert mm.coefficient("LONGITUDINAL_STIFFNESS") == pytest.approx(391219.8116, rel=1e-12)
    args = (np.array([3000.0, 9000.0]), np.array([0.05, -0.1]), np.array([0.1, -0.2]),
            np.array([0.02, 0.0]), 16.7)
    a, b = si.steady_state(*args), mm.steady_state(*args)
    for q in ("Fx", "Fy", "Mx", "My", "Mz", "Re", "Rl", "contact_length_2a", "sigmax"):
        np.testing.assert_allclose(b[q], a[q], rtol=1e-9, err_msg=q)
