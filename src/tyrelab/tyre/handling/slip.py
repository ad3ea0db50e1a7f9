"""Slip of the contact point, shared by the handling models.

Slip definitions (ISO / TYDEX W-axis, as the Magic Formula uses them)::

    kappa = -V_sx / |V_x|          (> 0 when driving)
    alpha = atan(V_sy / |V_x|)     (> 0 when the contact point slides left)

with V_x the wheel-centre speed along the W-axis x, V_sx and V_sy the slip
velocity of the tyre material at the contact point, and |V_x| held at or
above ``VXLOW`` so slip stays finite at standstill. Each handling model
(:mod:`.pac89`, :mod:`.mf.wheel`) turns slip into forces and registers
itself in :mod:`tyrelab.tyre.registry`.
"""

from __future__ import annotations

import math

import numba as nb

#: speed below which slip is computed with this speed instead [m/s]
VXLOW = 1.0
#: slip step of the forward difference giving the slip stiffness
DKAPPA = 1e-5


@nb.njit(cache=True)
def slip(v_long, v_slip_x, v_slip_y):
    """``(kappa, alpha)`` from the contact point's velocities (module docstring)."""
    vx = abs(v_long)
    if vx < VXLOW:
        vx = VXLOW
    return -v_slip_x / vx, math.atan(v_slip_y / vx)
