"""What travels inside tyrelab's FMU: the tyre's data, the road file, and the manifest naming them.

:func:`write_data` fills a folder (the FMU's ``resources/tyrelab_data/``) at
export; :func:`read_manifest` and :func:`build_stepper` turn it back into a
:class:`~.stepper.WheelStepper` when the FMU is initialised. The folder holds

* ``manifest.json`` -- the tyrelab version that exported it, the tyre (its
  file in the folder, the built-in name it came from, the pressure it
  describes, the stiffness mode), the contact and handling models and their
  options, the road (a name, or its file in the folder and the lateral offset),
  the terrain laid over it when there is one (a soil's name, or its file in the
  folder), and the defaults of the FMU's parameters;
* ``tyre/`` -- the tyre: a ``.tir`` or Chrono ``.json`` file as the user gave it,
  or a built-in tyre (or an MF-Tyre 6.x file moved to another pressure) written at the
  export's pressure (with the ring's
  ``[FLEXIBLE_RING]`` section when the ring needs it and the tyre's own file
  has none);
* ``road/`` -- the road file, when the road is one;
* ``terrain/`` -- the soil file, when the terrain is one.

Names, not code: the models themselves are the installed tyrelab's.
"""

from __future__ import annotations

import copy
import json
import math
import shutil
import weakref
from pathlib import Path

from .._version import __version__
from ..errors import InputError
from ..road.formats import road_file
from ..tyre.model import TyreModel
from .stepper import WheelStepper, wheel_stepper

#: the folder inside the FMU's resources, and its manifest's name and format versions: 2 has
#: a terrain (written only then, so that an FMU without one still opens in a tyrelab that
#: reads format 1 only)
DATA = "tyrelab_data"
MANIFEST = "manifest.json"
FORMAT = 1
FORMAT_TERRAIN = 2
#: option values a manifest can carry (JSON scalars)
SCALARS = (bool, int, float, str)


def _tyre_record(folder: Path, tm: TyreModel, tyre) -> dict:
    """Write the tyre into ``folder/tyre``; its manifest entry."""
    from ..tyre.library import BUILT_IN, SINGLE_FILE
    from ..tyre.params import Tyre

    names = {k.lower(): k for k in (*BUILT_IN, *SINGLE_FILE)}
    builtin = names.get(str(tyre).lower()) if isinstance(tyre, (str, Path)) else None
    (folder / "tyre").mkdir()
    t = tm.tyre
    user_file = builtin is None and not isinstance(tyre, Tyre)
    if user_file and _at_its_own_pressure(Path(tyre), t):  # the user's file, as it is
        source = Path(tyre)
        name = source.name
        shutil.copyfile(source, folder / "tyre" / name)
    else:  # a built-in tyre, a Tyre object, or an MF 6.x file moved to another pressure
        # (:func:`~tyrelab.tyre.pressure.at_pressure`), at its pressure, as a property file
        out = copy.deepcopy(t)
        if tm.contact_model.has_state and not out.tir.has("FLEXIBLE_RING"):
            _add_ring_section(out)
        name = f"{_file_stem(out.name)}.tir"
        out.write(folder / "tyre" / name)
    pressure = float(t.pressure)
    return {"file": f"tyre/{name}", "builtin": builtin,
            "pressure": pressure if math.isfinite(pressure) else None,
            "stiffness": t.stiffness, "unloaded_radius": float(t.unloaded_radius)}


def _at_its_own_pressure(path: Path, tyre) -> bool:
    """Whether ``tyre``, loaded from the user's ``path``, is at the pressure that file states."""
    from ..tyre.library import load_tyre

    own = load_tyre(path).pressure
    return not (math.isfinite(own) and math.isfinite(tyre.pressure)) or math.isclose(own, tyre.pressure)


def _add_ring_section(tyre) -> None:
    """Copy the identified ``[FLEXIBLE_RING]`` of a built-in tyre into its property file."""
    from importlib import resources

    from ..tyre.ring.parameters import BUILT_IN_RING, SECTION
    from ..tyre.tir import read_tir
    key = {k.lower(): k for k in BUILT_IN_RING}.get(str(tyre.name).lower())
    if key is None:
        return  # the ring's own build names what is missing
    with resources.as_file(resources.files("tyrelab.tyre").joinpath("data", BUILT_IN_RING[key])) as p:
        ring = read_tir(p)
    if ring.has(SECTION):
        tyre.tir.sections[SECTION] = copy.deepcopy(ring.sections[SECTION])


def _file_stem(name: str) -> str:
    """A file name from a tyre's name (its own characters where safe)."""
    stem = "".join(c if c.isalnum() or c in "-_." else "_" for c in Path(str(name)).name)
    return stem.strip(".") or "tyre"


def _road_record(folder: Path, road) -> dict:
    """Copy a road file into ``folder/road``; the road's manifest entry (a name or the file)."""
    if not isinstance(road, str):
        raise InputError("give the road by its name or file to put it in an FMU (a Road object "
                         "cannot travel inside one)", field="road")
    named = road_file(road)
    if named is None:
        return {"spec": road}
    _, path_text, offset = named
    source = Path(path_text)
    (folder / "road").mkdir()
    shutil.copyfile(source, folder / "road" / source.name)
    return {"file": f"road/{source.name}", "offset": offset}


def terrain_file(terrain) -> Path | None:
    """The soil file a terrain names (``FILE.toml``, as ``--terrain`` reads it), None for a
    name."""
    if isinstance(terrain, (str, Path)) and str(terrain).lower().endswith(".toml"):
        return Path(str(terrain))
    return None


def _terrain_record(folder: Path, terrain) -> dict:
    """Copy a soil file into ``folder/terrain``; the terrain's manifest entry (a name or the
    file)."""
    if not isinstance(terrain, (str, Path)):
        raise InputError("give the terrain by its name or file to put it in an FMU (a Soil object "
                         "cannot travel inside one)", field="terrain")
    source = terrain_file(terrain)
    if source is None:
        return {"spec": str(terrain)}
    (folder / "terrain").mkdir()
    shutil.copyfile(source, folder / "terrain" / source.name)
    return {"file": f"terrain/{source.name}"}


def write_data(folder, tm: TyreModel, tyre, road: str, load: float, frame: str,
               internal_step: float, terrain=None) -> dict:
    """Write the tyre, the road and ``manifest.json`` into ``folder`` (it must exist, empty).

    ``tm`` the checked model (:func:`tyrelab.api.make_tyre_model`) of ``tyre``
    (the name or file the user gave); ``road`` a road name or file
    ``FILE[@V]``; ``load`` [N], ``frame`` and ``internal_step`` [s] the
    defaults of the parameters INITIAL_LOAD, OUTPUT_FRAME and INTERNAL_STEP;
    ``terrain`` a soil's name or file laid over the road (checked by the caller), or None.
    Returns the manifest.
    """
    folder = Path(folder)
    bad = {k: v for k, v in tm.options.items() if not isinstance(v, SCALARS)}
    if bad or "pattern" in tm.options:
        raise InputError(f"the option(s) {', '.join(sorted(set(bad) | ({'pattern'} & set(tm.options))))} "
                         "cannot travel inside an FMU (numbers, true/false and texts can; a tread "
                         "pattern file cannot yet)", field="options")
    z_start = tm.tyre.unloaded_radius - (tm.tyre.static_deflection(load) if load > 0 else 0.0)
    manifest = {
        "format": FORMAT,
        "tyrelab": __version__,
        "tyre": _tyre_record(folder, tm, tyre),
        "model": tm.contact,
        "handling": tm.handling,
        "relaxation": (tm.relaxation if isinstance(tm.relaxation, str)
                       else [float(v) for v in tm.relaxation]),
        "options": dict(tm.options),
        "road": _road_record(folder, road),
        "load": float(load),
        "frame": frame,
        "internal_step": float(internal_step),
        "z_start": float(z_start),
    }
    if terrain is not None:
        manifest["format"] = FORMAT_TERRAIN
        manifest["terrain"] = _terrain_record(folder, terrain)
    (folder / MANIFEST).write_text(json.dumps(manifest, indent=1) + "\n", encoding="utf-8")
    return manifest


def read_manifest(resources) -> dict:
    """The manifest of an FMU's resources folder (``resources/tyrelab_data/manifest.json``)."""
    path = Path(_path(resources)) / DATA / MANIFEST
    if not path.is_file():
        raise InputError("no tyrelab manifest in the FMU's resources", source=str(path))
    manifest = json.loads(path.read_text(encoding="utf-8"))
    if manifest.get("format") not in (FORMAT, FORMAT_TERRAIN):
        raise InputError(f"manifest format {manifest.get('format')!r}; this tyrelab reads formats "
                         f"{FORMAT} and {FORMAT_TERRAIN}", source=str(path))
    return manifest


def _path(resources) -> str:
    """A folder from a resources location (a path or a ``file://`` URI)."""
    text = str(resources)
    if text.startswith("file://"):
        from urllib.parse import unquote, urlparse
        text = unquote(urlparse(text).path)
    return text


def road_spec(resources, manifest: dict) -> str:
    """The road of a manifest as :func:`tyrelab.road.spec.road_from_spec` takes it."""
    road = manifest["road"]
    if "spec" in road:
        return road["spec"]
    path = Path(_path(resources)) / DATA / road["file"]
    return f"{path}@{road['offset']}" if road["offset"] else str(path)


def terrain_spec(resources, manifest: dict):
    """The terrain of a manifest as ``--terrain`` takes it (a name or a file), or None."""
    terrain = manifest.get("terrain")
    if terrain is None:
        return None
    if "spec" in terrain:
        return terrain["spec"]
    return str(Path(_path(resources)) / DATA / terrain["file"])


def build_stepper(resources, manifest: dict, pressure: float, load: float, max_step: float,
                  frame: str, speed: float, start_time: float,
                  x_start: float = 0.0, y_start: float = 0.0,
                  soil_group: int = 0) -> WheelStepper:
    """The wheel an FMU instance steps, from its manifest and its parameters.

    ``pressure`` [Pa]: 0 or the tyre file's own takes the file in the FMU; another
    pressure takes the built-in tyre at that pressure from the installed tyrelab, or moves
    an MF-Tyre 6.x file with pressure terms there (any other tyre file describes one
    pressure only: an InputError). ``load`` [N] and
    ``speed`` [m/s] the equilibrium the state starts in; ``max_step`` [s], 0
    for the model's stable step. A terrain is laid over the road around the wheel's
    start ``(x_start, y_start)`` [m] (:func:`~tyrelab.rig.soil_ground.lay_terrain_around`:
    a soil's window follows the wheel anywhere, the stepper moving it). Instances with the
    same ``soil_group`` > 0 in one process share one soil (:func:`shared_terrain`).
    """
    from ..api import make_tyre_model

    tyre = manifest["tyre"]
    path = Path(_path(resources)) / DATA / tyre["file"]
    own = tyre["pressure"]
    if pressure == 0.0 or (own is not None and math.isclose(pressure, own, rel_tol=1e-9)):
        source, at = str(path), None
    elif tyre["builtin"] is not None:
        source, at = tyre["builtin"], pressure
    else:
        source, at = str(path), pressure
    # an FMU made before the transient slip existed ran its forces steady
    tm = make_tyre_model(source, manifest["model"], at, tyre["stiffness"], manifest["handling"],
                         manifest["options"], manifest.get("relaxation", "off"))
    road = road_spec(resources, manifest)
    terrain = terrain_spec(resources, manifest)
    if terrain is not None:
        road = shared_terrain(tm, terrain, road, soil_group, x_start, y_start,
                              _road_identity(resources, manifest))
    return wheel_stepper(model=tm, road=road, load=load,
                         speed=max(speed, 0.0), max_step=max_step if max_step != 0 else None,
                         frame=frame, start_time=start_time)


#: the soils FMU instances share in this process: SOIL_GROUP -> (what was laid, the ground);
#: a group's soil goes when its last instance does
_SHARED = {}


def _road_identity(resources, manifest: dict) -> tuple:
    """What a road is, whichever FMU carries it: its spec, or its file's bytes."""
    road = manifest["road"]
    if road.get("spec") is not None:
        return ("spec", road["spec"])
    return ("file", (Path(_path(resources)) / DATA / road["file"]).read_bytes())


def shared_terrain(model: TyreModel, terrain, road: str, group: int, x: float, y: float,
                   identity: tuple):
    """The ground an FMU instance's wheel runs on: ``terrain`` laid over ``road`` round its
    start ``(x, y)`` [m] (:func:`~tyrelab.rig.soil_ground.lay_terrain_around`), its own when
    ``group`` is 0; else the one ground of that group in this process, laid round the first
    instance's start, which the others join (the window then holds every wheel on it, and a
    rear wheel runs in the front wheels' ruts). An instance whose soil or road is not the
    group's is refused in one line. (``identity``: what the road is, :func:`_road_identity`.)"""
    from ..rig.soil_ground import lay_terrain_around
    from ..road.spec import road_from_spec
    from ..road.terrain import resolve_terrain

    if not group:
        return lay_terrain_around(model, terrain, road_from_spec(road), x, y)[0]
    if group < 0:
        raise InputError(f"SOIL_GROUP must be 0 (a soil of its own) or a group number > 0, got "
                         f"{group}", field="SOIL_GROUP")
    what = (resolve_terrain(terrain)[1], identity)
    held = _SHARED.get(group)
    ground = held[1]() if held is not None else None
    if ground is None:
        ground = lay_terrain_around(model, terrain, road_from_spec(road), x, y)[0]
        if not hasattr(ground, "cover"):
            raise InputError("this terrain cannot be shared between wheels (it has no window "
                             "that holds them all); SOIL_GROUP 0", field="SOIL_GROUP")
        _SHARED[group] = (what, weakref.ref(ground))
    elif held[0] != what:
        raise InputError(f"SOIL_GROUP {group} holds another soil or road than this instance's: "
                         "the wheels of one group run on one soil over one road", field="SOIL_GROUP")
    return ground
