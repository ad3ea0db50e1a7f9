"""From road-frame forces to the TYDEX C-axis system of a wheel (compiled)."""

import math

import numba as nb

from ..core.vec3 import cross, wheel_axes


@nb.njit(cache=True)
def c_axis_loads(pose, f, out):
    """Forces and moments of the road on the tyre at the wheel centre, C-axis.

    ``f`` is a :class:`~tyrelab.tyre.wheel.WheelLoads` (force and moment
    about the wheel centre, road frame) of a wheel at ``pose``. C-axis: x
    forward in the wheel plane parallel to the ground, y the spin axis,
    z = x cross y (upward). Writes FX, FY, FZ, MX, MY, MZ into ``out[0:6]``.
    """
    ax, ay, az = pose.ax, pose.ay, pose.az
    ex, ey, ez, _, _, _ = wheel_axes(ax, ay, az)
    zx, zy, zz = cross(ex, ey, ez, ax, ay, az)
    fx, fy, fz = f.fx, f.fy, f.fz
    mx, my, mz = f.mx, f.my, f.mz
    out[0] = fx * ex + fy * ey + fz * ez
    out[1] = fx * ax + fy * ay + fz * az
    out[2] = fx * zx + fy * zy + fz * zz
    out[3] = mx * ex + my * ey + mz * ez
    out[4] = mx * ax + my * ay + mz * az
    out[5] = mx * zx + my * zy + mz * zz


#: the channels every rig writes first, in this order (see :func:`wheel_row`)
WHEEL_CHANNELS = ("RUNTIME", "DISTANCE", "FX", "FY", "FZ", "MX", "MY", "MZ", "FXW", "FYW", "FZW",
                  "X_WC", "Y_WC", "Z_WC", "VX_WC", "VY_WC", "VZ_WC", "ROTSPEED", "INCLANGL",
                  "DEFLECT", "X_CP", "Y_CP", "Z_CP", "LONGSLIP", "SLIPANGL")
N_WHEEL = len(WHEEL_CHANNELS)


@nb.njit(cache=True)
def wheel_row(o, t, dist, pose, f, cax, y_offset=0.0):
    """Write a wheel's :data:`WHEEL_CHANNELS` into output row ``o``.

    ``f`` is the wheel's :class:`~tyrelab.tyre.wheel.WheelLoads` at ``pose``
    (``y_offset`` moves its contact point from the wheel's road frame to the
    rig's world frame: world y = road y + y_offset). The
    C-axis loads (FX, FY, FZ, MX, MY, MZ) are also left in ``cax`` for the
    rig's own channels (load cells).
    """
    c_axis_loads(pose, f, cax)
    o[0] = t
    o[1] = dist
    for k in range(6):
        o[2 + k] = cax[k]
    o[8] = f.fxw
    o[9] = f.fyw
    o[10] = f.fzw
    o[11] = pose.cx
    o[12] = pose.cy
    o[13] = pose.cz
    o[14] = pose.vx
    o[15] = pose.vy
    o[16] = pose.vz
    o[17] = pose.omega
    # inclination: angle of the wheel plane to the road normal (TYDEX, sin g = a . n)
    o[18] = math.asin(max(-1.0, min(1.0, pose.ax * f.nx + pose.ay * f.ny + pose.az * f.nz)))
    o[19] = f.deflection if f.deflection > 0.0 else 0.0
    o[20] = f.px
    o[21] = f.py + y_offset
    o[22] = f.pz
    o[23] = f.kappa
    o[24] = f.alpha
