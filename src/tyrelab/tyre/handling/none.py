"""No handling model: the tyre transmits only its normal force."""

from __future__ import annotations

from typing import NamedTuple

import numba as nb

from ..registry import HandlingModel, register_handling


class NoHandling(NamedTuple):
    """The parameter record of the "none" handling model (it has no parameters)."""

    unused: float = 0.0


def no_handling(tyre) -> NoHandling:
    return NoHandling()


@nb.njit(cache=True)
def no_forces(params, fz, v_long, v_slip_x, v_slip_y, gamma):
    """Zero tangential forces (never called in a wheel step: :func:`has_handling` is false)."""
    return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0


register_handling(HandlingModel("none", NoHandling, no_handling, no_forces,
                                "no tangential forces (vertical dynamics only)"))
