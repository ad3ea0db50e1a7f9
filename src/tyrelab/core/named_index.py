"""Positions in flat arrays by name: one tuple of names decides every position.

The rigs' output rows, their state arrays and the tyre kernels' result rows are
flat float arrays (numba writes them fast and the signal table is made from
them). Which slot holds what is decided once, by a tuple of names such as
``WHEEL_CHANNELS``; :func:`named_index` turns that tuple into a NamedTuple of
the names' positions, which the code indexes with (``o[WC.FX] = ...``).
Adding a name to the tuple is then the only place a position is decided: no
number has to be matched to a name by hand.

Compiled code reads such a record as a module-level constant: numba freezes it
(and the positions are plain integers, so the machine code is that of a
literal index). Because numba freezes it, the module defining the record is
part of the compile cache's digest (:mod:`tyrelab.core.jit_cache` follows the
kernels' imports), so a changed layout recompiles.
"""

from __future__ import annotations

from collections import namedtuple


def named_index(typename: str, names) -> tuple:
    """A NamedTuple whose field ``name`` holds the position of ``name`` in ``names``.

    >>> ix = named_index("Pose", ("CX", "CY", "CZ"))
    >>> ix.CY, len(ix), ix._fields
    (1, 3, ('CX', 'CY', 'CZ'))

    Names must be distinct Python identifiers not starting with an underscore
    (``ValueError`` otherwise).
    """
    names = tuple(names)
    if len(set(names)) != len(names):
        raise ValueError(f"{typename}: repeated name in {names}")
    bad = [n for n in names if not (isinstance(n, str) and n.isidentifier() and not n.startswith("_"))]
    if bad:
        raise ValueError(f"{typename}: not usable as a field name: {bad}")
    base = namedtuple(typename, names)

    class Index(base):
        __slots__ = ()

        def __reduce__(self):  # the class is made here, not importable: rebuild it
            return named_index, (typename, self._fields)

    Index.__name__ = Index.__qualname__ = typename
    return Index(*range(len(names)))
