"""The ground of a ``[[test]]`` table: ``terrain``, ``slips`` or ``torques`` and the models that run on it.

A test on the rigid road names no terrain. A rig that runs on soil only (the
single-wheel tester) needs ``terrain``, and only such a rig takes one here (the
trailer and the quarter vehicle also run on soil in :func:`tyrelab.simulate`, but
a study compares their runs as the thesis's rigid-road tests, so it keeps them
there): a built-in soil's name (``tyrelab soil
list``) or a soil file (TOML, relative to the spec's folder), read now so a bad
soil stops the study before it starts. A rig that drives at a prescribed slip
(the single-wheel tester) needs ``slips``, each in [-1, 1), or instead ``torques``
[N m], the driving torques the wheel spins freely under (its slip then the soil's
answer); its test is a *soil test* (:attr:`tyrelab.study.records.TestSpec.is_soil_test`). Each model a test
runs must run on its ground (:attr:`tyrelab.tyre.registry.ContactModel.terrains`).
Every mistake is one :class:`~tyrelab.errors.InputError` naming file, line and
key path (:class:`~.checker.Checker`).
"""

from __future__ import annotations

import json

from ..errors import InputError
from .checker import Checker, describe_value

#: simulated time of a soil test's run when the test gives none [s]: the default of
#: :func:`tyrelab.rig.single_wheel.slip_curve`, whose last half is the steady state
DEFAULT_SOIL_DURATION = 3.0
#: the group of every soil test (the thesis's groups are for its rigid-road tests)
SOIL_GROUP = "soil"


def ground_of(terrain: str | None):
    """The kind of ground a test runs on: the registered
    :class:`~tyrelab.road.terrain.TerrainKind` its terrain names (the rigid grid's without one)."""
    from ..road.terrain import resolve_terrain, terrain_kind
    return terrain_kind("rigid") if terrain is None else resolve_terrain(terrain)[0]


def check_terrain(ck: Checker, t: dict, path, rig) -> str | None:
    """The test's ``terrain`` as the study passes it to :func:`tyrelab.simulate`: a built-in
    soil's name (lower case) or a soil file's absolute path; None on the rigid road."""
    from ..road.soil import soil_names
    from ..road.terrain import resolve_terrain, terrain_kinds
    from ..rig.registry import rigs

    if "terrain" not in t:
        if rig.terrain == "soil":
            ck.fail(path, f"missing key 'terrain': the {rig.name} rig runs on soil; give a built-in "
                    f"soil ({', '.join(soil_names())}) or a soil file FILE.toml")
        return None
    key = path + ("terrain",)
    if rig.terrain == "rigid":
        on_soil = [name for name, r in rigs().items() if r.terrain != "rigid"]
        ck.fail(key, f"the {rig.name} rig runs on the rigid road only; a terrain needs a rig on "
                f"soil: {', '.join(on_soil)}")
    if rig.terrain != "soil":  # "any": a study evaluates these rigs on the thesis's terms only
        soil_rigs = [name for name, r in rigs().items() if r.terrain == "soil"]
        ck.fail(key, f"a study runs the {rig.name} rig on the rigid road only (its runs are "
                "compared as the thesis's rigid-road tests are); soil tests use a rig on soil: "
                f"{', '.join(soil_rigs)} (the {rig.name} on soil: tyrelab.simulate(terrain=...))")
    text = ck.string(t["terrain"], key, "a soil's name or a soil file FILE.toml").strip()
    if text.lower().endswith(".toml"):
        terrain = str(ck.path(text, key, "soil file"))
    elif text.lower() in soil_names():
        terrain = text.lower()
    else:
        terrain = text                       # another registered kind's (a plugin's) value
        try:
            resolve_terrain(terrain)
        except InputError:
            others = "; ".join(f"{k.name}: {k.hint}" for k in terrain_kinds().values()
                               if k.resolve is not None and k.name != "soil")
            ck.fail(key, f"unknown soil {json.dumps(text)}; expected one of: "
                    f"{', '.join(soil_names())} or a soil file FILE.toml"
                    + (f" (or another terrain: {others})" if others else ""))
    try:  # read it now: a broken soil file stops the study before it starts
        resolve_terrain(terrain)
    except InputError as exc:
        ck.fail(key, f"cannot use this soil: {exc}")
    return terrain


def check_slips(ck: Checker, t: dict, path, rig) -> tuple[float, ...]:
    """The test's ``slips`` (each in [-1, 1), no repeats: braking to -1, locked, driving below 1,
    spinning in place; :func:`tyrelab.rig.single_wheel.wheel_spin`); () for a rig without a slip."""
    from ..rig.registry import rigs

    takes_slip = "slip" in rig.options
    if "slips" not in t:
        if takes_slip and "torques" not in t:
            ck.fail(path, f"missing key 'slips': the {rig.name} rig drives at prescribed slips, "
                    "e.g. slips = [0, 0.2, 0.4] (or under driving torques, torques = [0, 5000] N m)")
        return ()
    key = path + ("slips",)
    if not takes_slip:
        with_slip = [name for name, r in rigs().items() if "slip" in r.options]
        ck.fail(key, f"the {rig.name} rig takes no slip; slips are for the rigs that drive at a "
                f"prescribed slip: {', '.join(with_slip)}")
    def below_one(s, v, at):
        if s >= 1.0:
            ck.fail(at, f"expected a slip in [-1, 1) (1 spins in place, at no speed), got {v!r}")

    return _distinct_numbers(ck, t["slips"], key, "slips in [-1, 1)", "slip",
                             "a slip in [-1, 1) (driving s = 1 - V / (R_e omega), braking "
                             "s = R_e omega / V - 1)", below_one, low=-1.0, high=1.0, low_open=False)


def _distinct_numbers(ck: Checker, value, key, plural: str, singular: str, what: str, check=None,
                      **bounds) -> tuple[float, ...]:
    """A non-empty array of ``plural`` at ``key``, each a number (``what``, within ``bounds``:
    :meth:`Checker.number`) that ``check(number, as written, its key)`` accepts, none twice."""
    if not isinstance(value, list) or not value:
        got = describe_value(value) if not isinstance(value, list) else "an empty array"
        ck.fail(key, f"expected a non-empty array of {plural}, got {got}")
    numbers = []
    for k, v in enumerate(value):
        x = ck.number(v, key + (k,), what, **bounds)
        if check is not None:
            check(x, v, key + (k,))
        if x in numbers:
            ck.fail(key + (k,), f"duplicate {singular} {v!r}")
        numbers.append(x)
    return tuple(numbers)


def check_torques(ck: Checker, t: dict, path, rig) -> tuple[float, ...]:
    """The test's ``torques`` [N m] (finite, no repeats; negative brakes, 0 tows the wheel:
    :func:`tyrelab.rig.single_wheel.single_wheel`), on a rig that takes a driving torque
    and in a test without ``slips``; () when the test has none."""
    from ..rig.registry import rigs

    if "torques" not in t:
        return ()
    key = path + ("torques",)
    if "torque" not in rig.options:
        with_torque = [name for name, r in rigs().items() if "torque" in r.options]
        ck.fail(key, f"the {rig.name} rig takes no driving torque; torques are for the rigs that "
                f"turn the wheel under one: {', '.join(with_torque)}")
    if "slips" in t:
        ck.fail(key, "a test drives the wheel at prescribed slips or under driving torques, not "
                "both; make two tests")
    return _distinct_numbers(ck, t["torques"], key, "driving torques in N m", "torque",
                             "a driving torque in N m (negative brakes, 0 tows the wheel)")


def check_models_on_ground(ck: Checker, path, names, models, terrain: str | None,
                           listed: bool) -> None:
    """Every model ``names`` labels runs on the test's ground; else a line naming the model,
    at its place in the test's ``models`` (``listed``) or at the test."""
    from ..rig.soil_ground import runs_on
    from ..tyre.registry import contact_model

    kind = ground_of(terrain)
    for k, name in enumerate(names):
        contact = next(m.contact for m in models if m.name == name)
        entry = contact_model(contact)
        if not runs_on(entry, kind):
            where = {"soil": "on soil", "rigid": "on the rigid road"}.get(kind.name, f"on {kind.name}")
            hint = ("remove it from this test's models" if listed else
                    "give this test a models list without it")
            ck.fail(path + ("models", k) if listed else path,
                    f"model {json.dumps(name)} ({contact}) does not run {where} (it runs on: "
                    f"{', '.join(entry.terrains)}); {hint}")
