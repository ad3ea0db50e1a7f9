"""The rig interface and registry: what carries the wheel, by name.

As Project Chrono's test rig takes any ``ChTire``, every tyrelab rig takes any
contact model: a rig is a :class:`Rig` record -- its name, how many wheels it
carries, whether it rolls over a road or stands on flat ground, its default
duration, its channels, what it asks of the tyre beyond the wheel interface, and
``run(request) -> signal table`` -- and :func:`tyrelab.simulate` drives every rig
through that record alone (no branch per rig). The five built-in rigs are
registered below; a plugin (:mod:`tyrelab.plugins`) registers its own with
:func:`register_rig`.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from typing import Any, Callable

from .. import plugins
from ..errors import InputError, named
from .frames import G


@dataclass(frozen=True)
class RigRequest:
    """One run as a rig receives it, every argument checked (SI).

    ``model`` is the test wheel's :class:`~tyrelab.tyre.model.TyreModel`; ``left`` the
    other wheel's of a two-wheel rig when it differs (None: the same model);
    ``road`` a :class:`~tyrelab.road.base.Road` (None for a rig that does not roll);
    ``load`` the load case name or wheel load as given and ``wheel_load`` the
    static wheel load it means [N]; ``duration`` [s] is None for "to the road's end";
    ``terrain`` the deformable ground's name or file (None: the rigid road); ``options``
    the rig's own options (:attr:`Rig.options`), checked."""

    model: Any
    left: Any
    road: Any
    speed: float
    load: Any
    wheel_load: float
    duration: float | None
    dt: float
    output_rate: float
    progress: bool | None
    terrain: Any = None
    options: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Rig:
    """A rig as the registry knows it.

    Attributes
    ----------
    name : str
        The name users type (``--rig``, a study test's ``rig``).
    run : callable
        ``run(request: RigRequest) -> pandas.DataFrame``: the signal table
        (:func:`tyrelab.rig.simulation.to_signal`), starting in equilibrium.
    summary : str
        One line for listings and the command line's help.
    wheels : int
        Wheels carried: 2 lets the other wheel run another contact model
        (``left_wheel``; it runs on flat ground).
    rolls : bool
        True: the rig rolls over the road at the speed asked for; False: it stands
        on flat ground (a drop test) and ignores road and speed.
    default_duration : float, optional
        Simulated time [s] when none is given; None: until the road ends.
    channels : str
        ``"module:NAME"`` of the rig's channel tuple (the signal table's columns,
        in order), read when asked for (:attr:`channel_names`).
    check : callable, optional
        ``check(model, wheel_load)``: what the rig asks of the tyre beyond the
        wheel interface, raising :class:`~tyrelab.errors.InputError` when it is not
        met (the quarter vehicle carries the wheel's mass on the tyre).
    options : dict
        The rig's own options (``simulate(rig_options=...)``, ``--slip``), name -> type.
    terrain : str
        ``"rigid"``: runs on the rigid road only; ``"soil"``: needs a deformable
        terrain (``--terrain``); ``"any"``: either.
    default_road : str
        The road (the soil's initial surface for a soil rig) when none is given.
    """

    name: str
    run: Callable[[RigRequest], Any]
    summary: str = ""
    wheels: int = 1
    rolls: bool = True
    default_duration: float | None = None
    channels: str = ""
    check: Callable[..., None] | None = None
    options: dict = field(default_factory=dict)
    terrain: str = "rigid"
    default_road: str = "cleat:50x50"

    @property
    def channel_names(self) -> tuple[str, ...]:
        """The rig's output channels, in the signal table's order."""
        module, _, name = self.channels.partition(":")
        return tuple(getattr(importlib.import_module(module), name)) if module else ()


_RIGS: dict[str, Rig] = {}


def register_rig(rig: Rig) -> Rig:
    """Make ``rig`` known by its name (a later registration of a name replaces it)."""
    _RIGS[rig.name] = rig
    return rig


def rigs() -> dict[str, Rig]:
    """Every registered rig by name: the built-in ones, then the plugins' in their order."""
    plugins.load()
    return dict(_RIGS)


def check_rig_options(rig: Rig, options: dict | None) -> dict:
    """``options`` for ``rig`` (a new dict), or InputError naming the unknown keys and the ones
    the rig takes (checked as a contact model's are: :func:`tyrelab.tyre.registry.checked_options`)."""
    from ..tyre.registry import checked_options
    return checked_options(options, rig.options, f"the '{rig.name}' rig", "rig_options")


def rig_named(name: str) -> Rig:
    """The rig called ``name``; an unknown name lists the known ones."""
    return named(rigs(), name, "rig", "rig")


# --- the built-in rigs ------------------------------------------------------------------------

def _trailer(req: RigRequest):
    from .trailer import Trailer
    return Trailer(req.model, req.load, left=req.left).run(req.road, req.speed, req.duration, req.dt,
                                                          req.output_rate, req.progress, req.terrain)


def _trailer_drop(req: RigRequest):
    from .trailer import Trailer
    return Trailer(req.model, req.load, left=req.left).drop(duration=req.duration, dt=req.dt,
                                                           output_rate=req.output_rate,
                                                           progress=req.progress)


def _rolling(req: RigRequest):
    from .rolling import roll
    return roll(req.model, req.road, req.speed, load=req.load, duration=req.duration, dt=req.dt,
                output_rate=req.output_rate, progress=req.progress)


def _quarter(req: RigRequest):
    """The quarter vehicle carrying ``wheel_load``: its body is the load less the wheel's mass
    (the tyre's wheel mass, else a tenth of the load)."""
    from .quarter_vehicle import QuarterVehicle
    mu = req.model.tyre.wheel_mass or 0.1 * req.wheel_load / G
    return QuarterVehicle(req.model, sprung_mass=req.wheel_load / G - mu, unsprung_mass=mu)


def _quarter_run(req: RigRequest):
    return _quarter(req).run(req.road, req.speed, req.duration, req.dt, req.output_rate, req.progress,
                             req.terrain)


def _quarter_drop(req: RigRequest):
    return _quarter(req).drop(duration=req.duration, dt=req.dt, output_rate=req.output_rate,
                              progress=req.progress)


def _carries_wheel_mass(model, wheel_load: float) -> None:
    """The quarter vehicle's tyre carries the wheel too: the load must exceed its weight."""
    weight = model.tyre.wheel_mass * G
    if weight >= wheel_load:
        raise InputError(f"wheel load {wheel_load:.6g} N does not exceed the weight of the wheel "
                         f"({model.tyre.wheel_mass:.6g} kg) the quarter vehicle carries; allowed: above "
                         f"{weight:.6g} N", field="load")


def _single_wheel(req: RigRequest):
    from .single_wheel import single_wheel
    if "slip" in req.options and "torque" in req.options:
        raise InputError("the single-wheel tester takes a slip or a driving torque, not both",
                         field="torque")
    return single_wheel(req.model, req.terrain, req.wheel_load, req.speed, slip=req.options.get("slip", 0.0),
                        duration=req.duration, dt=req.dt, output_rate=req.output_rate,
                        progress=req.progress, road=req.road, torque=req.options.get("torque"))


register_rig(Rig("trailer", _trailer, "the towed test trailer (thesis 3.4), two wheels", wheels=2,
                 channels="tyrelab.rig._trailer_kernel:CHANNELS", terrain="any"))
register_rig(Rig("quarter-vehicle", _quarter_run, "a sprung mass over one wheel",
                 channels="tyrelab.rig._quarter_kernel:CHANNELS", check=_carries_wheel_mass,
                 terrain="any"))
register_rig(Rig("rolling", _rolling, "the axle at the static height of the load, rolled",
                 channels="tyrelab.rig.rolling:CHANNELS"))
register_rig(Rig("drop", _trailer_drop, "the trailer's drop test (thesis 3.4.1)", wheels=2,
                 rolls=False, default_duration=3.0, channels="tyrelab.rig._trailer_kernel:CHANNELS"))
register_rig(Rig("wheel-drop", _quarter_drop, "the quarter vehicle dropped the same way",
                 rolls=False, default_duration=2.0, channels="tyrelab.rig._quarter_kernel:CHANNELS",
                 check=_carries_wheel_mass))
register_rig(Rig("single-wheel", _single_wheel, "a soil bin's single-wheel tester: prescribed speed "
                 "and slip or driving torque, dead-weight load",
                 channels="tyrelab.rig.single_wheel:CHANNELS",
                 options={"slip": float, "torque": float}, terrain="soil", default_road="flat"))
