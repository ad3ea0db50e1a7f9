"""``tyrelab study`` end to end: a small spec on a LocalCluster of 2 worker processes."""

from __future__ import annotations

import distributed  # noqa: F401 -- a required dependency: missing, this file fails, never skips
import numpy as np
import pytest

import tyrelab
from terminal import StreamWatcher, render
from tyrelab.cli.main import main
from tyrelab.study import open as open_study
from tyrelab.study.store import Store

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
    index = open_study(tmp_path / "out").index
    assert sorted(index["model"]) == ["3D VC nlk", "OPC lk"]
    assert set(index["status"]) == {"done"}
    # the stored point run is the run tyrelab.simulate makes from the same settings
    key = index.loc[index["model"] == "OPC lk", "key"].item()
    direct = tyrelab.simulate(model="point", stiffness="linear", road="cleat:50x50", speed=18 / 3.6,
                              load="LC1", duration=2.0, handling="none", progress=False)
    stored = Store(tmp_path / "out").signal(key)
    # the compact store keeps time and the compared force exactly (study.store)
    assert np.array_equal(stored["FZ_HUB"].to_numpy(), direct["FZ_HUB"].to_numpy())
    # a rerun finds every run finished: nothing is recomputed, the tables stay as they were
    mtime = (tmp_path / "out" / "runs" / f"{key}.parquet").stat().st_mtime_ns
    assert main(["study", str(spec), "--workers", "1"]) == 0
    assert (tmp_path / "out" / "runs" / f"{key}.parquet").stat().st_mtime_ns == mtime
    # one model's parameter changed: only that model's run is computed again
    vc_key = index.loc[index["model"] == "3D VC nlk", "key"].item()
    vc_mtime = (tmp_path / "out" / "runs" / f"{vc_key}.parquet").stat().st_mtime_ns
    spec.write_text(SPEC.replace('stiffness = "linear"', 'stiffness = "table"'))
    assert main(["study", str(spec), "--workers", "1"]) == 0
    after = open_study(tmp_path / "out").index
    assert len(after) == 2 and vc_key in set(after["key"]) and key not in set(after["key"])
    assert len(list((tmp_path / "out" / "runs").glob("*.parquet"))) == 3  # the old OPC run kept
    assert (tmp_path / "out" / "runs" / f"{vc_key}.parquet").stat().st_mtime_ns == vc_mtime


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


#: 16 runs of 40 s over the paving, 0.3-1 s each with a warm cache: the interrupt, sent as soon
#: as two are recorded, finds about 5 s of work left on 2 workers (14 runs)
INTERRUPT_SPEC = """\
[study]
name = "interrupted"
output = "out"

[[tyre]]
name = "xzl"
file = "xzl-16.00R20"

[[model]]
name = "3D VC nlk"
contact = "volume"

[[model]]
name = "OPC nlk"
contact = "point"

[[test]]
name = "belgian paving"
road = "belgian-paving"
speeds_kmh = [3, 4, 5, 6]
loads = ["LC1", "LC2"]
duration = 40.0
reference = { model = "OPC nlk" }
"""


def test_ctrl_c_keeps_finished_runs_and_rerun_completes(tmp_path):
    """Ctrl-C (SIGINT to the whole process group, as a terminal sends it) during a study:
    exit 130 with one line, every run recorded as done has its table, no temporary file
    is left, and a rerun computes exactly the runs that were missing."""
    import os
    import signal
    import subprocess
    import sys
    import time

    spec = tmp_path / "s.toml"
    spec.write_text(INTERRUPT_SPEC)
    runs = tmp_path / "out" / "runs"
    proc = subprocess.Popen([sys.executable, "-m", "tyrelab.cli.main", "study", str(spec), "--workers", "2"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, start_new_session=True)
    err = StreamWatcher(proc.stderr)
    try:
        # signalled once two runs are recorded (a record is renamed into place whole); the
        # bound only keeps a hung study from hanging the test
        deadline = time.monotonic() + 600
        while len(list(runs.glob("*.json"))) < 2:
            assert proc.poll() is None, err.data
            assert time.monotonic() < deadline, "no two runs recorded after 600 s"
            time.sleep(0.05)
        os.killpg(proc.pid, signal.SIGINT)
        proc.wait(timeout=120)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    raw = err.finish()
    shown = [ln for ln in render(raw) if ln.strip()]
    assert proc.returncode == 130, raw
    assert shown[-1:] == ["tyrelab: interrupted"], raw
    records = list(runs.glob("*.json"))
    assert 2 <= len(records) < 16  # some finished, not all
    store = Store(tmp_path / "out")
    finished = [p.stem for p in records if store.is_finished(p.stem)]
    assert len(finished) == len(records)
    assert not list(runs.glob(".tyrelab-*"))
    assert main(["study", str(spec), "--workers", "2"]) == 0
    index = open_study(tmp_path / "out").index
    assert len(index) == 16 and set(index["status"]) == {"done"}
