"""The ring model's Python side: its parameter record, its initial state, its registration.

:func:`ring_params` builds the :class:`~.records.RingParams` record the
compiled step takes, at the tyre's inflation pressure;
:func:`ring_initial_state` returns the belt (:class:`~.records.RingState`)
in static equilibrium on a flat road at the rigs' starting height
``R0 - static_deflection(load)``. The "ring" (evenly spaced blocks) and
"ring-tp" (blocks on the tread pattern) contact models register at the
bottom: both run :func:`~.kernel.ring_step`.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np

from ...errors import InputError
from ...limits import (DYNAMIC_INTERNAL_STEP, MAX_LATERAL_SAMPLES, MAX_RING_BLOCKS, MAX_RING_SEGMENTS,
                       MIN_RING_SEGMENTS, Bound, bounded_options)
from ..registry import ContactModel, register_contact
from .kernel import ring_step
from .parameters import ring_parameters, stable_step, tread_half_width
from .pattern import default_pattern, even_blocks, pattern_blocks, read_pattern
from .implicit import lateral_checksum, lateral_stiffness_matrix
from .records import KIN_TIME, RingParams, RingState, copy_state, empty_state, params_key
from ..static import PC
from .static import footprint_from_blocks, settle
#: default discretisation (thesis 2.3.4: 100-200 belt elements, 10-100 blocks each)
N_SEGMENTS = 100
N_BLOCKS = 10
#: relaxation damping rate [1/s] used to find static equilibria
RELAX_RATE = 250.0
#: largest default internal step [s], set by accuracy where stability would allow
#: more (:data:`tyrelab.limits.DYNAMIC_INTERNAL_STEP`, where it is set and why)
ACCURATE_STEP = DYNAMIC_INTERNAL_STEP
#: samples across a block's width in a static test on a road that varies across
#: the wheel (a longitudinal cleat): one every ~10 mm
STATIC_LATERAL_SAMPLES = 4

_OPTIONS = ("n_segments", "n_blocks", "friction", "dt_max", "pattern", "parameters", "relax",
            "lateral_samples")
#: what the model must be given, measured (thesis chapter 4)
#: the steps of ``tyrelab fit`` that identify the ring (its own step last: it starts from the others)
_FIT_STEPS = ("vertical", "damping", "patch", "shape", "ring")
_DATA = ("load-deflection curve + modal tests (belt eigenfrequencies) + static cleat tests + "
         "footprints")
#: the options by type (tyrelab.tyre.registry.check_options); ``pattern`` (a dict of blocks
#: or a file) and ``parameters`` (a RingParameters record) are Python values
_OPTION_TYPES = {"n_segments": int, "n_blocks": int, "friction": float, "dt_max": float,
                 "pattern": object, "parameters": object, "relax": float, "lateral_samples": int}


#: the bounded options of the ring models (``dt_max`` depends on the parameters:
#: :func:`ring_params` checks it)
RING_BOUNDS = {"n_segments": Bound("ring segments", MIN_RING_SEGMENTS, MAX_RING_SEGMENTS, whole=True),
               "n_blocks": Bound("tread blocks per segment", 1, MAX_RING_BLOCKS, whole=True),
               "friction": Bound("friction coefficient", 0.0),
               "relax": Bound("relaxation rate", 0.0, unit="1/s"),
               "lateral_samples": Bound("lateral samples", 1, MAX_LATERAL_SAMPLES, whole=True)}
#: the ring models' option values, checked (``ContactModel.check_values``)
ring_option_values = partial(bounded_options, bounds=RING_BOUNDS)


def ring_params(tyre, grid=None, tread_pattern=False, n_segments=N_SEGMENTS, n_blocks=N_BLOCKS,
                friction=None, dt_max=None, pattern=None, parameters=None, relax=0.0,
                lateral_samples=None, **options) -> RingParams:
    """The :class:`~.records.RingParams` of the flexible ring for ``tyre`` at ``tyre.pressure``.

    Parameters
    ----------
    tyre : Tyre
        Dimensions, carcass shape, pressure; ring parameters from its
        ``[FLEXIBLE_RING]`` or the built-in identified file.
    grid : RoadGrid, optional
        The road; only needed for the default of ``lateral_samples`` in a
        static build (the contact search adapts to any road).
    tread_pattern : bool
        Place blocks from the tread ``pattern`` ("ring-tp") instead of evenly.
    n_segments, n_blocks : int
        Belt segments N and blocks per segment NB.
    friction : float, optional
        Overrides FRICTION.
    dt_max : float, optional
        Largest internal step [s]; default the smaller of :data:`ACCURATE_STEP`
        and :func:`stable_step`; above twice the latter (its stability bound)
        an :class:`InputError`.
    pattern : dict or path, optional
        Tread pattern (default: the tyre's built-in pattern).
    parameters : RingParameters, optional
        Overrides the parameters read from files (identification uses it).
    relax : float
        Extra velocity damping rate [1/s] (static relaxation only; the
        registry adds ``relax=RELAX_RATE`` for static tests).
    lateral_samples : int, optional
        Samples across a block's width where the road is uneven under it
        (see :mod:`.tread`); 1 = along the strip only. Default 1, but
        :data:`STATIC_LATERAL_SAMPLES` in a static build (``relax`` > 0) on a
        ``grid`` that varies across the wheel (a longitudinal cleat).
    """
    unknown = set(options) - set(_OPTIONS)
    if unknown:
        raise InputError(f"unknown ring option(s) {', '.join(sorted(unknown))}; expected "
                         f"{', '.join(_OPTIONS)}", field="model")
    bounded = ring_option_values({"n_segments": n_segments, "n_blocks": n_blocks,
                                  "friction": friction, "relax": relax,
                                  "lateral_samples": lateral_samples})
    n, nb = bounded.get("n_segments", N_SEGMENTS), bounded.get("n_blocks", N_BLOCKS)
    relax = bounded.get("relax", 0.0)
    friction, lateral_samples = bounded.get("friction"), bounded.get("lateral_samples")
    rp = parameters if parameters is not None else ring_parameters(tyre)
    p = float(tyre.pressure)
    if not (math.isfinite(p) and p > 0):
        raise InputError("the ring model needs the inflation pressure (INFLPRES)",
                         source=tyre.tir.source, field="INFLPRES")
    if lateral_samples is None:
        varies_across = grid is not None and not grid.uniform_across()
        lateral_samples = STATIC_LATERAL_SAMPLES if relax > 0 and varies_across else 1
    r0 = tyre.unloaded_radius
    rb = r0 - rp.tread_depth
    dth = 2.0 * math.pi / n
    l0 = 2.0 * rb * math.sin(0.5 * dth)
    ks = rp.at_pressure(p)
    if tread_pattern:
        pat = read_pattern(pattern) if pattern is not None else default_pattern(tyre)
        y, s, h, area = pattern_blocks(tyre, rp, n, nb, pat)
    else:
        y, s, h, area = even_blocks(tyre, rp, n, nb)
    half = tread_half_width(tyre, rp)
    m = rp.ring_mass / n
    seg = rb * dth  # arc length per segment, for the per-length quantities
    stable = stable_step(rp, tyre, n, nb)
    if dt_max is None:
        step = min(stable, ACCURATE_STEP)
    else:
        step = float(dt_max)
        # stable_step keeps a safety factor of 2 below the stability bound
        if not (math.isfinite(step) and 0.0 < step <= 2.0 * stable):
            raise InputError(f"ring internal step dt_max = {step:g} s is outside (0, {2.0 * stable:.3g}] s, "
                             f"the stability limit of these parameters ({n} segments: foundation, "
                             f"tension, in-plane bending, tread); use at most {stable:.3g} s",
                             field="dt_max")
    if relax > 0:
        step = min(step, 0.5 / relax)
    th = dth * np.arange(n)

    def table(a):
        return np.ascontiguousarray(a, dtype=np.float64).copy()

    params = RingParams(
        n_segments=n, n_blocks=nb, lateral_samples=max(1, int(lateral_samples)),
        unloaded_radius=float(r0), belt_radius=float(rb), pressure=p,
        segment_mass=float(m), segment_twist_inertia=float(m * (2.0 * half) ** 2 / 12.0),
        radial_stiffness=float(ks["kr"] * seg), tangential_stiffness=float(ks["kt"] * seg),
        lateral_stiffness=float(ks["ky"] * seg), torsion_stiffness=float(ks["kb"] * seg),
        # the patch element's damper c = g tau k on the deflection rate, k the
        # tyre's linear vertical stiffness (eq. 2.2); static builds leave it out
        patch_hysteresis_gain=(float(rp.cp / (tyre.vertical_stiffness * rp.tau_p))
                               if relax == 0 and rp.cp > 0 else 0.0),
        patch_hysteresis_time=float(rp.tau_p),
        radial_damping=float(rp.cr * seg), tangential_damping=float(rp.ct * seg),
        lateral_damping=float(rp.cy * seg), torsion_damping=float(rp.cb * seg),
        # pre-tension in exact equilibrium with the pressure on the polygon
        pretension=float(ks["pb"] * rb * math.cos(0.5 * dth)),
        extension_stiffness=float(rp.ea), extension_damping=float(rp.cea),
        bending_stiffness=float(rp.ei), lateral_bending_stiffness=float(rp.eio),
        belt_torsion_stiffness=float(rp.gj), pressure_load=float(ks["pb"]),
        tread_stiffness=float(rp.tread_stiffness), tread_progression=float(rp.tread_progression),
        tread_damping=float(rp.tread_damping),
        tread_shear_stiffness=float(rp.tread_shear_stiffness),
        tread_shear_damping=float(rp.tread_shear_damping),
        friction=float(rp.friction if friction is None else friction),
        max_step=float(step), relax_rate=float(relax), chord_length=float(l0),
        segment_angle=float(dth), max_block_height=float(h.max()),
        tread_half_width=float(half),
        cos_theta=table(np.cos(th)), sin_theta=table(np.sin(th)),
        block_y=table(y), block_s=table(s), block_h=table(h), block_area=table(area),
        lateral_matrix=np.zeros((2 * n, 2 * n)), lateral_checksum=0.0, rolling_radius=float(r0))
    k = lateral_stiffness_matrix(params)
    return params._replace(lateral_matrix=k, lateral_checksum=lateral_checksum(k))


def nominal_state(params: RingParams) -> RingState:
    """The unloaded, undeformed belt at rest (p_i = Rb (cos, sin) th_i)."""
    state = empty_state(params.n_segments, params.n_blocks)
    state.p1[:] = params.belt_radius * params.cos_theta
    state.p2[:] = params.belt_radius * params.sin_theta
    return state


_CACHE: dict = {}
#: static and rolling equilibria are found to this share of the load
EQUILIBRIUM_TOLERANCE = 2e-4
#: an equilibrium search that ends further than this from the load is warned about: the
#: rigs are tested to start flat within it (tests/test_fidelity.py); the rolling search at
#: 3 km/h, LC2, ends at -0.085 % (the tread's stick renewal makes its windows noisy)
EQUILIBRIUM_WARNING = 2e-3
#: secant corrections of the static and the rolling equilibrium at most
EQUILIBRIUM_ITERATIONS = 8
ROLLING_ITERATIONS = 6
#: rolling equilibrium: settling time, then each correction rolls twice this window [s]
ROLL_SETTLE = 0.6
ROLL_WINDOW = 0.2


def _cached(key, make):
    if key not in _CACHE:
        if len(_CACHE) > 32:
            _CACHE.clear()
        _CACHE[key] = make()
    return _CACHE[key]


def unconverged_equilibrium(kind: str, force: float, load: float) -> None:
    """Warn (:class:`~tyrelab.guards.PhysicsWarning`, one line) when an equilibrium search
    ended further than :data:`EQUILIBRIUM_WARNING` from ``load`` (it aims at
    :data:`EQUILIBRIUM_TOLERANCE`): the rig then starts off equilibrium by that much."""
    if abs(force - load) < EQUILIBRIUM_WARNING * load:
        return
    import warnings

    from ...guards import PhysicsWarning
    warnings.warn(f"the ring's {kind} equilibrium under {load / 1e3:.4g} kN ended at "
                  f"{force / 1e3:.4g} kN ({100 * (force / load - 1):+.3g} %, more than "
                  f"{100 * EQUILIBRIUM_WARNING:g} %): the run starts that far from equilibrium; "
                  "check the ring's parameters", PhysicsWarning, stacklevel=2)


def ring_static_equilibrium(tyre, load, tread_pattern=False, **options):
    """``(height, state)``: the rim centre height [m] at which the ring, relaxed
    on a flat road, carries ``load`` [N], and that belt state.

    The ring's own load-deflection, not the tyre's ``[DEFLECTION_LOAD_CURVE]``
    (they differ by the identification's error, a few percent): secant
    iterations on the height, each a relaxed press (:func:`.static.settle`)
    from the last, until the force is within :data:`EQUILIBRIUM_TOLERANCE`.
    """
    from ...road.obstacles import Flat
    grid = Flat().grid()
    relaxed = dict(options)
    relaxed["relax"] = RELAX_RATE
    rp = ring_params(tyre, grid, tread_pattern=tread_pattern, **relaxed)
    load = float(load)

    def make():
        state = nominal_state(rp)
        road = grid.surface()
        h0 = tyre.unloaded_radius - tyre.static_deflection(load)
        f0 = float(settle(rp, state, road, [h0])[0, PC.FZ])
        h1 = h0 - (load - f0) / max(tyre.vertical_stiffness, 1.0)
        for k in range(EQUILIBRIUM_ITERATIONS):
            f1 = float(settle(rp, state, road, [h1], start=h1)[0, PC.FZ])
            if abs(f1 - load) < EQUILIBRIUM_TOLERANCE * load or f1 == f0 \
                    or k == EQUILIBRIUM_ITERATIONS - 1:  # the state stays the one at h1
                break
            h0, f0, h1 = h1, f1, h1 - (load - f1) * (h1 - h0) / (f0 - f1)
        unconverged_equilibrium("static", f1, load)
        return h1, state

    height, state = _cached(("static", params_key(rp), round(load, 6)), make)
    return height, _at_rest(copy_state(state), rp)


def _at_rest(state, rp):
    for velocity in (state.v1, state.v2, state.vy, state.vbeta):
        velocity[:] = 0.0
    # at rest the contact patch's Maxwell element has relaxed
    state.patch_relaxed[0] = float(state.block_force.sum())
    state.initialised[0] = False
    state.kinematics[KIN_TIME] = 0.0
    return state


def ring_initial_state(tyre, load, params=None, tread_pattern=False, **options) -> RingState:
    """Belt state in static equilibrium on a flat road under ``load`` [N].

    The rim stands at the ring's own static height for ``load``
    (:func:`ring_static_equilibrium`). For ``load`` <= 0 the state is the
    inflated belt as built (:func:`nominal_state`), which is its equilibrium
    off the road. ``params`` (the record the state will run with) is not needed.
    """
    if not load > 0:
        relaxed = dict(options)
        relaxed["relax"] = RELAX_RATE
        return nominal_state(ring_params(tyre, None, tread_pattern=tread_pattern, **relaxed))
    return ring_static_equilibrium(tyre, load, tread_pattern, **options)[1]


def ring_equilibrium(tyre, load, speed, params, tread_pattern=False, **options):
    """``(deflection, spin, state)`` of the ring carrying ``load`` [N] while rolling
    freely at ``speed`` [m/s] on a flat road: where the rigs start it.

    From the static equilibrium the ring rolls at a fixed height, spinning
    freely (:func:`tyrelab.tyre.static.roll_in_place`), until the belt and
    the tread have reached their rolling state, then the height is
    corrected (secant) until the mean vertical force over a window is within
    :data:`EQUILIBRIUM_TOLERANCE` of ``load``. The centrifugal
    growth of the belt and the rolling deformation change the force at a
    given height (+8 % at 42 km/h). Settling and windows last at least
    :data:`ROLL_SETTLE`, :data:`ROLL_WINDOW` seconds and a contact length
    of travel, so the tread's stick deflections are renewed at low speed.
    """
    from ...road.obstacles import Flat
    from ..handling.none import NoHandling
    from ..handling.relaxation import no_lag
    from ..static import roll_in_place
    from ...limits import rim_spin_inertia
    from ..vertical import VerticalLaw
    from ..wheel import Wheel
    height, state = ring_static_equilibrium(tyre, load, tread_pattern, **options)
    r0 = tyre.unloaded_radius
    if not speed > 0:
        return r0 - height, 0.0, state
    load = float(load)
    road = Flat().grid().surface()

    def make():
        st = copy_state(state)
        wheel = Wheel(VerticalLaw.linear(0.0, 0.0), params, NoHandling(), road, st, no_lag())
        dt = 1e-3
        # the rim as the rigs turn it (a file without a wheel's inertia: estimated)
        inertia = rim_spin_inertia(tyre, load, belt_carried(tyre, **options).spin_inertia)[0]
        travel = 2.0 * math.sqrt(max(r0 ** 2 - height ** 2, 0.0))   # a contact length
        n_settle = int(max(ROLL_SETTLE, 3.0 * travel / speed) / dt)
        n = int(max(ROLL_WINDOW, travel / speed) / dt)
        # free spin from the usual effective rolling radius R0 - deflection / 3
        motion = np.array([0.0, speed / (r0 - (r0 - height) / 3.0)])
        h = height
        roll_in_place(wheel, h, speed, inertia, motion, n_settle, dt)
        f0, h0 = roll_in_place(wheel, h, speed, inertia, motion, n, dt), h
        h = h - (load - f0) / max(tyre.vertical_stiffness, 1.0)
        for k in range(ROLLING_ITERATIONS):
            roll_in_place(wheel, h, speed, inertia, motion, n, dt)  # settle after the move
            f1 = roll_in_place(wheel, h, speed, inertia, motion, n, dt)
            if abs(f1 - load) < EQUILIBRIUM_TOLERANCE * load or f1 == f0 \
                    or k == ROLLING_ITERATIONS - 1:  # the state stays the one at h
                break
            h0, f0, h = h, f1, h - (load - f1) * (h - h0) / (f0 - f1)
        unconverged_equilibrium(f"rolling ({speed * 3.6:.4g} km/h)", f1, load)
        return r0 - h, float(motion[1]), st

    deflection, spin, st = _cached(("rolling", params_key(params), round(load, 6),
                                    round(float(speed), 9)), make)
    st = copy_state(st)
    st.kinematics[KIN_TIME] = 0.0
    return deflection, spin, st


def belt_carried(tyre, parameters=None, **_):
    """What the belt carries of the wheel's inertia (the registry's ``carried``): its mass
    ``RING_MASS`` and its spin inertia ``RING_MASS r_b^2``, the belt at its radius
    ``r_b = R0 - TREAD_DEPTH`` (the XZL's 154 kg and 64.4 kg m^2)."""
    from ...limits import Carried
    rp = parameters if parameters is not None else ring_parameters(tyre)
    mass = float(rp.ring_mass)
    return Carried(mass, mass * (tyre.unloaded_radius - rp.tread_depth) ** 2)


def ring_footprint_of(wheel, load, deflection, tyre) -> dict:
    """Footprint of a ring ``wheel`` pressed on the plate (the registry's ``footprint`` hook).

    ``wheel.state.block_force`` holds each block's normal force after the
    last step; ``load`` [N] the plate force, ``deflection`` [m] the press
    depth. See :func:`.static.footprint_from_blocks` for the dict.
    """
    return footprint_from_blocks(wheel.contact, wheel.state, wheel.state.block_force.copy(),
                                 load, deflection, tyre.pressure)


def _ring_build(tyre, grid=None, **options) -> RingParams:
    return ring_params(tyre, grid, tread_pattern=False, **options)


def _ring_tp_build(tyre, grid=None, **options) -> RingParams:
    return ring_params(tyre, grid, tread_pattern=True, **options)


def _ring_state(tyre, load, params=None, **options) -> RingState:
    return ring_initial_state(tyre, load, params, tread_pattern=False, **options)


def _ring_tp_state(tyre, load, params=None, **options) -> RingState:
    return ring_initial_state(tyre, load, params, tread_pattern=True, **options)


def _ring_equilibrium(tyre, load, speed, params, **options):
    return ring_equilibrium(tyre, load, speed, params, tread_pattern=False, **options)


def _ring_tp_equilibrium(tyre, load, speed, params, **options):
    return ring_equilibrium(tyre, load, speed, params, tread_pattern=True, **options)


register_contact(ContactModel("ring", RingParams, _ring_build, step=ring_step,
                              initial_state=_ring_state, equilibrium=_ring_equilibrium,
                              static_options={"relax": RELAX_RATE},
                              footprint=ring_footprint_of, options=_OPTION_TYPES, cost=0.08,
                              terrains=("rigid", "soil"), check_values=ring_option_values,
                              check_tyre=ring_parameters, carried=belt_carried,
                              parameterization=_DATA, fit_steps=_FIT_STEPS,
                              summary="flexible ring (FTire class), evenly spaced tread blocks"))
register_contact(ContactModel("ring-tp", RingParams, _ring_tp_build, step=ring_step,
                              initial_state=_ring_tp_state, equilibrium=_ring_tp_equilibrium,
                              static_options={"relax": RELAX_RATE}, footprint=ring_footprint_of,
                              options=_OPTION_TYPES, cost=0.085, terrains=("rigid", "soil"),
                              check_values=ring_option_values, check_tyre=ring_parameters,
                              carried=belt_carried,
                              parameterization=_DATA + " + tread pattern",
                              # no fit_steps: its pattern is a file the user gives, not fitted
                              summary="flexible ring with blocks on the tread pattern"))
