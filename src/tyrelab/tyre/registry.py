"""The model registry: every contact and handling model, by name and by record type.

A model registers itself in its own module (``register_contact(...)`` at the
bottom of the file); this module only imports the built-in ones on first
use, in the order of :data:`BUILTIN_CONTACT` and :data:`BUILTIN_HANDLING`.
Adding a model: write its module (parameter record, ``build``, compiled
geometry or step), call ``register_contact`` there, and add its module to
the tuple below -- see ARCHITECTURE.md, "Adding a contact model".

The compiled side finds a model's code from the type of its parameter
record (:func:`contact_by_record`), at compile time: numba specialises each
rig loop per combination of record types and caches each specialisation,
so no model id, flag or generated entry function is needed.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from .. import plugins
from ..errors import InputError, named


#: modules that register the built-in contact models (one line per model module)
BUILTIN_CONTACT = (
    "tyrelab.tyre.contact.point",
    "tyrelab.tyre.contact.volume",
    "tyrelab.tyre.contact.enveloping",
    "tyrelab.tyre.contact.enveloping_edge",
    "tyrelab.tyre.ring.model",
    "tyrelab.tyre.contact.soil_wheel",
)
#: modules that register the built-in handling models
BUILTIN_HANDLING = (
    "tyrelab.tyre.handling.none",
    "tyrelab.tyre.handling.pac89",
    "tyrelab.tyre.handling.mf.wheel",
    "tyrelab.tyre.handling.tmeasy",
    "tyrelab.tyre.handling.tmsimple",
    "tyrelab.tyre.handling.fiala",
)


def no_state(tyre, load, params, **options) -> np.ndarray:
    """The internal state of a model that keeps none."""
    return np.zeros(0)


@dataclass(frozen=True)
class ContactModel:
    """A contact model as the registry knows it.

    Attributes
    ----------
    name : str
        The name users type (``--model``).
    record : type
        Its parameter record (a NamedTuple class); the compiled code is
        chosen by this type.
    build : callable
        ``build(tyre, road, **options) -> record``; ``road`` is the ground it
        will run on (a :class:`~tyrelab.road.grid.RoadGrid`, asked only through
        the ``Ground`` protocol of :mod:`tyrelab.road.terrain_registry`; the soil
        bed for a soil model).
    geometry : numba dispatcher, optional
        Analytic models: ``geometry(params, road, pose) -> ContactGeometry``;
        the shared vertical law and handling models make the loads.
    step : numba dispatcher, optional
        Models with their own dynamics: ``step(wheel, pose, dt) -> WheelLoads``
        advances ``wheel.state`` by ``dt``.
    initial_state : callable
        ``initial_state(tyre, load, params, **options) -> state`` in static
        equilibrium under ``load`` [N] on a flat road.
    equilibrium : callable, optional
        ``equilibrium(tyre, load, speed, params, **options) -> (deflection,
        spin, state)``: where a rig starts the wheel carrying ``load`` [N]
        while rolling freely at ``speed`` [m/s] on a flat road, for models
        whose own load-deflection is not the tyre's vertical law (the
        ring). Without it: the vertical law's static deflection,
        ``speed / (R0 - deflection)`` and ``initial_state``.
    static_options : dict or callable
        Options added (unless the user gave them) when the model is built
        for a static test, e.g. the ring's relaxation damping; a callable
        takes the road grid and returns them.
    footprint : callable, optional
        ``footprint(wheel, load, deflection, tyre) -> dict`` from a wheel
        pressed on the plate (models with a pressure distribution, the ring);
        without it the static press draws the geometric footprint.
    summary : str
        One line for listings.
    cost : float, optional
        Wall time [s] per simulated second on the trailer at a 1 ms step on one
        core (README benchmarks): orders a study's runs, longest first, and
        estimates a request's time (:func:`tyrelab.resources.model_cost`; None: by
        kind). The built-in models state the mean over the built-in campaign's runs
        (its ``index.parquet``: ``wall_time_s`` over ``simulated_s``, two workers on
        two cores, 2026-11-27): ring 0.080, ring-tp 0.085, enveloping 0.022,
        enveloping-edge 0.011 (0.022 before it rested only its outline's cams), volume
        0.017, point 0.003. Only the ratios order the runs
        and set the study's "time left"; a ring costed 2.5 times too high made it
        say "22 s left" with 58 s of runs to go.
    parameterization : str
        What the model must be given, measured (thesis chapter 4), in a few
        words: the study report's cost table.
    terrains : tuple of str
        The kinds of ground it runs on (:func:`tyrelab.registry.terrains`):
        ``("rigid",)`` for the road models, ``("soil",)`` for the rigid wheel.
    fit_steps : tuple of str
        The steps of ``tyrelab fit`` (:data:`tyrelab.fit.workflow.STEPS`) that
        identify its parameters from a test campaign; a model with none here
        is not predicted by the fit's held-out cleat tests.
    options : dict
        The options ``build`` takes that a user may set (``simulate(options=...)``,
        ``--option KEY=VALUE``, a study spec's ``options`` table), name -> type
        (``int``, ``float``, ``bool``, ``str``, or ``object`` for a Python value);
        :func:`check_options` refuses any other name and a value of another type.
    check_values : callable, optional
        ``check_values(options)`` refuses an option's impossible value (an
        :class:`InputError` whose field is the option's name) before any work is
        started: :func:`check_options` calls it, so the command line and a study
        spec's check refuse the value, not the run; ``build`` checks again.
    carried : callable, optional
        ``carried(tyre, **options) -> tyrelab.limits.Carried``: the mass [kg] and the spin
        inertia about the axle [kg m^2] the model's own state carries (the ring's belt: its
        mass, at the belt radius); the rigs move and turn the rim with the rest
        (:func:`tyrelab.guards.rig_rim_mass`, :func:`tyrelab.guards.rig_spin_inertia`).
        Without it (the analytic models): nothing, the rigs move the whole wheel.
    check_tyre : callable, optional
        ``check_tyre(tyre)`` refuses a tyre that lacks what the model needs (an
        :class:`InputError` saying what, e.g. the ring's ``[FLEXIBLE_RING]``) before
        any work: a study spec's check calls it for each of its tyres, so a run does
        not fail halfway through a campaign; ``build`` refuses it again.
    """

    name: str
    record: type
    build: Callable[..., Any]
    geometry: Any = None
    step: Any = None
    initial_state: Callable[..., Any] = no_state
    equilibrium: Callable[..., Any] | None = None
    static_options: Any = field(default_factory=dict)
    footprint: Callable[..., Any] | None = None
    summary: str = ""
    options: dict = field(default_factory=dict)
    cost: float | None = None
    parameterization: str = ""
    fit_steps: tuple = ()
    terrains: tuple = ("rigid",)
    check_values: Callable[[dict], Any] | None = None
    check_tyre: Callable[[Any], Any] | None = None
    carried: Callable[..., Any] | None = None

    def __post_init__(self):
        if (self.geometry is None) == (self.step is None):
            raise ValueError(f"contact model {self.name!r} needs exactly one of geometry, step")

    @property
    def has_state(self) -> bool:
        return self.step is not None


@dataclass(frozen=True)
class HandlingModel:
    """A handling (tangential force) model.

    ``forces(params, fz, v_long, v_slip_x, v_slip_y, gamma)`` (compiled)
    returns ``(FXW, FYW, MZW, kappa, alpha, dFXW/dkappa)``; ``build(tyre)``
    returns its parameter record. ``rolling_radius(params, fz, omega)`` (compiled,
    optional) is the effective rolling radius Re [m] the model's longitudinal slip is
    defined with (``kappa = (omega Re - Vx) / |Vx|``; the Magic Formula's, from ``BREFF``,
    ``DREFF``, ``FREFF``); without it the slip is the contact point's, whose lever is the
    loaded radius. ``relaxation_lengths(params, fz, v_long, gamma)`` (compiled, optional)
    gives the model's own relaxation lengths ``(sigma_kappa, sigma_alpha)`` [m] at a load
    (the Magic Formula's), which its transient slip takes when asked for the file's
    (:mod:`tyrelab.tyre.handling.relaxation`); without it only given lengths lag the slip.
    ``rolling_resistance(params, fz, fx, v_long, omega, kappa, gamma, radius)`` (compiled,
    optional) is its rolling resistance moment My [N m] about the W-axis y (the spin axis;
    negative when rolling forward) at the loaded radius ``radius`` [m] (the contact point's
    distance from the wheel centre; Chrono's PAC89 uses it), which the wheel step adds to the
    tyre's moments.
    ``overturning(params, fz, fy, v_long, gamma)`` (compiled, optional) is its overturning
    moment Mx [N m] about the W-axis x at the contact point (the Magic Formula's QSX terms,
    Chrono's PAC89's ``Fz FYW / k_y``: the pressure's centre shifted across the patch by
    camber and lateral force), which the wheel step adds too; without it the tyre's loads
    act at the contact point.
    ``mirror(params)`` (Python, optional) returns the record of the same tyre mirrored through
    its wheel plane: a rig mounting it on the other side of a vehicle than its file's
    ``TYRESIDE`` uses it (:meth:`~tyrelab.tyre.model.TyreModel.handling_params`); without it
    the model's tyre is the same on either side.
    """

    name: str
    record: type
    build: Callable[..., Any]
    forces: Any
    summary: str = ""
    rolling_radius: Any = None
    relaxation_lengths: Any = None
    rolling_resistance: Any = None
    overturning: Any = None
    mirror: Any = None

    def at_slips(self, params, fz: float, speed: float, kappa: float, tan_alpha: float):
        """:attr:`forces` where the ISO slips are ``kappa`` and ``tan alpha`` at forward speed
        ``speed`` [m/s] (the slip velocities ``-kappa V`` and ``V tan alpha``), zero camber:
        a model's curves evaluated point by point (Python side)."""
        return self.forces(params, fz, speed, -kappa * speed, tan_alpha * speed, 0.0)


_CONTACT: dict[str, ContactModel] = {}
_HANDLING: dict[str, HandlingModel] = {}
_loaded = False


def register_contact(model: ContactModel) -> ContactModel:
    """Make ``model`` known by its name (a later registration of a name replaces it)."""
    _CONTACT[model.name] = model
    return model


def register_handling(model: HandlingModel) -> HandlingModel:
    """Make handling ``model`` known by its name."""
    _HANDLING[model.name] = model
    return model


def _load_builtins() -> None:
    """Import the built-in models' modules, then the plugins (:mod:`tyrelab.plugins`)."""
    global _loaded
    if not _loaded:
        _loaded = True
        for module in BUILTIN_CONTACT + BUILTIN_HANDLING:
            importlib.import_module(module)
    plugins.load()


def _ordered(registry, builtin):
    """Built-in models in the order of their modules' list, then the others as registered."""
    rank = {module: k for k, module in enumerate(builtin)}
    # sorted() is stable: models of one module, and all others, keep their registration order
    return dict(sorted(registry.items(),
                       key=lambda item: rank.get(item[1].build.__module__, len(rank))))


def contact_models() -> dict[str, ContactModel]:
    """Every registered contact model by name (built-ins first, in a fixed order)."""
    _load_builtins()
    return _ordered(_CONTACT, BUILTIN_CONTACT)


def handling_models() -> dict[str, HandlingModel]:
    """Every registered handling model by name (built-ins first, in a fixed order)."""
    _load_builtins()
    return _ordered(_HANDLING, BUILTIN_HANDLING)


def contact_model(name: str) -> ContactModel:
    """The contact model called ``name``; an unknown name lists the known ones."""
    return named(contact_models(), name, "model", "model")


def check_options(name: str, options: dict | None, field: str = "options") -> dict:
    """``options`` for the contact model ``name`` (a new dict), or InputError naming the
    unknown keys and the ones the model takes (:attr:`ContactModel.options`)."""
    model = contact_model(name)
    checked = checked_options(options, model.options, f"the '{name}' model", field)
    if model.check_values is not None:
        model.check_values(checked)
    return checked


def checked_options(options: dict | None, declared: dict, owner: str, field: str) -> dict:
    """``options`` checked against ``declared`` (name -> type) of ``owner`` ("the 'ring' model",
    "the 'single-wheel' rig"): a new dict, integers turned into floats where a number is
    declared; an unknown name or a value of another type is an InputError listing the names."""
    if options is not None and not isinstance(options, Mapping):
        raise InputError(f"the options of {owner} are a mapping of names to values, like "
                         f"{{'name': value}}, got {options!r}", field=field)
    options = dict(options or {})
    unknown = sorted(set(options) - set(declared))
    if unknown:
        allowed = ", ".join(declared) if declared else "none"
        raise InputError(f"unknown option(s) {', '.join(unknown)} of {owner}; it takes: {allowed}",
                         field=field)
    for key, value in options.items():
        options[key] = _typed(owner, key, value, declared[key], field)
    return options


_TYPE_WORDS = {int: "a whole number", float: "a number", bool: "true or false", str: "a text"}


def _typed(owner: str, key: str, value, kind, field: str):
    """``value`` as an option of type ``kind`` (an integer is a number too, a whole float an
    integer), or InputError."""
    if kind is object:
        return value
    if kind is float and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    if kind is int and isinstance(value, float) and value.is_integer():
        return int(value)  # TOML and the command line read 1e3 as a float
    if isinstance(value, kind) and not (kind is int and isinstance(value, bool)):
        return value
    raise InputError(f"option {key} of {owner}: expected {_TYPE_WORDS.get(kind, kind)}, "
                     f"got {value!r}", field=field)


def handling_model(name: str) -> HandlingModel:
    """The handling model called ``name``; an unknown name lists the known ones."""
    return named(handling_models(), name, "handling model", "handling")


def _by_record(registry, numba_type, what):
    _load_builtins()
    cls = getattr(numba_type, "instance_class", None)
    for model in registry.values():
        if model.record is cls:
            return model
    raise TypeError(f"{numba_type} is not the parameter record of a registered {what} model")


def contact_by_record(numba_type) -> ContactModel:
    """The contact model whose parameter record has numba type ``numba_type`` (compile time)."""
    return _by_record(_CONTACT, numba_type, "contact")


def handling_by_record(numba_type) -> HandlingModel:
    """The handling model whose parameter record has numba type ``numba_type`` (compile time)."""
    return _by_record(_HANDLING, numba_type, "handling")
