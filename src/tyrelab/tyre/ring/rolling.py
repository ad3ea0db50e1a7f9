"""Rolling at a fixed axle height: the enveloping test of Zegelaar (1998) and Schmeitz (2004).

The rim centre moves along x at constant height and speed; the wheel spins
freely (spin inertia I, driven by the tyre's moment about the axle), so the
tyre rolls over the road as on the "flat plank" machine. Over a short cleat a
flexible tyre envelops the obstacle: the vertical force shows a dip when the
cleat is in the middle of the contact patch, which a rigid disc cannot show
(its force is largest there).
"""

from __future__ import annotations

import numba as nb
import numpy as np

from ..wheel import WheelPose
from .kernel import ring_step


@nb.njit(cache=True)
def roll_fixed_height(wheel, x0, height, speed, omega0, inertia, n_steps, dt, res):
    """Roll ``n_steps``; ``res[k] = (x, Fx, Fz, My, omega)`` (road on tyre, at the rim).

    Step k: the rim at ``(x, 0, height)``, spin axis y, velocity ``(speed,
    0, 0)``, spin ``omega``; ``x`` and ``omega`` are recorded as they were
    at the start of the step, the loads as the step returns them; then
    ``omega += dt My / inertia`` (explicit Euler) and ``x += speed dt``.
    """
    omega = omega0
    x = x0
    for k in range(n_steps):
        loads = ring_step(wheel, WheelPose(x, 0.0, height, 0.0, 1.0, 0.0, speed, 0.0, 0.0,
                                           omega), dt)
        res[k, 0] = x
        res[k, 1] = loads.fx
        res[k, 2] = loads.fz
        res[k, 3] = loads.my
        res[k, 4] = omega
        omega += dt * loads.my / inertia
        x += speed * dt


def roll_over(model, road, height, x_start, x_end, speed=0.5, dt=1e-3, load=None):
    """Roll a ring ``model`` over ``road`` at axle ``height`` from ``x_start`` to ``x_end``.

    Starts from the static state at ``load`` (default: the load-deflection
    load at that height), spinning at ``speed / height``; the spin inertia
    is the tyre's (at least 1 kg m^2). Returns a dict of arrays ``x, FX,
    FZ, MY, omega``.
    """
    from ...road.spec import road_from_spec
    road = road_from_spec(road)
    grid = road.grid()
    tyre = model.tyre
    if load is None:
        load = float(tyre.vertical_law.static_load(tyre.unloaded_radius - height))
    wheel = model.wheel(grid, load)
    n = int(round((x_end - x_start) / (speed * dt)))
    res = np.zeros((n, 5))
    inertia = max(tyre.wheel_spin_inertia, 1.0)
    roll_fixed_height(wheel, x_start, height, speed, speed / height, inertia, n, dt, res)
    return {"x": res[:, 0], "FX": res[:, 1], "FZ": res[:, 2], "MY": res[:, 3], "omega": res[:, 4]}
