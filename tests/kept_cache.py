"""A folder for a test's own compiled module (a toy contact model, a toy terrain) and its
compile cache, kept between runs as numba keeps its own cache.

A test that registers a model or a terrain of its own runs it in a subprocess with its own
``NUMBA_CACHE_DIR``, so that the toy's record types never enter the package's cache index.
In a fresh folder every run, that subprocess compiled every rig loop it drives from nothing,
in every run of the suite (the toy model's driver: 12-13 s; the toy terrain's: 28 s). Here
the folder is named by the digest of the toy module, the driver and the package's kernels
(:func:`tyrelab.core.jit_cache.kernel_digest`), so an edit of any of them starts a new one,
and its cache starts as a copy of this process's (the package's own code then loads instead
of compiling). The driver itself runs every time: only compiled code is kept.

Each edit leaves the previous folder (30-60 MB) behind: the test process claims its folder
while it runs and removes the folders of its prefix that no process holds and none has used
for :data:`KEPT_FOR` (:mod:`tyrelab.core.cache_folders`, as the package's compile cache does).
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from tyrelab.core import cache_folders, jit_cache

#: a toy's folder unused for this long is removed [s]: an edit starts a new one
KEPT_FOR = 86400.0


def kept_home(prefix: str, module_file: str, module_text: str, driver: str) -> Path:
    """The folder ``<tmp>/<prefix>-<digest>`` holding ``module_file`` (its text
    ``module_text``) and the compile cache ``cache/``; made atomically on first use (two
    runs at once: the first one's is kept)."""
    kernels = jit_cache.kernel_digest()
    key = hashlib.sha256((module_text + driver + kernels).encode()).hexdigest()[:16]
    home = Path(tempfile.gettempdir()) / f"{prefix}-{key}"
    if not home.exists():
        build = Path(tempfile.mkdtemp(prefix=f"{prefix}-"))
        (build / module_file).write_text(module_text)
        ours = jit_cache.cache_dir()
        if ours is not None:
            shutil.copytree(ours, build / "cache" / f"tyrelab-{kernels[:16]}")
        try:
            build.rename(home)            # atomic: a concurrent run keeps the first one's
        except OSError:
            shutil.rmtree(build, ignore_errors=True)
    cache_folders.claim(home)
    cache_folders.prune_unused(home, max_age=KEPT_FOR)
    return home


def run_driver(home: Path, driver: str, timeout: float) -> dict:
    """Run ``driver`` (Python that prints a JSON object) with ``home`` first on the path and
    its ``cache/`` as numba's cache; the object it printed."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(home), env.get("PYTHONPATH", "")])
    env["NUMBA_CACHE_DIR"] = str(home / "cache")
    out = subprocess.run([sys.executable, "-c", driver], env=env, capture_output=True, text=True,
                         timeout=timeout)
    assert out.returncode == 0, out.stderr[-3000:]
    return json.loads(out.stdout)
