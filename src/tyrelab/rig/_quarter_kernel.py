"""Compiled time loop of the quarter-vehicle rig (see :mod:`.quarter_vehicle`)."""

import numba as nb
import numpy as np

from ..tyre.contact.point import GEO_SIZE
from ..tyre.kernel import OUT_SIZE, wheel_force
from .frames import N_WHEEL, WHEEL_CHANNELS, wheel_row

# parameter layout
QP_SPEED, QP_MS, QP_MU, QP_KS, QP_CS, QP_D0, QP_ISPIN, QP_G, QP_X0 = range(9)
QP_SIZE = 9
# state layout
Q_ZS, Q_VS, Q_ZU, Q_VU, Q_W, Q_T = range(6)
Q_SIZE = 6

CHANNELS = WHEEL_CHANNELS + ("FX_HUB", "FY_HUB", "FZ_HUB", "Z_BODY", "VZ_BODY", "F_SUSP")
N_CH = len(CHANNELS)


@nb.njit(cache=True)
def quarter_steps(model, handling, vp, kn, co, cp, hp, gp, z, zi, ts, qp, state, n_steps, dt,
                  out_every, out, row0):
    """Advance the quarter vehicle; semi-implicit Euler. Returns the next free row.

    Sprung mass m_s on a spring k_s and damper c_s over the wheel (mass
    m_u); the hub is carried along x at constant speed, free vertically::

        m_s z_s'' = F_susp - m_s g
        m_u z_u'' = F_tyre,z - F_susp - m_u g
        F_susp    = k_s (d0 - (z_s - z_u)) + c_s (z_u' - z_s')
    """
    geo = np.empty(GEO_SIZE)
    f = np.empty(OUT_SIZE)
    cax = np.empty(6)
    V = qp[QP_SPEED]
    ms = qp[QP_MS]
    mu = qp[QP_MU]
    g = qp[QP_G]
    row = row0
    for step in range(n_steps):
        t = state[Q_T]
        cx = qp[QP_X0] + V * t
        zs, vs, zu, vu = state[Q_ZS], state[Q_VS], state[Q_ZU], state[Q_VU]
        wheel_force(model, handling, vp, kn, co, cp, hp, gp, z, zi, ts, cx, 0.0, zu, 0.0, 1.0, 0.0,
                    V, 0.0, vu, state[Q_W], dt, geo, f)
        fsp = qp[QP_KS] * (qp[QP_D0] - (zs - zu)) + qp[QP_CS] * (vu - vs)
        a_s = fsp / ms - g
        a_u = (f[2] - fsp) / mu - g
        spin = f[15]   # the tyre's moment about the axle (+y)
        if (step % out_every) == 0 and row < out.shape[0]:
            o = out[row]
            wheel_row(o, t, cx - qp[QP_X0], cx, 0.0, zu, V, 0.0, vu, state[Q_W], 0.0, 1.0, 0.0, f, cax)
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
        state[Q_W] += dt * spin / (qp[QP_ISPIN] - dt * min(f[19], 0.0))
        state[Q_T] = t + dt
    return row

