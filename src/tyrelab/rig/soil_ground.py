"""A rig's wheel on soil: the soil bed under a run, and the wheel settled into it at the start.

Every rig that runs on soil (the single-wheel tester, the trailer, the quarter vehicle)
lays a soil bed (:class:`~tyrelab.road.soil.scm.SoilSurface`) over the part of the road it
drives, the road's heights (levelled to the run's start, as on a rigid road) its
undisturbed surface, and starts the wheel at rest in static equilibrium in it: at the
centre height where the soil, through the tyre, carries the wheel's static load
(:func:`settle`), the bed pressed there.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from ..errors import InputError
from ..limits import MAX_MEMORY
from ..tyre.wheel import WheelPose, wheel_step

#: the soil bed's node spacing [m]: halving it moves the pull of the XZL's rigid wheel on LETE
#: sand at s = 0.2 by 0.15 % and its sinkage by 1.8 %, and costs four times the time
BED_SPACING = 0.02
#: the bed's width [m] across the wheel's track (its centre line y = 0)
BED_WIDTH = 2.0
#: the bed reaches this far [m] behind the start and beyond the end of the run
BED_MARGIN = 1.0
#: memory of a soil node: undisturbed height, surface, shear displacement, stress
BYTES_PER_NODE = 4 * 8
#: the static equilibrium is found to this height [m]
SETTLE_TOLERANCE = 1e-7
#: a model with dynamics (the ring) then settles at rest, damped, for at most this long [s] ...
SETTLE_TIME = 2.0
#: ... until its centre moves slower than this [m/s]
SETTLE_SPEED = 1e-5
#: the settling's damping as a fraction of critical, on the stiffness load / (radius / 20)
SETTLE_DAMPING = 1.0


def soil_ground(soil, road, x0: float, x1: float, width: float = BED_WIDTH,
                spacing: float = BED_SPACING, level_at: float | None = None):
    """A fresh soil bed from ``x0`` to ``x1`` [m] (plus :data:`BED_MARGIN` each end), ``width``
    [m] across y = 0, nodes every ``spacing`` [m], over ``road``'s heights (less its height at
    ``(level_at, 0)`` when given); refused above the memory allowed (:data:`~tyrelab.limits.MAX_MEMORY`)."""
    from ..road.grid import RoadGrid
    from ..road.soil.scm import soil_bed
    x0, x1 = x0 - BED_MARGIN, x1 + BED_MARGIN
    nx = int(np.ceil((x1 - x0) / spacing)) + 1
    ny = int(np.ceil(width / spacing)) + 1
    if nx * ny * BYTES_PER_NODE > MAX_MEMORY:
        raise InputError(f"a soil bed {x1 - x0:.6g} m long and {width:g} m wide at {spacing:g} m "
                         f"needs {nx * ny * BYTES_PER_NODE / 1024 ** 3:.3g} GiB, above the "
                         f"{MAX_MEMORY / 1024 ** 3:g} GiB allowed; a shorter run or a coarser bed",
                         field="duration")
    xs = x0 + spacing * np.arange(nx)
    ys = -0.5 * width + spacing * np.arange(ny)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    z = np.asarray(road.height(X, Y), dtype=np.float64)
    if level_at is not None:
        z = z - float(road.height(level_at, 0.0))
    return soil_bed(soil, RoadGrid(x0, -0.5 * width, spacing, spacing, z))


@nb.njit(cache=True)
def _vertical_force(wheel, x, y, z):
    """The ground's vertical force on the wheel standing still with its centre at (x, y, z)
    (dt = 0: the shear does not grow; the nodes' plastic sinkage does -- call on a copy of
    the ground to leave no rut)."""
    pose = WheelPose(x, y, z, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    return wheel_step(wheel, pose, 0.0).fz


def _fresh(wheel):
    """The wheel on a copy of its ground's node state (an equilibrium trial leaves no rut)."""
    return wheel._replace(road=wheel.road.fresh_copy())


@nb.njit(cache=True)
def _settle_steps(wheel, mass, x, y, z, damping, dt, n_max, still):
    """The wheel at rest under a dead weight of ``mass`` [kg], its centre free vertically and
    damped by ``damping`` [N s/m], stepped until it moves slower than ``still`` [m/s] (at most
    ``n_max`` steps); returns the centre height [m]."""
    vz = 0.0
    g = 9.80665
    for _ in range(n_max):
        f = wheel_step(wheel, WheelPose(x, y, z, 0.0, 1.0, 0.0, 0.0, 0.0, vz, 0.0), dt)
        vz += dt * (f.fz - mass * g - damping * vz) / mass
        z += dt * vz
        if abs(vz) < still and abs(f.fz - mass * g) < 1e-3 * mass * g:
            break
    return z


def settle(wheel, load: float, x: float, radius: float, y: float = 0.0,
           dynamic: bool = False, dt: float = 1e-3) -> float:
    """The centre height [m] at which the soil carries ``load`` [N] under the wheel standing
    at (x, y), found by bisection between touching the highest soil and a full ``radius`` [m]
    deep; the bed is then pressed there (the run starts from it). A ``dynamic`` model (the
    ring, whose loads at a height depend on its state) then settles at rest under the load,
    critically damped, stepped at ``dt`` [s] (:data:`SETTLE_TIME`, :data:`SETTLE_SPEED`)."""
    top = wheel.road.zmax
    lo, hi = top, top + radius        # the force falls as the wheel rises
    if _vertical_force(_fresh(wheel), x, y, lo) < load:
        raise InputError(f"the soil does not carry {load:.6g} N under this wheel even a full radius "
                         "deep; a lighter load or a stiffer soil", field="load")
    while hi - lo > SETTLE_TOLERANCE:
        mid = 0.5 * (lo + hi)
        if _vertical_force(_fresh(wheel), x, y, mid) > load:
            lo = mid
        else:
            hi = mid
    z0 = 0.5 * (lo + hi)
    _vertical_force(wheel, x, y, z0)
    if dynamic:
        mass = load / 9.80665
        stiffness = load / (radius / 20.0)
        z0 = _settle_steps(wheel, mass, x, y, z0, SETTLE_DAMPING * 2.0 * np.sqrt(stiffness * mass),
                           dt, int(SETTLE_TIME / dt), SETTLE_SPEED)
    return z0


def soil_wheel(model, soil, road, x0: float, x1: float, load: float, level_at: float | None = None,
               spacing: float = BED_SPACING, width: float = BED_WIDTH, dt: float = 1e-3):
    """``(wheel, z0)``: ``model``'s :class:`~tyrelab.tyre.wheel.Wheel` on a fresh bed of
    ``soil`` under ``road`` from ``x0`` to ``x1`` [m], settled under ``load`` [N] at ``x0``
    (``z0`` its centre height [m])."""
    from ..road.soil import load_soil
    if "soil" not in model.contact_model.terrains:
        from ..tyre.registry import contact_models
        on_soil = [n for n, m in contact_models().items() if "soil" in m.terrains]
        raise InputError(f"the '{model.contact}' model does not run on soil; models that do: "
                         f"{', '.join(on_soil)}", field="model")
    soil_params, _ = load_soil(soil)
    bed = soil_ground(soil_params, road, x0, x1, width, spacing, level_at)
    wheel = model.wheel(bed, load)
    return wheel, settle(wheel, load, x0, model.tyre.unloaded_radius,
                         dynamic=model.contact_model.has_state, dt=dt)


def soil_meta(terrain) -> dict:
    """A run's soil for its metadata (nothing on a rigid road)."""
    if terrain is None:
        return {}
    from ..road.soil import load_soil
    return {"soil": load_soil(terrain)[1]}
