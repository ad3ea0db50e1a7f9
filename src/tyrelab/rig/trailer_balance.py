"""The trailer's rolling start balanced with its tyres' own forces (:meth:`.trailer.Trailer.run`).

The frame starts where its wheels' centres stand, each wheel in its free-rolling
equilibrium (:meth:`~tyrelab.tyre.model.TyreModel.equilibrium`) under a load. With the load
case's static load on both, the frame is balanced only if the tyres give it no moment of
their own. A handling model whose forces do not vanish at zero slip does: the Magic
Formula's lateral offsets (``PHY1``, ``PVY1``: ply-steer and conicity), its overturning
moment (``QSX1``) and the drag of a rolling resistance push and twist the frame about its
hitch. Started from the static loads, the trailer then rolled and pitched into the
balance it should have started in: the MF 6.1 example tyre (``examples/data/
MagicFormula61_Parameters.tir``, 4 kN, 42 km/h) rocked its test wheel's load by 25 N
(0.6 %) in the first 0.2 s, its roll mode ringing for seconds, where the quarter vehicle
and the rolling rig start still to 1e-8 N.

:func:`balanced_loads` finds the two wheel loads at which the frame, each wheel in its
free-rolling equilibrium at its load and the frame pitched and rolled to put the wheel
centres where those equilibria stand, has no angular acceleration: the rig's own step
(``trailer_steps``, one step from rest) gives the residual, so every force and moment the
run will apply is in it. Newton's method on the two loads, with a Jacobian by differences
(the residual is smooth in them: the loads move the wheels through the vertical law).
Where the static loads are balanced already (the thesis's models, handling models without
offsets) the start is left exactly as it was. Models with a state of their own (the
ring: its equilibrium at a load is a settling of its belt) and a start on soil are not
balanced here: the ring has no force offsets, and soil settles its own start.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from . import _trailer_kernel as K

#: the loads are balanced when Newton's step changes them by less than this share of
#: the static load (1e-9 of 4 kN: 4 micronewtons)
LOAD_TOLERANCE = 1e-9
#: the difference step of the Jacobian, a share of the static load
LOAD_STEP = 1e-5
#: a time step [s] after which the transient slip's deflections are steady (module
#: relaxation: the implicit Euler step's limit)
STEADY_STEP = 1e9
#: Newton steps before giving up (two or three suffice: the residual is nearly linear)
MAX_BALANCE_STEPS = 12


def frame_acceleration(trailer, tp, speed: float, loads, right_wheel, left_wheel, dt: float,
                       x0_road: float):
    """``((theta'', phi''), start)``: the frame's pitch and roll accelerations [rad/s^2] from
    rest, the test and left wheels in their free-rolling equilibria at ``loads`` [N] (right,
    left), the frame posed to hold their centres there; ``start`` the
    ``(pitch, roll, (right, left))`` of that pose and those equilibria. ``tp`` the rig's
    record at ``speed`` (:meth:`~.trailer.Trailer.params`).

    ``right_wheel``, ``left_wheel`` the :class:`~tyrelab.tyre.wheel.Wheel` records the run
    will use, started in each equilibrium (:meth:`~tyrelab.tyre.model.TyreModel.rolling_from`)."""
    r0 = trailer.model.tyre.unloaded_radius
    eqs = (trailer.model.equilibrium(loads[0], speed), trailer.left.equilibrium(loads[1], speed))
    pitch, roll = trailer.frame_angles(r0 - eqs[0].deflection, r0 - eqs[1].deflection)
    state = np.zeros(K.S_SIZE)
    state[K.S.THETA] = pitch
    state[K.S.PHI] = roll
    state[K.S.WR], state[K.S.WL] = eqs[0].spin, eqs[1].spin
    wheels = [model.rolling_from(wheel, eq) for wheel, eq, model in
              zip((right_wheel, left_wheel), eqs, (trailer.model, trailer.left))]
    out = np.zeros((1, K.N_CH))
    x_start = x0_road + trailer.geometry.hitch_to_axle * math.cos(pitch)  # as Trailer._run
    # the transient slip's carcass deflections steady at this pose: the universal joint
    # turns the wheels' axes by about pitch x roll (a slip angle of 7e-7 rad at 0.0185 rad
    # and 3.8e-5 rad), which the upright equilibria do not see. One step so long that the
    # lag's implicit Euler step is its steady state (relaxation.py: u = sigma V_sx / V to
    # sigma / (V STEADY_STEP)), on a copy of the frame's state
    K.trailer_steps(wheels[0], wheels[1], tp, state.copy(), 1, STEADY_STEP, 1, out, 0, x_start)
    eqs = tuple(eq._replace(carcass=tuple(float(d) for d in wheel.lag.deflection))
                for eq, wheel in zip(eqs, wheels))
    K.trailer_steps(wheels[0], wheels[1], tp, state, 1, dt, 1, out, 0, x_start)
    return (state[K.S.DTHETA] / dt, state[K.S.DPHI] / dt), (pitch, roll, eqs)


def balanced_loads(trailer, speed: float, right_wheel, left_wheel, dt: float, x0_road: float):
    """``(pitch, roll, (right, left))``: the frame's angles [rad] and the wheels'
    :class:`~tyrelab.tyre.model.Equilibrium` at the loads that balance it (module docstring).

    Starts from the load case's static load on both wheels; returns that start unchanged
    when Newton's first step would move the loads by less than :data:`LOAD_TOLERANCE`."""
    static = trailer.setup.wheel_load
    tp = trailer.params(speed)
    loads = np.array([static, static])
    h = LOAD_STEP * static
    for _ in range(MAX_BALANCE_STEPS):
        residual, start = frame_acceleration(trailer, tp, speed, loads, right_wheel, left_wheel,
                                             dt, x0_road)
        jacobian = np.empty((2, 2))
        for k in range(2):
            moved = loads.copy()
            moved[k] += h
            jacobian[:, k] = (np.subtract(frame_acceleration(trailer, tp, speed, moved,
                                                             right_wheel, left_wheel, dt,
                                                             x0_road)[0], residual)) / h
        step = np.linalg.solve(jacobian, -np.asarray(residual))
        if np.abs(step).max() <= LOAD_TOLERANCE * static:
            return start
        loads = loads + step
        if not np.all(loads > 0.0):
            raise InputError(f"the tyres' own forces at zero slip tip the trailer off a wheel "
                             f"(loads {loads[0]:.0f} N and {loads[1]:.0f} N to balance it)",
                             field="load")
    raise InputError(f"the trailer's start does not balance with the tyres' forces at zero slip "
                     f"in {MAX_BALANCE_STEPS} steps (loads {loads[0]:.6g} N, {loads[1]:.6g} N)",
                     field="load")
