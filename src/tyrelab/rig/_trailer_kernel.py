"""Compiled time loop of the towed tyre test trailer (see :mod:`.trailer`).

The trailer is one rigid body hanging on a hitch that moves in a straight
line at constant speed. The hitch is a universal joint: the body pitches
about the world y axis through the hitch and rolls about its own x axis,
orientation ``R = Ry(theta) Rx(phi)``; yaw is held by the towing vehicle.
Both wheels spin freely about their axles. Equations of motion (Euler's
equations about the hitch, which moves at constant velocity and so is an
inertial point, projected on the two joint axes)::

    (J^T I J) q'' = J^T (tau_b - w x I w - I Jdot q')

with body angular velocity ``w = J q'``, ``J = [Rx(phi)^T e_y, e_x]`` and
``Jdot q' = theta' phi' (0, -sin phi, -cos phi)``. Integrated with the
semi-implicit (symplectic) Euler method at a fixed step.
"""

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from ..tyre.wheel import WheelPose, wheel_step
from ..core.named_index import named_index
from .frames import CA, N_C_AXIS, WHEEL_CHANNELS, wheel_row


class TrailerParams(NamedTuple):
    """The trailer as its compiled loop takes it (SI).

    ``cg`` centre of mass and ``inertia`` (3 x 3) about the hitch, in the
    body frame; ``road_y``: the test wheel's road is the world shifted by
    this in y (its track runs along the road's y = 0), the left wheel's
    flat road by minus this.
    """

    speed: float
    hitch_to_axle: float
    track: float
    hitch_height: float
    mass: float
    cg: np.ndarray
    inertia: np.ndarray
    spin_inertia: float
    wheel_mass: float
    gravity: float
    road_y: float


#: the state array of :func:`trailer_steps`, in this order: pitch, roll [rad] and
#: their rates, the right (test) and left wheels' spins [rad/s], time [s], the
#: test wheel centre's velocity at the last step (its load cells' inertia force)
STATE = ("THETA", "PHI", "DTHETA", "DPHI", "WR", "WL", "T", "VXR", "VYR", "VZR")
S = named_index("TrailerStateIndex", STATE)
S_SIZE = len(STATE)

#: output columns: the test wheel's, then the load cells, the left wheel's load and the frame
CHANNELS = WHEEL_CHANNELS + ("FX_HUB", "FY_HUB", "FZ_HUB", "FZ_LEFT", "PITCH", "ROLL")
N_CH = len(CHANNELS)
TC = named_index("TrailerChannelIndex", CHANNELS)


@nb.njit(cache=True)
def _rotation(theta, phi, R):
    ct, st = math.cos(theta), math.sin(theta)
    cp, sp = math.cos(phi), math.sin(phi)
    # Ry(theta) @ Rx(phi)
    R[0, 0] = ct
    R[0, 1] = st * sp
    R[0, 2] = st * cp
    R[1, 0] = 0.0
    R[1, 1] = cp
    R[1, 2] = -sp
    R[2, 0] = -st
    R[2, 1] = ct * sp
    R[2, 2] = ct * cp


@nb.njit(cache=True)
def trailer_steps(right, left, tp, state, n_steps, dt, out_every, out, row0, x_start):
    """Advance the trailer ``n_steps`` steps from ``state``; write every
    ``out_every``-th step into ``out`` starting at row ``row0``. Returns the
    next free row.

    ``right`` (the test wheel) and ``left`` are :class:`~tyrelab.tyre.wheel.Wheel`
    records of any models; ``tp`` a :class:`TrailerParams`.
    """
    R = np.empty((3, 3))
    Ib = tp.inertia
    cax = np.empty(N_C_AXIS)
    L = tp.hitch_to_axle
    half = 0.5 * tp.track
    V = tp.speed
    g = tp.gravity
    m = tp.mass
    ispin = tp.spin_inertia
    mw = tp.wheel_mass
    road_y = tp.road_y
    row = row0
    for step in range(n_steps):
        th = state[S.THETA]
        ph = state[S.PHI]
        dth = state[S.DTHETA]
        dph = state[S.DPHI]
        t = state[S.T]
        _rotation(th, ph, R)
        hx = x_start + V * t
        hz = tp.hitch_height
        # world angular velocity: dth * e_y + dph * (Ry e_x)
        wx = dph * math.cos(th)
        wy = dth
        wz = -dph * math.sin(th)
        # axis of the wheels (body y) in the world
        ax, ay, az = R[0, 1], R[1, 1], R[2, 1]
        tau0 = 0.0
        tau1 = 0.0
        tau2 = 0.0
        spinR = 0.0
        spinL = 0.0
        dspinR = 0.0
        dspinL = 0.0
        for side in range(2):
            by = -half if side == 0 else half   # right (test) wheel first
            rx = -L * R[0, 0] + by * R[0, 1]
            ry = -L * R[1, 0] + by * R[1, 1]
            rz = -L * R[2, 0] + by * R[2, 1]
            cx = hx + rx
            cy = ry
            cz = hz + rz
            vx = V + wy * rz - wz * ry
            vy = wz * rx - wx * rz
            vz = wx * ry - wy * rx
            if side == 0:
                f = wheel_step(right, WheelPose(cx, cy + road_y, cz, ax, ay, az, vx, vy, vz,
                                                state[S.WR]), dt)
            else:
                f = wheel_step(left, WheelPose(cx, cy - road_y, cz, ax, ay, az, vx, vy, vz,
                                               state[S.WL]), dt)
            # moment about the hitch: the force at the wheel centre plus the
            # tyre's moment about the centre
            tau0 += ry * f.fz - rz * f.fy + f.mx
            tau1 += rz * f.fx - rx * f.fz + f.my
            tau2 += rx * f.fy - ry * f.fx + f.mz
            # spin: the tyre's moment about the axle, and its slope in omega
            sm = f.mx * ax + f.my * ay + f.mz * az
            dsm = f.dspin_domega
            if side == 0:
                spinR = sm
                dspinR = dsm
                if (step % out_every) == 0 and row < out.shape[0]:
                    o = out[row]
                    # the world pose (the wheel's road is shifted by road_y)
                    wheel_row(o, t, 0.0, WheelPose(cx, cy, cz, ax, ay, az, vx, vy, vz, state[S.WR]),
                              f, cax, -road_y)
                    # load-cell reading: tyre force less the wheel's inertia force,
                    # load cells tared with the wheel hanging free
                    if step > 0:
                        acx = (vx - state[S.VXR]) / dt
                        acy = (vy - state[S.VYR]) / dt
                        acz = (vz - state[S.VZR]) / dt
                    else:
                        acx = 0.0
                        acy = 0.0
                        acz = 0.0
                    o[TC.FX_HUB] = cax[CA.FX] - mw * (acx * R[0, 0] + acy * R[1, 0] + acz * R[2, 0])
                    o[TC.FY_HUB] = cax[CA.FY] - mw * (acx * ax + acy * ay + acz * az)
                    o[TC.FZ_HUB] = cax[CA.FZ] - mw * (acx * R[0, 2] + acy * R[1, 2] + acz * R[2, 2])
                    o[TC.PITCH] = th
                    o[TC.ROLL] = ph
                state[S.VXR] = vx
                state[S.VYR] = vy
                state[S.VZR] = vz
            else:
                spinL = sm
                dspinL = dsm
                if (step % out_every) == 0 and row < out.shape[0]:
                    out[row, TC.FZ_LEFT] = f.fzw
        if (step % out_every) == 0 and row < out.shape[0]:
            row += 1
        # gravity about the hitch: r_cg x (0, 0, -m g)
        cg = tp.cg
        gx = R[0, 0] * cg[0] + R[0, 1] * cg[1] + R[0, 2] * cg[2]
        gy = R[1, 0] * cg[0] + R[1, 1] * cg[1] + R[1, 2] * cg[2]
        tau0 += gy * (-m * g)
        tau1 -= gx * (-m * g)
        # to the body frame: tau_b = R^T tau
        tb0 = R[0, 0] * tau0 + R[1, 0] * tau1 + R[2, 0] * tau2
        tb1 = R[0, 1] * tau0 + R[1, 1] * tau1 + R[2, 1] * tau2
        tb2 = R[0, 2] * tau0 + R[1, 2] * tau1 + R[2, 2] * tau2
        sp_ = math.sin(ph)
        cp_ = math.cos(ph)
        j1 = (0.0, cp_, -sp_)          # column for theta'
        # body angular velocity and velocity-product terms
        w0 = dph
        w1 = dth * cp_
        w2 = -dth * sp_
        Iw0 = Ib[0, 0] * w0 + Ib[0, 1] * w1 + Ib[0, 2] * w2
        Iw1 = Ib[1, 0] * w0 + Ib[1, 1] * w1 + Ib[1, 2] * w2
        Iw2 = Ib[2, 0] * w0 + Ib[2, 1] * w1 + Ib[2, 2] * w2
        g0 = w1 * Iw2 - w2 * Iw1
        g1 = w2 * Iw0 - w0 * Iw2
        g2 = w0 * Iw1 - w1 * Iw0
        jd1 = -dth * dph * sp_
        jd2 = -dth * dph * cp_
        r0 = tb0 - g0 - (Ib[0, 1] * jd1 + Ib[0, 2] * jd2)
        r1 = tb1 - g1 - (Ib[1, 1] * jd1 + Ib[1, 2] * jd2)
        r2 = tb2 - g2 - (Ib[2, 1] * jd1 + Ib[2, 2] * jd2)
        # generalized mass matrix M = J^T I J, J = [j1, e_x]
        Ij1_0 = Ib[0, 1] * j1[1] + Ib[0, 2] * j1[2]
        Ij1_1 = Ib[1, 1] * j1[1] + Ib[1, 2] * j1[2]
        Ij1_2 = Ib[2, 1] * j1[1] + Ib[2, 2] * j1[2]
        m11 = j1[1] * Ij1_1 + j1[2] * Ij1_2
        m12 = Ij1_0
        m22 = Ib[0, 0]
        q1 = j1[1] * r1 + j1[2] * r2
        q2 = r0
        det = m11 * m22 - m12 * m12
        ddth = (m22 * q1 - m12 * q2) / det
        ddph = (m11 * q2 - m12 * q1) / det
        # semi-implicit Euler
        state[S.DTHETA] = dth + dt * ddth
        state[S.DPHI] = dph + dt * ddph
        state[S.THETA] = th + dt * state[S.DTHETA]
        state[S.PHI] = ph + dt * state[S.DPHI]
        # linearly implicit Euler for the spins: the slip stiffness makes them
        # stiff (time constant I V / (r^2 C_kappa), below a millisecond)
        state[S.WR] += dt * spinR / (ispin - dt * min(dspinR, 0.0))
        state[S.WL] += dt * spinL / (ispin - dt * min(dspinL, 0.0))
        state[S.T] = t + dt
    return row

