"""Every verb of the command line under bad input: one line, the right exit code, nothing left.

Issue 16's classes: output paths, non-finite and absurd numbers in property
files, damaged roads, sizes that cannot fit, edge values, physically
impossible runs, property-file physics, internal errors. Most cases run the
command in-process (``main(argv)``: the same code, without 1-2 s of start-up
per case); a few run it as a real process to see what a shell sees (forked off a server that
has imported tyrelab: ``tests/cli_process.py``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from cli_process import run_tyrelab
import tyrelab.study
from tyrelab.cli.main import main
from tyrelab.errors import InputError
from tyrelab.signal import make_signal, read_signal, write_signal

DATA = Path(__file__).parent / "data"
PACKAGE_DATA = Path(__file__).parents[1] / "src" / "tyrelab" / "tyre" / "data"
XZL = (PACKAGE_DATA / "xzl-16.00R20_300kPa.tir").read_text()
MF52 = DATA / "mfeval" / "MagicFormula52_Parameters.tir"
CRG = DATA / "roads" / "handmade_straight_minimalist.crg"


def _tir(tmp: Path, name: str, old: str, new: str) -> str:
    """The XZL file with ``old`` replaced by ``new`` (which must occur), written as ``name``."""
    assert old in XZL, old
    path = tmp / name
    path.write_text(XZL.replace(old, new, 1))
    return str(path)


def _crg(tmp: Path, name: str, old: str, new: str) -> str:
    text = CRG.read_text()
    assert old in text, old
    path = tmp / name
    path.write_text(text.replace(old, new, 1))
    return str(path)


def _files(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file()}


def run_cli(argv, capsys) -> tuple[int, list[str], str]:
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, [ln for ln in err.splitlines() if ln.strip()], out


@pytest.fixture(scope="module")
def work(tmp_path_factory):
    """A folder with a short valid run, its CSV twin with a text column, and bad input files."""
    tmp = tmp_path_factory.mktemp("bad")
    run = make_signal({"RUNTIME": np.arange(5) * 0.1, "DISTANCE": np.arange(5) * 0.3,
                       "FZW": np.full(5, 2e4)})
    write_signal(run, tmp / "run.parquet")
    (tmp / "text.csv").write_text("RUNTIME,DISTANCE,FZW,NOTE\n0,0,1,a\n0.1,0.3,2,b\n0.2,0.6,3,c\n")
    # a press whose loads (1e15 N at 10 mm) fit a stiffness no tyre has
    (tmp / "huge_press.csv").write_text("deflection_mm,load_N\n0,0\n10,1e15\n20,2e15\n")
    (tmp / "furlong.csv").write_text("deflection_furlong,load_N\n0,0\n1,3000\n2,7000\n")
    (tmp / "adir.parquet").mkdir()
    (tmp / "adir.png").mkdir()
    # property files (one damage each)
    _tir(tmp, "nan_curve.tir", "30.0 15559.0", "30.0 nan")
    _tir(tmp, "inf_stiffness.tir", "VERTICAL_STIFFNESS = 659.6", "VERTICAL_STIFFNESS = inf")
    _tir(tmp, "overflow.tir", "VERTICAL_STIFFNESS = 659.6", "VERTICAL_STIFFNESS = 1e400")
    _tir(tmp, "huge_stiffness.tir", "VERTICAL_STIFFNESS = 659.6", "VERTICAL_STIFFNESS = 1e9")
    _tir(tmp, "nonmonotonic.tir", "50.0 29011.0", "50.0 9011.0")
    _tir(tmp, "negative_load.tir", "10.0 3496.0", "10.0 -3496.0")
    _tir(tmp, "zero_width.tir", "WIDTH           = 438.0", "WIDTH = 0")
    _tir(tmp, "rim_outside.tir", "RIM_RADIUS      = 254.0", "RIM_RADIUS = 700.0")
    _tir(tmp, "zero_mass.tir", "WHEEL_MASS = 240.0", "WHEEL_MASS = 0")
    _tir(tmp, "zero_inertia.tir", "WHEEL_IYY  = 5.0e7", "WHEEL_IYY = 0")
    curve = XZL[XZL.index("{pen fz}"):XZL.index("$---", XZL.index("{pen fz}"))]
    _tir(tmp, "empty_curve.tir", curve, "{pen fz}\n")
    # roads
    _crg(tmp, "v0.crg", "LONG_SECTION_V_INCREMENT = 0.50", "LONG_SECTION_V_INCREMENT = 0.0")
    text = CRG.read_text()
    data_at = text.index("$$$$")
    cell = text.index(" 0.0000000", data_at)  # fixed 10-character fields
    (tmp / "cell.crg").write_text(text[:cell] + " 1.000E+30" + text[cell + 10:])
    (tmp / "road.crg").write_text(text)
    # measurements: an infinite sample in a TYDEX file and in a signal table
    from tyrelab.measure.tydex import tydex_text
    tdx = tydex_text(run).split("\n")
    row = tdx.index("**MEASURDATA") + 3
    tdx[row] = " ".join(["inf"] + tdx[row].split()[1:])
    (tmp / "meas.tdx").write_text("\n".join(tdx))
    (tmp / "inf.csv").write_text("RUNTIME,FZ\n0,1\n0.1,inf\n0.2,3\n")
    # a study spec with a non-finite time step
    (tmp / "study.toml").write_text(
        '[study]\nname = "s"\ndt = nan\n[[tyre]]\nname = "x"\nfile = "xzl-16.00R20"\n'
        '[[model]]\nname = "p"\ncontact = "point"\n[[test]]\nname = "c"\nroad = "cleat:50x50"\n'
        'speeds_kmh = [12]\nloads = ["LC1"]\n')
    (tmp / "afile").write_text("not a folder\n")
    return tmp


# (argv, exit code, words in the one stderr line); {d} is the work folder
CASES = [
    # -- output paths, every verb ---------------------------------------------------------
    (["simulate", "--duration", "1", "-o", "{d}/missing/out.parquet"], 2, "does not exist"),
    (["simulate", "--duration", "1", "-o", "{d}/adir.parquet"], 2, "is a folder"),
    (["simulate", "--duration", "1", "-o", "{d}/c.xyz"], 2, "must end in .parquet or .csv"),
    (["simulate", "--road", "{d}/road.crg", "--duration", "1", "-o", "{d}/road.crg"], 2,
     "must end in .parquet or .csv"),
    (["plot", "{d}/run.parquet", "-o", "{d}/c.xyz"], 2, "must end in .png, .pdf, .svg, .jpg or .jpeg"),
    (["plot", "{d}/run.parquet", "-o", "{d}/missing/p.png"], 2, "does not exist"),
    (["plot", "{d}/run.parquet", "-o", "{d}/adir.png"], 2, "is a folder"),
    (["plot", "{d}/run.parquet", "-o", "{d}/run.parquet"], 2, "must end in .png"),
    (["static", "-o", "{d}/missing/t.csv"], 2, "does not exist"),
    (["static", "--test", "footprint", "-o", "{d}/f.csv"], 2, "must end in .png"),
    (["road", "show", "flat", "-o", "{d}/missing/r.png"], 2, "does not exist"),
    (["road", "spectrum", "flat", "-o", "{d}/r.xyz"], 2, "must end in .png"),
    (["road", "export", "flat", "-o", "{d}/r.txt"], 2, "must end in .crg"),
    (["road", "export", "{d}/road.crg", "-o", "{d}/road.crg"], 2, "is also an input"),
    (["fit", "ring", "-o", "{d}/missing/ring.tir"], 2, "does not exist"),
    (["modal", "-o", "{d}/missing/m.csv"], 2, "does not exist"),
    (["modal", "-o", "{d}/m.txt"], 2, "must end in .csv"),
    (["validate", "{d}/run.parquet", "{d}/run.parquet", "--html", "{d}/missing/v.html"], 2,
     "does not exist"),
    (["mf", "curves", str(MF52), "-o", "{d}/c.xyz"], 2, "must end in .png"),
    (["mf", "curves", str(MF52), "-o", "{d}/missing/c.png"], 2, "does not exist"),
    (["study", "{d}/study.toml", "-o", "{d}/afile"], 2, "is a file, not a folder"),
    # -- non-finite and absurd numbers in a property file ----------------------------------
    (["simulate", "--tyre", "{d}/nan_curve.tir", "-o", "{d}/o.parquet"], 2,
     "nan_curve.tir, line 52: DEFLECTION_LOAD_CURVE"),
    (["simulate", "--tyre", "{d}/inf_stiffness.tir", "-o", "{d}/o.parquet"], 2, "'inf' is not a finite"),
    (["simulate", "--tyre", "{d}/overflow.tir", "-o", "{d}/o.parquet"], 2,
     "overflow.tir, line 42: VERTICAL_STIFFNESS"),
    (["static", "--tyre", "{d}/huge_stiffness.tir"], 2, "VERTICAL_STIFFNESS: 1e+12 N/m is not physical"),
    (["modal", "--tyre", "{d}/nan_curve.tir"], 2, "is not a finite number"),
    (["study", "{d}/study.toml"], 2, "study.dt"),
    # -- the transient slip's lengths -------------------------------------------------------
    (["simulate", "--relaxation", "0.3", "-o", "{d}/o.parquet"], 2,
     "--relaxation: expected one of auto, off, file or two lengths"),
    (["simulate", "--tyre", "hmmwv-pac89", "--relaxation", "file", "-o", "{d}/o.parquet"], 2,
     "--relaxation: 'file': the 'pac89' handling model has no relaxation lengths"),
    (["export", "fmu", "--relaxation", "nan,0.2", "-o", "{d}/t.fmu"], 2,
     "--relaxation: expected two lengths in metres, each 0 (no lag) to 100, got nan,0.2"),
    (["validate", "{d}/run.parquet", "{d}/meas.tdx", "--html", "{d}/v.html"], 2,
     "meas.tdx, line 16: RUNTIME: 'inf' is not a finite number"),
    (["plot", "{d}/inf.csv", "--channel", "FZ", "-o", "{d}/p.png"], 2, "inf.csv: FZ: sample 2 is infinite"),
    # -- damaged roads ----------------------------------------------------------------------
    (["simulate", "--road", "{d}/v0.crg", "-o", "{d}/o.parquet"], 2, "LONG_SECTION_V_INCREMENT is 0.0"),
    (["road", "show", "{d}/v0.crg", "-o", "{d}/r.png"], 2, "LONG_SECTION_V_INCREMENT"),
    (["road", "spectrum", "{d}/cell.crg"], 2, "height 1e+30 m in cross section 1"),
    # -- sizes that cannot fit ----------------------------------------------------------------
    (["simulate", "--road", "cleat:1e9x50", "-o", "{d}/o.parquet"], 2, "cleat width 1e+09 mm is out of"),
    (["simulate", "--road", "bump:1e9", "-o", "{d}/o.parquet"], 2, "bump height 1e+09 mm is out of range"),
    (["simulate", "--road", "pothole:100x1e9", "-o", "{d}/o.parquet"], 2, "pothole length"),
    # a road name's sizes are in mm: a refusal quotes them as typed, not converted to m
    (["simulate", "--road", "cleat:-1x5", "-o", "{d}/o.parquet"], 2,
     "--road: cleat width -1 mm is out of range; allowed: 1 <= cleat width <= 50000 mm"),
    (["simulate", "--road", "cleat:50x20/30", "-o", "{d}/o.parquet"], 2,
     "cleat bevel 30 mm is out of range; allowed: 0 <= cleat bevel <= 20 mm"),
    (["simulate", "--road", "bump:50x-3", "-o", "{d}/o.parquet"], 2, "bump ramp length -3 mm is out of"),
    (["simulate", "--road", "step:0", "-o", "{d}/o.parquet"], 2, "--road: step height must not be 0"),
    (["static", "--test", "cleat:5x5000"], 2,
     "test: cleat height 5000 mm is out of range; allowed: 0 < cleat height <= 1000 mm in static test"),
    (["simulate", "--speed", "1e-9", "-o", "{d}/o.parquet"], 2, "argument --speed: speed 1e-9 km/h"),
    (["simulate", "--duration", "1e9", "-o", "{d}/o.parquet"], 2, "duration 1e9 s is out of range"),
    (["simulate", "--dt", "1e-9", "-o", "{d}/o.parquet"], 2, "time step 1e-9 s is out of range"),
    (["simulate", "--dt", "1e-6", "--duration", "3000", "--rate", "10", "-o", "{d}/o.parquet"], 2,
     "pass --force"),
    (["road", "export", "flat", "--spacing", "0.0001", "0.0001", "-o", "{d}/r.crg"], 2,
     "spacing 0.0001 m is out of range"),
    (["road", "export", "belgian-paving", "--spacing", "0.001", "0.001", "-o", "{d}/r.crg"], 2,
     "pass --force"),
    (["modal", "--segments", "1000000"], 2, "--segments 1000000 is out of range; allowed: 12 to 600"),
    (["static", "--model", "ring", "--test", "footprint", "--load", "1e9", "-o", "{d}/f.png"], 2,
     "would press xzl-16.00R20 onto its rim"),
    (["road", "spectrum", "flat", "--lines", "100000"], 2, "--lines 100000 is out of range"),
    (["fit", "ring", "--max-evaluations", "1000000", "-o", "{d}/ring.tir"], 2, "out of range"),
    # -- edge values ------------------------------------------------------------------------
    (["simulate", "--duration", "1e-6", "-o", "{d}/o.parquet"], 2,
     "--duration: duration 1e-06 s is too short"),
    (["plot", "{d}/text.csv", "--channel", "NOTE", "-o", "{d}/p.png"], 2,
     "(--channel) holds str values, not numbers"),
    (["simulate", "--dt", "0.1", "-o", "{d}/o.parquet"], 2, "time step 0.1 s is out of range"),
    (["simulate", "--model", "ring", "--dt", "0.005", "--rate", "100", "-o", "{d}/o.parquet"], 2,
     "above the stable step of the ring model"),
    (["simulate", "--rate", "3000", "-o", "{d}/o.parquet"], 2, "--rate: output rate 3000 Hz is faster"),
    (["simulate", "--speed", "1e6", "-o", "{d}/o.parquet"], 2, "allowed: 0.036 <= speed <= 200 km/h"),
    (["simulate", "--speed", "nan", "-o", "{d}/o.parquet"], 2, "speed must be a finite number"),
    # a model's options: impossible numbers and sizes refused, named as given (--option NAME)
    (["simulate", "--model", "ring", "--option", "n_segments=100000", "-o", "{d}/o.parquet"], 2,
     "--option n_segments: ring segments 100000 is out of range; allowed: 12 to 1000"),
    (["simulate", "--model", "ring", "--option", "n_blocks=0", "-o", "{d}/o.parquet"], 2,
     "--option n_blocks: tread blocks per segment 0 is out of range"),
    (["simulate", "--model", "ring", "--option", "friction=-1", "-o", "{d}/o.parquet"], 2,
     "--option friction: friction coefficient -1 is out of range; allowed: >= 0"),
    (["simulate", "--model", "ring", "--option", "lateral_samples=0", "-o", "{d}/o.parquet"], 2,
     "--option lateral_samples: lateral samples 0 is out of range"),
    (["simulate", "--model", "ring", "--option", "relax=-1", "-o", "{d}/o.parquet"], 2,
     "--option relax: relaxation rate -1 1/s is out of range"),
    (["simulate", "--model", "enveloping", "--option", "step=0", "-o", "{d}/o.parquet"], 2,
     "--option step: sampling step 0 m is out of range; allowed: > 0 m"),
    (["simulate", "--model", "enveloping", "--option", "n_width=0", "-o", "{d}/o.parquet"], 2,
     "--option n_width: cams across the width 0 is out of range"),
    (["simulate", "--model", "volume", "--option", "discs=0", "-o", "{d}/o.parquet"], 2,
     "--option discs: discs per half width 0 is out of range; allowed: 1 to 100"),
    (["static", "--model", "ring", "--option", "n_blocks=0", "-o", "{d}/s.csv"], 2,
     "--option n_blocks: tread blocks per segment 0 is out of range"),
    (["simulate", "--road", "iso8608:C@-1", "-o", "{d}/o.parquet"], 2,
     "cannot read seed '-1' in road 'iso8608:C@-1'; expected a whole number >= 0"),
    # the cam study's roads: refused before its progress bar draws (it drew, then the line)
    (["fit", "cams", "--road", "bogus", "-o", "{d}/c.csv"], 2, "road: unknown road 'bogus'"),
    # the option named is the one given: the left wheel's, not the test wheel's --model
    (["simulate", "--left-wheel", "bogus", "-o", "{d}/o.parquet"], 2,
     "--left-wheel: unknown model 'bogus', expected one of point,"),
    (["static", "--max-deflection", "500"], 2, "--max-deflection: 500 mm would press"),
    (["validate", "{d}/run.parquet", "{d}/run.parquet", "--speed", "inf", "--html", "{d}/v.html"], 2,
     "speed must be a finite number"),
    (["mf", "curves", str(MF52), "--loads", "1,inf", "-o", "{d}/c.png"], 2, "--loads"),
    (["road", "show", "flat", "--y", "nan", "-o", "{d}/r.png"], 2, "y must be a finite number"),
    # -- physically impossible: refused before the run --------------------------------------
    (["simulate", "--road", "step:1e9", "-o", "{d}/o.parquet"], 2, "step height 1e+09 mm is out of range"),
    (["simulate", "--road", "cleat:50x1e9", "-o", "{d}/o.parquet"], 2, "cleat height 1e+09 mm is out of"),
    (["simulate", "--road", "step:800", "-o", "{d}/o.parquet"], 2, "taller than the tyre's unloaded radius"),
    (["simulate", "--road", "{d}/cell.crg", "-o", "{d}/o.parquet"], 2, "height 1e+30 m"),
    (["simulate", "--load", "1e9", "-o", "{d}/o.parquet"], 2, "--load: wheel load 1e+09 N would press"),
    # -- property-file physics ------------------------------------------------------------------
    (["simulate", "--tyre", "{d}/nonmonotonic.tir", "-o", "{d}/o.parquet"], 2,
     "nonmonotonic.tir, line 54: DEFLECTION_LOAD_CURVE: load 9011 N is below"),
    (["simulate", "--tyre", "{d}/negative_load.tir", "-o", "{d}/o.parquet"], 2,
     "negative_load.tir, line 50: DEFLECTION_LOAD_CURVE: load -3496 N is negative"),
    (["simulate", "--tyre", "{d}/zero_width.tir", "-o", "{d}/o.parquet"], 2,
     "zero_width.tir, line 28: WIDTH: 0 m is not physical"),
    (["simulate", "--tyre", "{d}/rim_outside.tir", "-o", "{d}/o.parquet"], 2,
     "line 29: RIM_RADIUS: RIM_RADIUS 0.7 m is not inside the tyre"),
    (["simulate", "--tyre", "{d}/zero_mass.tir", "-o", "{d}/o.parquet"], 2,
     "WHEEL_MASS: 0 kg is not physical"),
    (["static", "--tyre", "{d}/zero_inertia.tir"], 2, "WHEEL_IYY"),
    (["simulate", "--tyre", "{d}/empty_curve.tir", "-o", "{d}/o.parquet"], 2,
     "section [DEFLECTION_LOAD_CURVE] has no rows"),
    # a fitted value that is not physical names the tests it came from, not the file it would go to
    (["fit", "vertical", "{d}/huge_press.csv", "-o", "{d}/fitted.tir", "--no-report", "--radius", "671.5",
      "--width", "438"], 2,
     "huge_press.csv: the fit gives VERTICAL_STIFFNESS: 1e+17 N/m is not physical"),
    (["fit", "vertical", "{d}/furlong.csv", "-o", "{d}/fitted.tir", "--no-report"], 2,
     "column 'deflection_furlong': 'furlong' is not a unit of deflection (m); name it like deflection_m"),
]


class _LongWorkStarted(Exception):
    pass


@pytest.fixture()
def long_work(monkeypatch):
    """The entry points of the long work -- every rig's time-stepping loop, the study's runs,
    the ring's identification -- replaced by a stub that records the call and stops the
    command: a refusal must come before any of them (checked by what was called, not by
    how long the command took, which would measure the machine)."""
    import tyrelab.fit.ring
    import tyrelab.rig.quarter_vehicle
    import tyrelab.rig.rolling
    import tyrelab.rig.trailer
    import tyrelab.study.runner

    started = []

    def stub(name):
        def call(*args, **kwargs):
            started.append(name)
            raise _LongWorkStarted(name)
        return call
    for module in (tyrelab.rig.trailer, tyrelab.rig.rolling, tyrelab.rig.quarter_vehicle):
        monkeypatch.setattr(module, "run_chunks", stub(f"{module.__name__}.run_chunks"))
    monkeypatch.setattr(tyrelab.study.runner, "run_tasks", stub("study runs"))
    monkeypatch.setattr(tyrelab.fit.ring, "fit_ring", stub("ring identification"))
    return started


@pytest.mark.parametrize("argv, started", [
    (["simulate", "--road", "flat", "--duration", "1", "-o", "{d}/ok.parquet"],
     "tyrelab.rig.trailer.run_chunks"),
    (["simulate", "--rig", "quarter-vehicle", "--road", "flat", "--duration", "1", "-o", "{d}/ok.parquet"],
     "tyrelab.rig.quarter_vehicle.run_chunks"),
    (["simulate", "--rig", "rolling", "--road", "flat", "--duration", "1", "-o", "{d}/ok.parquet"],
     "tyrelab.rig.rolling.run_chunks"),
    (["fit", "ring", "-o", "{d}/ok.tir"], "ring identification"),
    (["study", "{d}/good_study.toml", "-o", "{d}/ok_study"], "study runs"),
], ids=["trailer", "quarter-vehicle", "rolling", "fit-ring", "study"])
def test_the_long_work_stub_sees_valid_commands(work, capsys, long_work, argv, started):
    """The control of the check below: a valid command does reach the stubbed long work."""
    (work / "good_study.toml").write_text((work / "study.toml").read_text().replace("dt = nan", "dt = 1e-3"))
    got, lines, _ = run_cli([a.replace("{d}", str(work)) for a in argv], capsys)
    assert long_work == [started], lines
    assert got == 1 and "_LongWorkStarted" in lines[-1], lines  # the stub stopped it: a 'bug'


@pytest.mark.parametrize("argv, code, words", CASES, ids=[" ".join(c[0][:3]) for c in CASES])
def test_bad_input_is_refused_in_one_line(work, capsys, long_work, argv, code, words):
    before = _files(work)
    got, lines, _ = run_cli([a.replace("{d}", str(work)) for a in argv], capsys)
    assert long_work == [], lines  # refused before any long work started
    assert got == code, lines
    assert len(lines) == 1, lines
    assert lines[0].startswith("tyrelab: error: "), lines
    assert words in lines[0], lines[0]
    assert "Traceback" not in lines[0]
    assert _files(work) == before  # no output, no temporary file left


def test_a_local_cluster_holds_no_more_workers_than_the_memory(work, capsys, long_work, monkeypatch):
    """Each local worker holds about 0.5 GiB (resources.WORKER_MEMORY): a machine of 4 GiB takes
    8 of them; 9 are refused, naming --workers, before any run, with or without a spec. (1000
    workers on this project's 24 GB machine used to start until it ran out of memory.)"""
    from tyrelab import resources

    gib = 1024 ** 3
    assert resources.max_local_workers(4 * gib) == 8
    assert resources.max_local_workers(gib // 4) == 1              # one worker always starts
    assert resources.max_local_workers(10 ** 6 * gib) == resources.MAX_WORKERS
    monkeypatch.setattr(resources, "machine_memory", lambda: 4 * gib)
    assert resources.check_local_workers(8) == 8
    for spec in ([], [work / "good_study.toml"]):
        (work / "good_study.toml").write_text(
            (work / "study.toml").read_text().replace("dt = nan", "dt = 1e-3"))
        code, lines, _ = run_cli(["study", *spec, "--workers", "9"], capsys)
        assert (code, long_work) == (2, []), lines
        assert lines == ["tyrelab: error: --workers: 9 worker processes need about 4.83 GB of memory "
                         "(537 MB each); this machine has 4.29 GB: allowed 1 to 8"]
    with pytest.raises(InputError, match="allowed 1 to 8"):             # the Python door
        tyrelab.study.run(work / "good_study.toml", workers=9, output=work / "nine")
    assert not (work / "nine").exists()                                 # refused before the folder


def test_physically_impossible_runs_warn(work, capsys, tmp_path):
    """A run that leaves the models' validity is kept but says so, one line per finding."""
    out = tmp_path / "pothole.parquet"
    code, lines, stdout = run_cli(["simulate", "--road", "pothole:500x2000x600", "-o", out], capsys)
    assert code == 0
    assert len(lines) == 3 and all(ln.startswith("tyrelab: warning: ") for ln in lines), lines
    assert "rim contact" in lines[0] and "overturned" in lines[1] and "left the road" in lines[2]
    assert "OUTSIDE the models' valid range: 3 warning(s)" in stdout
    assert read_signal(out).attrs["metadata"]["physics_warnings"][1].startswith("the trailer overturned")


def test_load_above_fzmax_warns(capsys, tmp_path):
    out = tmp_path / "mf.parquet"
    code, lines, _ = run_cli(["simulate", "--tyre", MF52, "--handling", "none", "--road", "flat",
                              "--load", "25000", "--duration", "0.1", "-o", out], capsys)
    assert code == 0 and out.exists()
    assert lines == [lines[0]] and "above FZMAX 20.47 kN" in lines[0]


def test_internal_error_is_one_line_and_debug_shows_it(work, capsys, monkeypatch):
    import tyrelab.cli.plot as plot

    def broken(args):
        raise ZeroDivisionError("float division by zero")
    monkeypatch.setattr(plot, "run", broken)
    code, lines, _ = run_cli(["plot", work / "run.parquet"], capsys)
    assert code == 1 and len(lines) == 1
    assert lines[0] == ("tyrelab: internal error (a bug) in 'tyrelab plot': ZeroDivisionError: float "
                        "division by zero; run again with --debug for the full trace")
    with pytest.raises(ZeroDivisionError):
        main(["--debug", "plot", str(work / "run.parquet")])


def test_divergence_is_one_line_naming_step_and_parameter(tmp_path, capsys, monkeypatch):
    """A divergence no check foresaw (the rig forced to report one) is one line naming the
    step size and the likely parameter; nothing is written."""
    import dataclasses

    from tyrelab.rig import registry
    from tyrelab.rig.simulation import SimulationError

    def diverging(request):
        raise SimulationError("the simulation diverged (non-finite FZW, Z_WC); try a smaller time step")
    quarter = registry.rig_named("quarter-vehicle")
    monkeypatch.setitem(registry._RIGS, "quarter-vehicle", dataclasses.replace(quarter, run=diverging))
    code, lines, _ = run_cli(["simulate", "--rig", "quarter-vehicle", "--road", "flat", "--dt", "0.002",
                              "--duration", "1", "-o", tmp_path / "o.parquet"], capsys)
    assert code == 2 and len(lines) == 1, lines
    assert lines[0].startswith("tyrelab: error: the simulation diverged (non-finite FZW, Z_WC)")
    assert "at time step 0.002 s" in lines[0]
    assert "VERTICAL_STIFFNESS" in lines[0] and "wheel mass 240 kg" in lines[0]
    assert not (tmp_path / "o.parquet").exists()


def test_a_closed_bound_holds_to_rounding_and_no_further():
    """The least towing speed the command line states, 0.036 km/h, is 0.036 / 3.6 =
    0.009999999999999998 m/s, one ulp below MIN_SPEED: it was refused by its own bound."""
    from tyrelab import limits

    assert limits.check_speed(0.036 / 3.6) == 0.036 / 3.6
    assert limits.check_speed(200 / 3.6) == 200 / 3.6
    for kmh in (0.0359, 200.001):
        with pytest.raises(InputError, match="out of range"):
            limits.check_speed(kmh / 3.6)
    assert limits.check_number(1e-300, "x", 0.0, 1.0, low_open=True) == 1e-300
    with pytest.raises(InputError, match="out of range"):  # an open bound stays open
        limits.check_number(0.0, "x", 0.0, 1.0, low_open=True)


def test_a_diverged_run_is_told_from_a_light_tyre_ringing():
    """No tyre carries 100 times its static load; a tyre barely touching the road (the ring
    with tread blocks under 1 N) rings to a few hundred newtons while it settles, which is
    no divergence: the factor applies to at least 1 kN."""
    from tyrelab.rig.simulation import SimulationError, to_signal

    def table(static, peak):
        data = np.array([[0.0, static], [1e-3, peak], [2e-3, static]])
        return to_signal(data, ("RUNTIME", "FZW"), {"static_wheel_load_N": static})

    assert table(1.0, 354.0)["FZW"].max() == 354.0                 # ring-tp under 1 N
    assert table(23.3e3, 2.3e6)["FZW"].max() == 2.3e6             # 98.7 x LC1: kept
    for static, peak in ((23.3e3, 2.4e6), (1.0, 1.01e5)):
        with pytest.raises(SimulationError, match="the simulation diverged"):
            table(static, peak)


def test_python_api_refuses_the_same(tmp_path):
    import tyrelab
    from tyrelab.errors import InputError
    for kwargs, words in [({"speed": 1e-9}, "speed"), ({"duration": 1e-6}, "too short"),
                          ({"dt": 1e-9}, "time step"), ({"output_rate": 3000.0}, "faster"),
                          ({"road": "bump:1e9"}, "bump height"), ({"load": 1e9}, "onto its rim"),
                          ({"options": "x"}, "a mapping of names to values"),   # a ValueError once
                          # a flag for a number: float(True) is 1 (a 1 N load, a 1 s run once)
                          ({"load": True}, "wheel load must be a number, got True"),
                          ({"duration": True}, "duration must be a number, got True")]:
        with pytest.raises(InputError, match=words):
            tyrelab.simulate(**kwargs)
    with pytest.raises(InputError, match="does not exist"):
        tyrelab.write_signal(make_signal({"RUNTIME": [0.0, 1.0]}), tmp_path / "no" / "x.parquet")


@pytest.mark.parametrize("argv, code, words", [
    (["simulate", "--road", "cleat:1e9x50", "-o", "out.parquet"], 2, "cleat width"),
    (["simulate", "--duration", "1", "-o", "missing/out.parquet"], 2, "does not exist"),
    (["modal", "--segments", "1000000"], 2, "out of range"),
])
def test_a_real_process_shows_one_line(tmp_path, argv, code, words):
    r = run_tyrelab(*argv, cwd=tmp_path, timeout=120)
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert r.returncode == code and len(lines) == 1 and words in lines[0], r.stderr
    assert "Traceback" not in r.stderr
    assert not list(tmp_path.iterdir())
