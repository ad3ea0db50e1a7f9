"""Road file formats: one record per format, the only list of road-file suffixes.

A road file is named ``path/to/FILE.SUFFIX[@V]`` wherever a road is asked for
(``--road``, a study spec's ``road``), ``V`` the lateral offset [m] it is driven
at. Each format registers a :class:`RoadFormat` -- its suffix, its reader, its
writer if it has one (``tyrelab road export``) and what of the file enters a
study's run keys -- and everything that must know the formats derives from
:func:`road_formats`: the road grammar (:mod:`tyrelab.road.spec`), the study
spec's check, the run keys (:mod:`tyrelab.study.keys`: a format's
:attr:`RoadFormat.identity`, so a changed file is computed again, never
reused), the command line's lists and the outputs kept off input files.

The built-in formats are registered below with readers and writers that import
their module only when used (pycrg, trimesh and the Adams parser are not
loaded to list the suffixes). A plugin (:mod:`tyrelab.plugins`) registers its
own with :func:`register_road_format`.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any, Callable

from .. import plugins
from ..errors import InputError


def file_sha256(path: Path) -> str:
    """SHA-256 (hex) of a file's bytes, cached while its size and modification time stay."""
    st = path.stat()
    return _sha256_of(str(path), st.st_mtime_ns, st.st_size)


@lru_cache(maxsize=64)
def _sha256_of(path: str, mtime_ns: int, size: int) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def file_identity(fmt: "RoadFormat", path: Path, offset: str) -> dict:
    """What of a road file enters a run key: its content digest, its format and the offset."""
    return {"road_file_sha256": file_sha256(path), "kind": fmt.suffix, "offset": offset or "0"}


@dataclass(frozen=True)
class RoadFormat:
    """A road file format.

    Attributes
    ----------
    suffix : str
        The file name's suffix, lower case with its dot (``".crg"``).
    name : str
        What the format is called (``"OpenCRG"``), in messages and lists.
    read : callable
        ``read(path, offset, force) -> Road``: the road in the file, driven at
        lateral offset ``offset`` [m]; ``force`` lifts the memory limit of a
        road built from data (:data:`tyrelab.resources.MAX_MEMORY`). A malformed
        file raises :class:`~tyrelab.errors.InputError` naming the file.
    write : callable, optional
        ``write(road, path, spacing=None, force=False, **options) -> (path, what)``:
        any road written in this format, ``what`` a few words for the message;
        ``spacing`` (dx, dy) [m] of a sampled grid, None for the format's default.
    write_options : tuple of str
        The ``tyrelab road export`` options the writer takes besides ``spacing``
        and ``force`` (``"format"``, ``"method"``, ``"mu"``).
    identity : callable
        ``identity(format, path, offset) -> dict``: what of the file a study's run
        key holds (default: the file's SHA-256, the suffix and the offset).
    summary : str
        One line for listings.
    """

    suffix: str
    name: str
    read: Callable[..., Any]
    write: Callable[..., Any] | None = None
    write_options: tuple = ()
    identity: Callable[..., dict] = file_identity
    summary: str = ""

    def __post_init__(self):
        if not (self.suffix.startswith(".") and self.suffix == self.suffix.lower() and len(self.suffix) > 1):
            raise ValueError(f"a road format's suffix is lower case with its dot, got {self.suffix!r}")


_FORMATS: dict[str, RoadFormat] = {}


def register_road_format(fmt: RoadFormat) -> RoadFormat:
    """Make ``fmt`` known by its suffix (a later registration of a suffix replaces it)."""
    _FORMATS[fmt.suffix] = fmt
    return fmt


def road_formats() -> dict[str, RoadFormat]:
    """Every road file format by suffix: the built-in ones, then the plugins' in their order."""
    plugins.load()
    return dict(_FORMATS)


def road_suffixes() -> tuple[str, ...]:
    """The suffixes of every road file format (``(".crg", ".rdf", ".obj", ...)``)."""
    return tuple(road_formats())


def road_format(path) -> RoadFormat | None:
    """The format of a road file named ``path`` (its suffix, any case), or None."""
    return road_formats().get(Path(str(path)).suffix.lower())


def road_file(text: str) -> tuple[RoadFormat, str, str] | None:
    """``(format, path, offset text)`` when ``text`` names a road file (``FILE.SUFFIX[@V]``),
    else None. The offset is left as text: readers and checks parse it."""
    path_text, _, offset = str(text).strip().partition("@")
    fmt = road_format(path_text)
    return None if fmt is None else (fmt, path_text, offset)


def writable_suffixes() -> tuple[str, ...]:
    """The suffixes ``tyrelab road export`` can write."""
    return tuple(s for s, f in road_formats().items() if f.write is not None)


def format_named(suffix: str) -> RoadFormat:
    """The format of ``suffix``; an unknown one names the known ones."""
    fmt = road_formats().get(suffix.lower())
    if fmt is None:
        raise InputError(f"unknown road file format '{suffix}', expected one of "
                         f"{', '.join(road_formats())}", field="road")
    return fmt


# --- the built-in formats (modules imported when a file is read or written) ------------------

def _read_crg(path, offset, force):
    from .crg import CrgRoad
    return CrgRoad(path, v_offset=offset, force=force)


def _write_crg(road, path, spacing=None, force=False, format="KDBI"):
    from .crg import write_crg
    return write_crg(road, path, spacing=spacing, fmt=format, force=force), f"OpenCRG {format}"


def _crg_identity(fmt, path, offset):
    # the keys of OpenCRG runs have always used these names: stored results stay valid
    return {"crg_sha256": file_sha256(path), "offset": offset or "0"}


def _read_rdf(path, offset, force):
    from .rdf import read_rdf
    return read_rdf(path, y_offset=offset)


def _write_rdf(road, path, spacing=None, force=False, method=None, mu=1.0):
    from .rdf_write import write_rdf
    method = method or ("3D" if road.varies_in_y() else "2D")
    return write_rdf(road, path, method=method, spacing=spacing, mu=mu), f"an Adams road data file ({method})"


def _read_obj(path, offset, force):
    from .mesh_files import read_obj
    return read_obj(path, y_offset=offset)


def _write_obj(road, path, spacing=None, force=False):
    from .mesh_files import write_obj
    return write_obj(road, path, spacing=spacing), "a triangle mesh"


register_road_format(RoadFormat(".crg", "OpenCRG", _read_crg, _write_crg, ("format",), _crg_identity,
                                "OpenCRG road (ASAM), a curved regular grid"))
register_road_format(RoadFormat(".rdf", "Adams road data", _read_rdf, _write_rdf, ("method", "mu"),
                                summary="Adams road data file: 2D road types or a 3D shell"))
register_road_format(RoadFormat(".obj", "OBJ mesh", _read_obj, _write_obj,
                                summary="triangle mesh (Wavefront OBJ, metres, z up)"))
