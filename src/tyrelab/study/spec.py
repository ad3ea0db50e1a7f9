"""The study spec: one TOML file describing a campaign of simulations (``tyrelab study``).

A study is every tyre x model variant x test x speed x load case, each run
compared with a reference (another model of the study, or measured files).
This module reads and checks the file; it runs nothing. Everything is
validated before any work starts: a bad spec raises :class:`InputError`
with one line naming the file, the line, the key path and what was
expected. The spec is data only -- no value is ever executed or evaluated.

Schema (km/h, kPa, mm at this edge, as the command line; SI in the parsed objects)::

    [study]
    name = "xzl-thesis-campaign"        # required
    output = "results"                  # folder, relative to the spec file's folder
    dt = 0.001                          # [s] rig time step (optional, 0.001)
    output_rate = 1000                  # [Hz] output sample rate (optional, 1000)

    [[tyre]]                            # one or more
    name = "xzl"                        # label
    file = "xzl-16.00R20"               # built-in name, or a .tir / Chrono .json path (relative to the spec)
    pressure_kpa = 300                  # optional, built-in tyres measured at several pressures only

    [[model]]                           # one or more model variants
    name = "OPC lk"                     # label used in every table
    contact = "point"                   # a registered contact model
    stiffness = "linear"                # "linear" | "table" (optional: the model's default)
    handling = "none"                   # a registered handling model (optional: the tyre file's)

    [[test]]                            # one or more
    name = "cleat 50x50 perpendicular"  # obstacle/track label (the thesis's words)
    group = "discrete obstacles"        # or "rough tracks" (optional: from the road)
    road = "cleat:50x50"                # a road name (tyrelab.road.spec) or a .crg/.rdf/.obj path [@offset]
    speeds_kmh = [12, 18, 42]           # 0 < v <= 200 km/h
    loads = ["LC1"]                     # "LC1".."LC3" (thesis Table 3-4) or a wheel load in N
    rig = "trailer"                     # optional (tyrelab.api.RIGS)
    duration = 6.0                      # [s] optional (default: the rig runs to the road's end)
    reference = { model = "FTire TP" }  # optional: a model label of this spec, or
    # reference = { files = ["field/c50_12.tdx", "field/c50_18.tdx", "field/c50_42.tdx"] }

    [metrics.limits."discrete obstacles"]   # optional pass limits per group and metric
    mRE_disturbance_pct = 20
    mRE_response_pct = 20

Rules beyond the types:

* Labels (tyre, model names) are unique. A test name may appear in more
  than one ``[[test]]`` (the thesis drives a track at 3 and 18 km/h in LC1
  but 3 and 11 km/h in LC2) if the entries name the same road and group and
  no (speed, load) pair repeats.
* ``reference.files``: paths relative to the spec's folder, each existing.
  Plain strings: with one speed and one load they are repeated measurements
  of that condition; otherwise there must be one per (speed, load) pair,
  in the order speeds then loads (``[12 LC1, 12 LC2, 18 LC1, ...]``). Or
  tables ``{ file = "...", speed_kmh = 12, load = "LC1" }`` naming the
  condition (several for one condition are repeats). Every condition of
  the test needs at least one file.
* ``[metrics] limits``: ``{group: {metric: limit}}`` with metrics of
  :data:`tyrelab.validate.compare.METRICS`; a group given replaces that
  group's default (:data:`tyrelab.validate.tables.DEFAULT_LIMITS`) whole.
* In key paths of error messages, ``test[3]`` is the third ``[[test]]``
  table and ``speeds_kmh[2]`` the second element (counted from 1).

:meth:`StudySpec.runs` expands the matrix; :func:`run_key` names a run by
everything that determines its result (see there).
"""

from __future__ import annotations

import json
import math
import re
import tomllib
from importlib import resources
from pathlib import Path

from .. import limits
from ..errors import InputError
from .checker import Checker, describe_value
from .keys import run_key, tyre_digest  # noqa: F401 - part of this module's API
from .records import (ModelSpec, ReferenceFile, RunSpec, StudySpec, TestSpec,  # noqa: F401
                      TyreSpec, TRAILER_RIGS)

#: the obstacle groups of the thesis (Table 5-15); the summary rules differ per group
GROUPS = ("discrete obstacles", "rough tracks")
#: speed range accepted [km/h] (:data:`tyrelab.limits.MIN_SPEED`, ``MAX_SPEED``)
MIN_SPEED_KMH = limits.MIN_SPEED * 3.6
MAX_SPEED_KMH = round(limits.MAX_SPEED * 3.6, 9)
DEFAULT_DT = 1e-3
DEFAULT_OUTPUT_RATE = 1000.0
#: the built-in thesis campaign (package data)
BUILTIN_SPEC = "thesis_campaign.toml"

_STUDY_KEYS = ("name", "output", "dt", "output_rate", "left_wheel")
_TYRE_KEYS = ("name", "file", "pressure_kpa")
_MODEL_KEYS = ("name", "contact", "stiffness", "handling")
_TEST_KEYS = ("name", "group", "road", "speeds_kmh", "loads", "rig", "duration", "reference")
_REFERENCE_KEYS = ("model", "files", "column_map")
_REFERENCE_FILE_KEYS = ("file", "speed_kmh", "load")
_TOP_KEYS = ("study", "tyre", "model", "test", "metrics")
_METRICS_KEYS = ("limits",)
_OBSTACLE_KINDS = ("cleat", "bump", "step", "pothole")
_DISCRETE_TRACKS = ("trapezoidal-bump",)


# ---------------------------------------------------------------------------
# the sections

def _study(ck: Checker, doc):
    if "study" not in doc:
        ck.fail(("study",), "missing: the spec needs a [study] table with at least 'name'")
    t = ck.table(doc["study"], ("study",), _STUDY_KEYS, required=("name",), what="a table [study]")
    name = ck.label(t["name"], ("study", "name"))
    out_text = ck.string(t.get("output", "results"), ("study", "output"), "a folder path (string)")
    if not out_text.strip():
        ck.fail(("study", "output"), "expected a folder path, got an empty string")
    out = Path(out_text).expanduser()
    output = (out if out.is_absolute() else ck.base / out).resolve()
    if output.exists() and not output.is_dir():
        ck.fail(("study", "output"), f"'{out_text}' is a file; expected a results folder")
    dt = ck.number(t.get("dt", DEFAULT_DT), ("study", "dt"), "a time step > 0 [s]", low=0.0)
    if not limits.MIN_DT <= dt <= limits.MAX_DT:
        ck.fail(("study", "dt"), f"time step {dt:g} s is out of range; allowed: {limits.MIN_DT:g} to "
                f"{limits.MAX_DT:g} s")
    rate = ck.number(t.get("output_rate", DEFAULT_OUTPUT_RATE), ("study", "output_rate"),
                     "an output rate > 0 [Hz]", low=0.0)
    if rate * dt > 1.0 + 1e-9:
        ck.fail(("study", "output_rate") if "output_rate" in t else ("study", "dt"),
                f"the output rate {rate:g} Hz is faster than the time step {dt:g} s allows "
                f"(at most {1 / dt:g} Hz)")
    left = None
    if "left_wheel" in t:
        from ..tyre.registry import contact_models
        left = ck.choice(t["left_wheel"], ("study", "left_wheel"), tuple(contact_models()),
                         "the trailer's left-wheel contact model")
    return name, output, dt, rate, left


def _tyres(ck: Checker, doc) -> tuple[TyreSpec, ...]:
    from ..tyre.library import BUILT_IN, SINGLE_FILE, load_tyre

    builtins = {k.lower(): k for k in (*BUILT_IN, *SINGLE_FILE)}
    tyres, seen = [], {}
    for i, raw in enumerate(ck.array_of_tables(doc, "tyre")):
        path = ("tyre", i)
        t = ck.table(raw, path, _TYRE_KEYS, required=("name", "file"), what="a table [[tyre]]")
        name = ck.unique_label(t["name"], path + ("name",), seen, "tyre")
        file_text = ck.string(t["file"], path + ("file",), "a built-in tyre name or a .tir path")
        builtin = builtins.get(file_text.strip().lower())
        pressure = None
        if builtin is not None:
            file = builtin
            if "pressure_kpa" in t:
                if builtin not in BUILT_IN:
                    ck.fail(path + ("pressure_kpa",),
                            f"{builtin} is described at one pressure only; remove pressure_kpa")
                lo, hi = BUILT_IN[builtin][0], BUILT_IN[builtin][-1]
                pressure = 1e3 * ck.number(t["pressure_kpa"], path + ("pressure_kpa",),
                                           f"a pressure in kPa within the measured "
                                           f"{lo / 1e3:g}-{hi / 1e3:g} kPa of {builtin}",
                                           low=lo / 1e3, high=hi / 1e3, low_open=False)
        else:
            if not file_text.strip().lower().endswith((".tir", ".json")):
                ck.fail(path + ("file",), f"unknown tyre {json.dumps(file_text)}; expected a built-in tyre "
                        f"({', '.join([*BUILT_IN, *SINGLE_FILE])}), a .tir or a Chrono .json file")
            file = str(ck.path(file_text, path + ("file",), "tyre property file"))
            if "pressure_kpa" in t:
                ck.fail(path + ("pressure_kpa",), "a .tir file describes one pressure; pressure_kpa is "
                        "for built-in tyres only")
        try:  # read it now: a broken property file stops the study before it starts
            tyre = load_tyre(file, pressure)
        except InputError as exc:
            ck.fail(path + ("file",), f"cannot use this tyre: {exc}")
        tyres.append((TyreSpec(name, file, pressure, builtin is not None), tyre))
    return tuple(tyres)


def _models(ck: Checker, doc, tyres) -> tuple[ModelSpec, ...]:
    from ..tyre.params import STIFFNESS_MODES
    from ..tyre.registry import contact_models, handling_model, handling_models

    contacts, handlings = list(contact_models()), list(handling_models())
    models, seen = [], {}
    for i, raw in enumerate(ck.array_of_tables(doc, "model")):
        path = ("model", i)
        t = ck.table(raw, path, _MODEL_KEYS, required=("name", "contact"), what="a table [[model]]")
        name = ck.unique_label(t["name"], path + ("name",), seen, "model")
        contact = ck.choice(t["contact"], path + ("contact",), contacts, "contact model")
        stiffness = None
        if "stiffness" in t:
            stiffness = ck.choice(t["stiffness"], path + ("stiffness",), STIFFNESS_MODES, "stiffness")
            if stiffness == "table":
                for tyre_spec, tyre in tyres:
                    if tyre.load_deflection is None:
                        ck.fail(path + ("stiffness",), f"tyre '{tyre_spec.name}' has no "
                                "[DEFLECTION_LOAD_CURVE] for a table stiffness; use \"linear\"")
        handling = None
        if "handling" in t:
            handling = ck.choice(t["handling"], path + ("handling",), handlings, "handling model")
            for tyre_spec, tyre in tyres:  # its coefficients must be in every tyre's file
                try:
                    handling_model(handling).build(tyre)
                except InputError as exc:
                    ck.fail(path + ("handling",), f"tyre '{tyre_spec.name}' has no {handling} "
                            f"coefficients: {exc}")
        models.append(ModelSpec(name, contact, stiffness, handling))
    return tuple(models)


def _road(ck: Checker, value, path) -> tuple[str, str]:
    """A road name checked without building it: ``(road for simulate, inferred group)``."""
    from ..road.spec import _NUM, _tracks, road_from_spec, road_names

    text = ck.string(value, path, "a road name").strip()
    if not text:
        ck.fail(path, f"expected a road name, got an empty string; one of: {', '.join(road_names())}")
    lower = text.lower()
    if lower in _tracks():  # built-in tracks are large: known by name, built when run
        return lower, "discrete obstacles" if lower in _DISCRETE_TRACKS else "rough tracks"
    path_text, _, offset = text.partition("@")
    if path_text.lower().endswith((".crg", ".rdf", ".obj")):
        if offset and not re.fullmatch(_NUM, offset):
            ck.fail(path, f"cannot read lateral offset '{offset}' in road '{text}'; expected metres")
        what = {".crg": "OpenCRG file", ".rdf": "Adams road data file", ".obj": "OBJ mesh file"}
        file = ck.path(path_text, path, what[Path(path_text).suffix.lower()])
        return f"{file}@{offset}" if offset else str(file), "rough tracks"
    kind, _, args = text.partition(":")
    kind = kind.lower()
    if kind in ("iso8608", "powerlaw") and args:  # synthesised when built: checked here instead
        body, _, seed = args.partition("@")
        if seed and not seed.isdigit():
            ck.fail(path, f"cannot read seed '{seed}' in road '{text}'; expected an integer")
        if kind == "iso8608" and body.upper() not in tuple("ABCDEFGH"):
            ck.fail(path, f"unknown ISO 8608 class '{body}' in road '{text}'; expected A to H")
        if kind == "powerlaw":
            parts = body.split(",")
            if len(parts) != 2 or not all(re.fullmatch(_NUM, p) for p in parts) or float(parts[0]) <= 0:
                ck.fail(path, f"cannot read '{body}' in road '{text}'; expected A,N with A > 0")
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


def _reference(ck: Checker, raw, path, speeds, loads, models, cases):
    t = ck.table(raw, path, _REFERENCE_KEYS, what="a table { model = ... } or { files = [...] }")
    if ("model" in t) == ("files" in t):
        ck.fail(path, "expected exactly one of 'model' (a model label) or 'files' (measured files)")
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


def _tests(ck: Checker, doc, models, dt: float = DEFAULT_DT,
           rate: float = DEFAULT_OUTPUT_RATE) -> tuple[TestSpec, ...]:
    from ..api import RIGS
    from ..tyre.library import load_cases

    cases = list(load_cases().index)
    tests, first = [], {}
    conditions: dict[tuple, int] = {}
    for i, raw in enumerate(ck.array_of_tables(doc, "test")):
        path = ("test", i)
        t = ck.table(raw, path, _TEST_KEYS, required=("name", "road", "speeds_kmh", "loads"),
                     what="a table [[test]]")
        name = ck.label(t["name"], path + ("name",))
        road, group = _road(ck, t["road"], path + ("road",))
        if "group" in t:
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
        rig = ck.choice(t.get("rig", "trailer"), path + ("rig",), RIGS, "rig")
        duration = None
        if "duration" in t:
            duration = ck.number(t["duration"], path + ("duration",), "a duration > 0 [s]", low=0.0)
            try:
                limits.check_duration(duration, dt, rate)
            except InputError as exc:
                ck.fail(path + ("duration",), exc.reason)
        reference_model, reference_files = None, ()
        if "reference" in t:
            reference_model, reference_files = _reference(ck, t["reference"], path + ("reference",),
                                                          speeds, loads, models, cases)
        if name in first:  # the same obstacle again: other conditions of it
            other = tests[first[name]]
            if (other.road, other.group) != (road, group):
                ck.fail(path + ("road",), f"test {json.dumps(name)} is also test[{first[name] + 1}] "
                        f"with road '{other.road}' ({other.group}); one name, one road and group")
        else:
            first[name] = i
        for k, v in enumerate(speeds):
            for load in loads:
                if (name, v, load) in conditions:
                    ck.fail(path + ("speeds_kmh", k), f"test {json.dumps(name)} at {v * 3.6:g} km/h, load "
                            f"{load} is also in test[{conditions[(name, v, load)] + 1}]")
                conditions[(name, v, load)] = i
        tests.append(TestSpec(name, group, road, tuple(speeds), tuple(loads), rig, duration,
                              reference_model, reference_files))
    return tuple(tests)


def _limits(ck: Checker, doc) -> dict:
    from ..validate.compare import METRICS
    from ..validate.tables import DEFAULT_LIMITS

    limits = {g: dict(m) for g, m in DEFAULT_LIMITS.items()}
    if "metrics" not in doc:
        return limits
    metrics = ck.table(doc["metrics"], ("metrics",), _METRICS_KEYS, what="a table [metrics]")
    if "limits" not in metrics:
        return limits
    given = ck.table(metrics["limits"], ("metrics", "limits"), GROUPS,
                     what="a table of groups, { \"discrete obstacles\" = {...}, \"rough tracks\" = {...} }")
    for group, table in given.items():
        path = ("metrics", "limits", group)
        ck.table(table, path, tuple(METRICS), what="a table of metric limits")
        if not table:
            ck.fail(path, f"expected at least one metric limit; metrics: {', '.join(METRICS)}")
        limits[group] = {m: ck.number(v, path + (m,), "a limit > 0 (|metric| <= limit passes)", low=0.0)
                         for m, v in table.items()}
    return limits


# ---------------------------------------------------------------------------
# the front doors

def parse_spec(text: str, source: str | Path = "<string>", base: str | Path | None = None) -> StudySpec:
    """Parse and validate a study spec given as text.

    ``source`` names the text in messages and is the spec file: relative
    paths in it (``output``, ``.tir``, ``.crg``, reference files) are taken
    from its folder, or from ``base`` when given (the current folder for
    ``"<string>"``). Raises :class:`InputError` naming file, line and key.
    """
    src = str(source)
    if base is None:
        base = Path(src).parent if src != "<string>" else Path.cwd()
    ck = Checker(text, src, Path(base).expanduser().absolute())
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        msg = str(exc)
        m = re.search(r"\(at line (\d+), column (\d+)\)$", msg)
        line = int(m.group(1)) if m else (text.count("\n") + 1 if "end of document" in msg else None)
        reason = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)$", "", msg)
        where = f" (column {m.group(2)})" if m else ""
        raise InputError(f"invalid TOML: {reason}{where}", source=src, line=line) from None
    ck.table(doc, (), _TOP_KEYS, what="a study spec")
    name, output, dt, rate, left = _study(ck, doc)
    tyres = _tyres(ck, doc)
    models = _models(ck, doc, tyres)
    tests = _tests(ck, doc, models, dt, rate)
    limits = _limits(ck, doc)
    return StudySpec(name, output, dt, rate, tuple(t for t, _ in tyres), models, tests, limits,
                     Path(src) if src != "<string>" else src, left, text, ck.base)


def load_spec(path: str | Path) -> StudySpec:
    """Read, parse and validate the study spec file at ``path``."""
    p = Path(path)
    try:
        data = p.read_bytes()
    except FileNotFoundError:
        raise InputError("no such study spec file", source=str(p)) from None
    except OSError as exc:
        raise InputError(f"cannot read the study spec: {exc.strerror}", source=str(p)) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise InputError("the study spec is not UTF-8 text", source=str(p), line=line) from None
    return parse_spec(text, p)


def builtin_spec_text() -> str:
    """The text of the built-in thesis campaign (``study/data/thesis_campaign.toml``)."""
    return resources.files("tyrelab.study").joinpath("data", BUILTIN_SPEC).read_text(encoding="utf-8")


def builtin_spec(base: str | Path | None = None) -> StudySpec:
    """The thesis campaign (chapter 5) as a parsed spec.

    Its output folder is ``results`` under ``base`` (default: the current
    folder), not inside the installed package.
    """
    source = resources.files("tyrelab.study").joinpath("data", BUILTIN_SPEC)
    return parse_spec(builtin_spec_text(), str(source), base=Path.cwd() if base is None else base)


def example_spec() -> str:
    """A commented example spec (every key, with units) that :func:`parse_spec` accepts
    (``study/data/example_spec.toml``)."""
    return resources.files("tyrelab.study").joinpath("data", "example_spec.toml").read_text(encoding="utf-8")
