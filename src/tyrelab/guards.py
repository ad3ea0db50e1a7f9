"""Physics guards: a run that leaves the physics its models hold for says so.

Two kinds of check, both outside the compiled kernels:

* **before a run** (:func:`check_road_for_tyre`, :func:`check_load_range`,
  :func:`check_level_for_trailer`, :func:`check_reaches_relief`): an obstacle edge
  taller than the tyre's radius is refused (:class:`~tyrelab.errors.InputError`); a
  static load above the property file's ``FZMAX``, a road with a grade under the trailer
  and a run that ends before the road's relief begins are warned about.
* **after a run** (:func:`check_run`), on the signal table: rim contact
  (deflection beyond the unloaded radius less the rim radius, or the wheel
  centre below the road), an overturned rig (trailer roll or pitch beyond
  :data:`OVERTURN_ANGLE`), a wheel that left the road for longer than
  :data:`AIRBORNE_TIME` (not on the rolling rig, whose axle is held at a
  fixed height), a peak normal force far above ``FZMAX``, and a wheel a driving
  torque spun up (:data:`SPIN_UP_SLIP`).

Each finding is one :class:`PhysicsWarning` line saying what happened, when,
and what to change; the command line prints it as ``tyrelab: warning: ...``.
The results themselves are never altered.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from . import limits
from .errors import InputError

#: a towed trailer whose frame rolls or pitches beyond this [deg] has overturned (a
#: 2.4 m track with its centre of mass near hitch height tips at about 40-50 deg; the
#: thesis's runs stay within a few degrees)
OVERTURN_ANGLE = 30.0
#: the test wheel off the road (zero normal force) for longer than this [s] has left the
#: road (a hop over a cleat at 42 km/h lasts a few tens of milliseconds)
AIRBORNE_TIME = 0.5
#: a wheel driven by a torque (the single-wheel tester's ``torque``) whose slip ends above
#: this has spun up: the torque is more than the soil's shear carries (s = 1 spins in place)
SPIN_UP_SLIP = 0.95
#: ... and one whose mean slip moves by more than this between the halves of the part of the
#: run a slip curve averages (the last :data:`tyrelab.limits.STEADY_FRACTION`) has not
#: settled: its means are not a steady state. (Settled, a wheel on soil still rings on the
#: soil's shear, its slip by up to +-0.06 about a steady mean; 3 s runs on the library's
#: soils: the mean moves by under 0.007, while 1 s runs, still settling, move by up to 0.09.)
UNSETTLED_SLIP = 0.01
#: ... or whose slip swings by more than this either side of its mean there: a cycle so wide
#: that its mean is not the slip the torque holds on the slip curve
SWINGING_SLIP = 0.1


class PhysicsWarning(UserWarning):
    """A run went outside the physics its models are valid for (rim contact, overturn ...)."""


def physics_warning(message: str, stacklevel: int = 3) -> None:
    """Issue ``message`` as a :class:`PhysicsWarning`, pointed ``stacklevel`` frames up (the
    default: the caller of the check that found it)."""
    warnings.warn(message, PhysicsWarning, stacklevel=stacklevel)


def path_edge(road, width: float, spacing: float | None = None) -> tuple[float, float]:
    """``(height, x)`` of the tallest edge along the wheel's path: the largest height change
    between neighbouring grid nodes along x, over y = 0 and the tyre's two shoulders."""
    g = getattr(road, "_grid", None)
    xmin, xmax, _, _ = road.extent()
    ys = np.array([-0.5 * width, 0.0, 0.5 * width])
    if g is not None:
        nx = g.z.shape[0]
        xs = g.x0 + g.dx * np.arange(nx)
    else:
        dx = spacing or road.default_spacing[0]
        nx = int(math.ceil((xmax - xmin) / dx - 1e-9)) + 1
        if nx > 50_000_000:  # the road's own bounds forbid this; never sample it whole
            raise InputError(f"the road's grid along x has {nx} nodes", field="road")
        xs = xmin + dx * np.arange(nx)
    best, where = 0.0, float("nan")
    chunk = 1_000_000
    for i0 in range(0, xs.size, chunk):
        x = xs[i0:min(i0 + chunk + 1, xs.size)]
        if x.size < 2:
            continue
        X, Y = (np.array(a) for a in np.broadcast_arrays(x[:, None], ys[None, :]))
        z = np.asarray(road.height(X, Y), dtype=float).reshape(X.shape)
        dz = np.abs(np.diff(z, axis=0)).max(axis=1)
        k = int(np.argmax(dz))
        if dz[k] > best:
            best, where = float(dz[k]), float(x[k])
    return best, where


def check_road_for_tyre(road, tyre) -> None:
    """Refuse a road with an edge on the wheel's path taller than the tyre's radius."""
    r0 = float(tyre.unloaded_radius)
    width = float(tyre.width) if tyre.width > 0 else 0.0
    edge, x = path_edge(road, width)
    limit = limits.MAX_EDGE_TO_RADIUS * r0
    if edge > limit:
        raise InputError(f"road '{road.name}': an edge {edge:.4g} m high at x = {x:.4g} m is taller "
                         f"than the tyre's unloaded radius {r0:.4g} m; the models hold for "
                         f"obstacles up to {limit:.4g} m: use a smaller obstacle or a larger tyre",
                         field="road")


#: a road whose height along the trailer's test-wheel path rises or falls by more than the
#: height that rolls the frame this far [deg] between the run's first and last quarter is
#: warned about: the trailer's hitch and left wheel stay on level ground
GRADE_ROLL = 5.0
#: ... and under the rolling rig, whose axle is held at a fixed height, by more than this
#: fraction of the tyre's static deflection (the load changes by about as much)
LEVEL_DEFLECTION = 0.5


def level_change(road, x0: float, x1: float) -> float:
    """How far [m] ``road``'s height along y = 0 rises from ``x0`` to ``x1`` [m]: the median of
    the path's last quarter less that of its first. A grade, a step up or down, a long wave;
    not an obstacle or a rough track between level ends (a pothole 0.5 m deep leaves both
    medians where they were, as a fitted line or the range would not)."""
    xmin, xmax = road.extent()[:2]
    x0, x1 = max(x0, xmin), min(x1, xmax)
    if not x1 > x0:
        return 0.0
    xs = np.linspace(x0, x1, 2001)
    z = np.asarray(road.height(xs, np.zeros_like(xs)), dtype=float)
    quarter = xs.size // 4
    return float(np.median(z[-quarter:]) - np.median(z[:quarter]))


def check_level(road, x0: float, x1: float, limit: float, why: str) -> str | None:
    """Warn when ``road`` rises or falls by more than ``limit`` [m] along the run from ``x0`` to
    ``x1`` [m] (:func:`level_change`), a rig that cannot follow it saying ``why``; returns the
    message, if any."""
    rise = level_change(road, x0, x1)
    if abs(rise) <= limit:
        return None
    message = (f"road '{road.name}' {'rises' if rise > 0 else 'falls'} {abs(rise):.3g} m from the "
               f"first quarter of the run's {x1 - x0:.3g} m to its last: {why}; for a road with a "
               "grade or long waves use the quarter-vehicle rig")
    physics_warning(message)
    return message


def check_level_for_trailer(road, x0: float, x1: float, track: float) -> str | None:
    """:func:`check_level` for the trailer, whose towing vehicle's hitch and left wheel stay on
    level ground: its frame rolls to follow the test wheel, beyond :data:`GRADE_ROLL` when
    the road rises by ``track`` sin(GRADE_ROLL) (on a 22 m road rising 1.2 m, 31 deg:
    "overturned", with advice about obstacles)."""
    return check_level(road, x0, x1, track * math.sin(math.radians(GRADE_ROLL)),
                       "the trailer's hitch and left wheel stay on level ground, so its frame "
                       f"rolls beyond {GRADE_ROLL:g} deg to follow the test wheel")


#: a height change [m] along the run's path from its start below which the road counts as level
RELIEF_TOLERANCE = 1e-3


def first_relief(road, x0: float) -> float | None:
    """The first x [m] from ``x0`` on at which ``road``'s height along y = 0 differs from its
    height at ``x0`` by more than :data:`RELIEF_TOLERANCE`; None if it is level to its end.
    Sampled at the road's own spacing (at most 5 cm)."""
    xmax = road.extent()[1]
    if not xmax > x0:
        return None
    step = max(min(float(road.default_spacing[0]), 0.05), (xmax - x0) / 2e6)
    xs = x0 + step * np.arange(int(np.floor((xmax - x0) / step)) + 1)
    z = np.asarray(road.height(xs, np.zeros_like(xs)), dtype=float)
    off = np.flatnonzero(np.abs(z - z[0]) > RELIEF_TOLERANCE)
    return float(xs[off[0]]) if off.size else None


def check_reaches_relief(road, x0: float, speed: float, duration: float, reach: float) -> str | None:
    """Warn when a run from ``x0`` at ``speed`` [m/s] for ``duration`` [s] ends before the
    tyre, reaching ``reach`` [m] (its radius) ahead of its centre, meets the road's first
    relief (:func:`first_relief`): such a run tests the tyre on level road only (a study's
    duration set for another speed, a measured road whose obstacle lies far along it).
    Returns the message, if any."""
    x1 = x0 + speed * duration
    relief = first_relief(road, x0)
    if relief is None or relief <= x1 + reach:
        return None
    need = (relief - reach - x0) / speed
    message = (f"the run ends {x1 - x0:.4g} m along road '{road.name}', before its first relief at "
               f"x = {relief:.4g} m (the road is level up to there): it rolls the tyre on level "
               f"road only; run it for at least {need:.3g} s (a run without a duration goes to the "
               "road's end)")
    physics_warning(message)
    return message


#: tyre files whose estimated spin inertia has been warned about in this process
_ESTIMATED_INERTIA: set = set()


def rig_spin_inertia(model, wheel_load: float) -> float:
    """The spin inertia [kg m^2] a rig turns ``model``'s wheel with at ``wheel_load`` [N]: the
    wheel's (:func:`tyrelab.limits.wheel_spin_inertia`), or its rim's where the model's own
    state carries the tyre's (the ring's belt, :func:`tyrelab.limits.rim_spin_inertia`). An
    estimate is warned about, once per file and process, when the wheel's spin matters: a
    handling model or a model with its own tangential forces (the ring) turns it; so is a rim
    the file's numbers left lighter than the floor."""
    tyre = model.tyre
    inertia, estimated = limits.wheel_spin_inertia(tyre, wheel_load)
    source = getattr(tyre.tir, "source", tyre.name)
    if estimated and (model.handling != "none" or model.has_state) and source not in _ESTIMATED_INERTIA:
        _ESTIMATED_INERTIA.add(source)
        mass = limits.wheel_mass(tyre, wheel_load)
        how = ("the file's" if tyre.wheel_mass > 0
               else "a tenth of the wheel load's, the quarter vehicle's rule")
        warnings.warn(f"{source}: no spin inertia ([INERTIA] WHEEL_IYY or IYY): the rig turns the "
                      f"wheel with {inertia:.3g} kg m^2, a uniform disc of the wheel's mass {mass:.4g} kg "
                      f"({how}) and its unloaded radius {tyre.unloaded_radius:.4g} m; give your wheel's "
                      "(tyre and rim), which its spin under the tyre's longitudinal force depends on",
                      UserWarning, stacklevel=3)
    carried = carried_inertia(model).spin_inertia
    if not carried > 0.0:
        return inertia
    rim, how = limits.rim_spin_inertia(tyre, wheel_load, carried)
    key = ("rim", source)
    if how == "floor" and key not in _ESTIMATED_INERTIA:
        _ESTIMATED_INERTIA.add(key)
        own = (f"its tyre's own {tyre.tyre_spin_inertia:.3g} kg m^2 ([INERTIA] IYY)"
               if tyre.tyre_spin_inertia > 0 else
               f"the {model.contact} model's {carried:.3g} kg m^2 (its belt at its radius; give the "
               "tyre's own as [INERTIA] IYY)")
        warnings.warn(f"{source}: the wheel's spin inertia {inertia:.3g} kg m^2 leaves less than "
                      f"{limits.RIM_SHARE:.0%} of it for the rim after {own}: the rig turns the rim "
                      f"with {rim:.3g} kg m^2", UserWarning, stacklevel=3)
    return rim


def carried_inertia(model) -> limits.Carried:
    """What ``model``'s own state carries of the wheel's inertia (the registry's ``carried``:
    the ring's belt), nothing for an analytic model."""
    hook = model.contact_model.carried
    return limits.NOTHING_CARRIED if hook is None else hook(model.tyre, **model.options)


def rig_rim_mass(model, mass: float, what: str = "the wheel's mass") -> float:
    """The mass [kg] a rig moves ``model``'s rim with, of ``mass`` [kg] (``what`` names it in
    the warning): all of it, less what the model's own state moves (the ring's belt,
    :func:`tyrelab.limits.rim_mass`). Told once per file and ``what`` when the numbers leave
    the rim less than the floor."""
    carried = carried_inertia(model).mass
    if not carried > 0.0:
        return float(mass)
    rim, floored = limits.rim_mass(mass, carried)
    source = getattr(model.tyre.tir, "source", model.tyre.name)
    if floored and ("mass", source, what) not in _ESTIMATED_INERTIA:
        _ESTIMATED_INERTIA.add(("mass", source, what))
        warnings.warn(f"{source}: {what} {mass:.4g} kg leaves less than {limits.RIM_SHARE:.0%} of "
                      f"it for the rim after the {model.contact} model's {carried:.4g} kg (its belt): "
                      f"the rig moves the rim with {rim:.4g} kg", UserWarning, stacklevel=3)
    return rim


def check_load_range(tyre, wheel_load: float) -> None:
    """Warn when the static wheel load is above the property file's FZMAX."""
    fz = limits.fzmax(tyre)
    if fz is not None and wheel_load > fz:
        physics_warning(f"the static wheel load {wheel_load / 1e3:.4g} kN is above FZMAX "
                        f"{fz / 1e3:.4g} kN of {tyre.name}: its handling coefficients are extrapolated; "
                        "use a load up to FZMAX")


def _longest_run(mask: np.ndarray) -> tuple[int, int]:
    """``(start, length)`` of the longest run of True in ``mask``."""
    if not mask.any():
        return 0, 0
    m = np.r_[False, mask, False].astype(np.int8)
    d = np.diff(m)
    starts = np.flatnonzero(d == 1)
    ends = np.flatnonzero(d == -1)
    lengths = ends - starts
    k = int(np.argmax(lengths))
    return int(starts[k]), int(lengths[k])


def _unsettled(t: np.ndarray, slip: np.ndarray, torque: float) -> list[str]:
    """The finding of a torque-driven run whose slip has not settled where a slip curve
    averages it (its mean still moving, :data:`UNSETTLED_SLIP`, or swinging wide,
    :data:`SWINGING_SLIP`), or none."""
    if len(t) < 4:
        return []
    start = t[0] + (1.0 - limits.STEADY_FRACTION) * (t[-1] - t[0])
    steady = slip[t >= start]
    half = 0.5 * (start + t[-1])
    first, second = float(np.mean(slip[(t >= start) & (t < half)])), float(np.mean(slip[t >= half]))
    low, high, mean = float(np.min(steady)), float(np.max(steady)), float(np.mean(steady))
    if abs(second - first) <= UNSETTLED_SLIP and max(high - mean, mean - low) <= SWINGING_SLIP:
        return []
    return [f"under the driving torque {torque:.6g} N m the slip has not settled in the run's last "
            f"{limits.STEADY_FRACTION:.0%} (the part a slip curve averages): its mean moved from "
            f"{first:.3g} to {second:.3g} between the halves and it ranges from {low:.3g} to {high:.3g}, "
            "so its means are no steady state; run it longer, or prescribe the slip (--slip)"]


def check_run(table, tyre) -> list[str]:
    """Check a run's signal table against the models' validity; warn once per finding.

    Returns the messages (also issued as :class:`PhysicsWarning`).
    """
    found: list[str] = []
    if len(table) == 0 or "RUNTIME" not in table.columns:
        return found
    t = table["RUNTIME"].to_numpy(dtype=float)
    r0 = float(tyre.unloaded_radius)
    if "DEFLECT" in table.columns:
        d = table["DEFLECT"].to_numpy(dtype=float)
        k = int(np.argmax(d))
        room, how = limits.rim_deflection(tyre)
        if d[k] >= r0:
            found.append(f"the wheel centre went below the road: deflection {d[k]:.3g} m at "
                         f"t = {t[k]:.3f} s is beyond the whole unloaded radius {r0:.4g} m; the "
                         "results after it are not physical: use a smaller obstacle, a lower speed "
                         "or load")
        elif d[k] > room:
            found.append(f"rim contact: deflection {d[k] * 1e3:.0f} mm at t = {t[k]:.3f} s is beyond "
                         f"the {room * 1e3:.0f} mm the tyre has ({how}); the models do not describe "
                         "a tyre pressed onto its rim: use a smaller obstacle, a lower speed or load")
    limit = math.radians(OVERTURN_ANGLE)
    for col, what in (("ROLL", "rolled"), ("PITCH", "pitched")):
        if col in table.columns:
            a = np.abs(table[col].to_numpy(dtype=float))
            k = int(np.argmax(a))
            if a[k] > limit:
                found.append(f"the trailer overturned: it {what} {math.degrees(a[k]):.0f} deg at "
                             f"t = {t[k]:.3f} s, beyond the {OVERTURN_ANGLE:g} deg the rig holds; "
                             "the results after it are not physical: use a smaller obstacle, a "
                             "smoother road class or a lower speed")
                break
    rig = str(table.attrs.get("metadata", {}).get("rig", ""))
    if "FZW" in table.columns and len(t) > 1:
        fz = table["FZW"].to_numpy(dtype=float)
        start, n = _longest_run(fz <= 0.0)
        if n > 1 and rig != "rolling":  # the rolling rig holds its axle: off the road is no jump
            dt_out = float(np.median(np.diff(t)))
            length = n * dt_out
            if length > AIRBORNE_TIME:
                found.append(f"the test wheel left the road for {length:.3g} s from t = {t[start]:.3f} s "
                             f"(longer than {AIRBORNE_TIME:g} s): the rig is airborne, not testing the "
                             "tyre: use a smaller obstacle or a lower speed")
        fzm = limits.fzmax(tyre)
        k = int(np.argmax(fz))
        if fzm is not None and fz[k] > limits.PEAK_LOAD_FACTOR * fzm:
            found.append(f"the normal force peaked at {fz[k] / 1e3:.4g} kN at t = {t[k]:.3f} s, more "
                         f"than {limits.PEAK_LOAD_FACTOR:g} x FZMAX {fzm / 1e3:.4g} kN of {tyre.name}: "
                         "the tyre's coefficients do not reach that far: use a lower load, speed or "
                         "obstacle")
    metadata = table.attrs.get("metadata", {})
    torque = float(metadata.get("torque_Nm", 0.0))
    if "torque_Nm" in metadata and "LONGSLIP" in table.columns:
        slip = float(table["LONGSLIP"].iloc[-1])
        if torque > 0.0 and slip > SPIN_UP_SLIP:
            found.append(f"the driving torque {torque:.6g} N m is more than the soil's shear "
                         f"carries under this load: the wheel spun up to a slip of {slip:.3g} "
                         f"({table['ROTSPEED'].iloc[-1]:.4g} rad/s at the end) and keeps "
                         "accelerating; a smaller torque, or a slip (--slip) for the pull at "
                         "full slip")
        else:
            found += _unsettled(t, table["LONGSLIP"].to_numpy(dtype=float), torque)
    for message in found:
        physics_warning(message)
    return found
