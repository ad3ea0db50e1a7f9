"""The command line: results for good input, one clear line for bad input."""

import numpy as np
import pytest

from cli_process import run_tyrelab
from tyrelab.signal import read_signal

G = 9.80665


def test_simulate_writes_the_signal_table(tmp_path):
    out = tmp_path / "run.parquet"
    r = run_tyrelab("simulate", "--tyre", "xzl-16.00R20", "--model", "point", "--road", "cleat:50x50",
                "--speed", "12", "--load", "LC1", "-o", str(out))
    assert r.returncode == 0, r.stderr
    run = read_signal(out)
    # SI, with units and the run description in the file
    assert run.attrs["units"]["FZW"] == "N"
    meta = run.attrs["metadata"]
    assert meta["speed_m_s"] == pytest.approx(12 / 3.6)
    assert meta["road"].startswith("cleat 50 x 50")
    # the first second is static rolling at the LC1 wheel load of Table 3-4
    assert run["FZW"].iloc[:1000].mean() == pytest.approx(2375 * G, rel=0.005)
    # 12 km/h for the time simulated
    assert run["DISTANCE"].iloc[-1] == pytest.approx(12 / 3.6 * run["RUNTIME"].iloc[-1], rel=1e-3)


def test_csv_output_and_plot(tmp_path):
    out = tmp_path / "run.csv"
    r = run_tyrelab("simulate", "--road", "step:50", "--duration", "2", "-o", str(out))
    assert r.returncode == 0, r.stderr
    run = read_signal(out)
    assert len(run) == 2000
    png = tmp_path / "fig.png"
    r = run_tyrelab("plot", str(out), str(out), "--x", "distance", "-o", str(png))
    assert r.returncode == 0, r.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("args, words", [
    (["simulate", "--road", "nowhere"], "unknown road 'nowhere'"),
    (["simulate", "--speed", "-12"], "speed must be a positive number"),
    (["simulate", "--speed", "fast"], "speed must be a number"),
    (["simulate", "--tyre", "missing.tir"], "missing.tir: no such tyre property file"),
    (["simulate", "--load", "LC9"], "unknown load case 'LC9'"),
    (["simulate", "--model", "magic"], "unknown model 'magic'"),
    (["simulate", "--pressure", "900"], "outside the measured range"),
    (["simulate", "-o", "run.txt"], "must end in .parquet or .csv"),
    (["plot", "nothing.parquet"], "nothing.parquet: no such file"),
    (["static", "--test", "cleat:51"], "unknown static test"),
])
def test_bad_input_is_one_clear_line(tmp_path, args, words):
    r = run_tyrelab(*args, cwd=tmp_path)
    assert r.returncode != 0
    assert "Traceback" not in r.stderr
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, r.stderr
    assert words in lines[0]
    # nothing that looks like a result was left behind
    assert not list(tmp_path.glob("*.parquet")) and not list(tmp_path.glob("*.png"))


def test_malformed_tir_names_file_and_line(tmp_path):
    bad = tmp_path / "bad.tir"
    bad.write_text("[UNITS]\nLENGTH = 'meter'\n[DIMENSION]\nUNLOADED_RADIUS = 0.5x\n")
    r = run_tyrelab("simulate", "--tyre", str(bad), "-o", str(tmp_path / "run.parquet"))
    assert r.returncode == 2
    assert "Traceback" not in r.stderr
    assert f"{bad}, line 4: UNLOADED_RADIUS: expected a number" in r.stderr
    assert not (tmp_path / "run.parquet").exists()


def test_missing_key_is_named(tmp_path):
    bad = tmp_path / "nokey.tir"
    bad.write_text("[DIMENSION]\nWIDTH = 0.3\n[VERTICAL]\nVERTICAL_STIFFNESS = 1e5\n")
    r = run_tyrelab("simulate", "--tyre", str(bad), "-o", str(tmp_path / "run.parquet"))
    assert r.returncode == 2 and "UNLOADED_RADIUS" in r.stderr and "Traceback" not in r.stderr


def test_python_api_in_three_lines():
    import tyrelab
    run = tyrelab.simulate(model="point", road="cleat:50x50", speed=12 / 3.6, load="LC1", duration=2.0)
    assert run["FZW"].iloc[:500].mean() == pytest.approx(2375 * G, rel=0.005)
    assert np.all(run["FZW"] >= 0)
