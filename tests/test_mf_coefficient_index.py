"""The generated Magic Formula index module is current with the coefficient name list.

``tyre/handling/mf/coefficient_index.py`` (one ``NAME = position`` line per coefficient,
read by the compiled kernels as ``C.NAME``) is written by
``python tools/make_mf_coefficient_index.py`` from ``coefficients.NAMES``. Were it stale,
the kernels would read the wrong slots of the packed vector: wrong forces, no error.
"""

from __future__ import annotations

import ast
import re

import pytest

from tyrelab.tyre.handling.mf import coefficient_index, coefficients


def test_the_generated_module_is_current():
    text = coefficients.INDEX_MODULE.read_text(encoding="utf-8")
    assert text == coefficients.index_module_source(), (
        "coefficient_index.py is not current: run python tools/make_mf_coefficient_index.py")
    assert coefficients.stale_index_names() == []


def test_every_name_sits_at_its_position_in_the_packed_vector():
    assert coefficient_index.N_COEFFICIENTS == coefficients.N_COEFFICIENTS == len(coefficients.NAMES)
    for i, name in enumerate(coefficients.NAMES):
        assert getattr(coefficient_index, name) == i == coefficients.INDEX[name]


def test_the_module_is_plain_assignments():
    """Explicit lines an editor and ruff can see, nothing computed (the old module made
    its constants with ``globals()[name] = i``)."""
    tree = ast.parse(coefficients.INDEX_MODULE.read_text(encoding="utf-8"))
    body = [node for node in tree.body if not (isinstance(node, ast.Expr) and node is tree.body[0])]
    assert all(isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant) for node in body)
    assert "globals()" not in coefficients.INDEX_MODULE.with_name("coefficients.py").read_text()


def test_a_stale_module_is_caught(monkeypatch):
    """A name added to the list without regenerating: the check and pack() both refuse."""
    monkeypatch.setattr(coefficients, "NAMES", coefficients.NAMES[:-1] + ("NEW_SLOT",)
                        + coefficients.NAMES[-1:])
    monkeypatch.setattr(coefficients, "N_COEFFICIENTS", len(coefficients.NAMES))
    assert "NEW_SLOT" in coefficients.stale_index_names()
    assert coefficients.index_module_source() != coefficients.INDEX_MODULE.read_text(encoding="utf-8")
    monkeypatch.setattr(coefficients, "_index_checked", False)
    with pytest.raises(RuntimeError, match="make_mf_coefficient_index"):
        coefficients.pack(None)


def test_the_kernels_read_the_generated_module():
    """Every ``C.NAME`` a kernel reads exists there; only the Python side (model.py: C.load,
    C.INDEX) imports the packer as C."""
    kernels = []
    for path in sorted(coefficients.INDEX_MODULE.parent.glob("*.py")):
        text = path.read_text(encoding="utf-8")
        if re.search(r"^from \. import coefficients as C$", text, re.M):
            assert path.name == "model.py", path.name
        if re.search(r"^from \. import coefficient_index as C$", text, re.M):
            kernels.append(path.name)
            used = set(re.findall(r"\bC\.([A-Za-z_]\w*)", text))
            missing = {n for n in used if not hasattr(coefficient_index, n)}
            assert not missing, (path.name, missing)
    assert {"forces.py", "geometry.py", "kernel.py", "limits.py", "moments.py"} <= set(kernels)
