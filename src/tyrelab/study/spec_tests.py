"""The ``[[test]]`` tables of a study spec: roads, speeds, loads, rig, models, reference.

Each value is checked without building anything (a road by its name, a
reference file by its existence; the ground -- ``terrain``, ``slips`` -- in
:mod:`.spec_soil`), and a mistake raises one
:class:`~tyrelab.errors.InputError` naming file, line and key path (through
:class:`~.checker.Checker`). The other sections and the front doors are in
:mod:`.spec`.
"""

from __future__ import annotations

import json
import math
import re

from .. import limits
from ..errors import InputError
from .checker import Checker, describe_value
from .records import ReferenceFile, TestSpec
from .spec_soil import (DEFAULT_SOIL_DURATION, SOIL_GROUP, check_models_on_ground, check_slips, check_torques,
                        check_terrain)

#: the obstacle groups of the thesis (Table 5-15); the summary rules differ per group
GROUPS = ("discrete obstacles", "rough tracks")
#: speed range accepted [km/h] (:data:`tyrelab.limits.MIN_SPEED`, ``MAX_SPEED``)
MIN_SPEED_KMH = limits.MIN_SPEED * 3.6
MAX_SPEED_KMH = round(limits.MAX_SPEED * 3.6, 9)
DEFAULT_DT = 1e-3
DEFAULT_OUTPUT_RATE = 1000.0

_TEST_KEYS = ("name", "group", "road", "speeds_kmh", "loads", "rig", "duration", "models",
              "reference", "terrain", "slips", "torques")
_REFERENCE_KEYS = ("model", "files", "column_map")
_REFERENCE_FILE_KEYS = ("file", "speed_kmh", "load")
_OBSTACLE_KINDS = ("cleat", "bump", "step", "pothole")
_DISCRETE_TRACKS = ("trapezoidal-bump",)


def _road(ck: Checker, value, path) -> tuple[str, str]:
    """A road name checked without building it: ``(road for simulate, inferred group)``."""
    from ..road.formats import road_file
    from ..road.spec import _NUM, RANDOM_KINDS, _tracks, random_road_args, road_from_spec, road_names

    text = ck.string(value, path, "a road name").strip()
    if not text:
        ck.fail(path, f"expected a road name, got an empty string; one of: {', '.join(road_names())}")
    lower = text.lower()
    if lower in _tracks():  # built-in tracks are large: known by name, built when run
        return lower, "discrete obstacles" if lower in _DISCRETE_TRACKS else "rough tracks"
    named = road_file(text)
    if named is not None:
        fmt, path_text, offset = named
        if offset and not re.fullmatch(_NUM, offset):
            ck.fail(path, f"cannot read lateral offset '{offset}' in road '{text}'; expected metres")
        file = ck.path(path_text, path, f"{fmt.name} file")
        return f"{file}@{offset}" if offset else str(file), "rough tracks"
    kind, _, args = text.partition(":")
    kind = kind.lower()
    if kind in RANDOM_KINDS and args:  # synthesised when built: its name is checked here instead
        try:
            random_road_args(kind, args, text)
        except InputError as exc:
            ck.fail(path, exc.reason)
        return text, "rough tracks"
    try:  # what is left is flat or an obstacle: small objects, no grid is built
        road_from_spec(text)
    except ValueError as exc:  # InputError, or anything else a constructor refuses
        reason = str(exc)
        if isinstance(exc, InputError):
            named = exc.field in (None, "road") or exc.field in exc.reason
            reason = exc.reason if named else f"{exc.field}: {exc.reason}"
        ck.fail(path, f"{reason} (road '{text}')" if text not in reason else reason)
    return text, "discrete obstacles" if kind in _OBSTACLE_KINDS else "rough tracks"


def _load(ck: Checker, value, path, cases):
    if isinstance(value, str):
        key = value.strip().upper()
        if key not in cases:
            ck.fail(path, f"unknown load case {json.dumps(value)}; expected one of {', '.join(cases)} "
                    "or a wheel load in N")
        return key
    load = ck.number(value, path, f"a load case ({', '.join(cases)}) or a wheel load > 0 in N", low=0.0)
    if load < limits.MIN_LOAD:
        ck.fail(path, f"wheel load {load:g} N is out of range; allowed: at least {limits.MIN_LOAD:g} N")
    return load


def _speed(ck: Checker, value, path):
    kmh = ck.number(value, path, f"a speed in km/h, 0 < v <= {MAX_SPEED_KMH:g}", low=0.0,
                    high=MAX_SPEED_KMH)
    if kmh < MIN_SPEED_KMH:
        ck.fail(path, f"speed {kmh:g} km/h is out of range; allowed: {MIN_SPEED_KMH:g} to "
                f"{MAX_SPEED_KMH:g} km/h")
    return kmh / 3.6


def _nonempty_list(ck: Checker, value, path, what):
    if not isinstance(value, list):
        ck.fail(path, f"expected an array of {what}, got {describe_value(value)}")
    if not value:
        ck.fail(path, f"expected a non-empty array of {what}")
    return value


def _models(ck: Checker, t: dict, path, models) -> tuple[str, ...]:
    """The test's ``models``: labels of the spec's model variants, each once (() if absent:
    every model)."""
    if "models" not in t:
        return ()
    names = [m.name for m in models]
    out = []
    for k, v in enumerate(_nonempty_list(ck, t["models"], path + ("models",), "model labels")):
        label = ck.string(v, path + ("models", k), "a model label")
        if label not in names:
            ck.fail(path + ("models", k), f"no model labelled {json.dumps(label)} in this spec; "
                    f"expected one of: {', '.join(json.dumps(n) for n in names)}")
        if label in out:
            ck.fail(path + ("models", k), f"duplicate model {json.dumps(label)}")
        out.append(label)
    return tuple(out)


def _reference(ck: Checker, raw, path, speeds, loads, models, cases, soil_test: bool = False):
    t = ck.table(raw, path, _REFERENCE_KEYS, what="a table { model = ... } or { files = [...] }")
    if ("model" in t) == ("files" in t):
        ck.fail(path, "expected exactly one of 'model' (a model label) or 'files' (measured files)")
    if soil_test and "files" in t:
        ck.fail(path + ("files",), "a soil test compares its models with a reference model "
                "(reference = { model = ... }); measured files are for the rigid-road tests")
    if "column_map" in t and "files" not in t:
        ck.fail(path + ("column_map",), "a column map belongs to measured 'files'")
    cmap = (ck.path(t["column_map"], path + ("column_map",), "column map file")
            if "column_map" in t else None)
    if "model" in t:
        names = [m.name for m in models]
        label = ck.string(t["model"], path + ("model",), "a model label")
        if label not in names:
            ck.fail(path + ("model",), f"no model labelled {json.dumps(label)} in this spec; "
                    f"expected one of: {', '.join(json.dumps(n) for n in names)}")
        return label, ()
    entries = _nonempty_list(ck, t["files"], path + ("files",), "file paths")
    pairs = [(v, c) for v in speeds for c in loads]
    strings = all(isinstance(e, str) for e in entries)
    if strings and len(pairs) > 1 and len(entries) != len(pairs):
        ck.fail(path + ("files",), f"{len(entries)} file(s) for {len(pairs)} speed/load conditions; give one "
                "per condition (speeds then loads) or tables { file, speed_kmh, load }")
    out = []
    for k, entry in enumerate(entries):
        epath = path + ("files", k)
        if isinstance(entry, str):
            if len(pairs) > 1 and not strings:
                ck.fail(epath, "with several speed/load conditions and tables in the list, name this "
                        "file's condition too: { file = ..., speed_kmh = ..., load = ... }")
            speed, load = pairs[0] if len(pairs) == 1 else pairs[k]
            out.append(ReferenceFile(ck.path(entry, epath, "reference file"), speed, load, cmap))
            continue
        e = ck.table(entry, epath, _REFERENCE_FILE_KEYS, required=_REFERENCE_FILE_KEYS,
                     what="a file path or a table { file, speed_kmh, load }")
        speed = _speed(ck, e["speed_kmh"], epath + ("speed_kmh",))
        if not any(math.isclose(speed, v, rel_tol=1e-12) for v in speeds):
            ck.fail(epath + ("speed_kmh",), f"{e['speed_kmh']!r} km/h is not among this test's speeds_kmh")
        speed = next(v for v in speeds if math.isclose(speed, v, rel_tol=1e-12))
        load = _load(ck, e["load"], epath + ("load",), cases)
        if load not in loads:
            ck.fail(epath + ("load",), f"{e['load']!r} is not among this test's loads")
        out.append(ReferenceFile(ck.path(e["file"], epath + ("file",), "reference file"), speed, load,
                                 cmap))
    covered = {(f.speed, f.load) for f in out}
    for v, c in pairs:
        if (v, c) not in covered:
            ck.fail(path + ("files",), f"no reference file for {v * 3.6:g} km/h, load {c}")
    return None, tuple(out)


#: the roads made of one obstacle, built in milliseconds: checked against each tyre in the spec
OBSTACLES = ("cleat", "step", "bump", "pothole")


def _check_obstacle_for_tyres(ck: Checker, road: str, path, tyres) -> None:
    """An obstacle with an edge taller than a tyre's radius
    (:func:`tyrelab.guards.check_road_for_tyre`) is the spec's error, not a failed run; tracks
    and road files are checked when a run builds them."""
    if road.partition(":")[0].strip().lower() not in OBSTACLES or not tyres:
        return
    from ..guards import check_road_for_tyre
    from ..road.spec import road_from_spec
    obstacle = road_from_spec(road)
    for spec, tyre in tyres:
        try:
            check_road_for_tyre(obstacle, tyre)
        except InputError as exc:
            ck.fail(path, f"{exc.reason} (tyre {json.dumps(spec.name)})")


def _tests(ck: Checker, doc, models, dt: float = DEFAULT_DT,
           rate: float = DEFAULT_OUTPUT_RATE, tyres=()) -> tuple[TestSpec, ...]:
    """The ``[[test]]`` tables; ``tyres``, the spec's ``(TyreSpec, Tyre)`` pairs, each test's
    loads are checked against (every tyre runs every test)."""
    from ..rig.registry import rigs
    from ..tyre.library import load_cases

    from ..rig.trailer import load_case_wheel_load

    cases = list(load_cases().index)
    tests, first = [], {}
    conditions: dict[tuple, int] = {}
    for i, raw in enumerate(ck.array_of_tables(doc, "test")):
        path = ("test", i)
        t = ck.table(raw, path, _TEST_KEYS, required=("name", "speeds_kmh", "loads"),
                     what="a table [[test]]")
        name = ck.label(t["name"], path + ("name",))
        rig_name = ck.choice(t.get("rig", "trailer"), path + ("rig",), tuple(rigs()), "rig")
        the_rig = rigs()[rig_name]
        terrain = check_terrain(ck, t, path, the_rig)
        slips = check_slips(ck, t, path, the_rig)
        torques = check_torques(ck, t, path, the_rig)
        soil_test = bool(slips or torques)
        if "road" not in t and the_rig.terrain != "soil":
            ck.fail(path, f"missing key 'road' (required; keys: {', '.join(_TEST_KEYS)})")
        road, group = _road(ck, t.get("road", the_rig.default_road), path + ("road",))
        _check_obstacle_for_tyres(ck, road, path + ("road",), tyres)
        if soil_test:  # a soil test: a slip curve, none of the thesis's groups
            if "group" in t:
                ck.fail(path + ("group",), f"a soil test (with slips or torques) is in the group "
                        f"'{SOIL_GROUP}'; the groups {', '.join(GROUPS)} are the rigid-road tests'")
            group = SOIL_GROUP
        elif "group" in t:
            group = ck.choice(t["group"], path + ("group",), GROUPS, "group")
        speeds = []
        for k, v in enumerate(_nonempty_list(ck, t["speeds_kmh"], path + ("speeds_kmh",), "speeds in km/h")):
            speed = _speed(ck, v, path + ("speeds_kmh", k))
            if speed in speeds:
                ck.fail(path + ("speeds_kmh", k), f"duplicate speed {v!r} km/h")
            speeds.append(speed)
        loads = []
        for k, v in enumerate(_nonempty_list(ck, t["loads"], path + ("loads",), "load cases or loads in N")):
            load = _load(ck, v, path + ("loads", k), cases)
            if load in loads:
                ck.fail(path + ("loads", k), f"duplicate load {v!r}")
            loads.append(load)
            newtons = load_case_wheel_load(load) if isinstance(load, str) else load
            for spec, tyre in tyres:  # refused here, not by each run of it
                try:
                    limits.check_wheel_load(newtons, tyre)
                except InputError as exc:
                    ck.fail(path + ("loads", k), f"{exc.reason} (tyre {json.dumps(spec.name)})")
        duration = DEFAULT_SOIL_DURATION if soil_test else None
        if "duration" in t:
            duration = ck.number(t["duration"], path + ("duration",), "a duration > 0 [s]", low=0.0)
        if duration is not None:
            try:
                limits.check_duration(duration, dt, rate)
            except InputError as exc:
                ck.fail(path + ("duration",), exc.reason)
        chosen = _models(ck, t, path, models)
        check_models_on_ground(ck, path, chosen or [m.name for m in models], models, terrain,
                               listed=bool(chosen))
        reference_model, reference_files = None, ()
        if "reference" in t:
            reference_model, reference_files = _reference(ck, t["reference"], path + ("reference",),
                                                          speeds, loads, models, cases, soil_test)
            if reference_model is not None and chosen and reference_model not in chosen:
                ck.fail(path + ("reference", "model"), f"the reference {json.dumps(reference_model)} "
                        "is not among this test's models")
        if name in first:  # the same obstacle again: other conditions of it
            other = tests[first[name]]
            if (other.road, other.group) != (road, group):
                ck.fail(path + ("road",), f"test {json.dumps(name)} is also test[{first[name] + 1}] "
                        f"with road '{other.road}' ({other.group}); one name, one road and group")
            if other.terrain != terrain:
                ck.fail(path + ("terrain",) if "terrain" in t else path,
                        f"test {json.dumps(name)} is also test[{first[name] + 1}] on "
                        f"{other.terrain or 'the rigid road'}; one name, one ground")
        else:
            first[name] = i
        for k, v in enumerate(speeds):
            for load in loads:
                if (name, v, load) in conditions:
                    ck.fail(path + ("speeds_kmh", k), f"test {json.dumps(name)} at {v * 3.6:g} km/h, load "
                            f"{load} is also in test[{conditions[(name, v, load)] + 1}]")
                conditions[(name, v, load)] = i
        tests.append(TestSpec(name, group, road, tuple(speeds), tuple(loads), rig_name, duration,
                              reference_model, reference_files, chosen, terrain, slips, torques))
    return tuple(tests)
