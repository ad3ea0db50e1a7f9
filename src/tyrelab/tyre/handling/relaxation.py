"""Transient slip: the carcass deflections that make a tyre's forces lag its slip.

A rolling tyre builds its force over a distance, not at once: the carcass
deflects at the contact patch, and the slip the tread feels follows the
kinematic slip with a first-order lag over the relaxation length
(Pacejka, *Tyre and Vehicle Dynamics*, 3rd ed. 2012, section 7.2, the
"single contact point" model; ADAMS/Tire's and MF-Tyre's "linear transient",
``USE_MODE`` +10). With ``u`` and ``v`` the longitudinal and lateral
deflections of the contact point relative to the rim [m]::

    du/dt + (V / sigma_kappa) u = V_sx            kappa' = -u / sigma_kappa
    dv/dt + (V / sigma_alpha) v = V_sy            tan alpha' = v / sigma_alpha

where ``V_sx``, ``V_sy`` are the contact point's slip velocities and ``V``
the forward speed ``|V_x|`` held at or above the slip's ``VXLOW`` (as the
steady slip of :func:`~.slip.slip` is, so that the steady state is exactly
the steady model's at every speed: ``u = sigma V_sx / V``). The handling
model then evaluates its own force law at the lagged slips ``kappa'``,
``alpha'``: it is handed the slip velocities that give them,
``V_s' = (u / sigma) V``, so each model keeps its own slip definition.

Integrated by implicit Euler over the rig's step ``dt`` (stable at every
step and speed, exact in the steady state): ``u1 = (u0 + dt V_sx) / (1 + dt
V / sigma)``. A length of zero is no lag in that direction. A step ``dt = 0``
(the loads at a pose, no time passing) gives the forces of the deflections as
they are and leaves them so: a table of steady-state loads is made with
``relaxation="off"``. Off the ground the deflections return to zero.

The lengths are either constants (a user's, in metres) or the handling
model's own, at the load (the Magic Formula's: PTX/PTY of MF 5.2, or the
slip stiffness over the carcass stiffness of MF 6.1/6.2, as MFeval's
``sigmax``, ``sigmay``), registered as
:attr:`~tyrelab.tyre.registry.HandlingModel.relaxation_lengths`.
"""

from __future__ import annotations

from typing import NamedTuple

import numba as nb
import numpy as np
from numba.extending import overload

from ...errors import InputError
from ..registry import handling_by_record

#: what ``relaxation`` may be besides two lengths (:func:`slip_lag`)
RELAXATION_WORDS = ("auto", "off", "file")


class SlipLag(NamedTuple):
    """The transient slip of a wheel (module docstring): its lengths and its state."""

    #: the handling model's own lengths at the load (True), else ``length_x``, ``length_y``
    from_model: bool
    #: constant relaxation lengths [m], longitudinal and lateral (0: no lag that way)
    length_x: float
    length_y: float
    #: the carcass deflections ``[u, v]`` [m], advanced in place by each wheel step
    deflection: np.ndarray

    @property
    def active(self) -> bool:
        return self.from_model or self.length_x > 0.0 or self.length_y > 0.0


def no_lag() -> SlipLag:
    """Steady-state slip: the forces answer the slip at once."""
    return SlipLag(False, 0.0, 0.0, np.zeros(2))


def own_lag() -> SlipLag:
    """The handling model's own relaxation lengths, at each step's load."""
    return SlipLag(True, 0.0, 0.0, np.zeros(2))


@nb.njit(cache=True)
def lagged(deflection, length, v_slip, v_ref, dt):
    """``(u1, V_s', gain)``: the deflection ``u1`` after a step ``dt`` [s] of
    ``du/dt + (v_ref / length) u = v_slip`` from ``deflection`` (implicit Euler), the
    slip velocity ``V_s' = u1 v_ref / length`` that gives the lagged slip, and the
    gain ``dV_s'/dV_s`` of that step (``decay / (1 + decay)``, ``decay = dt v_ref /
    length``), which scales the slip stiffness a rig integrates the spin with.
    No length: the steady state (``v_slip``, gain 1), the deflection kept."""
    if length <= 0.0:
        return deflection, v_slip, 1.0
    decay = dt * v_ref / length
    u1 = (deflection + dt * v_slip) / (1.0 + decay)
    return u1, u1 * v_ref / length, decay / (1.0 + decay)


def relaxation_lengths(handling, lag, fz, v_long, gamma):
    """``(sigma_kappa, sigma_alpha)`` [m] of ``lag`` for the handling record ``handling`` at
    load ``fz`` [N], speed ``v_long`` [m/s] and camber ``gamma`` [rad] (compiled)."""
    raise NotImplementedError("compiled only")


@overload(relaxation_lengths)
def _relaxation_lengths(handling, lag, fz, v_long, gamma):
    own = handling_by_record(handling).relaxation_lengths
    if own is None:
        def impl(handling, lag, fz, v_long, gamma):
            return lag.length_x, lag.length_y
        return impl

    def impl(handling, lag, fz, v_long, gamma):  # noqa: F811 - the other branch's
        if lag.from_model:
            return own(handling, fz, v_long, gamma)
        return lag.length_x, lag.length_y
    return impl


def use_mode_relaxes(tir) -> bool:
    """True when a property file's ``USE_MODE`` asks for relaxation: its tens digit
    1 (linear relaxation), 2 (non-linear) or 3 (rigid-ring dynamics) -- the MF-Tyre/ADAMS
    convention (``+10``: including relaxation behaviour, as the files' own header says);
    the sign (mirroring: the Magic Formula's coefficients read it) and the hundreds (contact
    method) are not read here."""
    mode = tir.get("MODEL", "USE_MODE")
    if isinstance(mode, bool) or not isinstance(mode, (int, float)):
        return False  # absent, or a bare word some writers put there
    return (int(abs(mode)) // 10) % 10 in (1, 2, 3)


def slip_lag(tyre, handling, relaxation="auto") -> SlipLag:
    """The :class:`SlipLag` of ``tyre`` under the handling model ``handling`` (registry
    record) for a ``relaxation`` of:

    * ``"auto"``: the model's own lengths where the file asks for relaxation (its
      ``USE_MODE`` with +10, :func:`use_mode_relaxes`; the Magic Formula's files carry it,
      ADAMS's Fiala files may), else none;
    * ``"off"``: none (steady-state slip);
    * ``"file"``: the handling model's own lengths (refused for a model without them);
    * ``(sigma_kappa, sigma_alpha)`` or the text ``"SIGMA_KAPPA,SIGMA_ALPHA"`` (the command
      line's ``--relaxation``): constant lengths [m], 0 for none that way.
    """
    field = "relaxation"
    if isinstance(relaxation, str) and "," in relaxation:  # the command line's form
        relaxation = relaxation.split(",")
    if isinstance(relaxation, str):
        if relaxation not in RELAXATION_WORDS:
            raise InputError(f"expected one of {', '.join(RELAXATION_WORDS)} or two "
                             f"lengths in metres 'SIGMA_KAPPA,SIGMA_ALPHA', got {relaxation!r}",
                             field=field)
        if relaxation == "off":
            return no_lag()
        own = handling.relaxation_lengths is not None
        if relaxation == "file":
            if not own:
                raise InputError(f"'file': the '{handling.name}' handling model has no "
                                 "relaxation lengths of its own; give two lengths in metres "
                                 "'SIGMA_KAPPA,SIGMA_ALPHA'", field=field)
            return own_lag()
        return own_lag() if own and use_mode_relaxes(tyre.tir) else no_lag()
    try:
        lengths = [float(v) for v in relaxation]
    except (TypeError, ValueError):
        lengths = []
    if len(lengths) != 2 or not all(0.0 <= v < 100.0 for v in lengths):
        given = (",".join(map(str, relaxation)) if isinstance(relaxation, (tuple, list))
                 else repr(relaxation))
        raise InputError(f"expected two lengths in metres, each 0 (no lag) to 100, got {given}",
                         field=field)
    return SlipLag(False, lengths[0], lengths[1], np.zeros(2))
