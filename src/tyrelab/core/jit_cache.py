"""Where numba keeps tyrelab's compiled kernels, so that a cached kernel is never stale.

Why not numba's own ``cache=True`` placement: numba checks a cached function only
against the file that defines it (in 0.68 a hash of that one file), but the rig
loops inline or call kernels from many other modules, and numba freezes the
globals a kernel reads (such as index constants imported from a plain-Python
module) into the machine code. An edit of any of those files would leave the
rigs' cached code stale: old physics, silently.

So every ``@njit(cache=True)`` function of tyrelab is cached in one folder named
by :func:`kernel_digest`, a hash of the *kernel modules* (those whose source
imports numba, plus the package modules they import at module level, since
their globals end up in the compiled code), the numba and the Python version.
A kernel edit gives a new folder and a fresh compile; an edit of plain Python
(cli, report, validate, ...) changes nothing and costs nothing. The folder is
``$NUMBA_CACHE_DIR/tyrelab-<digest16>`` when numba's cache dir is set, else
``$XDG_CACHE_HOME/tyrelab/numba/<digest16>`` (``~/.cache/...``); if neither can
be written, tyrelab compiles in memory. A folder is deleted only when it was last
used more than 30 days ago and no process holds it (:mod:`tyrelab.core.cache_folders`:
each process holds its own folder with a shared lock), since another process may be
loading its files.

How numba is pointed there. numba chooses a cache *locator* once per function,
when it is decorated: ``Dispatcher.enable_caching`` builds a ``FunctionCache``
whose ``_CacheImpl.__init__`` asks each class of ``_locator_classes`` in turn;
the first, ``UserProvidedCacheLocator``, reads ``numba.config.CACHE_DIR`` at
that moment. Assigning ``config.CACHE_DIR`` here would also move every other
package's cache into our folder, and ``config.reload_config()`` (run by the
compiler) resets it from the environment as soon as any ``NUMBA_*`` variable
changes, so a kernel module imported later would fall back to its
``__pycache__`` and to stale code. Instead :func:`configure` wraps
``Dispatcher.enable_caching``: a function whose source lies in this package gets
a cache whose only locator is our folder (or no cache: compile in memory); any
other function goes through numba unchanged. (An explicit
``NUMBA_CACHE_LOCATOR_CLASSES`` still overrides our locator, as it does numba's.)

Several processes may compile and load at once: numba writes every index
(``.nbi``) and data (``.nbc``) file to a uuid-named temporary file and
``os.replace``-s it into place (``IndexDataCacheFile._open_for_write``), so a
reader sees a whole old file or a whole new one; an index entry whose data file
is gone reads as a miss (``IndexDataCacheFile.load`` catches ``OSError``) and
the reader compiles for itself. numba's numbering of data files is not safe
against two processes adding different signatures at once, hence
:class:`_IndexDataFile`.

Several processes that need the same kernel at once compile it once: a miss takes the
signature's compile lock (:class:`_CompileLock`, an ``flock`` on a file beside the index)
and looks in the cache again once it holds it, so the process that waited loads what the
first one saved instead of compiling the same code beside it (on a cold cache, a
study's workers, the test suite's and the docs' processes all asked for the ring on soil
at once: four compiles of it, 11-57 s each). The lock is released when the code is saved,
when the compile fails, or when its process ends.

While numba compiles a kernel of the package, Python's cyclic garbage collector
is paused (:class:`_PausedCollector`): a compile makes millions of short-lived
objects (numba deep-copies the IR of every inlined function), and the
collector's passes over the heap they pass through took 1.0-1.7 s of a 6-8 s
cold compile of a trailer loop (measured, volume and enveloping models). The
collector runs again as soon as the outermost compile ends.
"""

from __future__ import annotations

import errno
import gc
import hashlib
from importlib import metadata
import os
import re
import sys
import tempfile
import time
from pathlib import Path

try:
    import fcntl
except ImportError:  # Windows: no compile lock
    fcntl = None

import numba
from numba.core import caching
from numba.core import event
from numba.core.dispatcher import Dispatcher

from . import cache_folders

_PACKAGE = Path(__file__).resolve().parents[1]
_folder: Path | None = None  # chosen by configure()
#: the numba releases, [first, past last) as (major, minor), that this module's use of
#: numba's internals (``Dispatcher.enable_caching``, ``caching._CacheLocator`` and
#: ``_SourceFileBackedLocatorMixin``, ``IndexDataCacheFile``) and the ring's
#: ``_nrt=False`` force step were tested on; ``pyproject.toml`` pins the same range and
#: ``tests/test_jit_cache.py`` fails when either or the installed numba leaves it
TESTED_NUMBA = ((0, 68), (0, 69))


def numba_release(version: str = numba.__version__) -> tuple[int, int]:
    """``(major, minor)`` of a numba version string."""
    major, minor = (int(re.match(r"\d+", part).group()) for part in version.split(".")[:2])
    return major, minor


def numba_is_tested(version: str = numba.__version__) -> bool:
    """Whether ``version`` lies in :data:`TESTED_NUMBA`."""
    return TESTED_NUMBA[0] <= numba_release(version) < TESTED_NUMBA[1]


def _module_file(package: Path, parts: list[str]) -> Path | None:
    if not parts:
        return None
    base = package.joinpath(*parts)
    for path in (base.with_name(base.name + ".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return None


# module-level imports, read with a regex: ast.parse of the kernels costs ~60 ms at every import
_IMPORT = re.compile(r"^from[ \t]+(\.*)([\w.]*)[ \t]+import[ \t]+(\([^)]*\)|.*)"
                     r"|^import[ \t]+tyrelab\.([\w.]+)", re.MULTILINE)


def _imports(path: Path, package: Path) -> set[Path]:
    """The package's modules that *path* imports at module level."""
    here = path.relative_to(package).parent.parts
    found = set()
    for dots, module, names, absolute in _IMPORT.findall(path.read_text(encoding="utf-8")):
        if absolute:
            found.add(_module_file(package, absolute.split(".")))
            continue
        parts = module.split(".") if module else []
        if dots:
            if len(dots) - 1 > len(here):
                continue
            parts = [*here[:len(here) - len(dots) + 1], *parts]
        elif parts[:1] == ["tyrelab"]:
            parts = parts[1:]
        else:
            continue
        names = re.findall(r"\w+", re.sub(r"#.*|\bas\s+\w+", "", names))
        found.update(_module_file(package, c) for c in [parts] + [parts + [n] for n in names])
    return found - {None}


def kernel_modules(package: Path = _PACKAGE) -> list[Path]:
    """The modules whose sources can end up in compiled code (see the module docstring)."""
    found = {p for p in package.rglob("*.py")
             if re.search(r"import numba|from numba", p.read_text(encoding="utf-8"))}
    todo = list(found)
    while todo:
        for dep in _imports(todo.pop(), package) - found:
            found.add(dep)
            todo.append(dep)
    return sorted(found)


#: the entry-point group of tyrelab's plugins (tyrelab.plugins.GROUP; this layer cannot import it)
PLUGIN_GROUP = "tyrelab.plugins"


def plugin_sources() -> list[tuple[str, bytes]]:
    """``(name, bytes)`` of the Python files of every installed plugin distribution.

    A plugin's model record enters the signatures of tyrelab's rig loops, which are cached
    here, and its compiled code is inlined into them: an edited or upgraded plugin must not
    meet the loops compiled with its old code. Read from the distributions' file lists
    (nothing is imported)."""
    out = []
    for ep in sorted(metadata.entry_points(group=PLUGIN_GROUP), key=lambda e: (e.name, e.value)):
        dist = ep.dist
        for f in sorted(dist.files or (), key=str) if dist is not None else ():
            if str(f).endswith(".py"):
                try:
                    out.append((f"{dist.name}/{f}", Path(f.locate()).read_bytes()))
                except OSError:
                    continue
    return out


def kernel_digest(package: Path = _PACKAGE) -> str:
    """SHA-256 of the kernel modules (relative paths and contents), the installed plugins'
    Python files (:func:`plugin_sources`), numba's and Python's versions."""
    h = hashlib.sha256(f"numba {numba.__version__}\0python {sys.version}\0".encode())
    for path in kernel_modules(package):
        h.update(path.relative_to(package).as_posix().encode() + b"\0")
        h.update(path.read_bytes() + b"\0")
    for name, content in plugin_sources():
        h.update(b"plugin\0" + name.encode() + b"\0" + content + b"\0")
    return h.hexdigest()


def cache_dir() -> Path | None:
    """The writable folder for this digest (created), or None if there is none."""
    digest = kernel_digest()[:16]
    try:
        if numba.config.CACHE_DIR:
            folder = Path(numba.config.CACHE_DIR) / f"{cache_folders.PREFIX}{digest}"
        else:
            base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
            folder = Path(base) / "tyrelab" / "numba" / digest
        folder.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=folder).close()
    except (OSError, RuntimeError):  # RuntimeError: Path.home() without a home
        return None
    return folder.resolve()


class _KernelLocator(caching._SourceFileBackedLocatorMixin, caching._CacheLocator):
    """numba's user-dir locator, with our digest folder in place of ``config.CACHE_DIR``."""

    def __init__(self, py_func, py_file):
        self._py_file = py_file
        self._lineno = py_func.__code__.co_firstlineno
        self._cache_path = str(_folder / self.get_suitable_cache_subpath(py_file))

    def get_cache_path(self):
        return self._cache_path


class _KernelCacheImpl(caching.CompileResultCacheImpl):
    _locator_classes = [_KernelLocator]


class _IndexDataFile(caching.IndexDataCacheFile):
    """numba's index + data files, but one data file per key, named by its hash.

    numba numbers a function's data files 1, 2, ... after the index it has read; two
    processes adding different signatures of one function at once may both take
    number 1, and the index left standing may then name the other signature's code.
    Named by key, a data file can only hold that key's code, whichever process wrote
    it; the worst left is an index entry lost to the other process (a recompile).
    """

    def save(self, key, data):
        digest = hashlib.sha256(repr(key).encode()).hexdigest()[:16]
        name = f"{self._index_name.removesuffix('.nbi')}.{digest}.nbc"
        self._save_data(name, data)  # before the index names it
        overloads = self._load_index()
        if overloads.get(key) != name:
            overloads[key] = name
            self._save_index(overloads)


class _CompileLock:
    """An exclusive ``flock`` on ``path`` (created), taken by polling so that a signal's
    handler runs while a process waits; after :data:`LOCK_PATIENCE` seconds the waiter goes
    on without it (it then compiles for itself, as without a lock). Where ``fcntl`` does
    not exist (Windows) or the file system cannot lock, it locks nothing."""

    def __init__(self, path: str):
        self.path = path
        self.fd: int | None = None

    def acquire(self) -> None:
        if fcntl is None:
            return
        try:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o666)
        except OSError:
            return
        deadline = time.monotonic() + LOCK_PATIENCE
        pause = 0.005
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                self.fd = fd
                return
            except OSError as exc:
                # held by another process: wait; no locking on this file system (ENOLCK on
                # some network mounts): go on without it, as without the lock
                if exc.errno not in (errno.EAGAIN, errno.EWOULDBLOCK, errno.EACCES) \
                        or time.monotonic() > deadline:
                    os.close(fd)
                    return
                time.sleep(pause)
                pause = min(2.0 * pause, 0.1)

    def release(self) -> None:
        if self.fd is not None:
            fd, self.fd = self.fd, None
            os.close(fd)  # closing the descriptor drops its flock


#: a process waits at most this long [s] for another to compile a kernel (the longest cold
#: compile measured, the ring on soil, took 57 s beside three others on 2 cores)
LOCK_PATIENCE = 600.0


class _KernelCache(caching.FunctionCache):
    """numba's function cache in our folder, with one data file per key
    (:class:`_IndexDataFile`) and a compile lock per signature (:class:`_CompileLock`)."""

    _impl_class = _KernelCacheImpl

    def __init__(self, py_func):
        super().__init__(py_func)
        old = self._cache_file
        self._cache_file = _IndexDataFile(old._cache_path, self._impl.filename_base, old._source_stamp)
        self._held: dict = {}  # signature -> the _CompileLock this process compiles it under

    def load_overload(self, sig, target_context):
        """The cached code for ``sig``; on a miss, None once this process holds the
        signature's compile lock (another process's compile of it saved and loaded first)."""
        cres = super().load_overload(sig, target_context)
        if cres is not None or not self._enabled or sig in self._held:
            return cres  # (held: this process compiles it already, e.g. a recursive kernel)
        key = repr(self._index_key(sig, target_context.codegen()))
        digest = hashlib.sha256(key.encode()).hexdigest()[:16]
        lock = _CompileLock(os.path.join(self._cache_path,
                                         f"{self._impl.filename_base}.{digest}.lock"))
        try:
            self._impl.locator.ensure_cache_path()
            lock.acquire()
            cres = super().load_overload(sig, target_context)
        except BaseException:
            lock.release()
            raise
        if cres is not None:
            lock.release()
        else:
            self._held[sig] = lock
        return cres

    def save_overload(self, sig, data):
        try:
            super().save_overload(sig, data)
        finally:
            self.release(sig)

    def release(self, sig=None) -> None:
        """Drop the compile lock of ``sig`` (None: every one this cache holds)."""
        for s in list(self._held) if sig is None else [sig]:
            lock = self._held.pop(s, None)
            if lock is not None:
                lock.release()


def _is_ours(py_func) -> bool:
    path = os.path.realpath(py_func.__code__.co_filename)
    return path.startswith(str(_PACKAGE) + os.sep)


class _PausedCollector(event.Listener):
    """Pauses the cyclic garbage collector while numba compiles a kernel of the package.

    numba fires ``numba:compile`` around every compile, nested for the functions a
    kernel calls, all under its global compiler lock; the collector is paused at the
    outermost start (if it was running) and resumed at the matching end.
    """

    def __init__(self):
        self.depth = 0
        self.resume = False

    def on_start(self, ev):
        if self.depth == 0:
            self.resume = gc.isenabled() and _is_ours(ev.data["dispatcher"].py_func)
            if self.resume:
                gc.disable()
        self.depth += 1

    def on_end(self, ev):
        self.depth -= 1
        if self.depth == 0 and self.resume:
            gc.enable()


class _FailedCompileUnlocks(event.Listener):
    """A compile that fails saves nothing: its compile lock goes at once, so that a process
    waiting for it compiles for itself (and meets the same error) instead of waiting for its
    :data:`LOCK_PATIENCE` or for this process to end."""

    def on_start(self, ev):
        pass

    def on_end(self, ev):
        # a compile that succeeded has added its overload by now (the save follows this
        # event); numba 0.68's Event.is_failed answers the opposite of its name, so not asked
        dispatcher = ev.data["dispatcher"]
        cache = getattr(dispatcher, "_cache", None)
        args = tuple(ev.data["args"])
        if isinstance(cache, _KernelCache) and args not in dispatcher.overloads:
            # the failed signature's lock (a signature given with its return type is held
            # under another key: then every lock of the function)
            cache.release(args if args in cache._held else None)


def configure() -> Path | None:
    """Send the package's compiled code to :func:`cache_dir`; call before any kernel is imported.

    Returns the folder, or None when tyrelab compiles in memory.
    """
    global _folder
    _folder = cache_dir()
    if _folder is not None:
        # this process's folder in use; the old digests' folders long unused, removed
        cache_folders.claim(_folder)
        cache_folders.prune_unused(_folder)
    if not numba_is_tested():
        import warnings
        lo, hi = TESTED_NUMBA
        warnings.warn(f"tyrelab was tested with numba {lo[0]}.{lo[1]} to before {hi[0]}.{hi[1]}, "
                      f"found {numba.__version__}: its kernel cache relies on numba internals "
                      f"(pip install 'numba>={lo[0]}.{lo[1]},<{hi[0]}.{hi[1]}')", RuntimeWarning,
                      stacklevel=3)
    if not getattr(Dispatcher.enable_caching, "_tyrelab", False):
        numba_enable_caching = Dispatcher.enable_caching

        def enable_caching(self):
            if not _is_ours(self.py_func):
                numba_enable_caching(self)
            elif _folder is not None:
                self._cache = _KernelCache(self.py_func)
            # else: keep numba's NullCache and compile in memory

        enable_caching._tyrelab = True
        Dispatcher.enable_caching = enable_caching
        event.register("numba:compile", _PausedCollector())
        event.register("numba:compile", _FailedCompileUnlocks())
    return _folder
