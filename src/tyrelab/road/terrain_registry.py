"""The registry of kinds of ground, and the Python side of the terrain interface.

Split from :mod:`tyrelab.road.terrain` (the compiled interface, which re-exports
everything here: import from there). A kind of ground registers itself in its
own module (:func:`register_terrain`, the rigid grid at the bottom of
:mod:`tyrelab.road.grid`); this module imports the built-in ones on first use,
then the plugins (:mod:`tyrelab.plugins`). The compiled side finds a kind's
functions from the type of its record (:func:`terrain_by_record`), at compile
time, as :mod:`tyrelab.tyre.registry` finds a tyre model's.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import Any, Protocol

import numba as nb
import numpy as np

from .. import plugins
from ..errors import InputError, named


#: modules that register the built-in kinds of ground
BUILTIN_TERRAIN = ("tyrelab.road.grid", "tyrelab.road.soil.terrain")


@nb.njit(cache=True, inline="always")
def unit_friction(terrain, x, y):
    """The friction scale of a ground that does not change the tyre's friction."""
    return 1.0


@nb.njit(cache=True, inline="always")
def rigid_contact(terrain, x, y, penetration, area, v1, v2, fn, f1, f2, dt):
    """A rigid ground carries whatever the tyre's own law gives and keeps no state."""
    return fn, f1, f2


@nb.njit(cache=True, inline="always")
def element_shear(terrain, x, y, fn, area, m1, m2, d1, d2, element_stiffness, limit):
    """A ground without a shear law of its own: the element's own law stands (``False``)."""
    return False, 0.0, 0.0, m1, m2


@dataclass(frozen=True)
class TerrainKind:
    """A kind of ground as the compiled contact models see it.

    Attributes
    ----------
    name : str
        The name (``"rigid"`` for the bilinear grid).
    record : type
        Its compiled record (a NamedTuple class); the functions are chosen by
        this type at compile time.
    height, height_gradient, penetration, zmax, range, lines, row, line_height,
    blocks, block_max : numba dispatchers
        The implementations of :func:`~tyrelab.road.terrain.terrain_height`,
        ... (same arguments, the record first; see each interface function
        of :mod:`tyrelab.road.terrain` for the meaning).
    friction : numba dispatcher
        ``terrain_friction`` (default: :func:`unit_friction`).
    contact : numba dispatcher
        ``terrain_contact`` (default: :func:`rigid_contact`; a kind that is
        not rigid must give its own).
    shear : numba dispatcher
        ``terrain_shear`` (default: :func:`element_shear`, the tyre element's own
        tangential law stands): a deformable ground whose shear has a law of its own
        (the soil) gives the element's tangential force with it.
    rigid : bool
        ``terrain_is_rigid``: the ground never moves.
    description : str
        One line for listings (``tyrelab models``).
    resolve : callable, optional
        For a kind a user names with ``--terrain`` (``simulate(terrain=...)``):
        ``resolve(value) -> (description, label)`` when ``value`` names ground of this
        kind (``label`` for the run's metadata), None when it does not; an
        :class:`~tyrelab.errors.InputError` when it does but is malformed.
    lay : callable, optional
        ``lay(description, road, x0, x1, level_at, **options) -> ground``: the Python
        ground (:class:`Ground`; a deformable one also ``fresh_copy()``, its state copied;
        one too long to hold at once also ``follow(x_behind, x_ahead)``, the record moved
        to cover that stretch or None, which the rigs call before each chunk of a run)
        over ``road`` from ``x0`` to ``x1`` [m] along y = 0, heights less the road's at
        ``(level_at, 0)`` when given; ``options`` a rig's (the soil bed's spacing, width).
    lay_around : callable, optional
        ``lay_around(description, road, x, y, level_at, **options) -> ground``: the ground
        for a wheel a host drives anywhere (co-simulation), laid around ``(x, y)`` [m]; one
        that holds a part of itself at a time also has ``cover(x_lo, x_hi, y_lo, y_hi,
        toward, behind, wheel)``, its record moved to hold that box (and those of the other
        wheels on it) or None (the soil: :class:`~tyrelab.road.soil.field.SoilField`).
        Without it, ``lay`` over a stretch along x is used.
    hint : str
        What ``--terrain`` takes for this kind, for the message listing them.
    """

    name: str
    record: type
    height: Any
    height_gradient: Any
    penetration: Any
    zmax: Any
    range: Any
    lines: Any
    row: Any
    line_height: Any
    blocks: Any
    block_max: Any
    friction: Any = unit_friction
    contact: Any = rigid_contact
    shear: Any = element_shear
    rigid: bool = True
    description: str = ""
    resolve: Any = None
    lay: Any = None
    lay_around: Any = None
    hint: str = ""

    def __post_init__(self):
        if not self.rigid and self.contact is rigid_contact:
            raise ValueError(f"terrain {self.name!r} deforms: it needs its own contact function")


class Ground(Protocol):
    """What a model's ``build(tyre, ground, **options)`` may ask of the Python ground object.

    The precomputed bounds and breaks that models keep in their parameter
    records come from here, never from the ground's data (the grid's
    :class:`~tyrelab.road.grid.RoadGrid` implements it).
    """

    def surface(self):
        """The compiled terrain record (built once)."""

    def sampling_step(self) -> float:
        """The finest spacing of the ground's data [m]: sampling a section at it misses
        no feature."""

    def uniform_across(self) -> bool:
        """True when every line of constant y sees the same ground, for the whole run."""

    def profile_breaks(self):
        """For a ground uniform across: per break line k, the next break line where the
        slope along x changes (int64 array); None otherwise (:func:`profile_breaks`)."""

    def row_maxima(self, length: float):
        """``(per, maxima)``: bounds of the ground over blocks of ``per`` break lines
        (about ``length`` [m]) for each row handle, ``maxima[b, row]`` bounding the
        ground between lines ``b per`` and ``(b + 1) per`` on any line of that row;
        valid for the whole run; shape ``(0, rows)`` when there is nothing to bound."""


_TERRAIN: dict[str, TerrainKind] = {}
_loaded = False


def register_terrain(kind: TerrainKind) -> TerrainKind:
    """Make ``kind`` known by its name (a later registration of a name replaces it)."""
    _TERRAIN[kind.name] = kind
    return kind


def _load_builtins() -> None:
    """Import the built-in kinds' modules, then the plugins (:mod:`tyrelab.plugins`)."""
    global _loaded
    if not _loaded:
        _loaded = True
        for module in BUILTIN_TERRAIN:
            importlib.import_module(module)
    plugins.load()


def terrain_kinds() -> dict[str, TerrainKind]:
    """Every registered kind of ground by name, built-ins first."""
    _load_builtins()
    return dict(_TERRAIN)


def terrain_names() -> tuple[str, ...]:
    """Names of the registered kinds of ground, built-ins first."""
    return tuple(terrain_kinds())


def terrain_kind(name: str) -> TerrainKind:
    """The kind of ground called ``name``; an unknown name lists the known ones."""
    return named(terrain_kinds(), name, "terrain", "terrain")


def resolve_terrain(value) -> tuple[TerrainKind, Any, str]:
    """``(kind, description, label)`` of the ground ``value`` names (``--terrain``): the first
    registered kind whose ``resolve`` claims it; none is an InputError listing what each
    kind takes."""
    kinds = [k for k in terrain_kinds().values() if k.resolve is not None]
    for kind in kinds:
        found = kind.resolve(value)
        if found is not None:
            return (kind, *found)
    takes = "; ".join(f"{k.name}: {k.hint}" for k in kinds)
    raise InputError(f"unknown terrain {value!r}, expected {takes}", field="terrain")


def terrain_by_record(numba_type) -> TerrainKind:
    """The kind whose record has numba type ``numba_type`` (compile time)."""
    _load_builtins()
    cls = getattr(numba_type, "instance_class", None)
    for kind in _TERRAIN.values():
        if kind.record is cls:
            return kind
    raise TypeError(f"{numba_type} is not the record of a registered terrain "
                    f"(tyrelab.road.terrain.register_terrain)")


# --- helpers for terrains on a lattice (the grid; a soil on its nodes) ------------------

def profile_breaks(z: np.ndarray) -> np.ndarray | None:
    """For heights ``z[k, row]`` at break line k that are the same on every row: for every
    line ``k``, the next line ``k' > k`` where the profile's slope changes (or the last
    line). Between ``k`` and ``k'`` the ground is one straight line. None when the rows
    differ.

    Returns
    -------
    ndarray of int64, shape (count,) or None
        The next kink's line index for every line.
    """
    if not np.all(z == z[:, :1]):
        return None
    h = z[:, 0]
    nx = h.size
    slope = np.diff(h)
    kink = np.zeros(nx, bool)
    kink[-1] = True
    if nx > 2:
        kink[1:-1] = np.abs(np.diff(slope)) > 1e-12
    kinks = np.flatnonzero(kink)
    nxt = kinks[np.searchsorted(kinks, np.arange(nx), side="right").clip(max=kinks.size - 1)]
    return nxt.astype(np.int64)


def block_maxima(z: np.ndarray, per: int) -> np.ndarray:
    """Maxima of heights ``z[k, j]`` at the lattice nodes over blocks of ``per`` lines, for
    each pair of node rows.

    Block b spans lines ``b per .. (b+1) per`` (both ends: a cell between two lines
    lies in one block) and rows j, j+1, so it bounds a bilinear ground on any line
    between those rows. Shape ``(n_blocks, rows - 1)``.
    """
    nx = z.shape[0]
    pair = np.maximum(z[:, :-1], z[:, 1:])
    n_blocks = -(-(nx - 1) // per)
    ends = np.minimum(np.arange(1, n_blocks + 1) * per, nx - 1)
    out = np.maximum.reduceat(pair, np.arange(n_blocks) * per, axis=0)
    return np.ascontiguousarray(np.maximum(out, pair[ends]), np.float64)
