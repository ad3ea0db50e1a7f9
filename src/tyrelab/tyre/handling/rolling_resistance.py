"""Rolling resistance moment of the simple handling models (Fiala, TMeasy, TMsimple).

The tyre's hysteresis shifts the centre of its vertical load ahead of the wheel centre by a
lever ``e`` (ADAMS's Fiala ``ROLLING_RESISTANCE`` [m]; ``f_r R0`` for a coefficient ``f_r``,
Chrono's TMeasy "Rolling Resistance Coefficient", stored as MF-Tyre's ``QSY1``, whose
low-speed term it is: Pacejka 2012, eq. 4.E70 with only QSY1)::

    My = -e Fz tanh(omega / SPIN_SMOOTHING)

about the W-axis y (the spin axis), negative when rolling forward. The ``tanh`` is Project
Chrono's (ChTMeasyTire, ChTMsimpleTire, 2023: "a ramp-like signum"): the moment turns over
smoothly through standstill instead of switching, which an implicit spin integration would
chatter on. The Magic Formula has its own (:func:`.mf.moments.rolling_resistance`).
"""

from __future__ import annotations

import math

import numba as nb

#: the section of a rolling resistance coefficient ``QSY1`` (MF-Tyre's, the same physics; TMeasy's
#: and Chrono's PAC89's are written there too)
ROLLING_SECTION = "ROLLING_COEFFICIENTS"
#: the spin over which the rolling resistance turns over through standstill [rad/s] (Chrono's
#: ``tanh(omega)``: 76 % of the moment at 1 rad/s)
SPIN_SMOOTHING = 1.0


@nb.njit(cache=True)
def rolling_resistance_moment(lever, fz, omega):
    """``My = -lever Fz tanh(omega / SPIN_SMOOTHING)`` [N m] for a load-centre shift ``lever``
    [m] at load ``fz`` [N] and spin ``omega`` [rad/s] (module docstring); 0 without load."""
    if not fz > 0.0:
        return 0.0
    return -lever * fz * math.tanh(omega / SPIN_SMOOTHING)
