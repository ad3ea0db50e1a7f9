"""The rigid wheel: a cylinder of the tyre's unloaded radius and width (terramechanics' wheel).

The textbook wheel of Bekker (1969) and Wong & Reece (1967): it does not deflect, so
on a deformable ground all of its sinkage is the soil's. It runs on soil only
(:mod:`tyrelab.road.soil`), where the soil computes the stresses on its surface node
by node (:func:`tyrelab.road.soil.scm.cylinder_loads`); on a rigid road a rigid
wheel would have no contact law, and :func:`rigid_params` refuses it.

The loads it returns (:class:`~tyrelab.tyre.wheel.WheelLoads`): force and moment of
the soil about the centre; ``deflection`` the sinkage of its lowest point below the
undisturbed surface (> 0 in contact); ``kappa`` the longitudinal slip
``(omega R - V) / max(omega R, V)`` (terramechanics' s for a driven wheel), ``alpha``
the slip angle.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb

from ...core.vec3 import cross, dot, wheel_axes
from ...road.soil.scm import cylinder_loads
from ..registry import ContactModel, register_contact
from ..wheel import WheelLoads


class RigidParams(NamedTuple):
    """``radius`` R0 and ``width`` b [m] of the rigid cylinder."""

    radius: float
    width: float


def rigid_params(tyre, ground, **options) -> RigidParams:
    """The rigid wheel's record (no options); ``ground`` must be a soil bed."""
    from ...errors import InputError
    from ...road.soil.scm import SoilSurface
    if options:
        raise InputError(f"the rigid model takes no options, got {', '.join(options)}", field="options")
    if not isinstance(ground, SoilSurface):
        raise InputError("the rigid model runs on soil only (a rigid wheel on a rigid road has no "
                         "contact law); give a terrain, e.g. --terrain lete-sand", field="model")
    if not tyre.width > 0:
        raise InputError("the rigid model needs the tyre's width (DIMENSION WIDTH)", field="model")
    return RigidParams(float(tyre.unloaded_radius), float(tyre.width))


@nb.njit(cache=True)
def rigid_step(wheel, pose, dt):
    """Loads of the soil on the rigid wheel over ``dt`` [s]; the soil's nodes advance."""
    p = wheel.contact
    L = cylinder_loads(wheel.road, pose.cx, pose.cy, pose.cz, pose.ax, pose.ay, pose.az,
                       pose.vx, pose.vy, pose.vz, pose.omega, p.radius, p.width, dt, True)
    fx_, fy_, fz_, dx_, dy_, dz_ = wheel_axes(pose.ax, pose.ay, pose.az)
    # W-axis: x forward, y along the axis, z up (normal to the ground plane)
    fxw = dot(L.fx, L.fy, L.fz, fx_, fy_, fz_)
    fyw = dot(L.fx, L.fy, L.fz, pose.ax, pose.ay, pose.az)
    zx, zy, zz = cross(fx_, fy_, fz_, pose.ax, pose.ay, pose.az)
    fzw = max(0.0, dot(L.fx, L.fy, L.fz, zx, zy, zz))
    v_fwd = dot(pose.vx, pose.vy, pose.vz, fx_, fy_, fz_)
    v_lat = dot(pose.vx, pose.vy, pose.vz, pose.ax, pose.ay, pose.az)
    v_rim = pose.omega * p.radius
    kappa = (v_rim - v_fwd) / max(abs(v_rim), abs(v_fwd), 1e-6)
    alpha = math.atan2(-v_lat, abs(v_fwd)) if abs(v_fwd) > 1e-6 else 0.0
    # the contact point: the cylinder's lowest point, a radius below the centre in its plane
    return WheelLoads(L.fx, L.fy, L.fz, L.mx, L.my, L.mz,
                      pose.cx + p.radius * dx_, pose.cy + p.radius * dy_, pose.cz + p.radius * dz_,
                      zx, zy, zz, L.sinkage if L.area > 0.0 else 0.0, 0.0, fxw, fyw, fzw,
                      kappa, alpha, 0.0)


register_contact(ContactModel("rigid", RigidParams, rigid_params, step=rigid_step,
                              summary="rigid cylinder of the tyre's radius and width (soil only)",
                              cost=0.02, parameterization="unloaded radius and width",
                              terrains=("soil",)))
