"""The compiled side of the stepping API: one step of a wheel that a host moves.

A host (a vehicle model, an FMI master) gives the wheel centre's pose and
velocities at the start of a step and asks for the loads over the step;
:func:`advance` sub-steps the tyre model through
:func:`~tyrelab.tyre.wheel.wheel_step`, the rigs' own step, in one compiled
loop. Across the compiled boundary everything is a named record:

* :class:`WheelCentre` -- what the host gives (TYDEX names of the signal table
  in the docs: ``X_WC``, ..., ``ROTSPEED``, ``INCLANGL`` and the wheel's yaw);
* :class:`CentreLoads` -- what it gets back: the forces and moments of the road
  on the tyre at the wheel centre, in the TYDEX C-axis system or in the road
  frame (the sign convention of :mod:`tyrelab.signal`), the contact patch's
  forces in the W-axis system, the deflection and the contact point.

Sub-steps: a step of length ``n_sub * h`` is ``n_sub`` calls of
``wheel_step(wheel, pose_k, h)`` with the centre moved along its velocity,
``c_k = c + v k h`` (the spin axis, velocities and spin held), as the ring
model extrapolates the rim inside its own internal steps
(:func:`tyrelab.tyre.ring.kernel.ring_advance`). Forces, moments and the spin
stiffness returned are the means over the sub-steps (the impulse of the step
divided by its length); the contact point, deflection and slips those of the
last sub-step. With one sub-step, the loads are exactly those a rig computes
at this pose (:func:`tyrelab.rig.rolling.rolling_steps`,
:func:`tyrelab.rig._quarter_kernel.quarter_steps`).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from ..rig.frames import CA, N_C_AXIS, c_axis_loads
from ..tyre.wheel import WheelLoads, WheelPose, wheel_step

#: values of :func:`advance`'s ``frame``: the TYDEX C-axis system of the wheel, the road frame
C_AXIS_FRAME = 0
ROAD_FRAME = 1


class WheelCentre(NamedTuple):
    """The wheel centre as a host moves it (road frame, SI).

    ``x, y, z`` position [m] (``X_WC, Y_WC, Z_WC``); ``vx, vy, vz`` its
    velocity [m/s] (``VX_WC, VY_WC, VZ_WC``); ``omega`` spin rate about the
    spin axis [rad/s], positive rolling forward (``ROTSPEED``);
    ``inclination`` [rad] the wheel plane's angle to the road frame's z axis,
    positive when the top of the wheel leans to its right (``INCLANGL`` on a
    level road; TYDEX measures it from the local road normal); ``yaw`` [rad]
    the heading of the wheel plane about z, 0 along +x, positive to the left.
    """

    x: float
    y: float
    z: float
    vx: float
    vy: float
    vz: float
    omega: float
    inclination: float = 0.0
    yaw: float = 0.0


class CentreLoads(NamedTuple):
    """The loads of the road on the tyre over one step.

    ``fx, fy, fz`` [N] and ``mx, my, mz`` [N m] at the wheel centre, in the
    frame asked for (TYDEX C-axis: ``FX`` ... ``MZ`` of the signal table; or
    the road frame); ``fxw, fyw, fzw`` [N] the contact force in the W-axis
    system (``fzw`` >= 0); ``deflection`` [m] (``DEFLECT``, 0 out of contact);
    ``px, py, pz`` [m] the contact point (``X_CP`` ...); ``kappa`` [-] and
    ``alpha`` [rad] the slips (``LONGSLIP``, ``SLIPANGL``); ``dmy_domega``
    [N m s] the derivative of the moment about the spin axis (C-axis ``MY``)
    with respect to the spin, which lets a host integrate the spin implicitly
    (0 for models that report none, as the ring).
    """

    fx: float
    fy: float
    fz: float
    mx: float
    my: float
    mz: float
    fxw: float
    fyw: float
    fzw: float
    deflection: float
    px: float
    py: float
    pz: float
    kappa: float
    alpha: float
    dmy_domega: float


@nb.njit(cache=True)
def centre_pose(centre):
    """The :class:`~tyrelab.tyre.wheel.WheelPose` of a :class:`WheelCentre`.

    The spin axis is the heading's left, ``(-sin yaw, cos yaw, 0)``, turned
    about the heading by the inclination: ``a = cos(i) left + sin(i) e_z``, so
    that ``asin(a . e_z)`` is the inclination (the rigs' ``INCLANGL``, from
    :func:`tyrelab.rig.frames.wheel_row`, on a level road).
    """
    cy = math.cos(centre.yaw)
    sy = math.sin(centre.yaw)
    ci = math.cos(centre.inclination)
    si = math.sin(centre.inclination)
    # + 0.0 turns a negative zero into zero: a level wheel heading +x has exactly the
    # rigs' axis (0, 1, 0)
    return WheelPose(centre.x, centre.y, centre.z, -sy * ci + 0.0, cy * ci + 0.0, si + 0.0,
                     centre.vx, centre.vy, centre.vz, centre.omega)


@nb.njit(cache=True)
def advance(wheel, centre, n_sub, h, frame):
    """Advance ``wheel`` by ``n_sub`` sub-steps of ``h`` [s] from ``centre``; a :class:`CentreLoads`.

    ``wheel`` a :class:`~tyrelab.tyre.wheel.Wheel` (its state advanced in
    place), ``centre`` a :class:`WheelCentre` at the start of the step,
    ``frame`` :data:`C_AXIS_FRAME` or :data:`ROAD_FRAME` for the loads at the
    wheel centre. ``h = 0`` gives the loads of the present state without
    advancing it (the ring's foundation forces; an analytic model's loads).
    """
    p = centre_pose(centre)
    f = wheel_step(wheel, p, h)
    fx, fy, fz, mx, my, mz = f.fx, f.fy, f.fz, f.mx, f.my, f.mz
    fxw, fyw, fzw, dspin = f.fxw, f.fyw, f.fzw, f.dspin_domega
    for k in range(1, n_sub):
        t = k * h
        pose = WheelPose(p.cx + p.vx * t, p.cy + p.vy * t, p.cz + p.vz * t, p.ax, p.ay, p.az,
                         p.vx, p.vy, p.vz, p.omega)
        f = wheel_step(wheel, pose, h)
        fx += f.fx
        fy += f.fy
        fz += f.fz
        mx += f.mx
        my += f.my
        mz += f.mz
        fxw += f.fxw
        fyw += f.fyw
        fzw += f.fzw
        dspin += f.dspin_domega
    if n_sub > 1:
        fx /= n_sub
        fy /= n_sub
        fz /= n_sub
        mx /= n_sub
        my /= n_sub
        mz /= n_sub
        fxw /= n_sub
        fyw /= n_sub
        fzw /= n_sub
        dspin /= n_sub
    if frame == C_AXIS_FRAME:
        mean = WheelLoads(fx, fy, fz, mx, my, mz, f.px, f.py, f.pz, f.nx, f.ny, f.nz,
                          f.deflection, f.deflection_rate, fxw, fyw, fzw, f.kappa, f.alpha, dspin)
        cax = np.empty(N_C_AXIS)
        c_axis_loads(p, mean, cax)
        fx, fy, fz = cax[CA.FX], cax[CA.FY], cax[CA.FZ]
        mx, my, mz = cax[CA.MX], cax[CA.MY], cax[CA.MZ]
    deflection = f.deflection if f.deflection > 0.0 else 0.0
    return CentreLoads(fx, fy, fz, mx, my, mz, fxw, fyw, fzw, deflection, f.px, f.py, f.pz,
                       f.kappa, f.alpha, dspin)
