"""Every output is written whole or not at all, and interrupts leave the previous file intact.

The writer (:mod:`tyrelab.io_atomic`) writes to a temporary sibling and renames it; an
exception (Ctrl-C included) removes the temporary file; a temporary file of a killed
writer is removed by the next write of the same target. The command line turns SIGTERM
into the same unwinding (exit 143) and Ctrl-C into exit 130.
"""

from __future__ import annotations

import os
import shutil
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


#: the long run the signal tests stop: 30 million steps, about a minute of work
SIMULATE = ["simulate", "--road", "flat", "--dt", "1e-4", "--rate", "10"]
LONG = ["--duration", "3000"]
#: bound on any wait of these tests [s]: a hung process fails here (never a speed limit)
HANG = 600
#: CPU time [s] the run must have spent after loading its loop's compiled code before it is
#: signalled: loading takes milliseconds and the first 0.5 s chunk of the loop ends within
#: 0.05 s of CPU (measured with the progress bar on a tty), the whole loop takes ~13 s
IN_LOOP_CPU = 0.5


def _cpu_seconds(pid: int) -> float:
    """User + system CPU time of a process [s] (/proc/PID/stat fields 14 and 15)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _wait(condition, p, what: str) -> None:
    """Until ``condition()``; fails if the process ends first or after :data:`HANG` seconds."""
    end = time.monotonic() + HANG
    while not condition():
        assert p.poll() is None, f"the run ended ({p.returncode}) before {what}"
        assert time.monotonic() < end, f"not {what} after {HANG} s"
        time.sleep(0.02)


class _Opened:
    """Names of the files opened in some folders from now on (Linux inotify, IN_OPEN)."""

    IN_OPEN = 0x20

    def __init__(self, folders):
        import ctypes
        self._libc = ctypes.CDLL(None, use_errno=True)
        self._fd = self._libc.inotify_init1(os.O_NONBLOCK | os.O_CLOEXEC)
        if self._fd < 0:
            raise OSError(ctypes.get_errno(), "inotify_init1")
        for folder in folders:
            if self._libc.inotify_add_watch(self._fd, os.fsencode(folder), self.IN_OPEN) < 0:
                raise OSError(ctypes.get_errno(), f"inotify_add_watch {folder}")
        self.names: list[str] = []

    def poll(self) -> list[str]:
        import struct
        while True:
            try:
                data = os.read(self._fd, 65536)
            except BlockingIOError:
                return self.names
            i = 0
            while i < len(data):  # struct inotify_event: wd, mask, cookie, len, name[len]
                length = struct.unpack_from("iIII", data, i)[3]
                self.names.append(data[i + 16:i + 16 + length].split(b"\0")[0].decode())
                i += 16 + length

    def close(self) -> None:
        os.close(self._fd)


def _kernel_files(cache: Path, pattern: str) -> dict[Path, float]:
    """Cached files of the trailer rig's kernels under a NUMBA_CACHE_DIR, with their mtimes."""
    return {f: f.stat().st_mtime for f in cache.glob(f"tyrelab-*/rig_*/{pattern}")}


@pytest.fixture(scope="module")
def warm_cache(tmp_path_factory):
    """A NUMBA_CACHE_DIR holding the compiled kernels of the signal tests' run: filled by a
    0.5 s run of the same command (after copying this session's cache, so it usually only
    loads them instead of compiling for 10 s)."""
    from tyrelab.core import jit_cache
    cache = tmp_path_factory.mktemp("numba-cache")
    if jit_cache._folder is not None and jit_cache._folder.is_dir():
        shutil.copytree(jit_cache._folder, cache / f"tyrelab-{jit_cache._folder.name}")
    warm = subprocess.run([sys.executable, "-m", "tyrelab.cli.main", *SIMULATE, "--duration", "0.5",
                           "-o", str(cache / "warm.parquet")],
                          env=dict(os.environ, NUMBA_CACHE_DIR=str(cache)), capture_output=True, timeout=HANG)
    assert warm.returncode == 0, warm.stderr
    assert _kernel_files(cache, "_trailer_kernel.trailer_steps-*.nbc")
    return cache


def _start(tmp_path, out: Path, cache: Path):
    p = subprocess.Popen([sys.executable, "-m", "tyrelab.cli.main", *SIMULATE, *LONG, "-o", str(out)],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=tmp_path,
                         env=dict(os.environ, NUMBA_CACHE_DIR=str(cache)))
    return p, StreamWatcher(p.stderr)


def _ended_in_one_line(p, err, code: int, words: str, out: Path, tmp_path: Path) -> None:
    p.wait(timeout=HANG)
    raw = err.finish()
    shown = [ln for ln in render(raw) if ln.strip()]
    assert p.returncode == code, raw
    assert shown == [words], raw
    assert b"Traceback" not in raw
    assert out.read_bytes() == b"an earlier result"
    assert _temporaries(tmp_path) == []


@linux
@pytest.mark.parametrize("sig, code, words", [
    (signal.SIGTERM, 143, "tyrelab: terminated"),
    (signal.SIGINT, 130, "tyrelab: interrupted"),
], ids=["SIGTERM", "SIGINT"])
def test_a_signal_to_a_running_simulation(tmp_path, warm_cache, sig, code, words):
    """SIGTERM / Ctrl-C in the time-stepping loop of a long run: one line, exit 143 / 130, the
    earlier output intact.

    ``tyrelab simulate`` reports no phase on a pipe (its bar is drawn only on a terminal), so
    the run is observed: the signal is sent once it has opened its loop's compiled code in the
    warm cache (inotify; or, if the kernels' sources changed since the cache was warmed, once
    it has written that code after compiling it) and then spent IN_LOOP_CPU s of CPU time."""
    out = tmp_path / "run.parquet"
    out.write_bytes(b"an earlier result")
    nbc = "_trailer_kernel.trailer_steps-*.nbc"
    before = _kernel_files(warm_cache, nbc)
    opened = _Opened({f.parent for f in before})
    p, err = _start(tmp_path, out, warm_cache)
    try:
        def loop_code_ready():
            loaded = any(Path(name).match(nbc) for name in opened.poll())
            return loaded or _kernel_files(warm_cache, nbc) != before
        _wait(loop_code_ready, p, "the loop's compiled code was loaded")
        assert _handler_installed(p.pid, signal.SIGTERM)  # the command's own handler is in place
        cpu = _cpu_seconds(p.pid)
        _wait(lambda: _cpu_seconds(p.pid) >= cpu + IN_LOOP_CPU, p, "the loop had run")
        p.send_signal(sig)
        _ended_in_one_line(p, err, code, words, out, tmp_path)
    finally:
        opened.close()
        if p.poll() is None:
            p.kill()


@linux
def test_sigterm_while_numba_compiles(tmp_path):
    """SIGTERM while numba compiles the run's loop (an empty compile cache): one line, exit 143.

    The signal arrives inside numba / llvmlite, where a C library may call back into Python
    and swallow the exception (tyrelab.cli.main._on_signal). The phase is observed: the run
    has llvmlite loaded, has compiled a function of the loop's own module (``_rotation``, which
    numba compiles when it types the loop ``trailer_steps``) but not yet written the loop --
    checked again right before the signal -- and the loop's code is never written."""
    out = tmp_path / "run.parquet"
    out.write_bytes(b"an earlier result")
    cache = tmp_path / "cache"
    cache.mkdir()
    loop = "_trailer_kernel.trailer_steps-*"
    p, err = _start(tmp_path, out, cache)
    try:
        def compiling_the_loop():
            return bool(_kernel_files(cache, "_trailer_kernel._rotation-*.nbi")) and \
                not _kernel_files(cache, f"{loop}.nbi")
        _wait(compiling_the_loop, p, "numba compiled the loop's callee")
        assert _handler_installed(p.pid, signal.SIGTERM)
        assert "llvmlite" in Path(f"/proc/{p.pid}/maps").read_text()
        assert not _kernel_files(cache, f"{loop}.nbi")  # still compiling, right before the signal
        p.send_signal(signal.SIGTERM)
        _ended_in_one_line(p, err, 143, "tyrelab: terminated", out, tmp_path)
    finally:
        if p.poll() is None:
            p.kill()
    # the loop's code was never written (its compile lock file, made at the miss, is no code)
    assert not _kernel_files(cache, f"{loop}.nb[ic]")


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


def test_a_message_after_a_bar_drawn_but_not_closed_starts_its_own_line():
    """The command's last line after a bar an interrupt caught mid-draw (tqdm wrote the bar
    but had not recorded it, so its close cleared nothing): the message still starts at the
    line's start; after a finished line nothing extra is written."""
    import io

    from tyrelab.cli import main as cli

    for before, extra in [("\ridentifying ring:   0%|          | 1/550", "\r\x1b[K"), ("done\n", "")]:
        tracker = cli._LineTracker(io.StringIO())
        tracker.write(before)
        old, sys.stderr = sys.stderr, tracker
        try:
            cli._say("tyrelab: terminated")
        finally:
            sys.stderr = old
        text = tracker._stream.getvalue()
        assert text == before + extra + "tyrelab: terminated\n"
        assert render(text)[-1] == "tyrelab: terminated"
