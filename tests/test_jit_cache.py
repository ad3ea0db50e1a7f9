"""tyrelab.core.jit_cache: compiled code follows the kernel sources, and only them.

The end-to-end tests run a copy of the current package (``tyrelab.__file__``'s
folder) in fresh interpreters, with every cache folder and ``HOME`` inside
``tmp_path``, so neither the work tree nor the user's caches are touched. Each
cold run compiles the smallest kernel that calls into another kernel module: the soil
wheel's tyre force (``tyre/contact/soil_wheel.py``), which calls ``rolling_load`` of
``tyre/vertical.py``, the module the edits below change. A cold run takes about 2 s, of
which 1.5 s is the interpreter and its imports (the point model's static press, used
before, took 5.5-7.5 s: the suite ran six of them).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numba
import pytest
from numba.core.caching import NullCache

import tyrelab
from tyrelab.core import jit_cache
from tyrelab.core.cache_folders import IN_USE

PACKAGE = Path(tyrelab.__file__).resolve().parent
#: the spline branch of ``_carcass_load`` (the built-in tyre uses the load-deflection table)
SPLINE_RETURN = "    return value if value > 0.0 else 0.0\n"
DOUBLED_RETURN = "    return 2.0 * value if value > 0.0 else 0.0\n"

RUN = r"""
import gc, json
import tyrelab
from numba.core.dispatcher import Dispatcher
from tyrelab.core.jit_cache import cache_dir
from tyrelab.tyre.contact.soil_wheel import _tyre_force

law = tyrelab.load_tyre("xzl-16.00R20").vertical_law
load = float(_tyre_force(law, 0.03, 0.03, 0.0, 0.0)[0])  # static, not spinning: at 30 mm [N]
ours = [d for d in gc.get_objects() if isinstance(d, Dispatcher)
        and d.py_func.__module__.startswith("tyrelab.")]
print(json.dumps({
    "file": tyrelab.__file__,
    "folder": str(cache_dir()),
    "load": load,
    "hits": sum(sum(d.stats.cache_hits.values()) for d in ours),
    "misses": sum(sum(d.stats.cache_misses.values()) for d in ours),
    "compiled": sorted(f"{d.py_func.__qualname__}{sig}" for d in ours
                       for sig, n in d.stats.cache_misses.items() if n),
}))
"""


def copy_package(tmp_path: Path) -> Path:
    """A copy of the package under ``tmp_path/src``; returns that ``src``."""
    shutil.copytree(PACKAGE, tmp_path / "src" / "tyrelab",
                    ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    return tmp_path / "src"


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert text.count(old) == 1, f"{old!r} not found once in {path}"
    path.write_text(text.replace(old, new))


def append_comment(path: Path) -> None:
    path.write_text(path.read_text() + "# an edit\n")


def environment(tmp_path: Path, src: Path, numba_cache_dir: Path | None) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "PYTHONPATH")}
    env.update(PYTHONPATH=str(src), HOME=str(tmp_path / "home"), XDG_CACHE_HOME=str(tmp_path / "xdg"))
    if numba_cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(numba_cache_dir)
    return env


def result(stdout: str, src: Path) -> dict:
    out = json.loads(stdout.strip().splitlines()[-1])
    assert Path(out["file"]).is_relative_to(src), "the subprocess imported another tyrelab"
    return out


def run(tmp_path: Path, src: Path, numba_cache_dir: Path | None) -> dict:
    proc = subprocess.run([sys.executable, "-c", RUN], env=environment(tmp_path, src, numba_cache_dir),
                          cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    return result(proc.stdout, src)


def files(folder: Path) -> dict:
    """The cache's files and their (time, size); not the folder's in-use mark, whose time
    every process sets (tyrelab.core.cache_folders)."""
    return {p: (p.stat().st_mtime_ns, p.stat().st_size) for p in folder.rglob("*")
            if p.is_file() and p.name != IN_USE}


# -- unit level: the digest and the choice of cache ---------------------------------------------

def test_digest_follows_kernel_sources_only(tmp_path):
    package = copy_package(tmp_path) / "tyrelab"
    before = jit_cache.kernel_digest(package)
    assert before == jit_cache.kernel_digest(PACKAGE)  # relative paths: the copy has the same digest

    append_comment(package / "cli" / "main.py")
    (package / "core" / "probe.py").write_text("K = 1\n")  # a new module no kernel imports
    assert jit_cache.kernel_digest(package) == before

    append_comment(package / "tyre" / "vertical.py")
    after_kernel = jit_cache.kernel_digest(package)
    assert after_kernel != before

    # a plain module imported by a kernel: its constants are frozen into the compiled code
    vertical = package / "tyre" / "vertical.py"
    vertical.write_text(vertical.read_text() + "from ..core.probe import K\n")
    assert package / "core" / "probe.py" in jit_cache.kernel_modules(package)
    with_probe = jit_cache.kernel_digest(package)
    (package / "core" / "probe.py").write_text("K = 2\n")
    assert jit_cache.kernel_digest(package) != with_probe


def test_digest_follows_the_generated_and_named_index_modules(tmp_path):
    """The MF kernels read ``C.PCX1`` from the generated ``coefficient_index.py`` and the rigs
    write ``o[WC.FX]`` through ``core/named_index.py``'s records: numba freezes both into the
    compiled code, so an edit of either must give a new cache folder."""
    package = copy_package(tmp_path) / "tyrelab"
    modules = jit_cache.kernel_modules(package)
    index = package / "tyre" / "handling" / "mf" / "coefficient_index.py"
    named = package / "core" / "named_index.py"
    assert index in modules and named in modules
    for path in (index, named):
        before = jit_cache.kernel_digest(package)
        append_comment(path)
        assert jit_cache.kernel_digest(package) != before, path


def test_cache_dir_honours_numba_cache_dir(tmp_path, monkeypatch):
    digest = jit_cache.kernel_digest()[:16]
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path / "numba"))
    assert jit_cache.cache_dir() == (tmp_path / "numba" / f"tyrelab-{digest}").resolve()

    monkeypatch.setattr(numba.config, "CACHE_DIR", "")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert jit_cache.cache_dir() == (tmp_path / "xdg" / "tyrelab" / "numba" / digest).resolve()

    (tmp_path / "a-file").write_text("")  # nothing can be created below a file
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path / "a-file"))
    assert jit_cache.cache_dir() is None


def function_in(path: Path):
    """A fresh Python function whose source file is *path* (which must exist)."""
    namespace = {}
    exec(compile("def f(x):\n    return x + 1\n", str(path), "exec"), namespace)
    return namespace["f"]


def test_only_tyrelab_functions_use_the_digest_folder(tmp_path, monkeypatch):
    other_file = tmp_path / "other.py"
    other_file.write_text("")
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path / "theirs"))
    monkeypatch.setattr(jit_cache, "_folder", tmp_path / "ours")

    ours = numba.njit(cache=True)(function_in(PACKAGE / "errors.py"))
    other = numba.njit(cache=True)(function_in(other_file))
    assert Path(ours.stats.cache_path).is_relative_to(tmp_path / "ours")
    assert Path(other.stats.cache_path).is_relative_to(tmp_path / "theirs")

    monkeypatch.setattr(jit_cache, "_folder", None)  # no writable folder: compile in memory
    in_memory = numba.njit(cache=True)(function_in(PACKAGE / "errors.py"))
    assert isinstance(in_memory._cache, NullCache)
    assert in_memory(1) == 2


def test_two_signatures_saved_at_once_keep_their_own_code(tmp_path):
    """Process B reads the index, A writes its entry, B saves all of its entry, A's data lands."""
    def cache_file():
        return jit_cache._IndexDataFile(str(tmp_path), "f-1.py311", source_stamp="stamp")

    a, b = cache_file(), cache_file()
    b._load_index = lambda: {}  # B's view of the index predates A's entry
    write_a = a._save_data

    def late_write(name, data):
        b.save("key B", "code B")
        write_a(name, data)

    a._save_data = late_write
    a.save("key A", "code A")
    assert cache_file().load("key B") == "code B"
    assert cache_file().load("key A") in (None, "code A")


def test_a_file_system_that_cannot_lock_does_not_stall_a_compile(tmp_path, monkeypatch):
    """flock failing for want of locking (ENOLCK, as on some network mounts) is not a lock
    held by another process: the compile goes on at once, unlocked; a held lock is waited for."""
    import errno
    import fcntl

    calls = []

    def flock(fd, op, error=errno.ENOLCK):
        calls.append(op)
        raise OSError(error, os.strerror(error))

    monkeypatch.setattr(fcntl, "flock", flock)
    monkeypatch.setattr(jit_cache, "LOCK_PATIENCE", 30.0)
    lock = jit_cache._CompileLock(str(tmp_path / "k.lock"))
    lock.acquire()
    assert lock.fd is None and len(calls) == 1    # one try, no wait

    # held by another process for three tries, then free: waited for, then taken
    def held_three_times(fd, op):
        if len(calls) < 4:
            flock(fd, op, errno.EWOULDBLOCK)
        calls.append(op)

    monkeypatch.setattr(fcntl, "flock", held_three_times)
    lock.acquire()
    assert lock.fd is not None and len(calls) == 5
    lock.release()
    assert lock.fd is None


def test_a_signature_this_process_compiles_already_takes_no_second_lock(tmp_path, monkeypatch):
    """A miss of a signature this process holds the lock of (a recursive kernel typing itself)
    returns at once: a second flock on the same file would wait for this very process."""
    import fcntl

    from numba import types
    from numba.core.registry import cpu_target

    from tyrelab.road.grid import road_height

    monkeypatch.setattr(jit_cache, "_folder", tmp_path)
    monkeypatch.setattr(jit_cache, "LOCK_PATIENCE", 0.05)  # a wrong wait ends, and fails below
    tries = []
    real = fcntl.flock
    monkeypatch.setattr(fcntl, "flock", lambda fd, op: (tries.append(op), real(fd, op))[1])
    cache = jit_cache._KernelCache(road_height.py_func)
    sig = (types.float32, types.float32, types.float32)     # never compiled: a miss
    try:
        assert cache.load_overload(sig, cpu_target.target_context) is None
        assert sig in cache._held and len(tries) == 1       # the miss took the lock ...
        assert cache.load_overload(sig, cpu_target.target_context) is None
        assert len(tries) == 1                              # ... the second miss did not wait
    finally:
        cache.release()
    assert not cache._held


# -- end to end, in fresh interpreters ----------------------------------------------------------

def kernel_edit_reaches_the_compiled_code(tmp_path, src, numba_cache_dir, first):
    """Double ``static_load``'s spline branch, in a file the kernel only calls into: new folder,
    new physics."""
    old_folder = Path(first["folder"])
    old_files = files(old_folder)
    edit(src / "tyrelab" / "tyre" / "vertical.py", SPLINE_RETURN, DOUBLED_RETURN)
    after = run(tmp_path, src, numba_cache_dir)
    assert after["folder"] != first["folder"]
    assert after["misses"] > 0
    assert after["load"] == pytest.approx(2.0 * first["load"], rel=0.05)
    assert files(old_folder) == old_files  # the old folder is left alone


def test_edits_with_numba_cache_dir(tmp_path):
    src = copy_package(tmp_path)
    base = tmp_path / "numba-cache"
    first = run(tmp_path, src, base)
    folder = Path(first["folder"])
    assert folder.parent == base.resolve() and folder.name.startswith("tyrelab-")
    assert first["misses"] > 0 and files(folder)

    # a non-kernel edit: same folder, everything loaded from it, nothing written
    append_comment(src / "tyrelab" / "cli" / "main.py")
    cached = files(base)
    second = run(tmp_path, src, base)
    assert second["folder"] == first["folder"]
    assert second["misses"] == 0 and second["hits"] > 0
    assert second["load"] == first["load"]
    assert files(base) == cached

    kernel_edit_reaches_the_compiled_code(tmp_path, src, base, first)


def test_edits_with_the_user_cache(tmp_path):
    """Without NUMBA_CACHE_DIR the code goes to the user's cache, in the folder of the same
    digest; that a kernel edit reaches the code is checked once, with NUMBA_CACHE_DIR above
    (the digest and the check do not depend on the base folder; a second cold compile of
    the edited copy here cost 6-13 s of the suite)."""
    src = copy_package(tmp_path)
    first = run(tmp_path, src, None)
    folder = Path(first["folder"])
    assert folder.parent == (tmp_path / "xdg" / "tyrelab" / "numba").resolve()
    assert folder.name == jit_cache.kernel_digest(src / "tyrelab")[:16]
    assert first["misses"] > 0 and files(folder)


def test_two_processes_compile_into_one_cache_at_once(tmp_path):
    """Started together on a cold cache, two processes compile each kernel once between them
    (the second waits on the first's compile lock and loads its code), and agree."""
    src = copy_package(tmp_path)
    env = environment(tmp_path, src, tmp_path / "numba-cache")
    procs = [subprocess.Popen([sys.executable, "-c", RUN], env=env, cwd=tmp_path, text=True,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE) for _ in range(2)]
    outputs = [p.communicate(timeout=300) for p in procs]
    for proc, (_, stderr) in zip(procs, outputs):
        assert proc.returncode == 0, stderr
    got = [result(stdout, src) for stdout, _ in outputs]
    assert got[0]["load"] == got[1]["load"] > 0.0
    compiled = [set(g["compiled"]) for g in got]
    assert compiled[0] | compiled[1]                # a cold cache: something was compiled ...
    assert not compiled[0] & compiled[1]            # ... and no signature by both processes
    assert not list((tmp_path / "numba-cache").rglob("*.tmp.*"))  # every write was renamed into place


GC_RUN = r"""
import gc, json
import numba
from numba.core import event
import tyrelab
from tyrelab.road.grid import road_height

seen = []  # gc.isenabled() at the end of every compile nested in another


class Probe(event.Listener):
    depth = 0

    def on_start(self, ev):
        self.depth += 1

    def on_end(self, ev):
        self.depth -= 1
        if self.depth > 0:
            seen.append(gc.isenabled())


event.register("numba:compile", Probe())
tyrelab.simulate(model="point", road="flat", duration=0.01)
after_run = gc.isenabled()
try:
    road_height(1, 2, 3)  # a typing error inside a compile of ours
except numba.TypingError:
    pass


def free(path):  # another open file description of the lock: takes it unless it is held
    import fcntl, os
    fd = os.open(path, os.O_RDWR)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        return True
    except OSError:
        return False
    finally:
        os.close(fd)


from pathlib import Path
from tyrelab.core.jit_cache import cache_dir
from tyrelab.core.cache_folders import IN_USE
locks = sorted(p for p in Path(cache_dir()).rglob("*.lock") if p.name != IN_USE)  # compile locks
print(json.dumps({"nested": len(seen), "paused": not any(seen), "after_run": after_run,
                  "after_error": gc.isenabled(), "locks": len(locks),
                  "free": [free(p) for p in locks],
                  "failed": sum("road_height" in p.name for p in locks)}))
"""


def test_collector_paused_while_compiling_and_resumed(tmp_path):
    """The cyclic collector is off during a compile of the package's kernels and on again
    afterwards, also when the compile fails (a user's process must keep its collector); the
    failed compile's lock is not held after it (a waiting process would wait in vain)."""
    env = dict(os.environ, HOME=str(tmp_path), NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    env.pop("XDG_CACHE_HOME", None)
    out = subprocess.run([sys.executable, "-c", GC_RUN], capture_output=True, text=True, env=env,
                         check=True)
    got = json.loads(out.stdout.strip().splitlines()[-1])
    assert got["nested"] > 5  # the probe saw the kernels' nested compiles
    assert got["paused"]
    assert got["after_run"] and got["after_error"]
    # every compile took its signature's lock and gave it back, the failed one too
    assert got["locks"] > 5 and got["failed"] >= 2     # road_height: the run's and the failure's
    assert all(got["free"])


def test_the_numba_range_pinned_is_the_range_tested_and_installed():
    """The cache patches numba's internals (and the ring's force step compiles with
    ``_nrt=False``): the range they were tested on is pinned in pyproject.toml, and a
    numba outside it -- installed by hand, or a pin edited alone -- fails here, loudly."""
    import re
    import tomllib

    from tyrelab.core.jit_cache import TESTED_NUMBA, numba_is_tested, numba_release

    lo, hi = TESTED_NUMBA
    pyproject = tomllib.loads((Path(__file__).parents[1] / "pyproject.toml").read_text(encoding="utf-8"))
    pins = [d for d in pyproject["project"]["dependencies"] if re.match(r"numba\b", d)]
    assert pins == [f"numba>={lo[0]}.{lo[1]},<{hi[0]}.{hi[1]}"]
    assert numba_is_tested(numba.__version__), f"numba {numba.__version__} outside {TESTED_NUMBA}"
    assert numba_release("0.68.1") == (0, 68) and numba_release("1.0.0rc1") == (1, 0)
    assert numba_is_tested("0.68.0") and not numba_is_tested("0.67.1") and not numba_is_tested("0.69.0")
