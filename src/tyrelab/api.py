"""The friendly front door: a simulation in one call.

>>> import tyrelab
>>> run = tyrelab.simulate(model="point", road="cleat:50x50", speed=12 / 3.6, load="LC1")
>>> run.plot(x="RUNTIME", y="FZW")                                  # doctest: +SKIP
"""

from __future__ import annotations

from .errors import InputError, named
from .limits import check_pressure
from .rig.simulation import SimulationError
from .tyre.model import TyreModel
from .tyre.library import DEFAULT_TYRE, load_tyre
from .tyre.params import Tyre
from .tyre.registry import contact_models

#: output sample rate [Hz] when none is given (every step when the step is longer than 1 ms)
DEFAULT_OUTPUT_RATE = 1000.0


def default_handling(tyre: Tyre) -> str:
    """The handling model a property file describes: its format picks it.

    PAC89 coefficients (``[LATERAL_COEFFICIENTS]`` with ``A0``) -> ``"pac89"``;
    Magic Formula 5.2/6.x (``FITTYP`` or ``PROPERTY_FILE_FORMAT`` 'MF_05',
    'PAC2002', 'MF_61', 'MF_62') -> ``"mf"``; TMeasy parameters (``[TYRE_LOAD] FZ_NOM``, as
    :mod:`tyrelab.tyre.chrono_json` writes from a Chrono TMeasy JSON) -> ``"tmeasy"``, under
    ``PROPERTY_FILE_FORMAT`` 'TMSIMPLE' (a Chrono TMsimple JSON's) -> ``"tmsimple"``; Fiala
    (``PROPERTY_FILE_FORMAT`` 'FIALA', or ``[PARAMETER] CSLIP``) -> ``"fiala"``; otherwise
    ``"none"``.
    """
    tir = tyre.tir
    fmt = str(tir.get("MODEL", "PROPERTY_FILE_FORMAT", "")).upper()
    if tir.has("LATERAL_COEFFICIENTS", "A0") or fmt.startswith("PAC89"):
        return "pac89"
    if tir.has("MODEL", "FITTYP") or fmt in ("MF_05", "PAC2002", "MF_61", "MF_62", "MF_52"):
        from .tyre.handling.mf import detect_version
        try:
            detect_version(tir)
        except InputError as exc:
            import warnings
            warnings.warn(f"no handling forces: {exc}", stacklevel=3)
            return "none"
        return "mf"
    from .tyre.handling.tmeasy import LOAD_SECTION
    if fmt == "TMSIMPLE":
        return "tmsimple"
    if tir.has(LOAD_SECTION, "FZ_NOM"):
        return "tmeasy"
    if fmt == "FIALA" or tir.has("PARAMETER", "CSLIP"):
        return "fiala"
    return "none"


def make_tyre_model(tyre: str | Tyre = DEFAULT_TYRE, model: str = "point", pressure: float | None = None,
                    stiffness: str | None = None, handling: str | None = None,
                    options: dict | None = None, relaxation="auto") -> TyreModel:
    """A :class:`TyreModel` from a tyre name or file, a contact model and its options.

    ``handling=None`` takes the handling model the property file describes
    (:func:`default_handling`); ``options`` are the contact model's
    (:attr:`tyrelab.tyre.registry.ContactModel.options`; others are refused,
    the allowed ones named); ``relaxation`` the handling forces' transient slip
    (:attr:`TyreModel.relaxation`).
    """
    from .tyre.registry import check_options
    options = check_options(model, options)
    if pressure is not None:
        check_pressure(pressure)
    t = tyre if isinstance(tyre, Tyre) else load_tyre(tyre, pressure)
    if stiffness is not None:
        t = t.with_stiffness(stiffness)
    return TyreModel(t, contact=model, handling=handling or default_handling(t), options=options,
                     relaxation=relaxation)


def _default_duration(road, speed: float) -> float:
    """The simulated time of a run to the road's end (as the rigs compute it)."""
    return max(road.extent()[1] - road.run_start, 1.0) / speed


def divergence_error(exc: Exception, tm: TyreModel, dt: float, wheel_load: float,
                     terrain=None) -> SimulationError:
    """A divergence as one line naming the step size and the likely parameter."""
    from .limits import stable_step, wheel_hop_omega
    limit, why = stable_step(tm, wheel_load)
    text = " ".join(str(exc).split())
    if terrain is not None:
        # the tyre's own stable step was checked before the run: the ground is what changed
        name = terrain if isinstance(terrain, str) else "the soil"
        return SimulationError(f"{text.rstrip('.;')} at time step {dt:g} s on the terrain {name}; "
                               "likely cause: its elastic_stiffness, damping or cohesion, too large "
                               "for the step (they push the wheel harder than the tyre does); try a "
                               "smaller time step or check the soil's values")
    if tm.has_state:
        likely = (f"the {tm.contact} model's parameters ([FLEXIBLE_RING] of the tyre) or the time "
                  f"step; its stated stable step is {limit:.3g} s")
    else:
        _, k_max, mass = wheel_hop_omega(tm.tyre, wheel_load)
        likely = (f"VERTICAL_STIFFNESS / [DEFLECTION_LOAD_CURVE] (stiffest {k_max:.3g} N/m) against "
                  f"the wheel mass {mass:.3g} kg of {tm.tyre.name}; stable step {limit:.3g} s ({why})")
    return SimulationError(f"{text.rstrip('.;')} at time step {dt:g} s; likely cause: {likely}; "
                           "try a smaller time step or check the property file")


def simulate(tyre: str | Tyre = DEFAULT_TYRE, model: str = "point", road=None,
             speed: float = 12 / 3.6, load="LC1", pressure: float | None = None,
             stiffness: str | None = None, handling: str | None = None,
             rig: str = "trailer", duration: float | None = None,
             dt: float = 1e-3, output_rate: float | None = None, progress: bool | None = None,
             left_wheel: str | None = None, force: bool = False, options: dict | None = None,
             terrain=None, rig_options: dict | None = None, relaxation="auto"):
    """Run a tyre model on a rig over a road; returns the signal table.

    Parameters
    ----------
    tyre : str or Tyre
        Built-in name (``"xzl-16.00R20"``) or path to a ``.tir`` file.
    model : str
        Contact model (``"point"``).
    road : str or Road, optional
        A road name (see :func:`tyrelab.road.spec.road_from_spec`); on soil, the
        soil's undisturbed surface. Default: the rig's (``cleat:50x50``; ``flat``
        for the single-wheel tester).
    speed : float
        Towing speed [m/s], :data:`tyrelab.limits.MIN_SPEED` to
        :data:`~tyrelab.limits.MAX_SPEED`.
    load : str or float
        ``"LC1"``-``"LC3"`` (thesis Table 3-4) or a static wheel load [N],
        below the load that presses the tyre onto its rim.
    pressure : float, optional
        Inflation pressure [Pa] (built-in tyres only).
    stiffness : {"table", "linear"}, optional
        Vertical stiffness: load-deflection spline or linear.
    handling : {"none", "pac89", "mf", "tmeasy", "tmsimple", "fiala"}, optional
        Tangential force model; by default the one the property file describes.
    relaxation : str or (float, float)
        Transient slip of the handling forces (:mod:`tyrelab.tyre.handling.relaxation`):
        ``"auto"`` (default) as the property file asks (a Magic Formula file's
        ``USE_MODE`` +10), ``"off"`` (steady state), ``"file"`` (the handling
        model's own relaxation lengths) or ``(sigma_kappa, sigma_alpha)`` [m].
    rig : str
        A registered rig (:func:`tyrelab.registry.rigs`; built in: ``"trailer"``,
        ``"quarter-vehicle"``, ``"rolling"``, ``"drop"``, ``"wheel-drop"``).
        ``rolling``: the axle at the static height of ``load``, rolled at
        ``speed`` (:mod:`tyrelab.rig.rolling`); ``drop``: the trailer at rest
        lifted until its wheels leave the ground and dropped (thesis 3.4.1;
        ``road`` and ``speed`` are ignored: flat ground, standing still);
        ``wheel-drop``: the quarter vehicle dropped the same way.
    duration, dt, output_rate : float
        Simulated time [s] (default: until the road ends; 3 s for a drop),
        time step [s], output sample rate [Hz] (at most ``1 / dt``; default
        1000 Hz, or every step when the step is longer than 1 ms). The step
        must not exceed the model's stable step
        (:func:`tyrelab.limits.stable_step`).
    left_wheel : str, optional
        Trailer rigs: contact model of the left wheel, which runs on flat
        ground (default: ``model``), e.g. ``"point"`` -- the same tyre and
        vertical law at a fraction of the ring's cost.
    force : bool
        Run even when the estimated memory or wall time is above
        :data:`tyrelab.resources.MAX_MEMORY` / :data:`~tyrelab.resources.MAX_WALL_TIME`.
    options : dict, optional
        The contact model's options, e.g. ``{"n_length": 5}`` for the
        enveloping model's cams or ``{"n_segments": 200}`` for the ring
        (:attr:`tyrelab.tyre.registry.ContactModel.options` lists each
        model's; an unknown key is refused with the allowed ones named). The
        trailer's left wheel (``left_wheel``, another model) takes none.
    terrain : str or Soil, optional
        A deformable ground: a built-in soil's name (``"lete-sand"``,
        :func:`tyrelab.road.soil.soil_names`) or a soil file ``FILE.toml``; the
        road gives its initial surface. Rigs that run on soil only (the
        ``single-wheel`` tester) need one.
    rig_options : dict, optional
        The rig's own options (:attr:`tyrelab.rig.registry.Rig.options`), e.g.
        ``{"slip": 0.2}`` for the single-wheel tester.

    Every argument is checked before any work (:mod:`tyrelab.limits`); a run
    that leaves the physics the models hold for (rim contact, an overturned
    trailer, a wheel off the road) issues a
    :class:`tyrelab.guards.PhysicsWarning` per finding (also listed in the
    table's ``attrs["metadata"]["physics_warnings"]``).
    """
    from . import guards, limits, resources
    from .rig.registry import RigRequest, check_rig_options, rig_named, rigs

    the_rig = rig_named(rig)
    rig_options = check_rig_options(the_rig, rig_options)
    if road is None:
        road = the_rig.default_road
    if terrain is None and the_rig.terrain == "soil":
        raise InputError(f"the {rig} rig runs on soil: give a terrain (a soil's name or FILE.toml)",
                         field="terrain")
    if terrain is not None and the_rig.terrain == "rigid":
        soil_rigs = [name for name, r in rigs().items() if r.terrain != "rigid"]
        raise InputError(f"the {rig} rig runs on the rigid road only; rigs on soil: "
                         f"{', '.join(soil_rigs)}", field="terrain")
    if terrain is not None:
        from .road.terrain import resolve_terrain
        resolve_terrain(terrain)  # an unknown terrain or a bad soil file: refused before any work
    if the_rig.rolls:
        speed = limits.check_speed(speed)
    dt = limits.check_dt(dt)
    if output_rate is None:
        output_rate = min(DEFAULT_OUTPUT_RATE, 1.0 / dt)
    output_rate = limits.check_rate(output_rate, dt)
    if duration is not None:
        duration = limits.check_duration(duration, dt, output_rate)
    tm = make_tyre_model(tyre, model, pressure, stiffness, handling, options, relaxation)
    if left_wheel is not None and the_rig.wheels < 2:
        two = ", ".join(name for name, r in rigs().items() if r.wheels > 1)
        raise InputError(f"left_wheel applies to the rigs with two wheels ({two}), not to '{rig}'",
                         field="left_wheel")
    if left_wheel is not None:  # looked up here, so that an unknown name is the left wheel's
        named(contact_models(), left_wheel, "model", "left_wheel")
    if isinstance(load, str):
        from .rig.trailer import load_case_wheel_load
        wheel_load = limits.check_wheel_load(load_case_wheel_load(load), tm.tyre)
    else:
        wheel_load = limits.check_wheel_load(load, tm.tyre)
    guards.check_load_range(tm.tyre, wheel_load)
    if the_rig.check is not None:
        the_rig.check(tm, wheel_load)
    left = None
    if the_rig.wheels > 1 and left_wheel is not None and left_wheel != tm.contact:
        left = TyreModel(tm.tyre, contact=left_wheel, handling=tm.handling,
                         relaxation=tm.relaxation)
    # the wheels the rig runs: a second one (the trailer's left) on flat ground
    models = [tm] + [left or tm] * (the_rig.wheels - 1)
    limits.check_stable_step(dt, [tm] if left is None else [tm, left], wheel_load)
    cells = 0
    if the_rig.rolls:
        from .road.spec import road_from_spec
        road = road_from_spec(road, force=force)
        run_time = _default_duration(road, speed) if duration is None else duration
        if duration is None and run_time > limits.MAX_DURATION:
            raise InputError(f"the run to the road's end at {speed:.6g} m/s would last {run_time:.6g} s, "
                             f"above the {limits.MAX_DURATION:g} s allowed; give a duration or a "
                             "higher speed", field="speed")
        cells = resources.grid_cells(road)
        guards.check_road_for_tyre(road, tm.tyre)
    else:
        road = None
        duration = run_time = duration or the_rig.default_duration
    resources.check_resources(f"a {run_time:.6g} s run at a {dt:g} s step",
                           memory=resources.run_memory(run_time, dt, output_rate, cells),
                           wall_time=resources.run_wall_time(models, run_time, dt), force=force,
                           hint="use a larger time step, a shorter duration or a higher speed")
    request = RigRequest(model=tm, left=left, road=road, speed=speed, load=load, wheel_load=wheel_load,
                         duration=duration, dt=dt, output_rate=output_rate, progress=progress,
                         terrain=terrain, options=rig_options)
    try:
        table = the_rig.run(request)
    except SimulationError as exc:
        raise divergence_error(exc, tm, dt, wheel_load, terrain) from None
    found = guards.check_run(table, tm.tyre)
    if found:
        table.attrs["metadata"]["physics_warnings"] = found
    return table
