"""The compile cache's old folders: which are in use, and removing those long unused.

Each kernel digest has its own folder (:mod:`tyrelab.core.jit_cache`): an upgrade of tyrelab,
numba or Python, or a plugin's, starts a new one of 30-90 MB and leaves the old one, which
nothing reads again unless that old version runs again. So every process:

* **claims** its folder for its lifetime: a shared ``flock`` on ``in-use.lock`` in it,
  whose modification time it sets to now (the folder's last use);
* **prunes** the sibling digest folders last used more than :data:`MAX_AGE` ago: each one
  whose ``in-use.lock`` it can lock exclusively at once (no process holds it) is deleted
  under that lock.

A process that finds its lock file deleted after it got the lock (a pruner removed the folder
between its ``mkdir`` and its lock) makes the folder again. Two versions used in turn within
:data:`MAX_AGE` keep both folders; one unused for longer costs a compile when it runs again.
Where ``fcntl`` does not exist (Windows) or the file system cannot lock, nothing is deleted.
"""

from __future__ import annotations

import os
import re
import shutil
import time
from pathlib import Path

try:
    import fcntl
except ImportError:  # Windows
    fcntl = None

#: the file whose shared lock marks a folder in use, and whose time is its last use
IN_USE = "in-use.lock"
#: a digest folder unused for this long [s] is removed (when no process holds it)
MAX_AGE = 30 * 86400.0
#: the digest folders' prefix in numba's cache folder (NUMBA_CACHE_DIR), beside other
#: packages' caches; in tyrelab's own cache folder a digest folder is the digest alone
#: (:func:`tyrelab.core.jit_cache.cache_dir`)
PREFIX = "tyrelab-"

#: a digest folder's name: a prefix, then the digest's first 16 hexadecimal digits
DIGEST_NAME = re.compile(r"(.*?)[0-9a-f]{16}")

_claimed: list[int] = []  # descriptors of the folders this process holds (kept open)


def claim(folder: Path) -> bool:
    """Hold ``folder`` (made if missing) in use for this process's lifetime and mark its use
    now; False where it cannot be locked."""
    if fcntl is None:
        return False
    for _ in range(3):
        try:
            folder.mkdir(parents=True, exist_ok=True)
            fd = os.open(folder / IN_USE, os.O_RDWR | os.O_CREAT, 0o666)
        except OSError:
            return False
        try:
            fcntl.flock(fd, fcntl.LOCK_SH)    # a pruner holds it exclusively only while deleting
            if os.fstat(fd).st_nlink > 0:     # not deleted before we got it
                os.utime(fd)
                _claimed.append(fd)
                return True
        except OSError:                       # ENOLCK: this file system cannot lock
            os.close(fd)
            return False
        os.close(fd)
    return False


def last_use(folder: Path) -> float:
    """When ``folder`` was last claimed [s since the epoch]: its lock file's time, or the
    folder's own for one made before folders were claimed."""
    try:
        return (folder / IN_USE).stat().st_mtime
    except FileNotFoundError:
        return folder.stat().st_mtime


def prune_unused(current: Path, max_age: float = MAX_AGE, now: float | None = None) -> list[Path]:
    """Delete the digest folders beside ``current`` (its name's prefix, then 16 hexadecimal
    digits) that were last used more than ``max_age`` seconds before ``now`` and that no
    process holds; returns the ones deleted."""
    if fcntl is None:
        return []
    now = time.time() if now is None else now
    # the siblings of its layout: the same name before the 16-digit digest ("" in tyrelab's
    # own folder, PREFIX under NUMBA_CACHE_DIR, a test's own prefix for its toy caches)
    layout = DIGEST_NAME.fullmatch(current.name)
    if layout is None:
        return []
    pattern = re.compile(re.escape(layout.group(1)) + "[0-9a-f]{16}")
    removed = []
    try:
        siblings = sorted(current.parent.iterdir())
    except OSError:
        return []
    for folder in siblings:
        if folder == current or not pattern.fullmatch(folder.name) or not folder.is_dir():
            continue
        try:
            seen = last_use(folder)
            if now - seen <= max_age:
                continue
            existed = (folder / IN_USE).exists()
            fd = os.open(folder / IN_USE, os.O_RDWR | os.O_CREAT, 0o666)
        except OSError:
            continue
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:                       # held: in use (or no locking here): kept
            os.close(fd)
            continue
        try:
            # claimed and left again since it was looked at: used, kept
            if existed and os.fstat(fd).st_mtime > seen:
                continue
            shutil.rmtree(folder, ignore_errors=True)
            removed.append(folder)
        finally:
            os.close(fd)
    return removed
