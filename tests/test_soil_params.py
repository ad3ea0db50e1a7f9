"""Soil files: the [soil] table in SI, checked value by value; the built-in library."""

from __future__ import annotations

import math

import pytest

from cli_process import run_tyrelab
from tyrelab.errors import InputError
from tyrelab.road.soil import load_soil, read_soil, soil_names

GOOD = """[soil]
name = "test soil"
n = 0.79
kc = 102e3
kphi = 5301e3
cohesion = 1.3e3
friction_angle = 31.1
janosi_k = 0.0115
"""


def test_a_soil_file_reads_in_si(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(GOOD + "damping = 25.0\n")
    soil, name = read_soil(path)
    assert name == "test soil"
    assert soil.friction_angle == pytest.approx(math.radians(31.1), rel=1e-15)
    assert (soil.n, soil.kc, soil.kphi, soil.cohesion, soil.janosi_k, soil.damping) == \
        (0.79, 102e3, 5301e3, 1.3e3, 0.0115, 25.0)
    # Bekker (1969): p = (kc / b + kphi) z^n, here at 50 mm under a 0.4 m wide plate
    assert soil.bekker_pressure(0.05, 0.4) == pytest.approx((102e3 / 0.4 + 5301e3) * 0.05 ** 0.79)
    assert soil.bekker_pressure(-0.01, 0.4) == 0.0


@pytest.mark.parametrize("line, value, key, words", [
    ("n = 0.79", "n = 2.5", "n", "n in (0, 2]"),
    ("n = 0.79", "n = 0", "n", "n in (0, 2]"),
    ("kc = 102e3", "kc = -5.0", "kc", ">= 0"),
    ("kphi = 5301e3", "kphi = nan", "kphi", "finite"),
    ("kphi = 5301e3", 'kphi = "stiff"', "kphi", "finite number"),
    ("friction_angle = 31.1", "friction_angle = 60.0", "friction_angle", "[0, 60) deg"),
    ("cohesion = 1.3e3", "cohesion = 1e7", "cohesion", "a cohesion up to 1e+06 Pa"),
    ("janosi_k = 0.0115", "janosi_k = 0", "janosi_k", "> 0"),
    ("cohesion = 1.3e3", "cohesion = 1.3e3\ncohesin = 3", "cohesin", "unknown key 'cohesin'"),
    ("janosi_k = 0.0115\n", "", None, "missing key 'janosi_k'"),
])
def test_bad_soil_values_are_one_line_naming_file_line_and_key(tmp_path, line, value, key, words):
    path = tmp_path / "bad.toml"
    text = GOOD.replace(line, value)
    path.write_text(text)
    with pytest.raises(InputError) as info:
        read_soil(path)
    message = str(info.value)
    assert words in message and "bad.toml" in message and "\n" not in message
    if key:  # the offending key's own line
        lines = text.splitlines()
        assert info.value.line == 1 + next(i for i, ln in enumerate(lines) if ln.startswith(key + " ="))
        assert info.value.field == f"soil.{key}"


def test_binary_garbage_and_a_missing_table_are_one_line(tmp_path):
    path = tmp_path / "noise.toml"
    path.write_bytes(bytes(range(256)) * 4)
    with pytest.raises(InputError, match="UTF-8|TOML"):
        read_soil(path)
    path.write_text("[ground]\nn = 1\n")
    with pytest.raises(InputError, match=r"one \[soil\] table"):
        read_soil(path)
    with pytest.raises(InputError, match="unknown soil 'quicksand'.*lete-sand"):
        load_soil("quicksand")


def test_the_library_reads_and_names_its_sources():
    from importlib import resources
    assert {"dry-sand", "lete-sand", "sandy-loam", "clayey-soil", "snow", "chrono-demo"} <= set(soil_names())
    for name in soil_names():
        soil, label = load_soil(name)
        text = resources.files("tyrelab.road.soil").joinpath("data", f"{name}.toml").read_text()
        assert "Source:" in text, name               # every built-in soil says where it comes from
        assert label and soil.kc + soil.kphi > 0


def test_soil_curve_command_writes_the_steady_table(tmp_path):
    """tyrelab soil curve: one run per slip, the table's pull rising with slip and its load the
    dead weight, each printed line naming its slip as given (0.005 was printed "0.01"); a slip
    outside [-1, 0.99] or an unknown soil is one line, exit 2, nothing written."""
    import pandas as pd
    cmd = ["soil", "curve", "--terrain", "lete-sand", "--duration", "1", "--load", "20000"]
    done = run_tyrelab(*cmd, "--slips", "0.005,0.05,0.3", "-o", tmp_path / "c.csv", timeout=600)
    assert done.returncode == 0, done.stderr
    curve = pd.read_csv(tmp_path / "c.csv")
    assert list(curve["slip"]) == [0.005, 0.05, 0.3]
    assert curve["FX"].is_monotonic_increasing
    printed = [ln.split(":")[0].split("s = ")[1] for ln in done.stdout.splitlines() if "pull" in ln]
    assert printed == ["0.005", "0.05", "0.3"]
    assert curve["FZ"].to_numpy() == pytest.approx(20000.0, rel=2e-3)
    for bad in (["--slips", "0,1.5"], ["--slips=-1.5,0"], ["--slips", "0.2", "--terrain", "quicksand"]):
        out = tmp_path / "bad.csv"
        done = run_tyrelab(*cmd, *bad, "-o", out, timeout=600)
        assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1, done.stderr
        assert not out.exists()
