"""The friendly front door: a simulation in one call.

>>> import tyrelab
>>> run = tyrelab.simulate(model="point", road="cleat:50x50", speed=12 / 3.6, load="LC1")
>>> run.plot(x="RUNTIME", y="FZW")                                  # doctest: +SKIP
"""

from __future__ import annotations

from .errors import InputError
from .tyre.model import TyreModel
from .tyre.library import DEFAULT_TYRE, load_tyre
from .tyre.params import Tyre

#: rigs that :func:`simulate` drives: the towed trailer, the quarter vehicle, the
#: fixed-height rolling test, the trailer's drop test (thesis 3.4.1), a single wheel dropped
RIGS = ("trailer", "quarter-vehicle", "rolling", "drop", "wheel-drop")


def default_handling(tyre: Tyre) -> str:
    """The handling model a property file describes: its format picks it.

    PAC89 coefficients (``[LATERAL_COEFFICIENTS]`` with ``A0``) -> ``"pac89"``;
    Magic Formula 5.2/6.x (``FITTYP`` or ``PROPERTY_FILE_FORMAT`` 'MF_05',
    'PAC2002', 'MF_61', 'MF_62') -> ``"mf"``; otherwise ``"none"``.
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
    return "none"


def make_tyre_model(tyre: str | Tyre = DEFAULT_TYRE, model: str = "point", pressure: float | None = None,
                    stiffness: str | None = None, handling: str | None = None) -> TyreModel:
    """A :class:`TyreModel` from a tyre name or file, a contact model and options.

    ``handling=None`` takes the handling model the property file describes
    (:func:`default_handling`).
    """
    t = tyre if isinstance(tyre, Tyre) else load_tyre(tyre, pressure)
    if stiffness is not None:
        t = t.with_stiffness(stiffness)
    return TyreModel(t, contact=model, handling=handling or default_handling(t))


def simulate(tyre: str | Tyre = DEFAULT_TYRE, model: str = "point", road="cleat:50x50",
             speed: float = 12 / 3.6, load="LC1", pressure: float | None = None,
             stiffness: str | None = None, handling: str | None = None,
             rig: str = "trailer", duration: float | None = None,
             dt: float = 1e-3, output_rate: float = 1000.0, progress: bool | None = None,
             left_wheel: str | None = None):
    """Run a tyre model on a rig over a road; returns the signal table.

    Parameters
    ----------
    tyre : str or Tyre
        Built-in name (``"xzl-16.00R20"``) or path to a ``.tir`` file.
    model : str
        Contact model (``"point"``).
    road : str or Road
        A road name (see :func:`tyrelab.road.spec.road_from_spec`).
    speed : float
        Towing speed [m/s].
    load : str or float
        ``"LC1"``-``"LC3"`` (thesis Table 3-4) or a static wheel load [N].
    pressure : float, optional
        Inflation pressure [Pa] (built-in tyres only).
    stiffness : {"table", "linear"}, optional
        Vertical stiffness: load-deflection spline or linear.
    handling : {"none", "pac89", "mf"}, optional
        Tangential force model; by default the one the property file describes.
    rig : {"trailer", "quarter-vehicle", "rolling", "drop", "wheel-drop"}
        ``rolling``: the axle at the static height of ``load``, rolled at
        ``speed`` (:mod:`tyrelab.rig.rolling`); ``drop``: the trailer at rest
        lifted until its wheels leave the ground and dropped (thesis 3.4.1;
        ``road`` and ``speed`` are ignored: flat ground, standing still);
        ``wheel-drop``: the quarter vehicle dropped the same way.
    duration, dt, output_rate : float
        Simulated time [s] (default: until the road ends; 3 s for a drop),
        time step [s], output sample rate [Hz].
    left_wheel : str, optional
        Trailer rigs: contact model of the left wheel, which runs on flat
        ground (default: ``model``), e.g. ``"point"`` -- the same tyre and
        vertical law at a fraction of the ring's cost.
    """
    if rig not in RIGS:
        raise InputError(f"unknown rig '{rig}', expected one of {', '.join(RIGS)}", field="rig")
    tm = make_tyre_model(tyre, model, pressure, stiffness, handling)
    if left_wheel is not None and rig not in ("trailer", "drop"):
        raise InputError(f"left_wheel applies to the trailer rigs, not to '{rig}'", field="left_wheel")
    if rig in ("trailer", "drop"):
        from .rig.trailer import Trailer
        left = None
        if left_wheel is not None and left_wheel != tm.contact:
            left = TyreModel(tm.tyre, contact=left_wheel, handling=tm.handling)
        trailer = Trailer(tm, load, left=left)
        if rig == "drop":
            return trailer.drop(duration=duration or 3.0, dt=dt, output_rate=output_rate,
                                progress=progress)
        return trailer.run(road, speed, duration, dt, output_rate, progress)
    if rig == "rolling":
        from .rig.rolling import roll
        return roll(tm, road, speed, load=load, duration=duration, dt=dt,
                    output_rate=output_rate, progress=progress)
    from .rig.quarter_vehicle import G, QuarterVehicle
    if isinstance(load, str):
        from .rig.trailer import load_case_wheel_load
        wheel = load_case_wheel_load(load)
    else:
        wheel = float(load)
    mu = tm.tyre.wheel_mass or 0.1 * wheel / G
    quarter = QuarterVehicle(tm, sprung_mass=wheel / G - mu, unsprung_mass=mu)
    if rig == "wheel-drop":
        return quarter.drop(duration=duration or 2.0, dt=dt, output_rate=output_rate,
                            progress=progress)
    return quarter.run(road, speed, duration, dt, output_rate, progress)
