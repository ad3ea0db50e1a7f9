"""From road-frame forces to the TYDEX C-axis system of a wheel (compiled), and the
channels every rig writes first.

Output rows are flat arrays whose slots are decided by a rig's channel tuple
alone: :data:`WHEEL_CHANNELS` here, extended by each rig
(``CHANNELS = WHEEL_CHANNELS + (...)``); code writes them through the
:func:`~tyrelab.core.named_index.named_index` of that tuple (``o[WC.FX]``), never
by a number.
"""

import math

import numba as nb

from ..core.named_index import named_index
from ..core.vec3 import cross, wheel_axes

#: standard gravity [m/s^2], the one value every rig uses
G = 9.80665

#: the loads :func:`c_axis_loads` writes, in this order
C_AXIS = ("FX", "FY", "FZ", "MX", "MY", "MZ")
CA = named_index("CAxisIndex", C_AXIS)
N_C_AXIS = len(C_AXIS)


@nb.njit(cache=True)
def c_axis_loads(pose, f, out):
    """Forces and moments of the road on the tyre at the wheel centre, C-axis.

    ``f`` is a :class:`~tyrelab.tyre.wheel.WheelLoads` (force and moment
    about the wheel centre, road frame) of a wheel at ``pose``. C-axis: x
    forward in the wheel plane parallel to the ground, y the spin axis,
    z = x cross y (upward). Writes :data:`C_AXIS` into ``out`` (``out[CA.FX]``, ...).
    """
    ax, ay, az = pose.ax, pose.ay, pose.az
    ex, ey, ez, _, _, _ = wheel_axes(ax, ay, az)
    zx, zy, zz = cross(ex, ey, ez, ax, ay, az)
    fx, fy, fz = f.fx, f.fy, f.fz
    mx, my, mz = f.mx, f.my, f.mz
    out[CA.FX] = fx * ex + fy * ey + fz * ez
    out[CA.FY] = fx * ax + fy * ay + fz * az
    out[CA.FZ] = fx * zx + fy * zy + fz * zz
    out[CA.MX] = mx * ex + my * ey + mz * ez
    out[CA.MY] = mx * ax + my * ay + mz * az
    out[CA.MZ] = mx * zx + my * zy + mz * zz


#: the channels every rig writes first, in this order (see :func:`wheel_row`); a
#: rig's own channels follow (its ``CHANNELS``)
WHEEL_CHANNELS = ("RUNTIME", "DISTANCE", "FX", "FY", "FZ", "MX", "MY", "MZ", "FXW", "FYW", "FZW",
                  "X_WC", "Y_WC", "Z_WC", "VX_WC", "VY_WC", "VZ_WC", "ROTSPEED", "INCLANGL",
                  "DEFLECT", "X_CP", "Y_CP", "Z_CP", "LONGSLIP", "SLIPANGL")
N_WHEEL = len(WHEEL_CHANNELS)
#: positions of :data:`WHEEL_CHANNELS` in an output row (also those of a rig's
#: ``CHANNELS``, which begin with them)
WC = named_index("WheelChannelIndex", WHEEL_CHANNELS)


@nb.njit(cache=True)
def wheel_row(o, t, dist, pose, f, cax, y_offset=0.0):
    """Write a wheel's :data:`WHEEL_CHANNELS` into output row ``o``.

    ``f`` is the wheel's :class:`~tyrelab.tyre.wheel.WheelLoads` at ``pose``
    (``y_offset`` moves its contact point from the wheel's road frame to the
    rig's world frame: world y = road y + y_offset). The
    C-axis loads (:data:`C_AXIS`) are also left in ``cax`` for the
    rig's own channels (load cells).
    """
    c_axis_loads(pose, f, cax)
    o[WC.RUNTIME] = t
    o[WC.DISTANCE] = dist
    o[WC.FX] = cax[CA.FX]
    o[WC.FY] = cax[CA.FY]
    o[WC.FZ] = cax[CA.FZ]
    o[WC.MX] = cax[CA.MX]
    o[WC.MY] = cax[CA.MY]
    o[WC.MZ] = cax[CA.MZ]
    o[WC.FXW] = f.fxw
    o[WC.FYW] = f.fyw
    o[WC.FZW] = f.fzw
    o[WC.X_WC] = pose.cx
    o[WC.Y_WC] = pose.cy
    o[WC.Z_WC] = pose.cz
    o[WC.VX_WC] = pose.vx
    o[WC.VY_WC] = pose.vy
    o[WC.VZ_WC] = pose.vz
    o[WC.ROTSPEED] = pose.omega
    # inclination: angle of the wheel plane to the road frame's z axis, the road normal of the
    # levelled road (TYDEX: to the road plane's normal; sin g = a . e_z). Not to the contact
    # normal: a disc's lies in its own plane, so the point model's INCLANGL was always 0
    o[WC.INCLANGL] = math.asin(max(-1.0, min(1.0, pose.az)))
    o[WC.DEFLECT] = f.deflection if f.deflection > 0.0 else 0.0
    o[WC.X_CP] = f.px
    o[WC.Y_CP] = f.py + y_offset
    o[WC.Z_CP] = f.pz
    o[WC.LONGSLIP] = f.kappa
    o[WC.SLIPANGL] = f.alpha
