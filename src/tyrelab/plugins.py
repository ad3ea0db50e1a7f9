"""Plugins: installed distributions that add models, rigs, terrains or road formats.

A distribution declares an entry point in the group ``tyrelab.plugins``, e.g. in
its ``pyproject.toml``::

    [project.entry-points."tyrelab.plugins"]
    my_models = "my_package.tyrelab_plugin:register"

The entry point names a callable (called once, without arguments) or a module
(imported); either registers its extensions with the registries' ``register_*``
functions (:mod:`tyrelab.registry` lists them). Every registry loads the plugins
the first time it is asked for its names, in every process -- so a plugin's model
reaches ``tyrelab simulate``, a study spec and the study's Dask workers alike,
as long as the distribution is installed where they run.

A plugin that fails to load is reported once as a :class:`PluginWarning` naming
the entry point and its error, and left out; the built-in extensions and the other
plugins still work.
"""

from __future__ import annotations

import warnings
from importlib import metadata

#: the entry-point group tyrelab reads
GROUP = "tyrelab.plugins"


class PluginWarning(UserWarning):
    """A plugin could not be loaded (it is left out)."""


_state = {"loaded": False, "loading": False}
#: the entry points loaded so far, ``name -> "distribution value"``
LOADED: dict[str, str] = {}


def load() -> None:
    """Load every installed plugin, once per process (later calls return at once; a call made
    while plugins load -- a plugin asking a registry for names -- returns too)."""
    if _state["loaded"] or _state["loading"]:
        return
    _state["loading"] = True
    try:
        for ep in sorted(metadata.entry_points(group=GROUP), key=lambda e: (e.name, e.value)):
            where = f"{ep.dist.name if ep.dist else '?'}: {ep.value}"
            try:
                target = ep.load()
                if callable(target):
                    target()
            except Exception as exc:  # a broken plugin must not stop tyrelab
                text = " ".join(str(exc).split()) or type(exc).__name__
                warnings.warn(f"tyrelab plugin '{ep.name}' ({where}) not loaded: "
                              f"{type(exc).__name__}: {text}", PluginWarning, stacklevel=2)
            else:
                LOADED[ep.name] = where
    finally:
        _state["loading"] = False
        _state["loaded"] = True
