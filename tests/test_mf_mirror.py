"""A mirrored Magic Formula tyre: a negative USE_MODE, or a tyre mounted on the other side of a
vehicle than its TYRESIDE (the trailer's wheels: ``tests/test_trailer.py``).

The kernel mirrors by evaluating the file's tyre at the mirrored slip angle and inclination
and turning its Fy, Mx and Mz over (:func:`tyrelab.tyre.handling.mf.kernel.mirror_sign`).
Oracle: Project Chrono's ``ChPac02Tire`` mirrors a PAC2002 file the other way, by negating
its 18 coefficients of the asymmetric effects; the CityBus file (MFeval's PAC2002 example,
most of those coefficients non-zero) with them negated must be the mirrored tyre.
"""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest

from tyrelab.tyre.handling.mf.model import MagicFormula
from tyrelab.tyre.tir import parse_tir

#: the coefficients ChPac02Tire negates to mirror a tyre (ChPac02Tire::Initialize)
CHRONO_MIRRORED = ("RHX1", "QSX1", "PEY3", "PHY1", "PHY2", "PVY1", "PVY2", "RBY3", "RVY1", "RVY2",
                   "QBZ4", "QDZ3", "QDZ6", "QDZ7", "QEZ4", "QHZ1", "QHZ2", "SSZ1")
NO_LIMITS = 211


def negated(text: str, names) -> str:
    """``text`` with the values of the keys ``names`` negated."""
    for name in names:
        text, n = re.subn(rf"^({name}\s*=\s*)(\S+)", lambda m: f"{m[1]}{-float(m[2])!r}", text,
                          flags=re.M)
        assert n == 1, name
    return text


def outputs(mf, fz, kappa, alpha, gamma):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = mf.steady_state(fz, kappa, alpha, gamma, 15.0, use_mode=NO_LIMITS)
    return np.stack([r[k] for k in ("Fx", "Fy", "Mx", "My", "Mz")])


@pytest.fixture(scope="module")
def citybus(data_dir):
    return (data_dir / "mfeval" / "CityBus_Pac02Tire.tir").read_text()


def test_a_negative_use_mode_mirrors_the_tyre_as_chrono_does(citybus):
    rng = np.random.default_rng(5)
    n = 400
    fz = rng.uniform(5e3, 4e4, n)
    kappa = rng.uniform(-0.4, 0.4, n)
    alpha = rng.uniform(-0.25, 0.25, n)
    gamma = rng.uniform(-0.08, 0.08, n)
    mirrored = citybus.replace("USE_MODE                   = 4 ", "USE_MODE                   = -4")
    assert mirrored != citybus
    ours = MagicFormula.from_tir(parse_tir(mirrored, "mirrored.tir"))
    assert ours.coefficient("MIRRORED") == 1.0
    chrono = MagicFormula.from_tir(parse_tir(negated(citybus, CHRONO_MIRRORED), "chrono.tir"))
    got, want = outputs(ours, fz, kappa, alpha, gamma), outputs(chrono, fz, kappa, alpha, gamma)
    scale = np.abs(want).max(axis=1, keepdims=True)
    assert np.all(np.abs(got - want) <= 1e-9 * scale)
    # and it is another tyre: the offsets turned over
    plain = outputs(MagicFormula.from_tir(parse_tir(citybus, "plain.tir")), fz, kappa, alpha, gamma)
    assert np.abs(plain[1] - got[1]).max() > 0.01 * scale[1, 0]


def test_mirroring_twice_gives_the_tyre_back(citybus):
    """A file mirrored by its USE_MODE, mounted on the other side, is the tyre as measured."""
    from tyrelab.tyre.handling.mf.wheel import MagicFormulaParams, mf_mirrored

    mirrored = MagicFormula.from_tir(parse_tir(citybus.replace("USE_MODE                   = 4 ",
                                                               "USE_MODE                   = -4"), "m.tir"))
    params = mf_mirrored(MagicFormulaParams(mirrored.coefficients, 111, 0.0))
    plain = MagicFormula.from_tir(parse_tir(citybus, "plain.tir"))
    assert np.array_equal(params.coefficients, plain.coefficients)
