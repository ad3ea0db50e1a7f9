"""``tyrelab models``: every registered extension -- contact and handling models, rigs, terrains,
road file formats -- with the plugins that added any (:mod:`tyrelab.registry`)."""

from __future__ import annotations


def register(sub):
    p = sub.add_parser("models", help="list the contact and handling models, rigs, terrains and road "
                                      "formats (built in and from plugins)",
                       description="List every registered extension: the names --model, --handling, "
                                   "--rig and a road file's suffix accept, and the installed plugins "
                                   "(entry-point group tyrelab.plugins).")
    p.set_defaults(func=run)


def _section(title: str, rows) -> list[str]:
    rows = list(rows)
    width = max((len(name) for name, _ in rows), default=0)
    return [f"{title}:"] + [f"  {name:<{width}}  {text}".rstrip() for name, text in rows] + [""]


def run(args) -> int:
    from .. import plugins
    from ..rig.registry import rigs
    from ..road.formats import road_formats
    from ..road.terrain_registry import terrain_kind, terrain_names
    from ..tyre.registry import contact_models, handling_models

    def contact_line(m) -> str:
        options = ", ".join(f"{k} ({t.__name__})" for k, t in m.options.items())
        return m.summary + (f"; options: {options}" if options else "")

    lines = _section("contact models (--model)", ((n, contact_line(m)) for n, m in contact_models().items()))
    lines += _section("handling models (--handling)", ((n, m.summary) for n, m in handling_models().items()))
    lines += _section("rigs (--rig)", ((n, r.summary) for n, r in rigs().items()))
    lines += _section("terrains", ((n, terrain_kind(n).description) for n in terrain_names()))
    formats = road_formats().items()
    lines += _section("road file formats (FILE.SUFFIX[@V])",
                      ((s, f.name + (" (read, write)" if f.write else " (read)")) for s, f in formats))
    lines += _section("plugins (entry-point group tyrelab.plugins)",
                      list(plugins.LOADED.items()) or [("none installed", "")])
    print("\n".join(lines).rstrip())
    return 0
