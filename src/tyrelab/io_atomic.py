"""Every file tyrelab writes goes through here: whole or not at all, checked first.

Writing
-------
:func:`atomic_output` (a context manager) and :func:`atomic_write` give a
writer a temporary sibling of the target, ``.tyrelab-<tag>-<pid>-<random>.part``
in the target's folder, and rename it over the target only when the writer
returned normally. An exception -- also ``KeyboardInterrupt`` and the
``SIGTERM`` the command line turns into one -- removes the temporary file,
so a reader never sees a partial file under the final name and a previous
file of that name stays intact. A process killed outright (``SIGKILL``, a
power cut) cannot clean up: its temporary file stays, and the next write of
the same target removes it (``<tag>`` is a digest of the target's name,
``<pid>`` the writer's process, which must no longer be running).

The final file gets the ordinary permissions of a new file (``0o666`` less
the umask), not the private ones of :func:`tempfile.mkstemp`.

Checking
--------
:func:`check_output_path` is what every command calls on its output path
right after parsing its arguments, before any work: the folder exists and is
writable, the name is not a folder, the suffix is one the writer knows, and
the file is not one of the command's inputs. :func:`check_output_folder` does
the same for a results folder (``tyrelab study``).
"""

from __future__ import annotations

import hashlib
import os
import secrets
import time
from contextlib import contextmanager
from pathlib import Path

from .errors import InputError

#: image formats every plotting command writes (matplotlib's own writers)
IMAGE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg")
#: signal tables
SIGNAL_SUFFIXES = (".parquet", ".csv")
#: a temporary file of a process that is still running is left alone unless older than this [s]
STALE_AFTER = 24 * 3600.0

_PREFIX = ".tyrelab-"
_SUFFIX = ".part"


def _tag(path: Path) -> str:
    """Short digest of the target's file name: marks its temporary files."""
    return hashlib.sha1(path.name.encode("utf-8", "surrogateescape")).hexdigest()[:12]


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError):
        return True  # exists, owned by someone else
    return True


def stale_temporaries(path) -> list[Path]:
    """Temporary files of earlier writes of ``path`` whose writer is gone (killed)."""
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    out = []
    try:
        candidates = list(folder.glob(f"{_PREFIX}{_tag(path)}-*{_SUFFIX}"))
    except OSError:
        return out
    now = time.time()
    for p in candidates:
        parts = p.name[len(_PREFIX):-len(_SUFFIX)].split("-")
        try:
            pid = int(parts[1])
        except (IndexError, ValueError):
            continue
        try:
            old = now - p.stat().st_mtime > STALE_AFTER
        except OSError:
            continue
        if old or not _alive(pid):
            out.append(p)
    return out


def remove_stale(path) -> int:
    """Remove the temporary files killed writers of ``path`` left; returns how many."""
    n = 0
    for p in stale_temporaries(path):
        try:
            p.unlink()
            n += 1
        except FileNotFoundError:
            pass
        except OSError:
            pass
    return n


def _writable_target(path: Path, field: str | None) -> None:
    """The checks a writer can make itself: the folder exists, the name is not a folder."""
    folder = path.parent if str(path.parent) else Path(".")
    if path.is_dir():
        raise InputError(f"'{path}' is a folder; give a file name", field=field)
    if not folder.is_dir():
        raise InputError(f"the folder '{folder}' of '{path}' does not exist; create it first",
                         field=field)
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(f"the folder '{folder}' of '{path}' is not writable", field=field)


def _new_temporary(path: Path) -> Path:
    folder = path.parent if str(path.parent) else Path(".")
    for _ in range(100):
        tmp = folder / f"{_PREFIX}{_tag(path)}-{os.getpid()}-{secrets.token_hex(4)}{_SUFFIX}"
        try:
            fd = os.open(tmp, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o666)
        except FileExistsError:
            continue
        except OSError as exc:
            raise InputError(f"cannot write in the folder '{folder}' ({exc.strerror})",
                             source=str(path)) from None
        os.close(fd)
        return tmp
    raise InputError("cannot create a temporary file", source=str(path))  # pragma: no cover


@contextmanager
def atomic_output(path, field: str | None = None):
    """Write ``path`` whole or not at all.

    Yields the name of a temporary sibling (a ``str``) to write to; it is
    renamed over ``path`` when the block ends normally and removed when it
    raises (any exception, also ``KeyboardInterrupt``). Stale temporary files
    of ``path`` left by killed writers are removed first. A missing folder or
    a ``path`` that is a folder is an :class:`InputError` before anything is
    written.
    """
    path = Path(path)
    _writable_target(path, field)
    remove_stale(path)
    tmp = _new_temporary(path)
    try:
        yield str(tmp)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.remove(tmp)
        except FileNotFoundError:
            pass
        raise


def atomic_write(path, writer, field: str | None = None):
    """Call ``writer(temporary_path)`` and rename the result over ``path``; returns ``path``.

    ``writer`` writes the complete file at the name it is given (a ``str``).
    """
    path = Path(path)
    with atomic_output(path, field) as tmp:
        writer(tmp)
    return path


def atomic_write_text(path, text: str, encoding: str = "utf-8", newline: str | None = None) -> Path:
    """Write ``text`` to ``path`` atomically."""
    def write(tmp):
        with open(tmp, "w", encoding=encoding, newline=newline) as fh:
            fh.write(text)
    return atomic_write(path, write)


def save_figure(fig, path, dpi: int = 120, close: bool = True, **kwargs) -> Path:
    """``fig.savefig`` to ``path`` atomically, in the format its suffix names.

    The suffix must be one of :data:`IMAGE_SUFFIXES`; the figure is closed
    afterwards (``close=False`` keeps it).
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in IMAGE_SUFFIXES:
        raise InputError(f"image file '{path}' must end in {_or(IMAGE_SUFFIXES)}", field="output")
    fmt = "jpeg" if suffix == ".jpg" else suffix.lstrip(".")
    try:
        atomic_write(path, lambda tmp: fig.savefig(tmp, dpi=dpi, format=fmt, **kwargs))
    finally:
        if close:
            import matplotlib.pyplot as plt
            plt.close(fig)
    return path


def _or(items) -> str:
    items = list(items)
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " or " + items[-1]


def _same_file(a: Path, b: Path) -> bool:
    try:
        if a.exists() and b.exists():
            return os.path.samefile(a, b)
    except OSError:
        pass
    return os.path.abspath(a) == os.path.abspath(b)


def check_output_path(path, allowed_suffixes, field: str = "-o", inputs=()) -> Path:
    """Check an output file name before any work is done; returns it as a Path.

    Refused, each with one :class:`InputError` line naming ``field``, the
    value and what is allowed: an empty name, a suffix not in
    ``allowed_suffixes`` (compared in lower case), a name that is a folder, a
    folder that does not exist or is not writable, and a file that is one of
    ``inputs`` (the command would overwrite what it reads).
    """
    text = "" if path is None else str(path)
    if not text.strip():
        raise InputError("an output file name is needed, got an empty string", field=field)
    p = Path(text)
    allowed = tuple(s.lower() for s in allowed_suffixes)
    if p.suffix.lower() not in allowed:
        raise InputError(f"output file '{text}' must end in {_or(allowed)}", field=field)
    _writable_target(p, field)
    for other in inputs:
        if other is None:
            continue
        if _same_file(p, Path(str(other))):
            raise InputError(f"output file '{text}' is also an input of this command; "
                             "choose another name", field=field)
    return p


def check_output_folder(path, field: str = "-o") -> Path:
    """Check a results folder before any work: not a file, and creatable/writable.

    The folder itself may not exist yet; its nearest existing ancestor must be
    a writable folder.
    """
    text = "" if path is None else str(path)
    if not text.strip():
        raise InputError("a results folder is needed, got an empty string", field=field)
    p = Path(text).expanduser()
    if p.exists() and not p.is_dir():
        raise InputError(f"'{text}' is a file, not a folder", field=field)
    probe = p
    while not probe.exists():
        parent = probe.parent
        if parent == probe:
            break
        probe = parent
    if not probe.is_dir():
        raise InputError(f"cannot create the folder '{text}': '{probe}' is a file", field=field)
    if not os.access(probe, os.W_OK | os.X_OK):
        raise InputError(f"cannot write in '{probe}' (no permission) for the folder '{text}'",
                         field=field)
    return p
