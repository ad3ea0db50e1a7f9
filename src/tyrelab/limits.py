"""The bounds every number a user gives must lie in, each with its reason.

One place for them. A value outside its bound is an
:class:`~tyrelab.errors.InputError` naming the argument, the value and the
allowed range, raised before any work. These physical bounds are hard; the
resources a request may use (memory, wall time, worker processes), which
``force=True`` lifts, are :mod:`tyrelab.resources`'.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from .errors import InputError

# --- the ring's internal step, the steady part of a slip curve ---------------------------

#: the part of a slip-curve run whose mean is its steady state: the second half
#: (:func:`tyrelab.rig.single_wheel.slip_curve`, the study's soil tables, the guards)
STEADY_FRACTION = 0.5
#: the ring's largest default internal step [s] (``tyrelab.tyre.ring.model.ACCURATE_STEP``), set
#: by accuracy where stability would allow a little more (400 us at 100 segments; docs/ring.md,
#: "Performance", "Why 1/3 ms": the cleat peak within 0.5 % of half the step; on the Belgian
#: paving the tangential forces no further from a 128 times finer step than the explicit
#: integrator was at 35.8 us; three internal steps per 1 ms rig step). Kept here, below the
#: models, because a run's cost estimate needs it too: a model with its own dynamics costs
#: more only for rig steps below it
DYNAMIC_INTERNAL_STEP = 1.0 / 3000.0
# --- speed, time, rate -----------------------------------------------------------------

#: towing speed [m/s]: above 0.01 m/s (0.036 km/h: slower, a run to a road's end lasts
#: hours and the rolling rig's quasi-static test is the better tool), up to 200 km/h
#: (the study spec's limit; the thesis drives at most 88 km/h and no off-road tyre
#: test is faster; above it a step of 1 ms moves the wheel past a 50 mm cleat)
MIN_SPEED, MAX_SPEED = 0.01, 200.0 / 3.6
#: simulated time [s]: at most one hour (no rig test lasts longer; the 100 m tracks at
#: 3 km/h take 2 min); at least :data:`MIN_STEPS` time steps and :data:`MIN_SAMPLES`
#: output samples (a shorter run has no signal to write)
MAX_DURATION = 3600.0
MIN_STEPS, MIN_SAMPLES = 10, 2
#: time step [s]: at least 1 us (smaller adds only round-off and hours of run time);
#: at most 10 ms (the rigs' slowest stated accuracy: the peak force over the 50 mm cleat
#: changes by 0.2 % from 1 ms to 0.1 ms) and the model's stable step (:func:`stable_step`)
MIN_DT, MAX_DT = 1e-6, 0.01
#: analytic models: dt <= STABILITY_FACTOR / omega, omega the wheel-hop mode
#: sqrt(k_max / m_wheel): about 12 steps per period. Semi-implicit Euler is stable for
#: omega dt < 2; at omega dt = 0.5 the quarter vehicle's peak force over the 50 mm cleat is
#: within 1 % of the 1 ms value, at omega dt = 1 it is 36 % off (measured, XZL 300 kPa)
STABILITY_FACTOR = 0.5
#: models with their own dynamics (the ring): largest rig step [s] (measured: the ring on
#: the quarter vehicle and the trailer over the 50 mm cleat is stable at 2 ms and
#: diverges at 3 ms; its internal step is separate and always stable)
DYNAMIC_MAX_DT = 2e-3
#: output rate [Hz]: positive and at most 1/dt (one sample per time step)
MAX_OUTPUT_RATE = 1.0 / MIN_DT

# --- loads and pressures ---------------------------------------------------------------

#: smallest wheel load [N]: 1 N (less is a number in the wrong unit; the rigs refuse loads
#: their own masses cannot carry)
MIN_LOAD = 1.0
#: inflation pressure [Pa]: 20 kPa (a deflated off-road tyre) to 1.5 MPa (earthmover
#: tyres run at 0.7-1.0 MPa)
MIN_PRESSURE, MAX_PRESSURE = 20e3, 1.5e6
#: a tyre file without RIM_RADIUS: rim contact is assumed at this fraction of R0 of
#: deflection (no tyre's sidewall is taller than its rim radius)
RIM_FALLBACK_DEFLECTION = 0.5
#: warn when a run's peak normal force exceeds this multiple of the file's FZMAX
PEAK_LOAD_FACTOR = 3.0

# --- tyre property files ---------------------------------------------------------------

#: unloaded radius [m]: up to 2.5 m (the largest mining tyres are 4 m in diameter)
MAX_RADIUS = 2.5
#: section width [m]: up to 2 m (mining tyres are 1.5 m wide)
MAX_WIDTH = 2.0
#: vertical stiffness [N/m]: up to 1e9 (a steel wheel on rail is about 1e9 N/m; tyres
#: are 1e5-1e7); a stiffer spring only makes every step unstable
MAX_STIFFNESS = 1e9
#: vertical damping [N s/m]: up to 1e7 (tyres: 1e2-1e4)
MAX_DAMPING = 1e7
#: wheel mass [kg] and spin inertia [kg m^2]: up to 10 t and 1e4 kg m^2 (mining wheels:
#: 5 t, about 5000 kg m^2)
MAX_WHEEL_MASS, MAX_WHEEL_INERTIA = 1e4, 1e4
#: any other number in a property file: its magnitude at most this (an absurd value is a
#: typo or a damaged file; 1e12 leaves room for stiffnesses per m^2 and pressures in Pa)
MAX_TIR_MAGNITUDE = 1e12

# --- model resolution (options) ---------------------------------------------------------

#: the flexible ring's belt segments: at least 12 (a polygon that still rolls), at most 1000.
#: Its out-of-plane matrix is 2N x 2N (32 MB at 1000; 298 GB at 100,000, which ended in an
#: out-of-memory error), and its stable step falls with N (400 us at 100, 161 us at 200)
MIN_RING_SEGMENTS, MAX_RING_SEGMENTS = 12, 1000
#: the ring's tread blocks per segment: at most 100 (the built-in ring has 10; each block is
#: a contact element evaluated every internal step)
MAX_RING_BLOCKS = 100
#: the ring's samples across a block's width: at most 16 (statics use 4)
MAX_LATERAL_SAMPLES = 16
#: the enveloping model's cams along and across the patch: at most 100 each way (the
#: built-in tyre has 15 x 10; ``tyrelab fit cams`` searches up to 20)
MAX_CAMS = 100
#: the volume model's discs per half width: at most 100 (the XZL's shape table gives 8)
MAX_DISCS = 100

# --- roads -----------------------------------------------------------------------------

#: obstacle heights and depths [m]: up to 1 m (a cleat, bump, step or pothole taller than
#: a large tyre's radius is no longer a road feature a tyre rolls over)
MAX_OBSTACLE_HEIGHT = 1.0
#: obstacle sizes along the road [m] (cleat width, pothole length, bump ramps and top):
#: at least 1 mm (the grid resolves edges to 1 mm; finer means millions of nodes) and at
#: most 50 m (longer is a change of road level: a step or a track)
MIN_OBSTACLE_SIZE, MAX_OBSTACLE_LENGTH = 1e-3, 50.0
#: obstacle sizes across the road [m] (pothole width): at most the 4 m road width
MAX_OBSTACLE_WIDTH = 4.0
#: an edge (height change between neighbouring grid nodes along the wheel's path) higher
#: than this multiple of the tyre's unloaded radius is refused: the wheel centre would be
#: below its top, which none of the models describes
MAX_EDGE_TO_RADIUS = 1.0
#: road grid spacing [m]: 1 mm to 10 m
MIN_GRID_SPACING, MAX_GRID_SPACING = 1e-3, 10.0
#: road heights in a file [m]: |z| at most 10 km (the highest road is at 5.8 km)
MAX_ROAD_HEIGHT = 1e4
#: synthesised random roads: at most 10 km long and 100 m wide
MAX_ROAD_LENGTH, MAX_ROAD_WIDTH = 1e4, 100.0
#: profiles averaged by ``road spectrum --lines``: at most 1000 (a 4 m road has 1000
#: lanes 4 mm apart; more add nothing)
MAX_SPECTRUM_LINES = 1000

# --- other commands --------------------------------------------------------------------

#: belt segments of the ring's modal analysis: 12 (fewer cannot show the modes of Table
#: 3-3) to 600 (the dense eigenproblem grows as n^3: 100 take 6 s, 400 take 50 s)
MIN_SEGMENTS, MAX_SEGMENTS = 12, 600
#: deflections of the static press: 2 to 200
MIN_STATIC_STEPS, MAX_STATIC_STEPS = 2, 200
#: optimizer budget of ``fit ring``: 1 to 1000 evaluations (25 take several minutes)
MAX_FIT_EVALUATIONS = 1000


# --- checks ----------------------------------------------------------------------------

def _g(value) -> str:
    return f"{value:.6g}"


#: relative rounding a value may have at a closed bound of :func:`check_number` (a unit
#: conversion's last bits), and still be on it
BOUND_ROUNDING = 1e-12


def check_number(value, field: str, low=None, high=None, unit: str = "", low_open: bool = False,
                 what: str | None = None, scale: float = 1.0, given: str | None = None) -> float:
    """``value`` as a finite float inside ``[low, high]`` (``(low, ...`` with ``low_open``).

    ``scale`` converts the bounds for the message (e.g. 3.6 to state m/s bounds in km/h);
    ``given``, the text the user typed, is quoted in it as typed.
    """
    name = what or field
    try:
        if isinstance(value, bool):  # float(True) is 1.0: a flag given for a number
            raise TypeError
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}", field=field) from None
    unit_txt = f" {unit}" if unit else ""
    if not math.isfinite(v):
        raise InputError(f"{name} must be a finite number, got {value!r}", field=field)
    # a closed bound holds to rounding: 0.036 km/h, the stated least speed, is
    # 0.036 / 3.6 = 0.009999999999999998 m/s, below MIN_SPEED's 0.01 by one ulp
    slack = BOUND_ROUNDING
    lo_bad = low is not None and (v <= low if low_open else v < low - slack * abs(low))
    hi_bad = high is not None and v > high + slack * abs(high)
    if lo_bad or hi_bad:
        if low is not None and high is not None:
            rng = f"{_g(low * scale)}{' <' if low_open else ' <='} {name} <= {_g(high * scale)}{unit_txt}"
        elif low is not None:
            rng = f"{'>' if low_open else '>='} {_g(low * scale)}{unit_txt}"
        else:
            rng = f"<= {_g(high * scale)}{unit_txt}"
        shown = given if given is not None else _g(v * scale)
        raise InputError(f"{name} {shown}{unit_txt} is out of range; allowed: {rng}",
                         field=field)
    return v


def check_count(value, field: str, low: int, high: int, what: str | None = None) -> int:
    """An integer in ``[low, high]``."""
    name = what or field
    if isinstance(value, bool) or not isinstance(value, int):
        try:
            if float(value) != int(value):
                raise ValueError
            value = int(value)
        except (TypeError, ValueError, OverflowError):
            raise InputError(f"{name} must be a whole number, got {value!r}", field=field) from None
    if not low <= value <= high:
        raise InputError(f"{name} {value} is out of range; allowed: {low} to {high}", field=field)
    return int(value)


class Bound(NamedTuple):
    """The bound of a model's option: ``what`` it is (for the message), ``low`` to ``high``
    (None: no bound that side; ``low_open``: ``low`` itself excluded) in ``unit``; ``whole``
    for a count (:func:`check_count`, which needs both ends)."""

    what: str | None
    low: float | None = None
    high: float | None = None
    unit: str = ""
    whole: bool = False
    low_open: bool = False


#: a contact model's sampling step [m] along a section: a finite number > 0
SAMPLING_STEP = Bound("sampling step", 0.0, unit="m", low_open=True)


def bounded_options(options: dict, bounds: dict) -> dict:
    """The options among ``options`` that ``bounds`` (name -> :class:`Bound`) bounds, checked
    and converted; one given as None is left out (the model's default). An impossible value
    is an :class:`InputError` whose field is the option's name."""
    out = {}
    for key, b in bounds.items():
        value = options.get(key)
        if value is None:
            continue
        out[key] = (check_count(value, key, b.low, b.high, b.what) if b.whole else
                    check_number(value, key, b.low, b.high, b.unit, low_open=b.low_open, what=b.what))
    return out


def check_speed(speed, field: str = "speed") -> float:
    """A towing speed [m/s] inside [MIN_SPEED, MAX_SPEED]."""
    return check_number(speed, field, MIN_SPEED, MAX_SPEED, "m/s")


def check_dt(dt, field: str = "dt") -> float:
    """A time step [s] inside [MIN_DT, MAX_DT] (the model's stable step is checked apart)."""
    return check_number(dt, field, MIN_DT, MAX_DT, "s", what="time step")


def check_rate(rate, dt, field: str = "output_rate") -> float:
    """An output rate [Hz]: positive and at most one sample per time step."""
    r = check_number(rate, field, 0.0, None, "Hz", low_open=True, what="output rate")
    if r * dt > 1.0 + 1e-9:
        raise InputError(f"output rate {_g(r)} Hz is faster than the time step {_g(dt)} s allows; "
                         f"allowed: at most {_g(1.0 / dt)} Hz (or a smaller time step)", field=field)
    return r


def check_duration(duration, dt, rate, field: str = "duration") -> float:
    """A simulated time [s]: at most MAX_DURATION, at least MIN_STEPS steps and MIN_SAMPLES samples."""
    low = max(MIN_STEPS * dt, MIN_SAMPLES / rate)
    d = check_number(duration, field, None, MAX_DURATION, "s", what="duration")
    if d < low * (1 - 1e-9):
        raise InputError(f"duration {_g(d)} s is too short; allowed: at least {_g(low)} s "
                         f"({MIN_STEPS} time steps of {_g(dt)} s and {MIN_SAMPLES} output samples "
                         f"at {_g(rate)} Hz)", field=field)
    return d


def check_pressure(pressure, field: str = "pressure") -> float:
    """An inflation pressure [Pa] inside [MIN_PRESSURE, MAX_PRESSURE]."""
    return check_number(pressure, field, MIN_PRESSURE, MAX_PRESSURE, "kPa", what="pressure",
                        scale=1e-3)


def rim_deflection(tyre) -> tuple[float, str]:
    """Deflection [m] at which the rim meets the road, and how it was found."""
    r0 = float(tyre.unloaded_radius)
    rim = None
    try:
        rim = tyre.tir.number("DIMENSION", "RIM_RADIUS", default=None)
    except InputError:
        rim = None
    if rim is not None and 0 < rim < r0:
        return r0 - rim, f"unloaded radius {r0:.4g} m less RIM_RADIUS {rim:.4g} m"
    return RIM_FALLBACK_DEFLECTION * r0, (f"{RIM_FALLBACK_DEFLECTION:g} x the unloaded radius "
                                          f"{r0:.4g} m (the file gives no RIM_RADIUS)")


def max_wheel_load(tyre) -> float:
    """The static load [N] that presses the tyre down to its rim (vertical law)."""
    room, _ = rim_deflection(tyre)
    law = tyre.vertical_law
    return float(law.static_load([room])[0])


def check_wheel_load(load, tyre, field: str = "load") -> float:
    """A static wheel load [N]: at least MIN_LOAD and below the load that puts the rim on the road."""
    v = check_number(load, field, MIN_LOAD, None, "N", what="wheel load")
    top = max_wheel_load(tyre)
    if v >= top:
        room, how = rim_deflection(tyre)
        raise InputError(f"wheel load {_g(v)} N would press {tyre.name} onto its rim (it reaches "
                         f"the rim, {room * 1e3:.0f} mm = {how}, at {_g(top)} N); allowed: "
                         f"{_g(MIN_LOAD)} N to below {_g(top)} N", field=field)
    return v


def fzmax(tyre) -> float | None:
    """The file's FZMAX [N] ([VERTICAL_FORCE_RANGE]), if it states one."""
    try:
        v = tyre.tir.number("VERTICAL_FORCE_RANGE", "FZMAX", default=None)
    except InputError:
        return None
    return v if v is not None and math.isfinite(v) and v > 0 else None


def wheel_hop_omega(tyre, wheel_load: float) -> tuple[float, float, float]:
    """``(omega, k_max, mass)`` of the wheel-hop mode: the stiffest tangent of the vertical
    law up to rim contact over the wheel mass (or, without one in the file, a tenth of the
    wheel load's mass, the quarter vehicle's rule)."""
    import numpy as np

    law = tyre.vertical_law
    room, _ = rim_deflection(tyre)
    if law.use_table:
        rho = np.linspace(0.0, room, 257)
        f = law.static_load(rho)
        k_max = float(np.max(np.diff(f) / np.diff(rho)))
        k_max = max(k_max, 0.0)
    else:
        k_max = float(law.stiffness)
    mass = max(wheel_mass(tyre, wheel_load), 1e-6)
    return math.sqrt(max(k_max, 1e-9) / mass), k_max, mass


def wheel_mass(tyre, wheel_load: float) -> float:
    """The wheel's mass [kg]: the file's (``WHEEL_MASS`` or ``MASS``), or without one a tenth of
    the static wheel load's mass, the quarter vehicle's rule."""
    return float(tyre.wheel_mass) if tyre.wheel_mass > 0 else 0.1 * float(wheel_load) / 9.80665


def wheel_spin_inertia(tyre, wheel_load: float) -> tuple[float, bool]:
    """``(inertia [kg m^2], estimated)``: the spin inertia a rig turns the wheel with.

    The file's (``WHEEL_IYY`` or ``IYY``); without one, a uniform disc of the wheel's mass
    (:func:`wheel_mass`) and the unloaded radius, ``m R0^2 / 2`` (a wheel of tyre and rim is
    0.4-0.6 m R0^2: the XZL's file 0.43, MFeval's MF 6.1 example tyre 0.41), never the
    :data:`tyrelab.tyre.params.MIN_SPIN_INERTIA` a file without one left before: under a
    handling model's slip stiffness that wheel's spin ran away past the force's peak
    (+-1e4 rad/s, step to step, over a 50 mm cleat).
    """
    if tyre.wheel_spin_inertia > 0:
        return float(tyre.wheel_spin_inertia), False
    return 0.5 * wheel_mass(tyre, wheel_load) * float(tyre.unloaded_radius) ** 2, True


#: the least share of the wheel's spin inertia a rig turns the rim with when the model's own state
#: carries the tyre's (:func:`rim_spin_inertia`): a rim and what turns with it are 5-30 % of a
#: wheel's (the XZL's file: 3.4 of 50 kg m^2, 7 %; a car's alloy wheel about a quarter)
RIM_SHARE = 0.05


class Carried(NamedTuple):
    """What a tyre model's own state carries of the wheel's inertia (the ring's belt): its mass
    [kg] and its spin inertia about the axle [kg m^2]. The rigs move the rim with the rest."""

    mass: float
    spin_inertia: float


#: what an analytic model carries: nothing (the rigs move the whole wheel)
NOTHING_CARRIED = Carried(0.0, 0.0)


def rim_mass(mass: float, carried: float) -> tuple[float, bool]:
    """``(mass [kg], floored)``: the mass a rig moves the rim with, the wheel's (or the quarter
    vehicle's unsprung) ``mass`` less the ``carried`` mass the tyre model's own state moves (the
    ring's belt: the XZL's 240 - 154 = 86 kg); at least :data:`RIM_SHARE` of it (``floored``:
    the numbers left less). The weight stays the whole ``mass``: the ring's belt has none of its
    own (its weight is the rim's to carry, as the file's wheel mass says)."""
    rim = float(mass) - float(carried)
    if rim < RIM_SHARE * float(mass):
        return RIM_SHARE * float(mass), True
    return rim, False


def rim_spin_inertia(tyre, wheel_load: float, carried: float) -> tuple[float, str]:
    """``(inertia [kg m^2], how)``: the spin inertia a rig turns the rim with when the tyre
    model's own state carries ``carried`` [kg m^2] of the tyre's (the ring's belt, its mass at
    the belt radius); ``how`` says where it came from, ``"floor"`` when the file's numbers left
    the rim less than :data:`RIM_SHARE` of the wheel's.

    The wheel's (:func:`wheel_spin_inertia`) less the tyre's own: the file's ``IYY`` (MF-Tyre's
    ``[INERTIA] IYY``, the tyre alone) when it also gives the wheel's ``WHEEL_IYY``, else what
    the model carries; at least ``RIM_SHARE`` of the wheel's. A model carrying none (the
    analytic models) turns the whole wheel. A rig that turned the whole wheel's inertia with the
    ring's belt turning its own counted the tyre's twice (the XZL: 50 + 64 kg m^2 where the ring's
    wheel has 3.4 + 64).
    """
    whole, _ = wheel_spin_inertia(tyre, wheel_load)
    if not carried > 0.0:
        return whole, "wheel"
    own = tyre.tyre_spin_inertia
    rim, how = (whole - own, "IYY") if own > 0.0 else (whole - carried, "carried")
    if rim < RIM_SHARE * whole:
        return RIM_SHARE * whole, "floor"
    return rim, how


def stable_step(model, wheel_load: float) -> tuple[float, str]:
    """Largest rig time step [s] for ``model`` (a TyreModel) carrying ``wheel_load`` [N],
    and the reason, for the message."""
    if model.has_state:
        return DYNAMIC_MAX_DT, (f"the {model.contact} model is stable up to "
                                f"{DYNAMIC_MAX_DT * 1e3:g} ms (measured)")
    omega, k_max, mass = wheel_hop_omega(model.tyre, wheel_load)
    dt = STABILITY_FACTOR / omega
    c = float(model.tyre.vertical_damping)
    why = (f"wheel hop at {omega:.3g} rad/s from the stiffest {k_max:.3g} N/m of the vertical law "
           f"and {mass:.3g} kg; stable step {STABILITY_FACTOR:g}/omega")
    if c > 0:
        dt_c = STABILITY_FACTOR * 2.0 * mass / c
        if dt_c < dt:
            dt = dt_c
            why = f"damping {c:.3g} N s/m on {mass:.3g} kg; stable step {STABILITY_FACTOR:g} x 2 m/c"
    return min(dt, MAX_DT), why


def check_stable_step(dt: float, models, wheel_load: float, field: str = "dt") -> None:
    """Refuse a time step above the stable step of any of ``models``."""
    for model in models:
        limit, why = stable_step(model, wheel_load)
        if dt > limit * (1 + 1e-9):
            raise InputError(f"time step {_g(dt)} s is above the stable step of the {model.contact} "
                             f"model on {model.tyre.name} ({why}); allowed: at most {_g(limit)} s",
                             field=field)
