"""The stepping API: a tyre model as a wheel that the user's vehicle model moves.

>>> from tyrelab.cosim import WheelCentre, wheel_stepper
>>> wheel = wheel_stepper("xzl-16.00R20", "point", "cleat:50x50")          # doctest: +SKIP
>>> loads = wheel.step(0.0, WheelCentre(x=0.0, y=0.0, z=0.63, vx=3.33, vy=0.0, vz=0.0,
...                                     omega=5.4), dt=1e-3)                 # doctest: +SKIP
>>> loads.fz                                                                   # doctest: +SKIP

As Project Chrono's ``ChTire`` (synchronise with the wheel's state, advance,
report the force): :meth:`WheelStepper.step` takes the wheel centre's pose,
velocities and spin at the start of a step (:class:`~.kernel.WheelCentre`),
advances the model's internal state over the step (the ring's belt and
tread blocks; the analytic models have none) in sub-steps no longer than
the model's stable step, and returns the loads of the road on the tyre at
the wheel centre over the step (:class:`~.kernel.CentreLoads`). The rigs
step the same kernel (:func:`tyrelab.tyre.wheel.wheel_step`): a host that
moves the wheel as a rig does gets the rig's loads, to round-off.

The host owns the wheel's motion: its position, its velocity and its spin
(integrate the spin with ``MY`` and :attr:`WheelStepper.spin_inertia`, the rim's for the
ring, whose belt turns its own; ``dmy_domega`` lets it do so implicitly, as the rigs do:
the ring's light rim needs it). The ring's belt also moves its own mass
(:attr:`WheelStepper.carried`): move the rim with the rest. Conventions: SI, the road
frame and the TYDEX C-axis sign convention of :mod:`tyrelab.signal` (loads of the road on
the tyre).
"""

from __future__ import annotations

import copy
import math
from functools import partial

from .. import limits
from ..api import make_tyre_model
from ..errors import InputError
from ..guards import physics_warning
from ..road.terrain import ground_range
from ..rig.soil_ground import KEEP_AHEAD, KEEP_BEHIND, on_fresh_ground
from ..tyre.model import TyreModel
from .kernel import C_AXIS_FRAME, ROAD_FRAME, CentreLoads, WheelCentre, advance

#: the frames the loads at the wheel centre may be given in (``frame``), by name
FRAMES = {"C-axis": C_AXIS_FRAME, "road": ROAD_FRAME}
#: relative tolerance on a step's start time against the stepper's own time
TIME_TOLERANCE = 1e-9
#: the internal step when no stable step can be stated (a tyre without a wheel mass, no load) [s]
DEFAULT_STEP = 1e-3


class WheelStepper:
    """A wheel a host steps: the model's state, its road and its time.

    Build one with :func:`wheel_stepper` (by names) or from a
    :class:`~tyrelab.tyre.model.TyreModel` and its
    :class:`~tyrelab.tyre.wheel.Wheel` record.

    Parameters
    ----------
    model : TyreModel
        The tyre and its contact and handling models.
    wheel : Wheel
        The record the compiled step takes (``model.wheel(ground, load, state=...)``);
        its state is advanced in place.
    max_step : float
        Longest internal step [s]; a step of length ``dt`` runs
        ``ceil(dt / max_step)`` equal sub-steps.
    frame : {"C-axis", "road"}
        Frame of the forces and moments at the wheel centre: the wheel's TYDEX
        C-axis system (:mod:`tyrelab.signal`) or the road frame.
    start_time : float
        Time [s] of the wheel's initial state.
    equilibrium : Equilibrium, optional
        Where the wheel's state was started (:meth:`TyreModel.equilibrium`):
        its ``deflection`` puts the wheel centre at ``R0 - deflection`` above
        a level road, its ``spin`` is the free-rolling spin.
    ground : optional
        The Python ground whose record the wheel holds. One that holds only a
        part of itself at a time and moves with the wheel is moved on before each
        step to cover it, with the rigs' margins
        (:data:`~tyrelab.rig.soil_ground.KEEP_BEHIND`, ``KEEP_AHEAD``): in x and y
        for a window that follows the wheel anywhere (the soil's field,
        :meth:`~tyrelab.road.soil.field.SoilField.cover`; several steppers may share one,
        the window then holding every wheel on it), forward along x for a strip (the
        rigs' active patch, :meth:`~tyrelab.road.soil.patch.SoilPatch.follow`).
    """

    def __init__(self, model: TyreModel, wheel, max_step: float, frame: str = "C-axis",
                 start_time: float = 0.0, equilibrium=None, ground=None, load: float = 0.0):
        if frame not in FRAMES:
            raise InputError(f"unknown frame '{frame}', expected one of {', '.join(FRAMES)}",
                             field="frame")
        if not (math.isfinite(max_step) and max_step > 0):
            raise InputError(f"the internal step must be a positive number of seconds, got "
                             f"{max_step!r}", field="max_step")
        if not math.isfinite(start_time):
            raise InputError(f"the start time must be a finite number, got {start_time!r}",
                             field="start_time")
        self.model = model
        self.wheel = wheel
        self.max_step = float(max_step)
        self.frame = frame
        self._frame = FRAMES[frame]
        self._time = float(start_time)
        self.equilibrium = equilibrium
        self.load = float(load)
        self._ground = ground
        self._cover = getattr(ground, "cover", None)
        self._follow = getattr(ground, "follow", None)
        self._held = getattr(ground, "held", None)
        # where the host's wheel leaves what the model holds (_check_pose): its centre below a
        # rigid road's highest point (then looked up; a soil has no height here: a wheel sinks
        # into it), or a deflection beyond the rim; each threshold is lifted once warned
        self._height = getattr(ground, "height", None)
        self._look_below = (float(ground_range(wheel.road)[1]) if self._height is not None
                            else -math.inf)
        self._rim_room, self._rim_how = limits.rim_deflection(model.tyre)
        #: what a finding of :meth:`_check_pose` is given to: a PhysicsWarning by default, as the
        #: rigs' guards give theirs, pointed at the host's call; the FMU's slave logs it through
        #: the host's logger instead
        self.warn = partial(physics_warning, stacklevel=4)

    @property
    def time(self) -> float:
        """The time [s] the model's state has been advanced to."""
        return self._time

    @property
    def spin_inertia(self) -> float:
        """The spin inertia [kg m^2] to turn the wheel with, as the rigs do
        (:func:`tyrelab.guards.rig_spin_inertia`): the wheel's (``WHEEL_IYY``), or for a model
        whose own state carries the tyre's (the ring's belt) the rim's, the wheel's less the
        tyre's own ``IYY`` (:func:`tyrelab.limits.rim_spin_inertia`; the XZL's ring: 3.4 of
        50 kg m^2). Turning the ring's rim with the whole wheel's counts the tyre's twice."""
        from ..guards import rig_spin_inertia
        return rig_spin_inertia(self.model, self.load)

    @property
    def carried(self):
        """What the model's own state moves of the wheel (:class:`tyrelab.limits.Carried`: the
        ring's belt, the XZL's 154 kg and 64.4 kg m^2; nothing for the analytic models): its
        inertia is in the loads, so a host moves its rim with the wheel's mass less
        ``carried.mass`` (the weight stays the whole wheel's: the belt has none of its own) and
        turns it with :attr:`spin_inertia`."""
        from ..guards import carried_inertia
        return carried_inertia(self.model)

    @property
    def carried_mass(self) -> float:
        """``carried.mass`` [kg] (the FMU's ``CARRIED_MASS``)."""
        return float(self.carried.mass)

    def sub_steps(self, dt: float) -> int:
        """How many internal steps a step of ``dt`` [s] takes."""
        return max(1, math.ceil(dt / self.max_step - 1e-9))

    def step(self, time: float, centre: WheelCentre, dt: float) -> CentreLoads:
        """Advance the wheel from ``time`` to ``time + dt`` [s]; the loads over the step.

        Parameters
        ----------
        time : float
            Start of the step [s]: the stepper's :attr:`time` (a wheel's state
            cannot be taken back or jump ahead).
        centre : WheelCentre
            The wheel centre's pose, velocity and spin at ``time`` (road frame,
            SI); over the step the centre moves along that velocity.
        dt : float
            Length of the step [s], positive.

        Returns
        -------
        CentreLoads
            Forces and moments of the road on the tyre at the wheel centre
            (means over the step), the contact force in the W-axis system, the
            deflection, contact point and slips at the step's end.
        """
        time, dt = _number(time, "time"), _number(dt, "dt")
        if not dt > 0:
            raise InputError(f"the step must be a positive number of seconds, got {dt!r}", field="dt")
        if not abs(time - self._time) <= TIME_TOLERANCE * max(1.0, abs(time)) + 1e-6 * dt:
            raise InputError(f"the wheel's state is at t = {self._time!r} s, the step starts at "
                             f"{time!r} s: step on from where the wheel is", field="time")
        centre = _checked(centre)
        if self._cover is not None:
            self._move_field(centre, dt)
        elif self._follow is not None:
            self._move_ground(centre, dt)
        n = self.sub_steps(dt)
        loads = advance(self.wheel, centre, n, dt / n, self._frame)
        self._time = time + dt
        self._check_pose(centre, loads)
        return loads

    def _check_pose(self, centre: WheelCentre, loads: CentreLoads) -> None:
        """Warn, once per kind, where the host has put the wheel outside what the model holds,
        as the rigs' :func:`~tyrelab.guards.check_run` warns (:class:`~tyrelab.guards.PhysicsWarning`;
        an FMU logs it): its centre below the road (a vertical axis pointing down? z is up in
        the road frame), where a contact model sees the road above the centre as if below it,
        a deflection that falls as the wheel sinks and no contact at all below one radius; and a
        deflection beyond the rim. Two comparisons per step; the road's height is looked up
        (in Python) only when the centre is below the road's highest point."""
        if centre.z < self._look_below:
            ground = float(self._height(centre.x, centre.y))
            if centre.z < ground:
                self._look_below = -math.inf
                self.warn(f"the wheel centre is below the road at t = {self._time:.6g} s: "
                          f"z = {centre.z:.4g} m under the road's {ground:.4g} m at "
                          f"(x, y) = ({centre.x:.4g}, {centre.y:.4g}) m; the loads are not "
                          "physical (the road frame's z axis points up: ISO 8855, TYDEX)")
        if loads.deflection > self._rim_room:
            room, self._rim_room = self._rim_room, math.inf
            self.warn(f"rim contact at t = {self._time:.6g} s: deflection "
                      f"{loads.deflection * 1e3:.0f} mm is beyond the {room * 1e3:.0f} mm the "
                      f"tyre has ({self._rim_how}); the model does not describe a tyre pressed "
                      "onto its rim")

    def _move_ground(self, centre: WheelCentre, dt: float) -> None:
        """Move a ground that follows the wheel (the soil's patch) on once this step would take
        the wheel's front to within :data:`~tyrelab.rig.soil_ground.KEEP_AHEAD` of the end it
        holds: from ``KEEP_BEHIND`` behind the centre to half its held length beyond that
        (forward along x only, as the rigs drive it: the soil behind is forgotten). Moved
        that far ahead, it moves on once every half patch, as the rigs' chunks move it,
        not at every step: each move lays the bed's origin again, to the rounding of its
        position."""
        radius = self.model.tyre.unloaded_radius
        start, end = self._held()
        if centre.x - radius < start:
            raise InputError(f"the wheel at x = {centre.x:.6g} m reaches behind the soil the "
                             f"bed holds (from x = {start:.6g} m): on soil a wheel steps forward "
                             "along x from where the soil starts, as the rigs drive it",
                             field="centre")
        ahead = centre.x + max(centre.vx, 0.0) * dt + radius + KEEP_AHEAD
        if ahead <= end:
            return
        record = self._follow(centre.x - KEEP_BEHIND, ahead + 0.5 * (end - start))
        if record is not None:
            self.wheel = self.wheel._replace(road=record)

    def _move_field(self, centre: WheelCentre, dt: float) -> None:
        """Move a ground that follows the wheel anywhere (the soil's field,
        :class:`~tyrelab.road.soil.field.SoilField`) once the wheel's reach over this step,
        its radius and :data:`~tyrelab.rig.soil_ground.KEEP_AHEAD` around the centre at the
        step's start and end, leaves the window it holds: the window then moves the way the
        wheel goes, keeping :data:`~tyrelab.rig.soil_ground.KEEP_BEHIND` behind it."""
        reach = self.model.tyre.unloaded_radius + KEEP_AHEAD
        x1, y1 = centre.x + centre.vx * dt, centre.y + centre.vy * dt
        speed = math.hypot(centre.vx, centre.vy)
        toward = (centre.vx / speed, centre.vy / speed) if speed > 0.0 else (0.0, 0.0)
        self._cover(min(centre.x, x1) - reach, max(centre.x, x1) + reach,
                    min(centre.y, y1) - reach, max(centre.y, y1) + reach,
                    toward=toward, behind=KEEP_BEHIND, wheel=self)
        self._on_current_ground()

    def _on_current_ground(self) -> None:
        """The wheel on the record its ground holds now: a field other wheels share may have
        been moved by their steps."""
        record = self._ground.surface()
        if self.wheel.road is not record:
            self.wheel = self.wheel._replace(road=record)

    def loads(self, centre: WheelCentre) -> CentreLoads:
        """The loads of the present state at ``centre``, leaving the state as it is.

        A step of length 0 on a copy of the state: for the analytic models the
        loads of the vertical law and the handling model at this pose, for the
        ring the foundation's reaction on the rim. On a ground with a state of
        its own (the soil's rut) the look presses a copy of it and of the contact
        model's record (a wheel on soil keeps its last deflection there), so it
        leaves no rut and no trace.
        """
        if self._cover is not None:
            self._on_current_ground()
        wheel = self.wheel._replace(state=copy.deepcopy(self.wheel.state))
        if getattr(self._ground, "fresh_copy", None) is not None:
            wheel = on_fresh_ground(wheel._replace(contact=copy.deepcopy(wheel.contact)),
                                    self._ground)
        centre = _checked(centre)
        loads = advance(wheel, centre, 1, 0.0, self._frame)
        self._check_pose(centre, loads)
        return loads


def _number(value, field: str, what: str | None = None) -> float:
    """``value`` as a finite float, or InputError naming ``field``."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    if not math.isfinite(v):
        raise InputError(f"{what or field} must be a finite number, got {value!r}", field=field)
    return v


def _checked(centre) -> WheelCentre:
    """``centre`` as a :class:`WheelCentre` of finite floats, or InputError naming the value."""
    if not isinstance(centre, WheelCentre):
        try:
            centre = WheelCentre(*centre)
        except TypeError:
            raise InputError(f"a wheel centre is {', '.join(WheelCentre._fields)} (the last two "
                             f"optional), got {centre!r}", field="centre") from None
    return WheelCentre(*(_number(v, name, f"the wheel centre's {name}")
                         for name, v in zip(WheelCentre._fields, centre)))


def rigid_ground(model: TyreModel, road):
    """The grid of a road name, file or :class:`~tyrelab.road.base.Road` for ``model``; an
    InputError when the model does not run on a rigid road."""
    from ..road.spec import road_from_spec
    from ..tyre.registry import contact_models

    if "rigid" not in model.contact_model.terrains:
        rigid = [n for n, m in contact_models().items() if "rigid" in m.terrains]
        raise InputError(f"the '{model.contact}' model does not run on a rigid road; models that "
                         f"do: {', '.join(rigid)}", field="model")
    return road_from_spec(road).grid()


def wheel_stepper(tyre="xzl-16.00R20", model: str | TyreModel = "point", road="flat", *,
                  pressure: float | None = None, stiffness: str | None = None,
                  handling: str | None = None, options: dict | None = None, load=0.0,
                  speed: float = 0.0, max_step: float | None = None, frame: str = "C-axis",
                  start_time: float = 0.0, relaxation="auto") -> WheelStepper:
    """A :class:`WheelStepper` from a tyre, a contact model and a road, by name.

    Parameters
    ----------
    tyre : str or Tyre
        Built-in name or ``.tir`` / Chrono ``.json`` file
        (:func:`tyrelab.api.make_tyre_model`).
    model : str or TyreModel
        Contact model (``point``, ``volume``, ``enveloping``, ``ring``, ...);
        a :class:`~tyrelab.tyre.model.TyreModel` is taken as it is (then
        ``tyre``, ``pressure``, ``stiffness``, ``handling`` and ``options`` are
        not used, nor ``relaxation``).
    road : str, Road, RoadGrid or ground
        A road name or file (:func:`tyrelab.road.spec.road_from_spec`), a road,
        its grid, or any ground of the terrain interface (an object with
        ``surface()``, :mod:`tyrelab.road.terrain`), such as a soil laid over
        a road: :func:`tyrelab.road.soil.field.lay_soil_field` (a window of it that
        follows the wheel anywhere, as the FMU lays it) or
        :func:`tyrelab.road.soil.terrain.lay_soil` (the rigs' strip, whose active
        patch moves on with the wheel, which then steps forward along x). Positions
        are in its own frame: unlike the rigs, the stepper does not level a
        road whose start is not at height zero.
    pressure, stiffness, handling, options, relaxation
        As :func:`tyrelab.api.make_tyre_model`.
    load : str or float
        Static load [N] (or a load case ``"LC1"`` ...) at which the model's
        internal state starts in equilibrium on a flat road, rolling at
        ``speed`` (:meth:`~tyrelab.tyre.model.TyreModel.equilibrium`, where the
        rigs start it); 0: unloaded (the ring's inflated belt off the road). A model that
        runs on soil only (``rigid``) has no such equilibrium: its state starts as it is.
        Start the wheel centre at ``R0 -`` that equilibrium's deflection above
        the road (:attr:`WheelStepper.equilibrium`).
    speed : float
        Rolling speed [m/s] of that equilibrium.
    max_step : float, optional
        Longest internal step [s]; default the model's stable step at
        ``load`` (:func:`tyrelab.limits.stable_step`: the ring's 2 ms, an
        analytic model's wheel-hop bound; 1 ms for a tyre without a wheel mass
        and no load).
    frame : {"C-axis", "road"}
        Frame of the forces and moments at the wheel centre.
    start_time : float
        Time [s] of the initial state.
    """
    from .. import limits

    if isinstance(model, TyreModel):
        tm = model
    else:
        tm = make_tyre_model(tyre, model, pressure, stiffness, handling, options, relaxation)
    if isinstance(load, str):
        from ..rig.trailer import load_case_wheel_load
        load = load_case_wheel_load(load)
    load = float(load)
    if load != 0.0:
        load = limits.check_wheel_load(load, tm.tyre)
    speed = limits.check_number(speed, "speed", 0.0, limits.MAX_SPEED, "m/s")
    ground = road if hasattr(road, "surface") else rigid_ground(tm, road)
    # where the rigs start a wheel: in equilibrium at the load, rolling at the speed, on a level
    # rigid road; a model that runs on soil only (the rigid wheel) has none there and starts as
    # it is (before, its FMU failed at initialisation with any INITIAL_LOAD)
    on_rigid = "rigid" in tm.contact_model.terrains
    eq = tm.equilibrium(load, speed) if load > 0 and on_rigid else None
    if max_step is None:
        if tm.tyre.wheel_mass > 0 or load > 0:
            max_step = limits.stable_step(tm, load)[0]
        else:
            max_step = DEFAULT_STEP
    max_step = limits.check_number(max_step, "max_step", 0.0, limits.MAX_DT, "s", low_open=True,
                                   what="internal step")
    wheel = tm.wheel(ground, load, rolling=eq)
    return WheelStepper(tm, wheel, max_step, frame, start_time, eq, ground=ground, load=load)
