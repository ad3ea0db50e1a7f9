"""Wheels on soil: the rigid wheel, and the analytic tyre models as flexible wheels.

**The rigid wheel** (model ``rigid``) is a cylinder of the tyre's unloaded radius
and width, the textbook wheel of Bekker (1969) and Wong & Reece (1967): it does
not deflect, so all of its sinkage is the soil's, which computes the stresses on
its surface node by node (:func:`tyrelab.road.soil.wheel.wheel_loads`). On a rigid
road it has no contact law, and its ``build`` refuses one.

**A flexible wheel** is how the analytic models (point, volume, enveloping,
enveloping-edge) run on soil: the tyre and the soil in series. A pneumatic tyre
on soft ground flattens where the soil would otherwise press it harder than its
carcass carries (Wong 2008, *Theory of Ground Vehicles*, sec. 2.4: the "elastic"
mode, a flat section in the footprint). Here the wheel is the cylinder cut flat at
``R - delta`` from the axis, and the tyre's deflection ``delta`` is where the
model's own vertical law (thesis eq. 2.2, with its damping) carries what the soil
under the cut wheel pushes back along the wheel plane's upward direction::

    F_tyre(delta, d delta / dt) = G(delta)        (G: the soil's force along -d)

solved every step by Newton's method safeguarded by bisection
(:func:`flexible_deflection`), from the last step's deflection (rolling steadily one
trial pass over the soil and the step's own pass). The flat's tread moves at
``omega (R - delta)``, as the analytic models' contact point turns at the loaded radius on
a rigid road: on a ground too hard to sink it rolls freely where they do. A soft soil
carries the tyre with ``delta`` near 0 (the rigid-wheel mode); a hard one with
``delta`` near the tyre's deflection on a rigid road. A stiffer tyre (higher
inflation) flattens less, so it sinks deeper. On soil the analytic models differ
only in their tyre (radius, width, vertical law): the footprint is the soil's,
and how each model envelopes a rigid obstacle does not apply there.

The loads (:class:`~tyrelab.tyre.wheel.WheelLoads`): force and moment of the soil
about the centre; the contact point the wheel's lowest point (on the flat);
``deflection`` the tyre's (0 for the rigid wheel); ``kappa`` the longitudinal
slip ``(omega (R - delta) - V) / max(omega (R - delta), V)`` (terramechanics' s for a
driven wheel),
``alpha`` the slip angle.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from ...core.vec3 import cross, dot, wheel_axes
from ...road.soil.scm import SoilSurface
from ...road.soil.wheel import wheel_loads
from ..registry import ContactModel, register_contact
from ..vertical import normal_force, rolling_load
from ..wheel import WheelLoads

#: Newton's iteration stops when the tyre and the soil agree to this force [N] ...
FORCE_TOLERANCE = 0.5
#: ... or the bracket of the deflection is this narrow [m]
DEFLECTION_TOLERANCE = 1e-9
#: a Newton step from a residual this small [N] is taken without a pass to check it (rolling
#: steadily the last step's deflection is that near: one trial pass per step)
TRUSTED_RESIDUAL = 50.0
#: at most this many trial passes over the soil per step
MAX_ITERATIONS = 40
#: step [m] of the finite difference of the vertical law's stiffness
STIFFNESS_STEP = 1e-7


class SoilWheelParams(NamedTuple):
    """A wheel on soil.

    ``radius`` R0 and ``width`` b [m]; ``flexible``: the tyre deflects by its vertical law
    (False: the rigid wheel); ``last``: the tyre's deflection at the end of the last step [m]
    (one element, updated in place: the damping's rate and the next step's first guess).
    """

    radius: float
    width: float
    flexible: bool
    last: np.ndarray


def soil_wheel_params(tyre, flexible: bool) -> SoilWheelParams:
    """The record of ``tyre`` as a wheel on soil (its unloaded radius and width)."""
    tyre.require_width("a wheel on soil")
    return SoilWheelParams(float(tyre.unloaded_radius), float(tyre.width), bool(flexible),
                           np.zeros(1))


def rigid_params(tyre, ground, **options) -> SoilWheelParams:
    """The rigid wheel's record (no options); ``ground`` must be a soil bed."""
    from ...errors import InputError
    if options:
        raise InputError(f"the rigid model takes no options, got {', '.join(options)}", field="options")
    if not _on_soil(ground):
        raise InputError("the rigid model runs on soil only (a rigid wheel on a rigid road has no "
                         "contact law); give a terrain, e.g. --terrain lete-sand", field="model")
    return soil_wheel_params(tyre, flexible=False)


def _on_soil(ground) -> bool:
    """Whether the Python ground (:class:`~tyrelab.road.terrain.Ground`) is a soil."""
    return isinstance(ground.surface(), SoilSurface)


def wheel_params(entry, tyre, ground, options: dict):
    """The contact record of the registered model ``entry`` for ``tyre`` on ``ground``: on a soil
    bed an analytic model is a flexible wheel (its options, which shape its view of a rigid
    road, do not apply there); anything else is the model's own ``build``."""
    if _on_soil(ground) and entry.geometry is not None:
        return soil_wheel_params(tyre, flexible=True)
    if _on_soil(ground) and ground.surface().soil.bulldozing and entry.step is not soil_wheel_step:
        from ...errors import InputError
        raise InputError(f"the '{entry.name}' model does not bulldoze: a soil with a [bulldozing] "
                         "table takes the rigid wheel and the analytic models", field="model")
    return entry.build(tyre, ground, **options)


@nb.njit(cache=True)
def _soil(wheel, pose, flat, dt, update, normal_only):
    """The soil's loads on the wheel cut flat at ``flat`` from its axis."""
    p = wheel.contact
    return wheel_loads(wheel.road, pose.cx, pose.cy, pose.cz, pose.ax, pose.ay, pose.az,
                       pose.vx, pose.vy, pose.vz, pose.omega, p.radius, p.width, flat, dt, update,
                       normal_only)


@nb.njit(cache=True)
def _tyre_force(law, delta, last, dt, omega):
    """The vertical law's force at deflection ``delta`` [m] spinning at ``omega`` [rad/s]
    (damped by the rate from ``last`` over ``dt``; undamped when ``dt`` is 0) and its slope
    [N/m]."""
    if dt > 0.0:
        rate = (delta - last) / dt
        f = normal_force(law, delta, rate, omega)
        df = (normal_force(law, delta + STIFFNESS_STEP, rate + STIFFNESS_STEP / dt, omega) - f) \
            / STIFFNESS_STEP
    else:
        f = rolling_load(law, delta, omega)
        df = (rolling_load(law, delta + STIFFNESS_STEP, omega) - f) / STIFFNESS_STEP
    return f, max(df, 0.0)


@nb.njit(cache=True)
def flexible_deflection(wheel, pose, dt):
    """The tyre's deflection [m] at which its vertical law carries what the soil under the
    flattened wheel pushes back (module docstring), the bed only read."""
    p = wheel.contact
    bed = wheel.road
    _, _, _, _, _, dz = wheel_axes(pose.ax, pose.ay, pose.az)
    # beyond hi the flat is above every node: no soil under it, the tyre's force wins
    hi = min(0.999 * p.radius, max(0.0, (bed.zmax - (pose.cz - p.radius)) / max(-dz, 1e-3)))
    lo = 0.0
    if hi <= 0.0:
        return 0.0
    last = p.last[0]
    delta = min(max(last, lo), hi)
    for _ in range(MAX_ITERATIONS):
        f, df = _tyre_force(wheel.law, delta, last, dt, pose.omega)
        soil = _soil(wheel, pose, p.radius - delta, dt, False, True)
        h = f - soil.normal
        if abs(h) <= FORCE_TOLERANCE:
            break
        if h > 0.0:
            hi = delta
        else:
            lo = delta
        if hi - lo <= DEFLECTION_TOLERANCE:
            break
        slope = df - soil.dnormal
        nxt = delta - h / slope if slope > 0.0 else -1.0
        if lo < nxt < hi and abs(h) <= TRUSTED_RESIDUAL:
            return nxt          # from so near the root the Newton step is not checked
        delta = nxt if lo < nxt < hi else 0.5 * (lo + hi)
    return delta


@nb.njit(cache=True)
def soil_wheel_step(wheel, pose, dt):
    """Loads of the soil on the wheel over ``dt`` [s]; the soil's nodes advance."""
    p = wheel.contact
    delta = flexible_deflection(wheel, pose, dt) if p.flexible else 0.0
    L = _soil(wheel, pose, p.radius - delta if p.flexible else p.radius, dt, True, False)
    if p.flexible:
        p.last[0] = delta       # (a static trial too: a run starts from its equilibrium's)
    fx_, fy_, fz_, dx_, dy_, dz_ = wheel_axes(pose.ax, pose.ay, pose.az)
    # W-axis: x forward, y along the axis, z up (normal to the ground plane)
    fxw = dot(L.fx, L.fy, L.fz, fx_, fy_, fz_)
    fyw = dot(L.fx, L.fy, L.fz, pose.ax, pose.ay, pose.az)
    zx, zy, zz = cross(fx_, fy_, fz_, pose.ax, pose.ay, pose.az)
    fzw = max(0.0, dot(L.fx, L.fy, L.fz, zx, zy, zz))
    v_fwd = dot(pose.vx, pose.vy, pose.vz, fx_, fy_, fz_)
    v_lat = dot(pose.vx, pose.vy, pose.vz, pose.ax, pose.ay, pose.az)
    v_rim = pose.omega * (p.radius - delta)      # the tread's speed on the flat (soil.wheel.wheel_loads)
    kappa = (v_rim - v_fwd) / max(abs(v_rim), abs(v_fwd), 1e-6)
    alpha = math.atan2(-v_lat, abs(v_fwd)) if abs(v_fwd) > 1e-6 else 0.0
    # the contact point: the wheel's lowest point, on the flat, in its plane below the centre
    r = p.radius - delta
    return WheelLoads(L.fx, L.fy, L.fz, L.mx, L.my, L.mz,
                      pose.cx + r * dx_, pose.cy + r * dy_, pose.cz + r * dz_,
                      zx, zy, zz, delta if L.area > 0.0 else 0.0, 0.0, fxw, fyw, fzw,
                      kappa, alpha, 0.0)


register_contact(ContactModel("rigid", SoilWheelParams, rigid_params, step=soil_wheel_step,
                              summary="rigid cylinder of the tyre's radius and width (soil only)",
                              cost=0.02, parameterization="unloaded radius and width",
                              terrains=("soil",)))
