"""Every output is written whole or not at all, and interrupts leave the previous file intact.

The writer (:mod:`tyrelab.io_atomic`) writes to a temporary sibling and renames it; an
exception (Ctrl-C included) removes the temporary file; a temporary file of a killed
writer is removed by the next write of the same target. The command line turns SIGTERM
into the same unwinding (exit 143) and Ctrl-C into exit 130.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from terminal import StreamWatcher, render
from tyrelab.errors import InputError
from tyrelab.io_atomic import (atomic_output, atomic_write, atomic_write_text, check_output_path,
                               stale_temporaries)

linux = pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs Linux /proc")


def _temporaries(folder: Path) -> list[Path]:
    return sorted(folder.glob(".tyrelab-*.part"))


def _dead_pid() -> int:
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def test_success_renames_and_failure_keeps_the_previous_file(tmp_path):
    target = tmp_path / "out.txt"
    atomic_write_text(target, "first\n")
    assert target.read_text() == "first\n"
    assert oct(target.stat().st_mode & 0o777) == oct(0o666 & ~_umask())  # a normal file's mode

    def half(tmp):
        Path(tmp).write_text("half of a sec")
        raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        atomic_write(target, half)
    assert target.read_text() == "first\n"
    assert _temporaries(tmp_path) == []


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_a_stale_temporary_of_a_killed_writer_is_removed_on_the_next_write(tmp_path):
    target = tmp_path / "run.csv"
    atomic_write_text(target, "old\n")
    with atomic_output(target) as tmp:  # a name of this writer, to learn the target's tag
        tag = Path(tmp).name.split("-")[1]
        Path(tmp).write_text("x")
    stale = tmp_path / f".tyrelab-{tag}-{_dead_pid()}-deadbeef.part"
    stale.write_text("left by a killed run")
    alive = tmp_path / f".tyrelab-{tag}-{os.getppid()}-cafecafe.part"  # a running writer's file
    alive.write_text("being written")
    other = tmp_path / ".tyrelab-000000000000-1-00000000.part"          # another target's
    other.write_text("another target")
    assert stale_temporaries(target) == [stale]
    atomic_write_text(target, "new\n")
    assert target.read_text() == "new\n"
    assert not stale.exists() and alive.exists() and other.exists()


def test_output_checks_name_the_argument_and_what_is_allowed(tmp_path):
    (tmp_path / "dir.png").mkdir()
    (tmp_path / "in.csv").write_text("RUNTIME\n0\n")
    for path, words in [(tmp_path / "no" / "x.png", "the folder"), (tmp_path / "dir.png", "is a folder"),
                        (tmp_path / "x.xyz", "must end in .png or .pdf"), ("", "empty")]:
        with pytest.raises(InputError, match=words) as err:
            check_output_path(path, (".png", ".pdf"), "-o")
        assert err.value.field == "-o"
    with pytest.raises(InputError, match="is also an input"):
        check_output_path(tmp_path / "in.csv", (".csv",), "-o", inputs=[str(tmp_path / "in.csv")])


# a process started in the background by a non-interactive shell (as CI may start
# the tests) inherits SIGINT ignored: the writer restores Python's own handler
WRITER = textwrap.dedent("""
    import signal, sys, time
    signal.signal(signal.SIGINT, signal.default_int_handler)
    from tyrelab.io_atomic import atomic_write
    def slow(tmp):
        with open(tmp, "w") as fh:
            fh.write("partial ")
            fh.flush()
            print("writing", flush=True)
            for _ in range(600):
                time.sleep(0.05)
                fh.write("more ")
    atomic_write(sys.argv[1], slow)
""")


@linux
@pytest.mark.parametrize("sig, leaves_temporary", [(signal.SIGINT, False), (signal.SIGKILL, True)])
def test_a_write_killed_midway_leaves_the_previous_file(tmp_path, sig, leaves_temporary):
    target = tmp_path / "table.csv"
    target.write_text("previous, complete\n")
    p = subprocess.Popen([sys.executable, "-c", WRITER, str(target)], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "writing"   # the temporary file is half written now
    assert len(_temporaries(tmp_path)) == 1
    p.send_signal(sig)
    p.wait(timeout=30)
    assert p.returncode != 0
    assert target.read_text() == "previous, complete\n"
    assert bool(_temporaries(tmp_path)) == leaves_temporary
    atomic_write_text(target, "next\n")                # the next write cleans up
    assert _temporaries(tmp_path) == [] and target.read_text() == "next\n"


def _handler_installed(pid: int, signum: int) -> bool:
    status = Path(f"/proc/{pid}/status").read_text()
    caught = int(next(ln for ln in status.splitlines() if ln.startswith("SigCgt:")).split()[1], 16)
    return bool(caught >> (signum - 1) & 1)


@linux
@pytest.mark.parametrize("sig, code, words, cold", [
    (signal.SIGTERM, 143, "tyrelab: terminated", False),
    (signal.SIGINT, 130, "tyrelab: interrupted", False),
    (signal.SIGTERM, 143, "tyrelab: terminated", True),    # while numba compiles the kernels
], ids=["SIGTERM", "SIGINT", "SIGTERM-compiling"])
def test_a_signal_to_a_running_simulation(tmp_path, sig, code, words, cold):
    """SIGTERM / Ctrl-C during a long run: one line, exit 143 / 130, the earlier output intact."""
    out = tmp_path / "run.parquet"
    out.write_bytes(b"an earlier result")
    env = dict(os.environ)
    if cold:  # an empty compile cache: the signal arrives inside numba / llvmlite
        env["NUMBA_CACHE_DIR"] = str(tmp_path / "cache")
    # a long run (about a minute of work) that is stopped after a second
    p = subprocess.Popen([sys.executable, "-m", "tyrelab.cli.main", "simulate", "--road", "flat",
                          "--duration", "3000", "--dt", "1e-4", "--rate", "10", "-o", str(out)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path, env=env)
    t0 = time.monotonic()
    while not _handler_installed(p.pid, signal.SIGTERM):  # the command's own handler is in place
        assert p.poll() is None and time.monotonic() - t0 < 60
        time.sleep(0.05)
    time.sleep(1.0)
    p.send_signal(sig)
    _, err = p.communicate(timeout=60)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert p.returncode == code, err
    assert lines == [words], err
    assert "Traceback" not in err
    assert out.read_bytes() == b"an earlier result"
    assert _temporaries(tmp_path) == []


def test_every_writer_goes_through_the_atomic_writer(tmp_path, monkeypatch):
    """Signal tables, property files, TYDEX, OpenCRG, plots, pages: each calls the one writer."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    import tyrelab.io_atomic as io
    from tyrelab.measure.tydex import write_tydex
    from tyrelab.report.validation_page import write_page
    from tyrelab.road.crg import write_crg
    from tyrelab.road.obstacles import Flat
    from tyrelab.signal import make_signal, write_signal
    from tyrelab.tyre.library import load_tyre

    seen = []
    real = io.atomic_output

    def spy(path, field=None):
        seen.append(Path(path).name)
        return real(path, field)
    monkeypatch.setattr(io, "atomic_output", spy)
    table = make_signal({"RUNTIME": np.arange(3) * 0.1, "FZ": np.ones(3)})
    write_signal(table, tmp_path / "a.parquet")
    write_tydex(table, tmp_path / "a.tdx")
    load_tyre("xzl-16.00R20").write(tmp_path / "a.tir")
    write_crg(Flat(), tmp_path / "a.crg")
    fig = plt.figure()
    io.save_figure(fig, tmp_path / "a.png")
    write_page(tmp_path / "a.html", "<html></html>")
    assert seen == ["a.parquet", "a.tdx", "a.tir", "a.crg", "a.png", "a.html"]
    assert _temporaries(tmp_path) == []


@linux
@pytest.mark.parametrize("command, output, phase", [
    (["fit", "ring", "--max-evaluations", "50"], "ring.tir", b"identifying ring"),
    (["study", "--workers", "1"], "results", b"study:"),
], ids=["fit-ring", "study"])
def test_sigterm_to_a_long_command_leaves_nothing_that_looks_complete(tmp_path, command, output, phase):
    """SIGTERM during the ring's identification (minutes) and during the built-in
    campaign: one line, exit 143, no output file (fit), no report (study).

    The signal is sent once the command's own progress bar says it is in the phase under
    test (the ring's bar is drawn after a second of identifying; the study's bar when the
    runs start), and stderr is read as bytes and rendered as a terminal shows it, so a bar
    that leaves the cursor mid-line makes the message visibly indented and fails here."""
    out = tmp_path / output
    p = subprocess.Popen([sys.executable, "-m", "tyrelab.cli.main", *command, "-o", str(out)],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=tmp_path)
    err = StreamWatcher(p.stderr)
    try:
        assert err.wait_for(phase, p, timeout=600), err.data
        assert p.poll() is None
        p.send_signal(signal.SIGTERM)
        p.wait(timeout=120)
    finally:
        if p.poll() is None:
            p.kill()
    raw = err.finish()
    shown = [ln for ln in render(raw) if ln.strip()]
    assert p.returncode == 143, raw
    assert shown[-1:] == ["tyrelab: terminated"], (shown, raw)
    assert b"Traceback" not in raw
    if output == "ring.tir":
        assert not out.exists()
    else:
        assert not (out / "report.html").exists() and not (out / "metrics.parquet").exists()
    assert _temporaries(tmp_path) == []


def test_the_terminal_rendering_the_signal_tests_read():
    """The renderer the signal tests rely on, against what a VT100 shows (worked by hand)."""
    assert render(b"abc\rX\n") == ["Xbc"]
    assert render(b"one\ntwo\x1b[Aa") == ["onea", "two"]            # up one line, same column
    assert render(b"long line\r\x1b[Kshort") == ["short"]           # erase to the end of line
    # tqdm's bar at position 1 closing (down, clear, up) leaves the cursor past the cleared
    # text: a message printed next is indented, as the ring's bar did before this was fixed
    closed_at_1 = b"\n\r" + b" " * 10 + b"\x1b[A"
    assert render(closed_at_1 + b"tyrelab: terminated\n") == [" " * 10 + "tyrelab: terminated"]
    assert render(b"\r" + b" " * 10 + b"\rtyrelab: terminated\n") == ["tyrelab: terminated"]
