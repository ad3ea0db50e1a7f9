"""Compiled time loop of the quarter-vehicle rig (see :mod:`.quarter_vehicle`)."""

from typing import NamedTuple

import numba as nb
import numpy as np

from ..tyre.wheel import WheelPose, wheel_step
from ..core.named_index import named_index
from .frames import CA, N_C_AXIS, WHEEL_CHANNELS, wheel_row


class QuarterParams(NamedTuple):
    """The quarter vehicle as its compiled loop takes it (SI).

    ``spring_free_length``: the suspension length at which the spring force
    is zero (the static length plus the sprung weight over the stiffness);
    ``x_start``: where the hub starts along x.
    """

    speed: float
    sprung_mass: float
    unsprung_mass: float
    rim_mass: float
    stiffness: float
    damping: float
    spring_free_length: float
    spin_inertia: float
    gravity: float
    x_start: float


#: the state array of :func:`quarter_steps`, in this order: sprung mass height [m] and
#: velocity [m/s], hub height and velocity, wheel spin [rad/s], time [s]
STATE = ("ZS", "VS", "ZU", "VU", "W", "T")
Q = named_index("QuarterStateIndex", STATE)
Q_SIZE = len(STATE)

#: output columns: the wheel's, then the load cells, the body and the suspension force
CHANNELS = WHEEL_CHANNELS + ("FX_HUB", "FY_HUB", "FZ_HUB", "Z_BODY", "VZ_BODY", "F_SUSP")
N_CH = len(CHANNELS)
QC = named_index("QuarterChannelIndex", CHANNELS)


@nb.njit(cache=True)
def quarter_steps(wheel, qp, state, n_steps, dt, out_every, out, row0):
    """Advance the quarter vehicle; semi-implicit Euler. Returns the next free row.

    Sprung mass m_s on a spring k_s and damper c_s over the wheel (mass
    m_u); the hub is carried along x at constant speed, free vertically::

        m_s z_s'' = F_susp - m_s g
        m_r z_u'' = F_tyre,z - F_susp - m_u g
        F_susp    = k_s (d0 - (z_s - z_u)) + c_s (z_u' - z_s')

    ``m_r`` the rim's mass, ``m_u`` less what the tyre model's own state moves (the ring's
    belt, whose inertia is in ``F_tyre``; its weight is the rim's to carry): ``m_u`` for the
    analytic models.
    """
    cax = np.empty(N_C_AXIS)
    V = qp.speed
    ms = qp.sprung_mass
    mu = qp.unsprung_mass
    mr = qp.rim_mass
    g = qp.gravity
    weight = g * (mu / mr)   # the unsprung weight per unit of the rim's mass (g without a belt)
    row = row0
    for step in range(n_steps):
        t = state[Q.T]
        cx = qp.x_start + V * t
        zs, vs, zu, vu = state[Q.ZS], state[Q.VS], state[Q.ZU], state[Q.VU]
        pose = WheelPose(cx, 0.0, zu, 0.0, 1.0, 0.0, V, 0.0, vu, state[Q.W])
        f = wheel_step(wheel, pose, dt)
        fsp = qp.stiffness * (qp.spring_free_length - (zs - zu)) + qp.damping * (vu - vs)
        a_s = fsp / ms - g
        a_u = (f.fz - fsp) / mr - weight
        spin = f.my   # the tyre's moment about the axle (+y)
        if (step % out_every) == 0 and row < out.shape[0]:
            o = out[row]
            wheel_row(o, t, cx - qp.x_start, pose, f, cax)
            o[QC.FX_HUB] = cax[CA.FX]
            o[QC.FY_HUB] = cax[CA.FY]
            o[QC.FZ_HUB] = cax[CA.FZ] - mr * a_u   # load-cell reading, tared with the wheel hanging free
            o[QC.Z_BODY] = zs
            o[QC.VZ_BODY] = vs
            o[QC.F_SUSP] = fsp
            row += 1
        state[Q.VS] = vs + dt * a_s
        state[Q.VU] = vu + dt * a_u
        state[Q.ZS] = zs + dt * state[Q.VS]
        state[Q.ZU] = zu + dt * state[Q.VU]
        # linearly implicit Euler: the slip stiffness makes the spin stiff
        state[Q.W] += dt * spin / (qp.spin_inertia - dt * min(f.dspin_domega, 0.0))
        state[Q.T] = t + dt
    return row

