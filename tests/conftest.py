"""Shared fixtures. Test data live in tests/data (copied from the project's
reference set); nothing here reads outside the repository."""

from pathlib import Path

import pytest

DATA = Path(__file__).parent / "data"


@pytest.fixture(scope="session")
def data_dir():
    return DATA


@pytest.fixture(scope="session")
def xzl():
    from tyrelab.tyre.library import load_tyre
    return load_tyre("xzl-16.00R20", 300e3)
