"""``tyrelab road show|spectrum|export``: the command line over roads."""

import re
from pathlib import Path

import numpy as np
import pytest

from tyrelab.cli.main import main
from tyrelab.road.crg import CrgRoad
from tyrelab.road.spec import road_from_spec

DATA = Path(__file__).parent / "data" / "roads"
PNG = b"\x89PNG\r\n\x1a\n"


def test_show_writes_a_png(tmp_path, capsys):
    out = tmp_path / "road.png"
    assert main(["road", "show", "corrugations-angled", "-o", str(out)]) == 0
    assert out.read_bytes()[:8] == PNG
    assert "corrugations" in capsys.readouterr().out
    assert [p.name for p in tmp_path.iterdir()] == ["road.png"]


def test_show_a_crg_at_an_offset(tmp_path):
    out = tmp_path / "crg.png"
    assert main(["road", "show", f"{DATA / 'handmade_curved.crg'}@0.5", "-o", str(out)]) == 0
    assert out.read_bytes()[:8] == PNG


def test_spectrum_prints_a_and_n_and_plots(tmp_path, capsys):
    out = tmp_path / "dsd.png"
    assert main(["road", "spectrum", "fatigue-track", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    fitted = re.search(r"A = ([-+.\de]+) m\^2/\(cycles/m\), n = ([-+.\d]+)", text)
    a, n = float(fitted.group(1)), float(fitted.group(2))
    assert a == pytest.approx(3.42e-5, rel=0.05) and n == pytest.approx(2.9, abs=0.05)
    assert out.read_bytes()[:8] == PNG


def test_spectrum_without_plot_writes_nothing(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["road", "spectrum", "bump:150"]) == 0
    assert "A = " in capsys.readouterr().out
    assert list(tmp_path.iterdir()) == []


def test_export_round_trip(tmp_path):
    out = tmp_path / "bump.crg"
    assert main(["road", "export", "bump:100", "-o", str(out), "--format", "LDFI"]) == 0
    road, back = road_from_spec("bump:100"), CrgRoad(out)
    x = np.linspace(0, 25, 2001)
    assert np.max(np.abs(back.height(x, 0 * x) - road.grid().height(x, 0 * x))) < 1e-6


@pytest.mark.parametrize("argv, words", [
    (["road", "show", "missing.crg"], ["missing.crg", "no such"]),
    (["road", "show", "flat", "-o", "road.txt"], ["road.txt"]),
    (["road", "spectrum", "no-such-track"], ["unknown road"]),
    (["road", "spectrum", "flat", "--band", "10", "1"], ["band"]),
])
def test_bad_input_is_one_line_and_exit_2(tmp_path, monkeypatch, capsys, argv, words):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and all(w in err for w in words)
    assert list(tmp_path.iterdir()) == []


def test_corrupted_crg_names_the_file(tmp_path, capsys):
    bad = tmp_path / "cut.crg"
    bad.write_bytes((DATA / "belgian_block.crg").read_bytes()[:500_000])
    assert main(["road", "show", str(bad), "-o", str(tmp_path / "x.png")]) == 2
    err = capsys.readouterr().err
    assert str(bad) in err and "truncated" in err
    assert not (tmp_path / "x.png").exists()
