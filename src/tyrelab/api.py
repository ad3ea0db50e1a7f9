"""The friendly front door: a simulation in one call.

>>> import tyrelab
>>> run = tyrelab.simulate(model="point", road="cleat:50x50", speed=12 / 3.6, load="LC1")
>>> run.plot(x="RUNTIME", y="FZW")                                  # doctest: +SKIP
"""

from __future__ import annotations

from .errors import InputError
from .tyre.kernel import TyreModel
from .tyre.library import DEFAULT_TYRE, load_tyre
from .tyre.params import Tyre

RIGS = ("trailer", "quarter-vehicle")


def make_tyre_model(tyre: str | Tyre = DEFAULT_TYRE, model: str = "point", pressure: float | None = None,
                    stiffness: str | None = None) -> TyreModel:
    """A :class:`TyreModel` from a tyre name or file, a contact model and options."""
    t = tyre if isinstance(tyre, Tyre) else load_tyre(tyre, pressure)
    if stiffness is not None:
        t = t.with_stiffness(stiffness)
    return TyreModel(t, contact=model)


def simulate(tyre: str | Tyre = DEFAULT_TYRE, model: str = "point", road="cleat:50x50",
             speed: float = 12 / 3.6, load="LC1", pressure: float | None = None,
             stiffness: str | None = None, rig: str = "trailer", duration: float | None = None,
             dt: float = 1e-3, output_rate: float = 1000.0, progress: bool | None = None):
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
    rig : {"trailer", "quarter-vehicle"}
    duration, dt, output_rate : float
        Simulated time [s] (default: until the road ends), time step [s],
        output sample rate [Hz].
    """
    tm = make_tyre_model(tyre, model, pressure, stiffness)
    if rig == "trailer":
        from .rig.trailer import Trailer
        return Trailer(tm, load).run(road, speed, duration, dt, output_rate, progress)
    if rig == "quarter-vehicle":
        from .rig.quarter_vehicle import G, QuarterVehicle
        if isinstance(load, str):
            from .rig.trailer import load_case_wheel_load
            wheel = load_case_wheel_load(load)
        else:
            wheel = float(load)
        mu = tm.tyre.wheel_mass or 0.1 * wheel / G
        return QuarterVehicle(tm, sprung_mass=wheel / G - mu, unsprung_mass=mu).run(
            road, speed, duration, dt, output_rate, progress)
    raise InputError(f"unknown rig '{rig}', expected one of {', '.join(RIGS)}", field="rig")
