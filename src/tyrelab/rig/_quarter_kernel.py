"""Compiled time loop of the quarter-vehicle rig (see :mod:`.quarter_vehicle`)."""

from typing import NamedTuple

import numba as nb
import numpy as np

from ..tyre.wheel import WheelPose, wheel_step
from .frames import N_WHEEL, WHEEL_CHANNELS, wheel_row


class QuarterParams(NamedTuple):
    """The quarter vehicle as its compiled loop takes it (SI).

    ``spring_free_length``: the suspension length at which the spring force
    is zero (the static length plus the sprung weight over the stiffness);
    ``x_start``: where the hub starts along x.
    """

    speed: float
    sprung_mass: float
    unsprung_mass: float
    stiffness: float
    damping: float
    spring_free_length: float
    spin_inertia: float
    gravity: float
    x_start: float


# state layout (this module's own array)
Q_ZS, Q_VS, Q_ZU, Q_VU, Q_W, Q_T = range(6)
Q_SIZE = 6

CHANNELS = WHEEL_CHANNELS + ("FX_HUB", "FY_HUB", "FZ_HUB", "Z_BODY", "VZ_BODY", "F_SUSP")
N_CH = len(CHANNELS)


@nb.njit(cache=True)
def quarter_steps(wheel, qp, state, n_steps, dt, out_every, out, row0):
    """Advance the quarter vehicle; semi-implicit Euler. Returns the next free row.

    Sprung mass m_s on a spring k_s and damper c_s over the wheel (mass
    m_u); the hub is carried along x at constant speed, free vertically::

        m_s z_s'' = F_susp - m_s g
        m_u z_u'' = F_tyre,z - F_susp - m_u g
        F_susp    = k_s (d0 - (z_s - z_u)) + c_s (z_u' - z_s')
    """
    cax = np.empty(6)
    V = qp.speed
    ms = qp.sprung_mass
    mu = qp.unsprung_mass
    g = qp.gravity
    row = row0
    for step in range(n_steps):
        t = state[Q_T]
        cx = qp.x_start + V * t
        zs, vs, zu, vu = state[Q_ZS], state[Q_VS], state[Q_ZU], state[Q_VU]
        pose = WheelPose(cx, 0.0, zu, 0.0, 1.0, 0.0, V, 0.0, vu, state[Q_W])
        f = wheel_step(wheel, pose, dt)
        fsp = qp.stiffness * (qp.spring_free_length - (zs - zu)) + qp.damping * (vu - vs)
        a_s = fsp / ms - g
        a_u = (f.fz - fsp) / mu - g
        spin = f.my   # the tyre's moment about the axle (+y)
        if (step % out_every) == 0 and row < out.shape[0]:
            o = out[row]
            wheel_row(o, t, cx - qp.x_start, pose, f, cax)
            o[N_WHEEL] = cax[0]
            o[N_WHEEL + 1] = cax[1]
            o[N_WHEEL + 2] = cax[2] - mu * a_u   # load-cell reading, tared with the wheel hanging free
            o[N_WHEEL + 3] = zs
            o[N_WHEEL + 4] = vs
            o[N_WHEEL + 5] = fsp
            row += 1
        state[Q_VS] = vs + dt * a_s
        state[Q_VU] = vu + dt * a_u
        state[Q_ZS] = zs + dt * state[Q_VS]
        state[Q_ZU] = zu + dt * state[Q_VU]
        # linearly implicit Euler: the slip stiffness makes the spin stiff
        state[Q_W] += dt * spin / (qp.spin_inertia - dt * min(f.dspin_domega, 0.0))
        state[Q_T] = t + dt
    return row

