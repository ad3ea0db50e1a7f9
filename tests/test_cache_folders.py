"""The compile cache's old digest folders: removed when long unused and held by no process."""

from __future__ import annotations

import fcntl
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tyrelab.core import cache_folders
from tyrelab.core.cache_folders import IN_USE, claim, prune_unused

DAY = 86400.0


def _folder(parent: Path, name: str, used_days_ago: float | None, lock: bool = True) -> Path:
    """A digest folder with a file in it, last used ``used_days_ago`` (its lock file's time,
    or the folder's own when it has none, as one made before folders were claimed)."""
    folder = parent / name
    (folder / "sub").mkdir(parents=True)
    (folder / "sub" / "f.nbi").write_bytes(b"x")
    when = time.time() - used_days_ago * DAY
    if lock:
        (folder / IN_USE).touch()
        os.utime(folder / IN_USE, (when, when))
    os.utime(folder, (when, when))
    return folder


def test_only_old_unused_digest_folders_go(tmp_path):
    current = _folder(tmp_path, "0123456789abcdef", 400)      # this process's: never removed
    old = _folder(tmp_path, "1111111111111111", 40)
    older_unclaimed = _folder(tmp_path, "2222222222222222", 90, lock=False)
    young = _folder(tmp_path, "3333333333333333", 29)
    held = _folder(tmp_path, "4444444444444444", 60)
    other = _folder(tmp_path, "not-a-digest", 400)             # not ours: never touched
    holder = os.open(held / IN_USE, os.O_RDWR)
    fcntl.flock(holder, fcntl.LOCK_SH)                         # as a running process holds it
    try:
        removed = prune_unused(current)
    finally:
        os.close(holder)
    assert sorted(removed) == [old, older_unclaimed]
    assert not old.exists() and not older_unclaimed.exists()
    assert current.exists() and young.exists() and held.exists() and other.exists()
    # once its holder is gone, the held one is as old as it was: it goes too
    assert prune_unused(current) == [held]


def test_numba_cache_dir_siblings_are_other_packages_folders(tmp_path):
    """Under NUMBA_CACHE_DIR the folders are tyrelab-<digest> beside other packages' caches."""
    current = _folder(tmp_path, "tyrelab-0123456789abcdef", 0)
    ours = _folder(tmp_path, "tyrelab-1111111111111111", 40)
    bare = _folder(tmp_path, "1111111111111111", 40)           # a name of the other layout
    theirs = _folder(tmp_path, "otherpkg", 400)
    assert prune_unused(current) == [ours]
    assert bare.exists() and theirs.exists()


def test_a_tests_own_prefix_is_its_layout(tmp_path):
    """The kept toy caches of the tests (tests/kept_cache.py): <prefix>-<digest> in the temporary
    folder, beside the other toy's and tyrelab's own layouts, which stay."""
    current = _folder(tmp_path, "tyrelab-toy-model-0123456789abcdef", 0)
    ours = _folder(tmp_path, "tyrelab-toy-model-1111111111111111", 2)
    young = _folder(tmp_path, "tyrelab-toy-model-2222222222222222", 0.5)
    other_toy = _folder(tmp_path, "tyrelab-toy-terrain-1111111111111111", 2)
    package = _folder(tmp_path, "tyrelab-1111111111111111", 40)
    assert prune_unused(current, max_age=DAY) == [ours]
    assert young.exists() and other_toy.exists() and package.exists()
    assert prune_unused(tmp_path / "no-digest", max_age=0.0) == []   # no layout: nothing goes


def test_a_folder_used_after_it_was_looked_at_is_kept(tmp_path, monkeypatch):
    """A process that claimed and left the folder between the pruner's look and its lock has
    used it: its lock file's time is newer than the one the pruner judged by."""
    current = _folder(tmp_path, "0123456789abcdef", 0)
    old = _folder(tmp_path, "1111111111111111", 40)
    real = cache_folders.last_use

    def looked_then_used(folder):
        seen = real(folder)
        os.utime(folder / IN_USE)                              # claimed meanwhile, now
        return seen
    monkeypatch.setattr(cache_folders, "last_use", looked_then_used)
    assert prune_unused(current) == []
    assert old.exists()


def test_a_claim_makes_its_folder_again_when_a_pruner_deleted_it_first(tmp_path, monkeypatch):
    """The pruner may delete a folder between a claimant's mkdir and its lock: the lock then
    sits on a deleted file, and the claimant makes the folder again and locks that."""
    folder = tmp_path / "0123456789abcdef"
    real_flock = fcntl.flock
    calls = []

    def pruned_first(fd, op):
        calls.append(op)
        if len(calls) == 1:
            (folder / IN_USE).unlink()
            folder.rmdir()
        return real_flock(fd, op)
    monkeypatch.setattr(cache_folders.fcntl, "flock", pruned_first)
    try:
        assert claim(folder)
        assert len(calls) == 2 and (folder / IN_USE).exists()
        assert time.time() - (folder / IN_USE).stat().st_mtime < 60
        monkeypatch.setattr(cache_folders.fcntl, "flock", real_flock)
        probe = os.open(folder / IN_USE, os.O_RDWR)
        with pytest.raises(BlockingIOError):                   # held by this process
            real_flock(probe, fcntl.LOCK_EX | fcntl.LOCK_NB)
        os.close(probe)
    finally:
        while cache_folders._claimed:
            os.close(cache_folders._claimed.pop())


def test_a_running_process_keeps_its_folder(tmp_path):
    """A real tyrelab process holds its folder while it runs: a pruner that judges every
    folder old (max_age 0) leaves it, and removes it once the process has ended."""
    env = dict(os.environ, XDG_CACHE_HOME=str(tmp_path))
    env.pop("NUMBA_CACHE_DIR", None)
    p = subprocess.Popen([sys.executable, "-c", "import sys, tyrelab.core.jit_cache as j; "
                          "print(j._folder, flush=True); sys.stdin.read()"],
                         env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        theirs = Path(p.stdout.readline().strip())
        assert theirs.parent == tmp_path / "tyrelab" / "numba"
        mine = theirs.parent / "0123456789abcdef"
        mine.mkdir()
        assert prune_unused(mine, max_age=0.0, now=time.time() + 1.0) == []
        assert theirs.exists()
    finally:
        p.stdin.close()
        p.wait(timeout=60)
    assert prune_unused(mine, max_age=0.0, now=time.time() + 1.0) == [theirs]


def test_a_claim_marks_the_folders_use_now(tmp_path):
    """A version run again after weeks claims its old folder: its last use is now, so a
    pruner run later (by another version) keeps it for MAX_AGE more, even once it has ended."""
    folder = _folder(tmp_path, "1111111111111111", 40)
    other = _folder(tmp_path, "0123456789abcdef", 0)
    try:
        assert claim(folder)
    finally:
        while cache_folders._claimed:
            os.close(cache_folders._claimed.pop())
    assert time.time() - cache_folders.last_use(folder) < 60
    assert prune_unused(other) == [] and folder.exists()
