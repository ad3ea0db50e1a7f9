"""Keep numba's on-disk cache of the whole package consistent with its sources.

numba's ``cache=True`` checks only the file that defines a function, but the
rig loops inline the contact, vertical and handling kernels from other
modules; after an edit (or an update) of any of those, a rig's cached
machine code would be stale. A digest of all the package's sources is kept
beside the caches; when it changes, every cache file of the package is
removed before anything is compiled. Called once, from ``tyrelab/__init__``.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

_PACKAGE = Path(__file__).resolve().parents[1]
_STAMP = _PACKAGE / "__pycache__" / "tyrelab_sources.sha1"


def sources_digest() -> str:
    """SHA-1 over the package's Python sources (paths and contents)."""
    h = hashlib.sha1()
    for path in sorted(_PACKAGE.rglob("*.py")):
        h.update(str(path.relative_to(_PACKAGE)).encode())
        h.update(path.read_bytes())
    return h.hexdigest()


def refresh() -> None:
    """Remove every ``*.nbi``/``*.nbc`` of the package if any source changed."""
    try:
        digest = sources_digest()
        if _STAMP.is_file() and _STAMP.read_text().strip() == digest:
            return
        for pattern in ("*.nbi", "*.nbc"):
            for path in _PACKAGE.rglob(pattern):
                path.unlink(missing_ok=True)
        _STAMP.parent.mkdir(exist_ok=True)
        _STAMP.write_text(digest + "\n")
    except OSError:
        pass  # read-only install: numba then caches elsewhere or compiles in memory
