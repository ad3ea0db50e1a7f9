"""Run keys: a short stable hash of everything that decides a run's result.

A run's key covers the content of the tyre files it reads, the model's
settings, the road (a CRG file by its content), the soil (a soil file's, or the
built-in soil's file's, content) and the slip or driving torque of a soil test's run, speed, load,
rig, duration, time step, output rate and the package version -- and nothing else (labels,
groups, references, limits and the output folder are left out), so a result
is reused exactly when it would be computed again identically.
"""

from __future__ import annotations

import bisect
import functools
import hashlib
import json
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

from .._version import __version__

if TYPE_CHECKING:
    from .records import ModelSpec, RunSpec, TyreSpec


def _data_bytes(package: str, name: str) -> bytes:
    return resources.files(package).joinpath("data", name).read_bytes()


def _tyre_files(tyre: TyreSpec) -> list[tuple[str, bytes]]:
    """The files whose content defines ``tyre`` (as the library and the ring model read them)."""
    from ..tyre.library import BUILT_IN, DEFAULT_PRESSURE, SINGLE_FILE
    from ..tyre.ring.parameters import BUILT_IN_RING
    from ..tyre.ring.pattern import BUILT_IN_PATTERN

    files = []
    if tyre.builtin and tyre.file in SINGLE_FILE:
        files.append((SINGLE_FILE[tyre.file], _data_bytes("tyrelab.tyre", SINGLE_FILE[tyre.file])))
    elif tyre.builtin:
        pressures = BUILT_IN[tyre.file]
        p = DEFAULT_PRESSURE if tyre.pressure is None else tyre.pressure
        exact = [q for q in pressures if abs(p - q) <= 1e-8 + 1e-5 * abs(q)]  # as load_tyre
        if exact:
            used = exact
        else:  # interpolated between the two measured pressures around it
            hi = bisect.bisect_left(pressures, p)
            used = [pressures[hi - 1], pressures[hi]]
        for q in used:
            name = f"{tyre.file}_{q / 1e3:.0f}kPa.tir"
            files.append((name, _data_bytes("tyrelab.tyre", name)))
    elif Path(tyre.file).suffix.lower() == ".json":
        # a Chrono tyre may name a .tir beside it: the tyre as read is what counts
        from ..tyre.chrono_json import read_chrono_json
        from ..tyre.tir import format_tir
        path = Path(tyre.file)
        files.append((path.name, format_tir(read_chrono_json(path)).encode()))
    else:
        path = Path(tyre.file)
        files.append((path.name, path.read_bytes()))
    # the ring model reads a built-in tyre's ring parameters and tread pattern from
    # companion files when the property file has none (matched by the tyre's name)
    stem = tyre.file if tyre.builtin else Path(tyre.file).stem
    for table in (BUILT_IN_RING, BUILT_IN_PATTERN):
        match = {k.lower(): v for k, v in table.items()}.get(stem.lower())
        if match is not None:
            files.append((match, _data_bytes("tyrelab.tyre", match)))
    return files


def tyre_digest(tyre: TyreSpec) -> str:
    """SHA-256 (hex) of a tyre's parameter content.

    Built-in tyres: the property file(s) :func:`tyrelab.tyre.library.load_tyre`
    reads at the tyre's pressure (the two measured ones around it when it
    interpolates) and the pressure; ``.tir`` files: the file's bytes. Both
    add the ring model's companion files (ring parameters, tread pattern)
    the tyre's name selects. Labels do not enter it.
    """
    h = hashlib.sha256(b"tyrelab tyre digest 1\0")
    h.update(json.dumps({"builtin": tyre.builtin, "name": tyre.file if tyre.builtin else None,
                         "pressure": tyre.pressure}, sort_keys=True).encode())
    for name, content in _tyre_files(tyre):
        h.update(b"\0" + name.encode() + b"\0" + str(len(content)).encode() + b"\0")
        h.update(content)
    return h.hexdigest()


def _road_identity(road: str):
    """The road as it enters a run key: its name, or a road file's identity as its format gives
    it (:attr:`tyrelab.road.formats.RoadFormat.identity`: the file's content digest and offset)."""
    from ..road.formats import road_file
    named = road_file(road)
    if named is None:
        return road
    fmt, path_text, offset = named
    return fmt.identity(fmt, Path(path_text), offset)


def _terrain_identity(terrain: str) -> dict:
    """The soil as it enters a run key: the SHA-256 of its file's bytes (a built-in soil's
    packaged file, with its name), so editing a soil file computes its runs again, as a road
    file's content does."""
    if terrain.strip().lower().endswith(".toml"):
        return {"soil_file_sha256": hashlib.sha256(Path(terrain).read_bytes()).hexdigest()}
    from ..road.soil import soil_names
    if terrain.strip().lower() not in soil_names():
        return {"terrain": terrain}          # another kind's value says all there is (slick:0.5)
    name = terrain.strip().lower()
    content = resources.files("tyrelab.road.soil").joinpath("data", f"{name}.toml").read_bytes()
    return {"soil": name, "soil_file_sha256": hashlib.sha256(content).hexdigest()}


@functools.lru_cache(maxsize=None)
def _load_case(name: str) -> tuple[float, float]:
    from ..tyre.library import load_cases
    row = load_cases().loc[name]
    return float(row["ballast_kg"]), float(row["wheel_load_kg"])


def _load_identity(load):
    if isinstance(load, str):
        ballast, wheel = _load_case(load)
        return {"case": load, "ballast_kg": ballast, "wheel_load_kg": wheel}
    return float(load)


def relaxation_in_effect(tyre: TyreSpec, model: ModelSpec) -> str:
    """The transient slip a run of ``model`` on ``tyre`` simulates, in the words of its
    metadata (:attr:`tyrelab.tyre.model.TyreModel.relaxation_used`): ``"off"``, ``"file"``
    or the two lengths; ``"auto"`` resolved against the tyre's file."""
    import warnings

    from ..api import make_tyre_model

    with warnings.catch_warnings():  # the spec's check has said what the file lacks
        warnings.simplefilter("ignore")
        return make_tyre_model(tyre.file, model.contact, tyre.pressure, model.stiffness,
                               model.handling, dict(model.options) or None,
                               model.relaxation).relaxation_used


def run_key(run: RunSpec, tyre_digest: str, relaxation: str = "off") -> str:
    """A short stable key (16 hex digits) of everything that determines a run's result.

    SHA-256 of a canonical JSON of: ``tyre_digest`` (pass
    :func:`tyre_digest` of ``run.tyre``: the tyre's parameter content, not
    its label) and pressure; the model's contact, stiffness, handling and options, and the
    transient slip in effect (``relaxation``, :func:`relaxation_in_effect`; only when not
    ``"off``, so the keys of steady runs are those of before it existed);
    the road (its name, or a ``.crg`` file's content digest and offset);
    the speed [m/s]; the load (a load case with its ballast and wheel mass
    from Table 3-4, or the force [N]); the rig (and the trailer's left-wheel model when
    it differs from the test wheel's), duration, dt, output rate; on soil, the soil
    file's content (:func:`_terrain_identity`) and the slip or driving torque of a soil test;
    and ``tyrelab.__version__``. Labels (study, tyre, model and test names,
    the group), references, limits and the output folder are left out:
    they do not change what is simulated, so renaming a model keeps its
    stored runs, and editing one model variant changes only its own runs'
    keys. Two labels with identical settings share their runs' keys.
    """
    payload = {
        "tyrelab": __version__,
        "tyre": {"digest": tyre_digest, "pressure": run.tyre.pressure},
        "model": {"contact": run.model.contact, "stiffness": run.model.stiffness,
                  "handling": run.model.handling,
                  # only when set, so the keys of runs without options are those of before
                  **({"options": dict(run.model.options)} if run.model.options else {}),
                  **({"relaxation": relaxation} if relaxation != "off" else {})},
        "road": _road_identity(run.road),
        "speed": float(run.speed),
        "load": _load_identity(run.load),
        "rig": run.rig,
        "duration": None if run.duration is None else float(run.duration),
        "dt": float(run.dt),
        "output_rate": float(run.output_rate),
    }
    if run.left_contact is not None:  # only when set: keys of runs without it stay as they were
        payload["left_wheel"] = run.left_contact
    if run.terrain is not None:       # as left_wheel: the keys of rigid-road runs stay
        payload["terrain"] = _terrain_identity(run.terrain)
    if run.slip is not None:
        payload["slip"] = float(run.slip)
    if run.torque is not None:
        payload["torque"] = float(run.torque)
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return hashlib.sha256(text.encode()).hexdigest()[:16]
