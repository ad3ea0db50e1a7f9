"""Every kind of extension in one place: contact and handling models, rigs, terrains, road formats.

Each kind keeps its records and its ``register_*`` function in its own layer
(:mod:`tyrelab.tyre.registry`, :mod:`tyrelab.rig.registry`,
:mod:`tyrelab.road.terrain_registry`, :mod:`tyrelab.road.formats`); this module is the one
door to all of them. The command line's choices, the study spec's checks, the
cost estimates, the study keys and the documentation's lists are derived from
these functions; no other list of names exists.

>>> import tyrelab.registry as reg
>>> reg.contact_models()[:3]
('point', 'volume', 'enveloping')
>>> "trailer" in reg.rigs() and ".crg" in reg.road_formats()
True

Adding an extension: write its module and call the ``register_*`` function
there -- in the package (ARCHITECTURE.md, "How to add ...") or in an installed
plugin distribution (:mod:`tyrelab.plugins`, entry-point group
``tyrelab.plugins``); either reaches ``tyrelab simulate``, ``tyrelab static``, a
study spec and the study's Dask workers.
"""

from __future__ import annotations

from .plugins import GROUP as PLUGIN_GROUP  # noqa: F401  (documented here)
from .rig.registry import Rig, RigRequest, register_rig, rig_named  # noqa: F401
from .rig.registry import rigs as _rigs
from .road.formats import RoadFormat, register_road_format  # noqa: F401
from .road.formats import road_formats as _road_formats
from .tyre.registry import (ContactModel, HandlingModel, contact_model, handling_model,  # noqa: F401
                            register_contact, register_handling)
from .tyre.registry import contact_models as _contact_models
from .tyre.registry import handling_models as _handling_models


def contact_models() -> tuple[str, ...]:
    """Names of the contact models (``--model``), built-ins first."""
    return tuple(_contact_models())


def handling_models() -> tuple[str, ...]:
    """Names of the handling models (``--handling``), built-ins first."""
    return tuple(_handling_models())


def rigs() -> tuple[str, ...]:
    """Names of the rigs (``--rig``), built-ins first."""
    return tuple(_rigs())


def terrains() -> tuple[str, ...]:
    """Names of the kinds of ground the compiled contact models run on."""
    from .road.terrain_registry import terrain_names
    return tuple(terrain_names())


def __getattr__(name: str):
    # the terrain records load numba: imported when first asked for, not to list rigs or formats
    if name in ("TerrainKind", "register_terrain", "terrain_kind"):
        from .road import terrain_registry
        return getattr(terrain_registry, name)
    raise AttributeError(f"module 'tyrelab.registry' has no attribute {name!r}")


def road_formats() -> tuple[str, ...]:
    """Suffixes of the road file formats (``FILE.crg[@V]`` ...), built-ins first."""
    return tuple(_road_formats())
