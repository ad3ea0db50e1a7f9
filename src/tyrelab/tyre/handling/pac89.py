"""Pacejka '89 handling forces -- placeholder until built.

Interface (kept by the implementation): ``pac89_params(tyre) -> float64
array`` (A0-A13, B0-B10, C0-C17 in the Adams/Bakker convention, read from
the tyre's property file); ``pac89_forces(hp, fz, kappa, alpha, gamma)``
(numba, cache=True) returns ``(Fx, Fy, Mz)`` in SI, W-axis, from fz [N],
kappa [-], alpha [rad], gamma [rad].
"""

import numba as nb

from ...errors import InputError


def pac89_params(tyre):
    raise InputError("the PAC89 handling model is not available yet", field="handling")


@nb.njit(cache=True)
def pac89_forces(hp, fz, kappa, alpha, gamma):
    return 0.0, 0.0, 0.0
