"""A rig's wheel on a terrain (soil): the ground under a run, and the wheel settled into it.

Every rig that takes a terrain (``--terrain``: the single-wheel tester, the trailer, the
quarter vehicle) asks the registry which kind of ground the value names
(:func:`~tyrelab.road.terrain.resolve_terrain`), has that kind lay its ground over the
part of the road the run drives (:attr:`~tyrelab.road.terrain.TerrainKind.lay`; the soil:
a soil bed, the road's heights levelled to the run's start, as on a rigid road, its
undisturbed surface) and starts the wheel at rest in static equilibrium on it: at the
centre height where the ground, through the tyre, carries the wheel's static load
(:func:`settle`), a deformable ground pressed there.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from ..errors import InputError
from ..road.soil.terrain import BED_SPACING, BED_WIDTH  # noqa: F401  (the rigs' defaults)
from ..road.terrain import terrain_range
from ..tyre.wheel import WheelPose, wheel_step
from .frames import G

#: the static equilibrium is found to this height [m] ...
SETTLE_TOLERANCE = 1e-7
#: ... between the centre this fraction of the radius above the highest ground and a radius
BURIED = 0.05
#: a model with dynamics (the ring) then settles at rest, damped, for at most this long [s] ...
SETTLE_TIME = 2.0
#: ... until its centre moves slower than this [m/s]
SETTLE_SPEED = 1e-5
#: the settling's damping as a fraction of critical, on the stiffness load / (radius / 20)
SETTLE_DAMPING = 1.0


@nb.njit(cache=True)
def _stand(wheel, x, y, z, ax, ay, az, mass, damping, dt, n_max, still):
    """``(z, fz)``: the wheel standing still at (x, y) on its ground, its centre at ``z``, its
    spin axis ``(ax, ay, az)`` (a unit vector; ``(0, 1, 0)`` upright).

    ``n_max`` = 0: the ground's vertical force [N] at ``z`` (dt = 0: the shear does not grow;
    the nodes' plastic sinkage does -- call on a copy of the ground to leave no rut).
    Else: the centre free vertically under a dead weight of ``mass`` [kg], damped by
    ``damping`` [N s/m], stepped by ``dt`` [s] until it moves slower than ``still`` [m/s] (at
    most ``n_max`` steps); the centre height [m] and the force there.

    One kernel for both, not two: each kernel that steps the wheel compiles the whole model
    again (the ring on soil: 20-50 s cold), and a settling needs both."""
    if n_max == 0:
        return z, wheel_step(wheel, WheelPose(x, y, z, ax, ay, az, 0.0, 0.0, 0.0, 0.0), 0.0).fz
    vz = 0.0
    fz = 0.0
    for _ in range(n_max):
        f = wheel_step(wheel, WheelPose(x, y, z, ax, ay, az, 0.0, 0.0, vz, 0.0), dt)
        fz = f.fz
        vz += dt * (fz - mass * G - damping * vz) / mass
        z += dt * vz
        if abs(vz) < still and abs(fz - mass * G) < 1e-3 * mass * G:
            break
    return z, fz


#: the spin axis of a wheel standing upright
UPRIGHT = (0.0, 1.0, 0.0)


def _vertical_force(wheel, x: float, y: float, z: float, axis=UPRIGHT) -> float:
    """The ground's vertical force [N] on the wheel standing still with its centre at
    (x, y, z) and its spin ``axis`` (:func:`_stand` with no step)."""
    return _stand(wheel, float(x), float(y), float(z), *(float(a) for a in axis),
                  0.0, 0.0, 0.0, 0, 0.0)[1]


def on_fresh_ground(wheel, ground):
    """The wheel on a copy of its ground's state (an equilibrium trial, or a look at the loads,
    leaves no rut); a ground without state (no ``fresh_copy``) as it is."""
    copy = getattr(ground, "fresh_copy", None)
    return wheel._replace(road=copy().surface()) if copy else wheel


@nb.njit(cache=True)
def ground_top(wheel):
    """The highest the wheel's ground reaches anywhere [m] (where a settling starts)."""
    return terrain_range(wheel.road)[1]


def settle(wheel, ground, load: float, x: float, radius: float, y: float = 0.0,
           dynamic: bool = False, dt: float = 1e-3, axis=UPRIGHT, press: bool = True) -> float:
    """The centre height [m] at which the ground carries ``load`` [N] under the wheel standing
    at (x, y) with its spin ``axis`` (a rig's frame may incline it), found by bisection
    between touching the highest ground and sunk to :data:`BURIED` of its ``radius`` [m]; a
    deformable ground is then pressed there (the run starts from it; with ``press`` False a
    copy of it: a trial that leaves no rut). A ``dynamic`` model (the ring, whose loads at a
    height depend on its state) then settles at rest under the load, critically damped,
    stepped at ``dt`` [s] (:data:`SETTLE_TIME`, :data:`SETTLE_SPEED`).
    ``ground`` the wheel's Python ground (its ``fresh_copy`` makes the trials)."""
    top = ground_top(wheel)
    # the force falls as the wheel rises; the lowest trial keeps the centre off the ground (a
    # contact point at the centre has no direction)
    lo, hi = top + BURIED * radius, top + radius
    if _vertical_force(on_fresh_ground(wheel, ground), x, y, lo, axis) < load:
        raise InputError(f"the ground does not carry {load:.6g} N under this wheel even sunk to "
                         "its axle; a lighter load or a stiffer ground", field="load")
    while hi - lo > SETTLE_TOLERANCE:
        mid = 0.5 * (lo + hi)
        if _vertical_force(on_fresh_ground(wheel, ground), x, y, mid, axis) > load:
            lo = mid
        else:
            hi = mid
    z0 = 0.5 * (lo + hi)
    if not press:
        wheel = on_fresh_ground(wheel, ground)
    _vertical_force(wheel, x, y, z0, axis)
    if dynamic:
        mass = load / G
        stiffness = load / (radius / 20.0)
        z0 = _stand(wheel, float(x), float(y), z0, *(float(a) for a in axis), mass,
                    SETTLE_DAMPING * 2.0 * np.sqrt(stiffness * mass), float(dt),
                    int(SETTLE_TIME / dt), SETTLE_SPEED)[0]
    return z0


def _terrain_for(model, terrain):
    """``(kind, description, label)`` of the ground ``terrain`` names, once ``model`` is known
    to run on it (else one InputError naming the models that do)."""
    from ..road.terrain import resolve_terrain
    kind, description, label = resolve_terrain(terrain)
    if not runs_on(model.contact_model, kind):
        from ..tyre.registry import contact_models
        takers = [n for n, m in contact_models().items() if runs_on(m, kind)]
        raise InputError(f"the '{model.contact}' model does not run on {kind.name}; models that "
                         f"do: {', '.join(takers) or 'none'}", field="model")
    return kind, description, label


def lay_terrain(model, terrain, road, x0: float, x1: float, level_at: float | None = None,
                **lay_options):
    """``(ground, meta)``: the ground ``terrain`` names (``--terrain``: a soil's name or file)
    laid over ``road`` from ``x0`` to ``x1`` [m] (``lay_options``: the soil bed's ``spacing``,
    ``width``), once ``model`` is known to run on it; ``meta`` names the ground for a run's
    metadata."""
    kind, description, label = _terrain_for(model, terrain)
    return kind.lay(description, road, x0, x1, level_at, **lay_options), {kind.name: label}


#: how far along x a kind without ``lay_around`` is laid for a host's wheel [m]
AROUND_RUN = 10000.0


def lay_terrain_around(model, terrain, road, x: float, y: float, level_at: float | None = None,
                       **lay_options):
    """``(ground, meta)`` as :func:`lay_terrain`, for a wheel a host drives anywhere from
    ``(x, y)`` [m] (co-simulation): the kind's ``lay_around`` (the soil: a window that follows
    the wheel in x and y, :class:`~tyrelab.road.soil.field.SoilField`); a kind without it is
    laid along x from ``x`` on, as a rig would lay it (:data:`AROUND_RUN`)."""
    kind, description, label = _terrain_for(model, terrain)
    if kind.lay_around is None:
        return kind.lay(description, road, x, x + AROUND_RUN, level_at, **lay_options), \
            {kind.name: label}
    return kind.lay_around(description, road, x, y, level_at, **lay_options), {kind.name: label}


def terrain_wheel(model, terrain, road, x0: float, x1: float, load: float,
                  level_at: float | None = None, dt: float = 1e-3, **lay_options):
    """``(wheel, ground, z0, meta)``: ``model``'s :class:`~tyrelab.tyre.wheel.Wheel` on the
    ground ``terrain`` names, laid over ``road`` from ``x0`` to ``x1`` [m]
    (:func:`lay_terrain`), settled under ``load`` [N] at ``x0`` (``z0`` its centre height
    [m]); ``meta`` names the ground for the run's metadata."""
    ground, meta = lay_terrain(model, terrain, road, x0, x1, level_at, **lay_options)
    wheel = model.wheel(ground, load)
    z0 = settle(wheel, ground, load, x0, model.tyre.unloaded_radius,
                dynamic=model.contact_model.has_state, dt=dt)
    return wheel, ground, z0, meta


def with_sinkage(data, channels, ground, index, road_y: float = 0.0):
    """``(data, channels)`` with a ``SINKAGE`` column after the rig's own, or as they are where
    the ground does not say where its surface was laid (no ``undisturbed(x, y)``: a rigid
    road, a plugin's terrain). ``SINKAGE`` [m] is the test wheel's contact point below the
    surface as laid where it carries load, else 0 -- what the single-wheel tester's kernel
    writes; ``index`` the rig's channel index, ``road_y`` [m] where the wheel's ground lies
    across from the rig's y."""
    undisturbed = getattr(ground, "undisturbed", None)
    if undisturbed is None:
        return data, channels
    depth = undisturbed(data[:, index.X_CP], data[:, index.Y_CP] + road_y) - data[:, index.Z_CP]
    depth = np.where(data[:, index.FZW] > 0.0, np.maximum(depth, 0.0), 0.0)
    return np.column_stack([data, depth]), (*channels, "SINKAGE")


#: a rig keeps this much of its ground behind its wheel's centre [m] (where a moving ground,
#: the soil's active patch, may forget it) ...
KEEP_BEHIND = 2.0
#: ... and this much, beyond its radius, ahead of where a chunk of its run ends
KEEP_AHEAD = 1.0


class Following:
    """A rig's wheel, moving forward at ``speed`` [m/s] from ``x`` [m], kept on the part of its
    Python ``ground`` each chunk of the run drives: a ground too long to hold at once (the
    soil, :mod:`tyrelab.road.soil.patch`) moves with the wheel; any other stays as it is."""

    def __init__(self, ground, x: float, speed: float, dt: float, radius: float):
        self._follow = getattr(ground, "follow", None)
        self.x, self.speed, self.dt, self.radius = float(x), float(speed), float(dt), float(radius)

    def wheel(self, wheel, n: int):
        """``wheel`` with its ground covering the next ``n`` steps (and the rut just behind)."""
        travel = abs(self.speed) * n * self.dt
        if self._follow is not None:
            record = self._follow(self.x - KEEP_BEHIND, self.x + travel + self.radius + KEEP_AHEAD)
            if record is not None:
                wheel = wheel._replace(road=record)
        self.x += travel
        return wheel


def runs_on(entry, kind) -> bool:
    """Whether the registered contact model ``entry`` runs on terrain ``kind``: a kind it names,
    or any rigid kind for a model of the rigid road (it reads the ground through the terrain
    interface only)."""
    return kind.name in entry.terrains or (kind.rigid and "rigid" in entry.terrains)
