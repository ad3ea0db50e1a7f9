"""Rolling at a fixed axle height: the enveloping test of Zegelaar (1998) and Schmeitz (2004).

The rim centre moves along x at constant height and speed; the wheel spins
freely (spin inertia I, driven by the tyre's moment about the axle), so the
tyre rolls over the road as on the "flat plank" machine. This is the
classic way to compare contact models' road filtering: over a short cleat a
rigid disc's vertical force peaks when the cleat is under the centre, an
enveloping model's rises over about the contact length (lengthening) and
less high (swallowing), and a flexible tyre shows a dip when the cleat is
in the middle of the contact patch.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from ..core.named_index import named_index
from ..errors import InputError
from ..road.spec import road_from_spec
from ..tyre.model import TyreModel
from ..tyre.wheel import WheelPose, wheel_step
from .frames import WHEEL_CHANNELS, wheel_row
from .simulation import levelled_grid, run_chunks, to_signal
from .trailer import load_case_wheel_load

CHANNELS = WHEEL_CHANNELS
N_CH = len(CHANNELS)
#: the state array of :func:`rolling_steps`: axle x [m], spin [rad/s], time [s]
STATE = ("X", "OMEGA", "T")
R = named_index("RollingStateIndex", STATE)


@nb.njit(cache=True)
def rolling_steps(wheel, x_start, height, speed, inertia, state, n_steps, dt, out_every, out,
                  row0):
    """Roll ``n_steps`` from ``state`` (:data:`STATE`); rows of :data:`CHANNELS` into ``out``.

    The spin follows the tyre's moment about the axle, linearly implicit in
    the slip stiffness (explicit for models that report none, as the ring).
    Returns the next free row.
    """
    cax = np.empty(6)
    row = row0
    for step in range(n_steps):
        x, omega, t = state[R.X], state[R.OMEGA], state[R.T]
        pose = WheelPose(x, 0.0, height, 0.0, 1.0, 0.0, speed, 0.0, 0.0, omega)
        f = wheel_step(wheel, pose, dt)
        if (step % out_every) == 0 and row < out.shape[0]:
            wheel_row(out[row], t, x - x_start, pose, f, cax)
            row += 1
        state[R.OMEGA] = omega + dt * f.my / (inertia - dt * min(f.dspin_domega, 0.0))
        state[R.X] = x + speed * dt
        state[R.T] = t + dt
    return row


def roll(model: TyreModel, road="cleat:50x50", speed: float = 0.5, height: float | None = None,
         load="LC1", x_start: float | None = None, duration: float | None = None,
         dt: float = 1e-3, output_rate: float = 1000.0, progress: bool | None = None):
    """Roll ``model`` at a fixed axle height over ``road``; returns the signal table.

    Parameters
    ----------
    model : TyreModel
        Any contact model.
    road : str or Road
    speed : float
        Axle speed [m/s] (the classic test rolls slowly, well under 1 m/s).
    height : float, optional
        Axle height [m] above the road's start; default: where the model
        carries ``load`` rolling freely at ``speed`` on a level road
        (:meth:`~tyrelab.tyre.model.TyreModel.equilibrium`).
    load : str or float
        Static load [N] or a load case of thesis Table 3-4; sets the default
        height and the tyre's initial state.
    x_start : float, optional
        Where the axle starts [m]; default the road's run start.
    duration, dt, output_rate : float
        Simulated time [s] (default: to the end of the road), step [s],
        output rate [Hz].
    """
    road = road_from_spec(road)
    if not (np.isfinite(speed) and speed > 0):
        raise InputError(f"speed must be a positive number, got {speed}", field="speed")
    tyre = model.tyre
    wheel_load = load_case_wheel_load(load) if isinstance(load, str) else float(load)
    eq = None
    if height is None:  # where the model carries the load rolling freely at this speed
        eq = model.equilibrium(wheel_load, speed)
        height = tyre.unloaded_radius - eq.deflection
    x0 = road.run_start if x_start is None else float(x_start)
    if duration is None:
        duration = max(road.extent()[1] - x0, 1.0) / speed
    from ..guards import LEVEL_DEFLECTION, check_level, check_reaches_relief, rig_spin_inertia
    deflection = tyre.unloaded_radius - height
    check_level(road, x0, x0 + speed * duration, LEVEL_DEFLECTION * max(deflection, 0.0),
                f"the rolling rig holds its axle at a fixed height, so that presses the tyre "
                f"that much more or less than its static {deflection * 1e3:.3g} mm")
    check_reaches_relief(road, x0, speed, duration, tyre.unloaded_radius)
    grid = levelled_grid(road, road.run_start)
    if eq is None:
        state_load = float(tyre.vertical_law.static_load(tyre.unloaded_radius - height))
        wheel = model.wheel(grid, state_load)
        spin = speed / height
    else:
        state_load = wheel_load
        wheel = model.wheel(grid, wheel_load, rolling=eq)
        spin = eq.spin
    state = np.zeros(len(STATE))
    state[R.X], state[R.OMEGA] = x0, spin
    inertia = rig_spin_inertia(model, wheel_load)
    n_steps = int(round(duration / dt))
    out_every = max(1, int(round(1.0 / (output_rate * dt))))

    def advance(n, out, row):
        return rolling_steps(wheel, x0, float(height), float(speed), inertia, state, n, dt,
                             out_every, out, row)

    data = run_chunks(advance, n_steps, out_every, N_CH, dt, progress)
    meta = {"rig": "rolling", "tyre": tyre.name, "model": model.contact,
            "handling": model.handling, "relaxation": model.relaxation_used,
            "stiffness": tyre.stiffness, "road": road.name,
            "speed_m_s": speed, "axle_height_m": float(height), "static_wheel_load_N": state_load,
            "pressure_Pa": tyre.pressure, "dt_s": dt, "output_rate_Hz": 1.0 / (out_every * dt)}
    return to_signal(data, CHANNELS, meta)


def roll_over(model, road, height, x_start, x_end, speed=0.5, dt=1e-3):
    """Roll ``model`` over ``road`` at axle ``height`` from ``x_start`` to ``x_end``.

    Starts from the static state at the load the vertical law gives at that
    height. Returns a dict of arrays ``x, FX, FZ, MY, omega`` (road on tyre,
    at the rim; one sample per step).
    """
    run = roll(model, road, speed=speed, height=height, load=0.0, x_start=x_start,
               duration=(x_end - x_start) / speed, dt=dt, output_rate=1.0 / dt, progress=False)
    return {"x": run["X_WC"].to_numpy(), "FX": run["FX"].to_numpy(), "FZ": run["FZ"].to_numpy(),
            "MY": run["MY"].to_numpy(), "omega": run["ROTSPEED"].to_numpy()}
