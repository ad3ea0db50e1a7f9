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
    store = "compact"                   # how runs are kept: "compact" | "lossless" | "full"
                                        # (optional, "compact"; tyrelab.study.store)

    [[tyre]]                            # one or more
    name = "xzl"                        # label
    file = "xzl-16.00R20"               # built-in name, or a .tir / Chrono .json path (relative to the spec)
    pressure_kpa = 300                  # optional: a built-in tyre measured at several pressures, or
                                        # an MF-Tyre 6.1/6.2 file with pressure terms (in its range)

    [[model]]                           # one or more model variants
    name = "OPC lk"                     # label used in every table
    contact = "point"                   # a registered contact model
    stiffness = "linear"                # "linear" | "table" (optional: the model's default)
    handling = "none"                   # a registered handling model (optional: the tyre file's)
    options = { n_length = 5 }          # the contact model's options (optional; tyre.registry)
    relaxation = "auto"                 # transient slip: "auto" (as the file's USE_MODE says),
                                        # "off", "file" or [sigma_kappa, sigma_alpha] in m (optional)

    [[test]]                            # one or more
    name = "cleat 50x50 perpendicular"  # obstacle/track label (the thesis's words)
    group = "discrete obstacles"        # or "rough tracks" (optional: from the road)
    road = "cleat:50x50"                # a road name (tyrelab.road.spec) or a .crg/.rdf/.obj path [@offset]
    speeds_kmh = [12, 18, 42]           # 0 < v <= 200 km/h
    loads = ["LC1"]                     # "LC1".."LC3" (thesis Table 3-4) or a wheel load in N
    rig = "trailer"                     # optional (tyrelab.registry.rigs())
    duration = 6.0                      # [s] optional (default: the rig runs to the road's end)
    models = ["OPC lk", "FTire TP"]     # optional: the model labels this test runs (default: all)
    reference = { model = "FTire TP" }  # optional: a model label of this spec, or
    # reference = { files = ["field/c50_12.tdx", "field/c50_18.tdx", "field/c50_42.tdx"] }

    [[test]]                            # a soil test: a slip curve per model (tyrelab.study.soil)
    name = "LETE sand slip curve"
    rig = "single-wheel"                # a rig on soil (Rig.terrain "soil"), driven at each slip
    terrain = "lete-sand"               # a built-in soil (tyrelab soil list) or a soil .toml path
    slips = [0, 0.2, 0.4]               # driving s = 1 - V / (R_e omega) in [0, 1); braking
                                        # s = R_e omega / V - 1 in [-1, 0) (-1: locked)
    # torques = [0, 4000, 8000]         # or instead: driving torques [N m], the slip the soil's answer
    speeds_kmh = [3.6]
    loads = [23300]
    duration = 3.0                      # [s] optional (default 3 s: the steady part is the last half)
    # road = "flat"                     # optional: the soil's undisturbed surface (default flat)

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
* A soil test (:mod:`.spec_soil`): ``terrain`` only on a rig that runs on soil
  only (the single-wheel tester; the trailer and the quarter vehicle stay on the
  rigid road in a study), ``slips`` only on a rig that takes a slip, both then
  required (or, instead of ``slips``, ``torques`` on a rig that takes a driving
  torque); no ``group`` (its group is "soil") and no measured reference. Every
  model it runs must run on soil (``ContactModel.terrains``), as every model of a
  rigid-road test must run on the rigid road.
* In key paths of error messages, ``test[3]`` is the third ``[[test]]``
  table and ``speeds_kmh[2]`` the second element (counted from 1).

:meth:`StudySpec.runs` expands the matrix; :func:`run_key` names a run by
everything that determines its result (see there).
"""

from __future__ import annotations

import json
import re
import tomllib
from importlib import resources
from pathlib import Path

from .. import limits
from ..errors import InputError
from .checker import Checker, describe_value
from .keys import run_key, tyre_digest  # noqa: F401 - part of this module's API
from .records import (ModelSpec, ReferenceFile, RunSpec, StudySpec, TestSpec,  # noqa: F401
                      TyreSpec)
from .spec_tests import DEFAULT_DT, DEFAULT_OUTPUT_RATE, GROUPS, MAX_SPEED_KMH, MIN_SPEED_KMH, _tests  # noqa: F401
from .store import DEFAULT_STORAGE, STORAGE

#: the built-in thesis campaign (package data)
BUILTIN_SPEC = "thesis_campaign.toml"

_STUDY_KEYS = ("name", "output", "dt", "output_rate", "left_wheel", "store")
_TYRE_KEYS = ("name", "file", "pressure_kpa")
_MODEL_KEYS = ("name", "contact", "stiffness", "handling", "options", "relaxation")
_TOP_KEYS = ("study", "tyre", "model", "test", "metrics")
_METRICS_KEYS = ("limits",)


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
    store = ck.choice(t.get("store", DEFAULT_STORAGE), ("study", "store"), STORAGE, "store form")
    return name, output, dt, rate, left, store


def _tyres(ck: Checker, doc) -> tuple[TyreSpec, ...]:
    from ..limits import MAX_PRESSURE, MIN_PRESSURE
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
            if "pressure_kpa" in t:   # an MF-Tyre 6.x file moves (tyrelab.tyre.pressure.at_pressure)
                pressure = 1e3 * ck.number(t["pressure_kpa"], path + ("pressure_kpa",),
                                           "a pressure in kPa", low=MIN_PRESSURE / 1e3,
                                           high=MAX_PRESSURE / 1e3, low_open=False)
        try:  # read it now: a broken property file stops the study before it starts
            tyre = load_tyre(file, pressure)
        except InputError as exc:
            if exc.field == "pressure" and "pressure_kpa" in t:
                ck.fail(path + ("pressure_kpa",), exc.reason)
            ck.fail(path + ("file",), f"cannot use this tyre: {exc}")
        tyres.append((TyreSpec(name, file, pressure, builtin is not None), tyre))
    return tuple(tyres)


def _models(ck: Checker, doc, tyres) -> tuple[ModelSpec, ...]:
    from ..tyre.params import STIFFNESS_MODES
    from ..tyre.registry import contact_model, contact_models, handling_model, handling_models

    contacts, handlings = list(contact_models()), list(handling_models())
    models, seen = [], {}
    for i, raw in enumerate(ck.array_of_tables(doc, "model")):
        path = ("model", i)
        t = ck.table(raw, path, _MODEL_KEYS, required=("name", "contact"), what="a table [[model]]")
        name = ck.unique_label(t["name"], path + ("name",), seen, "model")
        contact = ck.choice(t["contact"], path + ("contact",), contacts, "contact model")
        needs = contact_model(contact).check_tyre
        if needs is not None:  # what the model needs of a tyre
            _every_tyre(ck, path + ("contact",), tyres, needs,
                        lambda tyre, exc: f"tyre '{tyre}' cannot run the {contact} model: {exc.reason}")
        stiffness = None
        if "stiffness" in t:
            stiffness = ck.choice(t["stiffness"], path + ("stiffness",), STIFFNESS_MODES, "stiffness")
            if stiffness == "table":
                for tyre_spec, tyre in tyres:
                    if not tyre.has_nonlinear_law:
                        ck.fail(path + ("stiffness",), f"tyre '{tyre_spec.name}' has no "
                                "[DEFLECTION_LOAD_CURVE] (nor MF-Tyre's Q_FZ2) for a table "
                                "stiffness; use \"linear\"")
        handling = None
        if "handling" in t:
            handling = ck.choice(t["handling"], path + ("handling",), handlings, "handling model")
            # its coefficients must be in every tyre's file
            _every_tyre(ck, path + ("handling",), tyres, handling_model(handling).build,
                        lambda tyre, exc: f"tyre '{tyre}' has no {handling} coefficients: {exc}")
        options = _options(ck, t.get("options"), path + ("options",), contact)
        relaxation = _relaxation(ck, t.get("relaxation", "auto"), path + ("relaxation",), tyres,
                                 handling)
        models.append(ModelSpec(name, contact, stiffness, handling, options, relaxation))
    return tuple(models)


def _relaxation(ck: Checker, raw, path, tyres, handling):
    """A model's ``relaxation``: a word or two lengths [m] (a tuple), possible for every tyre
    under the model's handling (the tyre file's when none is named)."""
    from ..api import default_handling
    from ..tyre.handling.relaxation import slip_lag
    from ..tyre.registry import handling_model

    value = tuple(raw) if isinstance(raw, list) else raw
    if value == "auto":  # always possible (and the default: no tyre's handling looked up)
        return value
    if not isinstance(value, (str, tuple)):
        ck.fail(path, f"expected \"auto\", \"off\", \"file\" or two lengths in metres "
                      f"[sigma_kappa, sigma_alpha], got {describe_value(raw)}")
    _every_tyre(ck, path, tyres,
                lambda tyre: slip_lag(tyre, handling_model(handling or default_handling(tyre)), value),
                lambda tyre, exc: f"tyre '{tyre}': {exc.reason}")
    return value


def _every_tyre(ck: Checker, key, tyres, check, says) -> None:
    """``check(tyre)`` for each of the spec's tyres; the first it refuses fails the spec at
    ``key`` with ``says(tyre's label, error)``."""
    for tyre_spec, tyre in tyres:
        try:
            check(tyre)
        except InputError as exc:
            ck.fail(key, says(tyre_spec.name, exc))


def _options(ck: Checker, raw, path, contact: str) -> tuple:
    """A model's ``options`` table as sorted ``(name, value)`` pairs, each checked against
    the contact model's options (name and type; :func:`tyrelab.tyre.registry.check_options`)."""
    from ..tyre.registry import check_options, contact_model
    if raw is None:
        return ()
    if not isinstance(raw, dict):
        ck.fail(path, f"expected a table of the '{contact}' model's options, e.g. "
                      "options = { n_length = 5 }")
    known = contact_model(contact).options
    options = {}
    for key, value in raw.items():
        if known.get(key) is object:
            ck.fail(path + (key,), f"the '{contact}' model's option {key} is set from Python only")
        try:
            options.update(check_options(contact, {key: value}))
        except InputError as exc:
            ck.fail(path + (key,), exc.reason)
    return tuple(sorted(options.items()))


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
    name, output, dt, rate, left, store = _study(ck, doc)
    tyres = _tyres(ck, doc)
    models = _models(ck, doc, tyres)
    tests = _tests(ck, doc, models, dt, rate, tyres)
    limits = _limits(ck, doc)
    return StudySpec(name, output, dt, rate, tuple(t for t, _ in tyres), models, tests, limits,
                     Path(src) if src != "<string>" else src, left, text, ck.base, store)


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
