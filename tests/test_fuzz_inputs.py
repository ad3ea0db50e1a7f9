"""Fuzzed inputs: damaged property files, roads, TYDEX files, road names and option strings.

A seeded generator (``random.Random``, fixed seeds: the same cases on every run)
damages real inputs -- truncation, flipped bytes, swapped or deleted lines and
sections, absurd numbers -- and every case must end one of two ways: refused
cleanly (:class:`InputError`, or a one-line message and exit 2 on the command
line) or run correctly (finite numbers, no NaN). Never another exception, a
traceback, a hang or a NaN. A few hundred cases.

No case is timed: how long a case takes depends on the machine, its load and on
whether numba's compile cache is warm, so a wall-clock limit would test the machine.
A hang is caught by :func:`_no_hang` instead: a test still running after
:data:`HANG_LIMIT` seconds (many times what the slowest takes on a loaded machine
with a cold cache) has hung, and the test process is stopped with the traceback of
every thread (``faulthandler``) rather than left waiting forever.
"""

from __future__ import annotations

import faulthandler
import random
import re
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from tyrelab.errors import InputError

DATA = Path(__file__).parent / "data"
PACKAGE = Path(__file__).parents[1] / "src" / "tyrelab" / "tyre" / "data"
#: numbers a damaged file or a careless user writes
NASTY = ["nan", "NaN", "inf", "-inf", "1e400", "-1e400", "1e308", "-1e308", "1e30", "1e-320", "0", "-0.0",
         "-1", "9" * 40, "1e-9", "1D+400", "0x10", "", "1e", "--5"]
#: a test of this file still running after this long [s] has hung (a bound on a hang, never
#: on speed: each takes seconds to a minute or two on a loaded machine with a cold cache)
HANG_LIMIT = 900.0


@pytest.fixture(autouse=True)
def _no_hang():
    """Stop the test process, with every thread's traceback, if a test runs for longer than
    :data:`HANG_LIMIT` (numba's compiled loops do not return to Python to be interrupted, so
    a Python-level alarm could not stop them)."""
    faulthandler.dump_traceback_later(HANG_LIMIT, exit=True, file=sys.__stderr__)
    try:
        yield
    finally:
        faulthandler.cancel_dump_traceback_later()


def _damage(data: bytes, rng: random.Random) -> bytes:
    """One random kind of damage to a file's bytes."""
    kind = rng.randrange(6)
    if kind == 0 and data:                          # truncated
        return data[:rng.randrange(len(data))]
    if kind == 1 and data:                          # flipped bytes
        b = bytearray(data)
        for _ in range(rng.randint(1, 6)):
            b[rng.randrange(len(b))] = rng.randrange(256)
        return bytes(b)
    lines = data.split(b"\n")
    if kind == 2:                                   # two lines swapped
        i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
        return b"\n".join(lines)
    if kind == 3:                                   # two sections swapped, or one dropped
        starts = [i for i, ln in enumerate(lines) if ln.startswith((b"[", b"$", b"**"))] + [len(lines)]
        if len(starts) > 2:
            k = rng.randrange(len(starts) - 2)
            a, b_, c = starts[k], starts[k + 1], starts[k + 2]
            if rng.random() < 0.5:
                lines = lines[:a] + lines[b_:c] + lines[a:b_] + lines[c:]
            else:
                lines = lines[:a] + lines[b_:]
        return b"\n".join(lines)
    if kind == 4:                                   # a line deleted or doubled
        i = rng.randrange(len(lines))
        lines[i:i + 1] = [] if rng.random() < 0.5 else [lines[i], lines[i]]
        return b"\n".join(lines)
    numbers = list(re.finditer(rb"-?\d+\.?\d*(?:[eE][-+]?\d+)?", data))  # an absurd number
    if not numbers:
        return data
    m = rng.choice(numbers)
    return data[:m.start()] + rng.choice(NASTY).encode() + data[m.end():]


def _finite_table(df) -> bool:
    values = df.select_dtypes("number").to_numpy(dtype=float)
    return bool(np.all(np.isfinite(values)))


# --- property files --------------------------------------------------------------------

TIR_FILES = [PACKAGE / "xzl-16.00R20_300kPa.tir", PACKAGE / "hmmwv-pac89.tir",
             DATA / "tir" / "335_65R22_5_G275MSA_40psi.tir"]


def test_damaged_property_files(tmp_path):
    """160 damaged .tir files: refused naming the file, or a tyre whose vertical law works;
    every twentieth loaded one is also driven for 0.2 s (point model, no handling)."""
    import tyrelab
    from tyrelab.rig.simulation import SimulationError
    from tyrelab.tyre.params import Tyre
    from tyrelab.tyre.tir import parse_tir

    rng = random.Random(1601)
    texts = [p.read_bytes() for p in TIR_FILES]
    refused = loaded = driven = 0
    for case in range(160):
        data = _damage(rng.choice(texts), rng)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                text = data.decode("latin-1")
                tyre = Tyre.from_tir(parse_tir(text, source="fuzz.tir"), name="fuzz")
                law = tyre.vertical_law
                d = tyre.static_deflection(0.5 * tyre.vertical_stiffness * 0.01)
                assert np.isfinite(d) and d >= 0, (case, d)
                assert np.all(np.isfinite(law.static_load(np.linspace(0, 0.1, 11)))), case
                loaded += 1
                if loaded % 20 == 0:
                    run = tyrelab.simulate(tyre=tyre, handling="none", road="flat", load=10e3,
                                           duration=0.2, progress=False)
                    assert _finite_table(run), case
                    driven += 1
        except InputError as exc:
            assert "fuzz.tir" in str(exc) or exc.field, (case, str(exc))
            refused += 1
        except SimulationError as exc:  # a divergence is reported, not hidden: one line
            assert "diverged" in str(exc), case
            refused += 1
    assert refused > 20 and loaded > 20  # the damage both breaks and spares files


# --- OpenCRG roads -------------------------------------------------------------------------

CRG_FILES = [DATA / "roads" / n for n in ("handmade_straight.crg", "handmade_banked.crg",
                                          "handmade_straight_minimalist.crg", "halfround_4in.crg")]


def test_damaged_crg_files(tmp_path):
    """100 damaged .crg files (text and binary): refused, or a road whose grid is finite and
    whose heights stay within the road-height bound."""
    from tyrelab.limits import MAX_ROAD_HEIGHT
    from tyrelab.road.crg import CrgRoad

    rng = random.Random(1602)
    sources = [p.read_bytes() for p in CRG_FILES]
    path = tmp_path / "fuzz.crg"
    refused = loaded = 0
    for case in range(100):
        path.write_bytes(_damage(rng.choice(sources), rng))
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                road = CrgRoad(path)
            z = road.grid().z
            assert np.all(np.isfinite(z)) and np.abs(z).max() <= 2 * MAX_ROAD_HEIGHT, case
            loaded += 1
        except InputError as exc:
            assert "fuzz.crg" in str(exc), (case, str(exc))
            refused += 1
    assert refused > 10 and loaded > 10


# --- TYDEX measurements --------------------------------------------------------------------

def test_damaged_tydex_files(tmp_path):
    """100 damaged TYDEX files: refused naming the file, or a table with finite numbers only."""
    from tyrelab.measure.tydex import read_tydex, tydex_text
    from tyrelab.signal import make_signal

    t = np.arange(40) * 1e-3
    table = make_signal({"RUNTIME": t, "FZ": 2e4 + 1e3 * np.sin(40 * t), "FX": 50 * t, "Z_WC": 0.6 + 0 * t})
    source = tydex_text(table, units={"FZ": "kN"}).encode()
    rng = random.Random(1603)
    path = tmp_path / "fuzz.tdx"
    refused = loaded = 0
    for case in range(100):
        path.write_bytes(_damage(source, rng))
        try:
            with warnings.catch_warnings():      # a file damaged past its **END warns of it
                warnings.simplefilter("ignore", UserWarning)   # (tests/test_tydex.py)
                run = read_tydex(path)
            assert _finite_table(run), case
            loaded += 1
        except InputError as exc:
            assert "fuzz.tdx" in str(exc), (case, str(exc))
            refused += 1
    assert refused > 10 and loaded > 10


# --- road names ----------------------------------------------------------------------------

def _road_name(rng: random.Random) -> str:
    def num():
        return rng.choice(NASTY + [f"{rng.uniform(-200, 2000):.3g}", f"{10 ** rng.uniform(-4, 12):.3g}",
                                   str(rng.randint(1, 500))])
    kind = rng.choice(["cleat", "bump", "step", "pothole", "iso8608", "powerlaw", "flat", "garbage",
                       "crg"])
    if kind == "cleat":
        name = f"cleat:{num()}x{num()}" + (f"@{num()}" if rng.random() < 0.3 else "") \
            + (f"/{num()}" if rng.random() < 0.2 else "")
    elif kind == "bump":
        name = "bump:" + "x".join(num() for _ in range(rng.randint(1, 4)))
    elif kind == "step":
        name = f"step:{num()}"
    elif kind == "pothole":
        name = "pothole:" + "x".join(num() for _ in range(rng.randint(1, 4)))
    elif kind == "iso8608":
        name = f"iso8608:{rng.choice('ABCDHZ')}" + (f"@{rng.choice(['1', '-1', 'x', '99'])}"
                                                    if rng.random() < 0.5 else "")
    elif kind == "powerlaw":
        name = f"powerlaw:{num()},{num()}"
    elif kind == "crg":
        name = f"{DATA / 'roads' / 'handmade_straight.crg'}@{num()}"
    elif kind == "flat":
        name = "flat"
    else:
        name = "".join(rng.choice("cleatbump:x@/0123456789.-e ") for _ in range(rng.randint(0, 15)))
    return name


def test_fuzzed_road_names():
    """150 generated road names: refused, or a road that is checked against the tyre before a
    run and, for a sample, driven (point model, 0.3 s) with finite results."""
    import tyrelab
    from tyrelab.guards import check_road_for_tyre
    from tyrelab.resources import MAX_MEMORY, grid_cells
    from tyrelab.road.spec import road_from_spec
    from tyrelab.tyre.library import load_tyre

    tyre = load_tyre("xzl-16.00R20")
    rng = random.Random(1604)
    refused = built = 0
    for case in range(150):
        name = _road_name(rng)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                road = road_from_spec(name)
                assert 8 * grid_cells(road) < MAX_MEMORY, name
                check_road_for_tyre(road, tyre)
                built += 1
                if built % 10 == 0:
                    run = tyrelab.simulate(road=road, duration=0.3, progress=False)
                    assert _finite_table(run), name
        except InputError:
            refused += 1
    assert refused > 30 and built > 20


# --- option strings on the command line ------------------------------------------------------

def test_fuzzed_simulate_options(tmp_path, capsys):
    """50 generated ``tyrelab simulate`` command lines: exit 2 with one line, or exit 0 with a
    finite table written (warnings, one line each, allowed)."""
    from tyrelab.cli.main import main
    from tyrelab.signal import read_signal

    good = {"--speed": ["12", "42", "200", "3"], "--dt": ["1e-3", "5e-4", "2e-3"],
            "--duration": ["0.2", "0.5", "0.05"], "--rate": ["1000", "100", "250"],
            "--load": ["LC1", "20000", "LC3"], "--pressure": ["300", "120", "550"],
            "--road": ["flat", "cleat:50x50", "step:-30", "bump:80"]}
    bad = {"--speed": ["0", "-5", "1e-9", "1e6", "nan", "inf", "fast"],
           "--dt": ["0", "1e-9", "0.1", "nan", "-1e-3"],
           "--duration": ["1e-6", "0", "-1", "nan", "inf", "1e9", "x"],
           "--rate": ["3000", "0", "nan", "-5"], "--load": ["LC9", "1e9", "-5", "nan", "0.5"],
           "--pressure": ["900", "0", "nan", "1e9"],
           "--road": ["bump:1e9", "cleat:1e9x50", "nowhere", "step:800", "pothole:1x1e9"]}
    rng = random.Random(1605)
    ok = refused = 0
    for case in range(50):
        out = tmp_path / f"run{case}.parquet"
        argv = ["simulate", "-o", str(out)]
        for opt in good:
            if opt == "--duration" or rng.random() < 0.5:  # every run short
                argv += [opt, rng.choice(bad[opt] if rng.random() < 0.12 else good[opt])]
        code = main(argv)
        err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
        assert code in (0, 2), (argv, err)
        errors = [ln for ln in err if not ln.startswith("tyrelab: warning: ")]
        if code == 2:
            assert len(errors) == 1 and errors[0].startswith("tyrelab: error: "), (argv, err)
            assert not out.exists(), argv
            refused += 1
        else:
            assert errors == [], (argv, err)
            assert _finite_table(read_signal(out)), argv
            ok += 1
    assert list(tmp_path.glob(".tyrelab-*.part")) == []
    assert ok > 3 and refused > 20


@pytest.mark.parametrize("seed", [1606])
def test_fuzzed_tir_on_the_command_line(tmp_path, capsys, seed):
    """30 damaged property files through ``tyrelab static``: one line and exit 2, or a table."""
    from tyrelab.cli.main import main

    rng = random.Random(seed)
    source = (PACKAGE / "xzl-16.00R20_300kPa.tir").read_bytes()
    for case in range(30):
        path = tmp_path / f"f{case}.tir"
        path.write_bytes(_damage(source, rng))
        code = main(["static", "--tyre", str(path), "--steps", "3", "--max-deflection", "30"])
        cap = capsys.readouterr()
        err = [ln for ln in cap.err.splitlines() if ln.strip() and not ln.startswith("tyrelab: warning: ")]
        assert code in (0, 2), (case, cap.err)
        if code == 2:
            assert len(err) == 1 and err[0].startswith("tyrelab: error: "), (case, cap.err)
        else:
            loads = [float(ln.split()[1]) for ln in cap.out.splitlines()[2:]]
            assert len(loads) == 3 and np.all(np.isfinite(loads)), (case, cap.out)


def test_binary_bytes_as_a_column_map_or_a_mapped_csv(tmp_path, capsys):
    """Random bytes given as --column-map (or as the CSV it maps): one line naming the file
    and exit 2, never a decoding traceback (issue "Lean and fast", point 6)."""
    from tyrelab.cli.main import main
    from tyrelab.measure.columns import read_column_map, read_mapped_csv

    rng = random.Random(1605)
    good_map = tmp_path / "map.csv"
    good_map.write_text("t,RUNTIME,s\nfz,FZ,N\n")
    for case in range(20):
        junk = tmp_path / f"junk{case}.csv"
        junk.write_bytes(bytes([0xF0, 0x80]) + bytes(rng.randrange(256) for _ in range(200)))
        with pytest.raises(InputError) as err:
            read_column_map(junk)
        assert err.value.source == str(junk) and "UTF-8" in str(err.value)
        with pytest.raises(InputError):
            read_mapped_csv(junk, read_column_map(good_map))
    measured = tmp_path / "m.csv"
    measured.write_text("t,fz\n0,1\n0.001,2\n")
    assert main(["validate", str(measured), str(measured), "--column-map", str(junk)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and str(junk) in err[0] and "internal error" not in err[0], err


@pytest.mark.parametrize("kind", ["tir", "rdf", "tdx", "spec", "campaign", "soil", "column_map"])
def test_random_bytes_to_every_text_input_are_one_clear_error(tmp_path, kind):
    """Random bytes (some valid UTF-8 by chance, most not) given to each reader of a text
    input -- .tir, .rdf, TYDEX, a study spec, a campaign manifest, a soil file, a column map:
    always an InputError naming the file, never a decoding or parsing traceback (issue "Lean
    and fast", point 6)."""
    from tyrelab.fit.campaign import read_campaign
    from tyrelab.measure.columns import read_column_map
    from tyrelab.measure.tydex import read_tydex
    from tyrelab.road.rdf import read_rdf
    from tyrelab.road.soil import read_soil
    from tyrelab.study.spec import load_spec
    from tyrelab.tyre.tir import read_tir

    readers = {"tir": (read_tir, "x.tir"), "rdf": (read_rdf, "x.rdf"), "tdx": (read_tydex, "x.tdx"),
               "spec": (load_spec, "x.toml"), "campaign": (read_campaign, "campaign.toml"),
               "soil": (read_soil, "x.toml"), "column_map": (read_column_map, "x.csv")}
    reader, name = readers[kind]
    rng = random.Random(1606 + sorted(readers).index(kind))
    path = tmp_path / name
    for case in range(15):
        size = rng.choice([1, 7, 64, 500, 4000])
        data = bytes(rng.randrange(256) for _ in range(size))
        if case % 3 == 0:  # printable noise: valid UTF-8 that is no format at all
            data = bytes(rng.choice(b"[]=#\"'\n\t abcXYZ0123.,{}-$") for _ in range(size))
        path.write_bytes(data)
        with pytest.raises(InputError) as err:
            reader(tmp_path if kind == "campaign" else path)
        assert name in str(err.value), (kind, case, str(err.value))
