"""Roads by name: the strings users type after ``--road``.

Grammar (sizes in millimetres, angles in degrees, as engineers say them)::

    flat
    cleat:WxH[@ANGLE][/BEVEL]   square cleat W wide, H high; ANGLE 0 = perpendicular
    bump:H[xRAMPxTOP]           trapezoidal bump (ramp and top lengths in mm)
    step:H                      step of height H (negative: step down)
    pothole:DEPTHxLENGTH[xWIDTH]
    iso8608:CLASS[@SEED]        ISO 8608 random road, class A-H, 100 m x 4 m
    powerlaw:A,N[@SEED]         random road with S = A phi^-N (thesis eq. 3.8)
    <track name>                a built-in test track (see :func:`road_names`)
    path/to/file.SUFFIX[@V]     a road file, driven at lateral offset V [m]: a
                                format of :mod:`tyrelab.road.formats` -- .crg
                                (OpenCRG), .rdf (Adams road data: 2D road types,
                                3D shell), .obj (triangle mesh), a plugin's

Every obstacle starts at x = 5 m so a run can settle first.
"""

from __future__ import annotations

import functools
import re
from pathlib import Path

from ..errors import InputError
from .base import Road
from .formats import road_file, road_suffixes

#: where each obstacle starts [m]; the wheel starts at x = 0
OBSTACLE_START = 5.0

_NUM = r"[+-]?\d+(?:\.\d*)?(?:[eE][+-]?\d+)?"


def _tracks() -> dict:
    try:
        from .tracks import TRACKS
    except ModuleNotFoundError as exc:
        if exc.name != "tyrelab.road.tracks":
            raise
        return {}
    return TRACKS


@functools.lru_cache(maxsize=None)
def built_track(name: str) -> Road:
    """The built-in track ``name``, built once per process, its grid at its own spacing too.

    The tracks are fixed, seeded roads, and a study runs each of them many times in one
    worker: building the fatigue track took 0.4 s and the Belgian paving 0.2-0.4 s (its grid
    0.15 s more) of every run on them, 75 % of a point-contact run over the 100 m fatigue
    track. Nothing writes into a road's grid (a soil lays its bed from the road's heights,
    as a copy), so every run may share it. Memory: about 32 MB per track held.
    """
    road = _tracks()[name]()
    build_grid, default = road.grid, []

    def grid(spacing=None):
        if spacing is not None:
            return build_grid(spacing)
        if not default:
            default.append(build_grid())
        return default[0]

    road.grid = grid  # the instance's, in front of the class's method
    return road


def road_names() -> list[str]:
    """Names accepted by :func:`road_from_spec` besides the obstacle grammar."""
    return ["flat", "cleat:WxH[@ANGLE]", "bump:H[xRAMPxTOP]", "step:H",
            "pothole:DEPTHxLENGTH[xWIDTH]", "iso8608:CLASS[@SEED]", "powerlaw:A,N[@SEED]",
            *sorted(_tracks()), *(f"FILE{suffix}[@V]" for suffix in road_suffixes())]


def _numbers(text: str, spec: str, count_min: int, count_max: int) -> list[float]:
    parts = text.split("x")
    if not (count_min <= len(parts) <= count_max) or not all(re.fullmatch(_NUM, p) for p in parts):
        raise InputError(f"cannot read sizes '{text}' in road '{spec}'; expected "
                         f"{count_min} to {count_max} numbers in mm separated by 'x'", field="road")
    return [float(p) for p in parts]


#: the road names whose road is synthesised from a spectrum: ``iso8608:CLASS[@SEED]``,
#: ``powerlaw:A,N[@SEED]``
RANDOM_KINDS = ("iso8608", "powerlaw")


def random_road_args(kind: str, args: str, text: str) -> tuple:
    """``(spectrum, seed)`` of the random road named ``text`` (``kind:args``, a kind of
    :data:`RANDOM_KINDS`): the ISO 8608 class letter or the power law's ``(A, N)``, and the
    seed (default 0), read without building the road; an :class:`InputError` on ``road``."""
    body, _, seed_txt = args.partition("@")
    if seed_txt and not seed_txt.isdigit():
        raise InputError(f"cannot read seed '{seed_txt}' in road '{text}'; expected a whole "
                         "number >= 0", field="road")
    seed = int(seed_txt) if seed_txt else 0
    if kind == "iso8608":
        if body.upper() not in tuple("ABCDEFGH"):
            raise InputError(f"unknown ISO 8608 class '{body}' in road '{text}'; expected A to H",
                             field="road")
        return body.upper(), seed
    parts = body.split(",")
    if len(parts) != 2 or not all(re.fullmatch(_NUM, p) for p in parts) or float(parts[0]) <= 0:
        raise InputError(f"cannot read '{body}' in road '{text}'; expected A,N with A > 0 "
                         "(A in m^2/(cycles/m), N the road exponent)", field="road")
    return (float(parts[0]), float(parts[1])), seed


def road_from_spec(spec: str | Road, force: bool = False) -> Road:
    """A :class:`Road` from its name (see the module docstring).

    ``force`` lifts the memory limit (:data:`tyrelab.resources.MAX_MEMORY`) of the
    roads built from data, a random road's or an OpenCRG file's grid.
    """
    if isinstance(spec, Road):
        return spec
    from . import obstacles as ob

    text = str(spec).strip()
    kind, _, args = text.partition(":")
    kind = kind.lower()
    if text.lower() == "flat":
        return ob.Flat()
    with ob.sizes_quoted_in_mm():  # the grammar's sizes are in mm: so are its messages
        if kind == "cleat" and args:
            bevel = 0.0
            if "/" in args:
                args, bevel_txt = args.split("/", 1)
                bevel = _numbers(bevel_txt, text, 1, 1)[0]
            angle = 0.0
            if "@" in args:
                args, angle_txt = args.split("@", 1)
                if not re.fullmatch(_NUM, angle_txt):
                    raise InputError(f"cannot read angle '{angle_txt}' in road '{text}'; expected degrees",
                                     field="road")
                angle = float(angle_txt)
            w, h = _numbers(args, text, 2, 2)
            return ob.Cleat(width=w / 1e3, height=h / 1e3, angle=angle, bevel=bevel / 1e3,
                            start=OBSTACLE_START)
        if kind == "bump" and args:
            vals = _numbers(args, text, 1, 3)
            h = vals[0] / 1e3
            ramp = vals[1] / 1e3 if len(vals) > 1 else None
            top = vals[2] / 1e3 if len(vals) > 2 else None
            return ob.TrapezoidalBump(height=h, ramp_length=ramp, top_length=top, start=OBSTACLE_START)
        if kind == "step" and args:
            (h,) = _numbers(args, text, 1, 1)
            return ob.Step(height=h / 1e3, start=OBSTACLE_START)
        if kind == "pothole" and args:
            vals = _numbers(args, text, 2, 3)
            width = vals[2] / 1e3 if len(vals) > 2 else None
            return ob.Pothole(depth=vals[0] / 1e3, length=vals[1] / 1e3, width=width, start=OBSTACLE_START)
    if kind in RANDOM_KINDS and args:
        from .iso8608 import RandomRoad
        spectrum, seed = random_road_args(kind, args, text)
        return RandomRoad(spectrum, seed=seed, start=OBSTACLE_START, taper=2.0, force=force)
    if text.lower() in _tracks():
        return built_track(text.lower())
    named = road_file(text)
    if named is not None:
        fmt, path_text, offset = named
        path = Path(path_text)
        if not path.is_file():
            raise InputError(f"no such {fmt.name} file", source=str(path))
        v = 0.0
        if offset:
            if not re.fullmatch(_NUM, offset):
                raise InputError(f"cannot read lateral offset '{offset}' in road '{text}'; expected metres",
                                 field="road")
            v = float(offset)
        return fmt.read(path, v, force)
    raise InputError(f"unknown road '{text}'; expected one of: {', '.join(road_names())}",
                     field="road")
