"""A wheel pressed to static equilibrium: the one press loop of every model.

The rim is held level at x = y = 0 (spin axis y, no spin) and lowered through
a list of centre heights in ramps; at each height it is held and the loads of
the end of the hold are averaged -- the lab press of thesis 3.3 (rim fixed,
hydraulic actuator, load averaged). Analytic models reach their static value
at once; models with dynamics (the ring, built with relaxation damping) relax
to static equilibrium during the hold, so the same loop also finds the ring's
static states (:func:`tyrelab.tyre.ring.static.settle`). The static press rig
(:mod:`tyrelab.rig.static_press`) drives it.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from ..core.named_index import named_index
from .wheel import WheelPose, wheel_step

#: press rate [m/s], hold time [s], averaging window [s] and step [s]
PRESS_RATE = 0.25
HOLD = 0.12
WINDOW = 0.02
DT = 1e-3
#: channels of :func:`press_path`'s result rows, and their positions (``res[k, PC.FZ]``)
PRESS_COLUMNS = ("FX", "FY", "FZ", "DEFLECT", "MX", "MY", "MZ")
PC = named_index("PressColumnIndex", PRESS_COLUMNS)
#: the state array of :func:`roll_in_place`: centre x [m], spin [rad/s]
ROLL_STATE = ("X", "OMEGA")
RS = named_index("RollStateIndex", ROLL_STATE)


@nb.njit(cache=True)
def press_path(wheel, z_start, heights, rate, hold, window, dt, res):
    """Lower the rim centre from ``z_start`` through ``heights`` [m]; returns the last height.

    To each height the rim moves in steps of ``dt`` at the constant speed that
    reaches it in a whole number of steps no faster than ``rate`` (each step
    posed at the height before it), then holds it for ``hold``. ``res[k]``
    receives :data:`PRESS_COLUMNS` at height k: the loads averaged over the
    last ``window`` of the hold, the deflection of its last step.
    """
    zc = z_start
    n_hold = int(np.ceil(hold / dt))
    n_win = int(np.ceil(window / dt))
    for k in range(heights.shape[0]):
        target = heights[k]
        n_ramp = int(np.ceil(abs(target - zc) / (rate * dt)))
        if n_ramp > 0:
            vz = (target - zc) / (n_ramp * dt)
            for s in range(n_ramp):
                wheel_step(wheel, WheelPose(0.0, 0.0, zc, 0.0, 1.0, 0.0, 0.0, 0.0, vz, 0.0), dt)
                zc += vz * dt
        zc = target
        for q in range(res.shape[1]):
            res[k, q] = 0.0
        for s in range(n_hold):
            f = wheel_step(wheel, WheelPose(0.0, 0.0, zc, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0), dt)
            if s >= n_hold - n_win:
                res[k, PC.FX] += f.fx / n_win
                res[k, PC.FY] += f.fy / n_win
                res[k, PC.FZ] += f.fz / n_win
                res[k, PC.DEFLECT] = f.deflection
                res[k, PC.MX] += f.mx / n_win
                res[k, PC.MY] += f.my / n_win
                res[k, PC.MZ] += f.mz / n_win
    return zc


@nb.njit(cache=True)
def roll_in_place(wheel, height, speed, inertia, state, n_steps, dt):
    """Roll ``n_steps`` at a fixed centre ``height`` [m] over a level road, the wheel
    spinning freely (spin inertia ``inertia``, driven by the tyre's moment about
    the axle, as in :func:`tyrelab.rig.rolling.rolling_steps`); returns the mean
    vertical load on the rim [N].

    ``state`` (:data:`ROLL_STATE`: x, omega) is advanced in place. A model's rolling equilibrium
    (the ring's initial state at speed) is found with it.
    """
    fz = 0.0
    for s in range(n_steps):
        x = state[RS.X]
        omega = state[RS.OMEGA]
        f = wheel_step(wheel, WheelPose(x, 0.0, height, 0.0, 1.0, 0.0, speed, 0.0, 0.0, omega),
                       dt)
        state[RS.OMEGA] = omega + dt * f.my / (inertia - dt * min(f.dspin_domega, 0.0))
        state[RS.X] = x + speed * dt
        fz += f.fz
    return fz / n_steps
