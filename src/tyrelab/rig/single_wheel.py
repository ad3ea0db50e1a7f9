"""The single-wheel tester: a soil bin's carriage over deformable soil (terramechanics' test).

As in Wong's and Bekker's soil bins: the carriage moves forward at a prescribed speed
``V``, the wheel is driven at the spin that gives the prescribed slip
``s = 1 - V / (R_e omega)`` (s = 1 spins in place) or braked to the skid
``s = R_e omega / V - 1`` (negative; s = -1 is locked; :func:`wheel_spin`) -- or, given a
driving ``torque`` instead, spins freely under it (its spin inertia, stepped as the
trailer's and the quarter vehicle's wheels are; 0: a towed wheel) and finds its own
slip -- and the
vertical load is a dead weight: the carriage
and wheel, of mass ``W / g``, are free to sink. It starts at rest in static
equilibrium in the soil (the sinkage at which the soil carries ``W``), then drives.

``R_e`` is the wheel's effective rolling radius, as terramechanics defines the slip of a
pneumatic tyre (Wong 2008, 2.4): its free-rolling ``V / omega`` on a hard flat surface
under the same load -- each model's own (:func:`rolling_radius`: the rigid wheel's is its
radius, an analytic model's its loaded radius, the ring's from its rolling equilibrium). So
s = 0 rolls each model freely on hard ground, and slips compare across models.

Channels: the wheel channels (``FX`` the drawbar pull, positive forward; ``FZ``;
``MY`` the soil's moment on the wheel about its axis; ``LONGSLIP`` the tester's slip ``s``
from the wheel's spin and ``R_e``, :func:`tester_slip`, whatever the model), plus ``SINKAGE``
(depth of the tyre's contact point below the undisturbed surface) and ``TORQUE``
(the driving torque the axle applies: ``-MY`` where the spin is held, the given torque
where it is free).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
from numba.extending import overload
import numpy as np

from ..core.named_index import named_index
from ..errors import InputError
from ..limits import STEADY_FRACTION  # the part of a run a slip curve averages
from ..road.soil.scm import SoilSurface, undisturbed_height
from ..road.terrain import terrain_height
from ..tyre.wheel import WheelPose, wheel_step
from .frames import WHEEL_CHANNELS, WC, wheel_row
from .soil_ground import BED_SPACING, BED_WIDTH, Following, settle, terrain_wheel
from .simulation import run_chunks, to_signal
from .frames import G

CHANNELS = WHEEL_CHANNELS + ("SINKAGE", "TORQUE")
SC = named_index("SingleWheelChannelIndex", CHANNELS)
#: the carriage's state: height of the wheel centre [m], its vertical speed [m/s], time [s],
#: the wheel's spin [rad/s]
STATE = ("Z", "VZ", "T", "W")
S = named_index("SingleWheelStateIndex", STATE)
#: where the carriage starts along the bin [m]
X_START = 0.0
#: the rig's time step [s] unless a run gives one (the slip curves' step)
STEP = 1e-3
#: the slowest speed [m/s] at which a model's rolling radius is found (rolling_radius)
ROLLING_RADIUS_SPEED = 1.0
#: the longest step [s] at which the tester turns a model with its own dynamics (the ring)
#: free under a torque; a longer ``dt`` is split into steps this long. Until the ring took its
#: rim's spin change at once (:func:`tyrelab.tyre.ring.kernel.rim_spin_change`, 2026-11-28),
#: rim and belt wound each other up at 1 ms (the XZL's ring on LETE sand under 9.1 kN m: the
#: soil's moment +-450 kN m, the spin -16 to 71 rad/s by 3 s). Now, its rim turned with its
#: own 3.4 kg m^2, 1 ms holds the soil's moment there within 0.1 %, but the rim rings more on
#: the soil's shear: the slip's scatter over the last 1.5 s of 3 s under 5 kN m +-0.038
#: against +-0.014 at 0.5 ms (under 1.15 kN m 0.025 and 0.023; the mean 0.059 and 0.060)
FREE_STATEFUL_STEP = 5e-4

def undisturbed(ground, x, y):
    """The undisturbed surface's height at (x, y) [m] (compiled only): the soil's before any
    rut, another ground's height."""
    raise NotImplementedError("compiled only")


@overload(undisturbed)
def _undisturbed(ground, x, y):
    if getattr(ground, "instance_class", None) is SoilSurface:
        return lambda ground, x, y: undisturbed_height(ground, x, y)
    return lambda ground, x, y: terrain_height(ground, x, y)


@nb.njit(cache=True)
def single_wheel_steps(wheel, mass, moved, speed, drive, state, n_steps, dt, out_every, out, row0):
    """Drive ``n_steps`` from ``state`` (:data:`STATE`); rows of :data:`CHANNELS` into ``out``.

    The carriage's height follows the soil's vertical force against the dead weight of
    ``mass`` [kg] (semi-implicit Euler), which moves with the carriage but for what the tyre
    model's own state moves (the ring's belt): ``moved`` [kg]. x is prescribed. ``drive``
    (:class:`Drive`): the spin is held at the state's, or with ``free`` turns under the
    driving ``torque`` [N m] and the soil's moment about the axle, as the trailer's and the
    quarter vehicle's wheels do (implicit in the moment's slope ``dspin_domega`` where the
    model gives one: the ring's foundation; the rigid wheel and the analytic models on soil
    give none, so there the step is explicit: stable at 1 ms, measured). Returns the next
    free row.
    """
    cax = np.empty(6)
    row = row0
    for step in range(n_steps):
        z, vz, t, omega = state[S.Z], state[S.VZ], state[S.T], state[S.W]
        x = X_START + speed * t
        pose = WheelPose(x, 0.0, z, 0.0, 1.0, 0.0, speed, 0.0, vz, omega)
        f = wheel_step(wheel, pose, dt)
        if (step % out_every) == 0 and row < out.shape[0]:
            o = out[row]
            wheel_row(o, t, x - X_START, pose, f, cax)
            o[SC.SINKAGE] = max(0.0, undisturbed(wheel.road, f.px, f.py) - f.pz) \
                if f.fzw > 0.0 else 0.0
            o[SC.TORQUE] = drive.torque if drive.free else -o[WC.MY]
            # the tester's slip, as it prescribes it: the soil wheel's kappa measures the
            # tread on its own radius, and the ring has none of its own
            o[WC.LONGSLIP] = tester_slip(speed, omega, drive.rolling_radius)
            row += 1
        vz += dt * (f.fz - mass * G) / moved
        state[S.VZ] = vz
        state[S.Z] = z + dt * vz
        state[S.T] = t + dt
        if drive.free:      # the soil's moment about the axle a = e_y is f.my
            w = omega + dt * (drive.torque + f.my) / (
                drive.spin_inertia - dt * min(f.dspin_domega, 0.0))
            # a brake (a negative torque) stops the wheel; it does not turn it backwards: at
            # rest it holds up to its torque, and the soil turns the wheel on only past it
            state[S.W] = max(w, 0.0) if drive.torque < 0.0 and omega >= 0.0 else w
    return row


class Drive(NamedTuple):
    """How the tester turns its wheel: held at its spin (``free`` False), or free under the
    driving ``torque`` [N m] with the wheel's ``spin_inertia`` [kg m^2]; its slip measured
    against the model's effective ``rolling_radius`` ``R_e`` [m]."""

    free: bool
    torque: float
    spin_inertia: float
    rolling_radius: float


def wheel_spin(speed: float, rolling_radius: float, slip: float) -> float:
    """The wheel's spin [rad/s] at carriage speed ``V`` [m/s] and ``slip`` (Wong 2008, 2.4).

    Driving, ``0 <= s < 1``: ``s = 1 - V / (R_e omega)``, so ``omega = V / (R_e (1 - s))``
    (s = 1 would spin in place). Braking, ``-1 <= s < 0``: the skid ``i_s = 1 - R_e omega / V``
    with a minus sign, ``s = R_e omega / V - 1``, so ``omega = V (1 + s) / R_e`` (s = -1 is
    the locked wheel). One axis for both: each is the tread's speed less the carriage's over
    the larger of the two, as the soil wheel's ``kappa`` (``LONGSLIP``) is measured."""
    if slip >= 0.0:
        return speed / (rolling_radius * (1.0 - slip))
    return speed * (1.0 + slip) / rolling_radius


@nb.njit(cache=True)
def tester_slip(speed, omega, rolling_radius):
    """The tester's slip at carriage speed ``V`` [m/s] and spin ``omega`` [rad/s] (the
    inverse of :func:`wheel_spin`): ``(R_e omega - V) / max(R_e omega, V)``, driving
    ``1 - V / (R_e omega)``, braking ``R_e omega / V - 1`` (Wong 2008, 2.4)."""
    tread = rolling_radius * omega
    return (tread - speed) / max(tread, speed)


def rolling_radius(model, load: float, speed: float) -> float:
    """The effective rolling radius ``R_e`` [m] of ``model`` under ``load`` [N]: its free-rolling
    ``V / omega`` on a hard flat road at ``speed`` [m/s], at least :data:`ROLLING_RADIUS_SPEED`
    (its rigs' rolling equilibrium; the ring's takes long to find at a crawl, and at soil-bin
    speeds hardly depends on speed); a model that runs on no rigid road (the rigid wheel)
    rolls at its unloaded radius."""
    if "rigid" not in model.contact_model.terrains:
        return float(model.tyre.unloaded_radius)
    v = max(float(speed), ROLLING_RADIUS_SPEED)
    return float(v / model.equilibrium(load, v).spin)


def single_wheel(model, soil, load: float, speed: float, slip: float = 0.0, length: float = 10.0,
                 width: float = BED_WIDTH, spacing: float = BED_SPACING, duration: float | None = None,
                 dt: float = STEP, output_rate: float = 1000.0, progress: bool | None = None,
                 road=None, passes: int = 1, return_bed: bool = False, torque: float | None = None):
    """Drive ``model`` through a soil bin; returns the signal table (a list of them, one per
    pass over the same bed, when ``passes`` > 1; with ``return_bed`` also the soil bed after,
    a :class:`~tyrelab.road.soil.scm.SoilSurface`).

    Parameters
    ----------
    model : TyreModel
        A contact model that runs on soil (``rigid``, and the analytic models as flexible
        wheels: :mod:`tyrelab.tyre.contact.soil_wheel`).
    soil : str or Soil
        A built-in soil's name or a soil file (:func:`tyrelab.road.soil.load_soil`).
    load : float
        Dead weight on the wheel [N].
    speed : float
        Carriage speed [m/s].
    slip : float
        Driving ``s = 1 - V / (R_e omega)``, 0 to below 1; braking ``s = R_e omega / V - 1``,
        -1 (locked) to 0 (:func:`wheel_spin`; ``R_e``: :func:`rolling_radius`).
    torque : float, optional
        Instead of a slip: the driving torque [N m] (negative brakes; 0 tows the wheel) under
        which the wheel spins freely from the free-rolling spin ``V / R_e``; its slip is
        then what the soil lets it reach (``LONGSLIP``). A model with its own dynamics (the
        ring) is then stepped at :data:`FREE_STATEFUL_STEP` at most.
    length, width, spacing : float
        The soil bed [m] and its node spacing [m]; the bed starts 1 m behind the wheel.
    duration, dt, output_rate : float
        Simulated time [s] (default: until the wheel is 1 m from the bed's end), step [s],
        output rate [Hz].
    road : Road, optional
        The undisturbed surface (default flat).
    passes : int
        Runs over the same bed, each from the start, in static equilibrium on the rut the
        earlier ones left (the soil keeps its plastic sinkage).
    """
    from ..road.obstacles import Flat
    if not -1.0 <= slip < 1.0:
        raise InputError(f"slip must be in [-1, 1), got {slip!r}", field="slip")
    if torque is not None and not np.isfinite(torque):
        raise InputError(f"torque must be a finite number of N m, got {torque!r}", field="torque")
    if duration is not None:
        length = max(length, X_START + speed * duration + 2.0)
    road = road or Flat()
    if torque is not None and model.has_state and dt > FREE_STATEFUL_STEP:
        dt = dt / math.ceil(dt / FREE_STATEFUL_STEP - 1e-9)
    x_end = X_START + length - 1.0
    wheel, ground, z0, ground_meta = terrain_wheel(model, soil, road, X_START, x_end, load,
                                                   dt=dt, spacing=spacing, width=width,
                                                   moving=passes == 1)
    radius = model.tyre.unloaded_radius
    if duration is None:
        duration = (x_end - X_START) / speed
    r_e = rolling_radius(model, load, speed)
    omega = wheel_spin(speed, r_e, 0.0 if torque is not None else slip)
    from ..guards import rig_rim_mass, rig_spin_inertia
    inertia = rig_spin_inertia(model, load) if torque is not None else model.tyre.spin_inertia
    moved = rig_rim_mass(model, load / G, "the dead weight's mass")
    drive = Drive(torque is not None, float(torque or 0.0), inertia, r_e)
    n_steps = int(round(duration / dt))
    out_every = max(1, int(round(1.0 / (output_rate * dt))))
    tables = []
    for k in range(passes):
        if k:                               # again from the start, settled into the rut
            z0 = settle(wheel, ground, load, X_START, radius, dynamic=model.contact_model.has_state,
                        dt=dt)
        state = np.zeros(len(STATE))
        state[S.Z] = z0
        state[S.W] = omega

        follow = Following(ground, X_START, speed, dt, radius)

        def advance(n, out, row, state=state, follow=follow):
            nonlocal wheel
            wheel = follow.wheel(wheel, n)
            return single_wheel_steps(wheel, load / G, moved, float(speed), drive, state, n, dt,
                                      out_every, out, row)

        data = run_chunks(advance, n_steps, out_every, len(CHANNELS), dt, progress)
        meta = {"rig": "single-wheel", "tyre": model.tyre.name, "model": model.contact,
                **ground_meta, "road": road.name, "speed_m_s": speed,
                **({"slip": slip} if torque is None else {"torque_Nm": float(torque)}),
                "static_wheel_load_N": load, "pass": len(tables) + 1, "rolling_radius_m": r_e,
                # the settled start's SINKAGE: the tyre's contact point below the surface (the
                # centre's depth less the radius was the undeformed circle's, a flexible
                # tyre's deflection too deep)
                "static_sinkage_m": float(data[0, SC.SINKAGE]),
                "soil_spacing_m": spacing, "dt_s": dt, "output_rate_Hz": 1.0 / (out_every * dt)}
        tables.append(to_signal(data, CHANNELS, meta))
    result = tables[0] if passes == 1 else tables
    return (result, wheel.road) if return_bed else result


def slip_curve(model, soil, load: float, speed: float, slips, duration: float = 3.0,
               progress=None, **bed):
    """Steady drawbar pull, torque, sinkage and load against slip: one single-wheel run per
    slip, averaged over the last :data:`STEADY_FRACTION` of its ``duration`` [s].

    Returns a table with columns ``slip``, ``FX`` [N] (pull), ``TORQUE`` [N m], ``SINKAGE``
    [m], ``FZ`` [N]; ``progress(done)`` is called after each run."""
    import pandas as pd
    rows = []
    for k, s in enumerate(slips):
        run = single_wheel(model, soil, load, speed, slip=float(s), duration=duration, **bed)
        steady = run[run["RUNTIME"] >= (1.0 - STEADY_FRACTION) * duration]
        rows.append({"slip": float(s), **{c: float(steady[c].mean())
                                          for c in ("FX", "TORQUE", "SINKAGE", "FZ")}})
        if progress:
            progress(k + 1)
    return pd.DataFrame(rows)
