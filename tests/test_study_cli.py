"""``tyrelab study`` end to end: a small spec on a LocalCluster of 2 worker processes."""

from __future__ import annotations

import numpy as np
import pytest

import tyrelab
from tyrelab.cli.main import main
from tyrelab.study import open as open_study
from tyrelab.study.store import Store

pytest.importorskip("distributed")

SPEC = """\
[study]
name = "small"
output = "out"

[[tyre]]
name = "xzl"
file = "xzl-16.00R20"

[[model]]
name = "OPC lk"
contact = "point"
stiffness = "linear"

[[model]]
name = "3D VC nlk"
contact = "volume"
stiffness = "table"

[[test]]
name = "cleat 50x50 perpendicular"
road = "cleat:50x50"
speeds_kmh = [18]
loads = ["LC1"]
duration = 2.0
reference = { model = "3D VC nlk" }
"""


def test_small_study_end_to_end_and_rerun(tmp_path, capsys):
    spec = tmp_path / "small.toml"
    spec.write_text(SPEC)
    assert main(["study", str(spec), "--workers", "2"]) == 0
    index = open_study(tmp_path / "out")
    assert sorted(index["model"]) == ["3D VC nlk", "OPC lk"]
    assert set(index["status"]) == {"done"}
    # the stored point run is the run tyrelab.simulate makes from the same settings
    key = index.loc[index["model"] == "OPC lk", "key"].item()
    direct = tyrelab.simulate(model="point", stiffness="linear", road="cleat:50x50", speed=18 / 3.6,
                              load="LC1", duration=2.0, handling="none", progress=False)
    stored = Store(tmp_path / "out").signal(key)
    assert np.array_equal(stored["FZW"].to_numpy(), direct["FZW"].to_numpy())
    # a rerun finds every run finished: nothing is recomputed, the tables stay as they were
    mtime = (tmp_path / "out" / "runs" / f"{key}.parquet").stat().st_mtime_ns
    assert main(["study", str(spec), "--workers", "1"]) == 0
    assert (tmp_path / "out" / "runs" / f"{key}.parquet").stat().st_mtime_ns == mtime


@pytest.mark.parametrize("edit,line,words", [
    (('contact = "point"', 'contact = "fiala"'), 11, "fiala"),
    (('speeds_kmh = [18]', 'speeds_kmh = ["fast"]'), 22, "speeds_kmh"),
    (('road = "cleat:50x50"', 'road = "moon:5"'), 21, "moon"),
    (('reference = { model = "3D VC nlk" }', 'reference = { files = ["nowhere.tdx"] }'), 25, "nowhere.tdx"),
])
def test_bad_spec_one_line_exit_2(tmp_path, capsys, edit, line, words):
    spec = tmp_path / "bad.toml"
    spec.write_text(SPEC.replace(*edit))
    assert main(["study", str(spec)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert f"line {line}" in err and words in err and "bad.toml" in err
    assert not (tmp_path / "out").exists()  # refused before any work
