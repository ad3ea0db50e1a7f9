"""Magic Formula model against MFeval 4.3.1 tables (every row, both use modes).

The tables in tests/data/mfeval are MFeval's outputs (see README.md there);
nothing here is computed by tyrelab.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tyrelab.tyre.handling.mf import MagicFormula, mf_forces_many

DATA = Path(__file__).parent / "data" / "mfeval"
FILES = {"CityBus_Pac02Tire": "5.2", "MagicFormula52_Parameters": "5.2",
         "MagicFormula61_Parameters": "6.1"}
CASES = [(name, mode) for name in FILES for mode in (111, 121)]

FORCES = ("Fx", "Fy", "Mx", "My", "Mz")
LENGTHS = ("Re", "Rl", "rho", "contact_length_2a", "contact_width_2b")
#: further MFeval outputs, compared at 1e-6 relative (or 1e-9 absolute near zero)
OTHERS = ("mux", "muy", "t", "Mzr", "omega", "Kya", "Kxk", "Cx", "Cy", "Cz", "sigmax",
          "sigmay", "P", "iKya")
ECHOED = {"Fz": "Fz_out", "kappa": "kappa_out", "alpha": "alpha_out", "gamma": "gamma_out",
          "phit": "phit_out", "Vx": "Vx_out"}


@pytest.fixture(scope="module")
def models():
    return {name: MagicFormula.from_tir(DATA / f"{name}.tir") for name in FILES}


def _table(name, mode):
    table = pd.read_csv(DATA / f"{name}.mode{mode}.csv.gz")
    assert len(table) == 1014
    return table


def _run(model, table, mode):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the tables stay inside every limit: no warning
        return model.steady_state(table["Fz"].to_numpy(), table["kappa"].to_numpy(),
                                  table["alpha"].to_numpy(), table["gamma"].to_numpy(),
                                  table["Vx"].to_numpy(), use_mode=mode)


def _assert_close(name, got, ref, rel, abs_):
    tol = np.maximum(rel * np.abs(ref), abs_)
    err = np.abs(got - ref)
    bad = np.flatnonzero(~(err <= tol))
    assert bad.size == 0, (f"{name}: {bad.size} rows out of tolerance, first row {bad[0]}: "
                           f"got {got[bad[0]]!r}, MFeval {ref[bad[0]]!r}")


@pytest.mark.parametrize("name", FILES)
def test_version_detected(models, name):
    assert models[name].version == FILES[name]


@pytest.mark.parametrize("name,mode", CASES)
def test_forces_and_moments_match_mfeval(models, name, mode):
    table = _table(name, mode)
    result = _run(models[name], table, mode)
    for q in FORCES:
        _assert_close(q, result[q], table[q].to_numpy(), 1e-6, 1e-3)


@pytest.mark.parametrize("name,mode", CASES)
def test_radii_and_contact_patch_match_mfeval(models, name, mode):
    table = _table(name, mode)
    result = _run(models[name], table, mode)
    for q in LENGTHS:
        _assert_close(q, result[q], table[q].to_numpy(), 0.0, 1e-6)


@pytest.mark.parametrize("name,mode", CASES)
def test_other_outputs_match_mfeval(models, name, mode):
    table = _table(name, mode)
    result = _run(models[name], table, mode)
    for q in OTHERS:
        _assert_close(q, result[q], table[q].to_numpy(), 1e-6, 1e-9)
    for q, column in ECHOED.items():
        _assert_close(q, result[q], table[column].to_numpy(), 0.0, 1e-12)


@pytest.mark.parametrize("name,mode", CASES)
def test_compiled_mf_forces_matches_mfeval(models, name, mode):
    """The scalar kernel for the lead's rigs gives the same table values."""
    table = _table(name, mode)
    n = len(table)
    out = np.zeros((n, 6))
    cols = [table[c].to_numpy(dtype=float) for c in ("Fz", "kappa", "alpha", "gamma", "Vx")]
    mf_forces_many(models[name].coefficients, mode, *cols, np.zeros(n), out)
    for i, q in enumerate(FORCES):
        _assert_close(q, out[:, i], table[q].to_numpy(), 1e-6, 1e-3)
    assert np.all(out[:, 5] == 0.0)  # no limit flag inside the ranges
