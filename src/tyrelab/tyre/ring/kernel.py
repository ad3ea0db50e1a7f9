"""Compiled force of the flexible ring model on the rim -- placeholder until built.

Interface (kept by the implementation):

``ring_wheel_force(model, cp, ts, gp, z, zinfo, cx, cy, cz, ax, ay, az,
vx, vy, vz, omega, dt, out)`` advances the belt state ``ts`` by ``dt`` under
the given rim motion and writes the loads on the rim into ``out`` with the
layout of :mod:`tyrelab.tyre.kernel` (force 0:3, resultant contact point
3:6, normal 6:9, deflection 9, FXW..FZW 11:14, moment about the wheel
centre 14:17). ``model`` is 3 (ring) or 4 (ring with tread pattern).
"""

import numba as nb


@nb.njit(cache=True)
def ring_wheel_force(model, cp, ts, gp, z, zinfo, cx, cy, cz, ax, ay, az,
                     vx, vy, vz, omega, dt, out):
    out[9] = -1.0
