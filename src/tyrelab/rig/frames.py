"""From road-frame forces to the TYDEX C-axis system of a wheel (compiled)."""

import math

import numba as nb

from ..core.vec3 import cross, wheel_axes


@nb.njit(cache=True)
def c_axis_loads(cx, cy, cz, ax, ay, az, f, out):
    """Forces and moments of the road on the tyre at the wheel centre, C-axis.

    ``f`` is the :func:`tyrelab.tyre.kernel.wheel_force` output (force and
    moment about the wheel centre, road frame). C-axis: x forward in the
    wheel plane parallel to the ground, y the spin axis, z = x cross y
    (upward). Writes FX, FY, FZ, MX, MY, MZ into ``out[0:6]``.
    """
    ex, ey, ez, _, _, _ = wheel_axes(ax, ay, az)
    zx, zy, zz = cross(ex, ey, ez, ax, ay, az)
    fx, fy, fz = f[0], f[1], f[2]
    mx, my, mz = f[14], f[15], f[16]
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
def wheel_row(o, t, dist, cx, cy, cz, vx, vy, vz, omega, ax, ay, az, f, cax):
    """Write a wheel's :data:`WHEEL_CHANNELS` into output row ``o``.

    ``f`` is the :func:`tyrelab.tyre.kernel.wheel_force` output. The C-axis
    loads (FX, FY, FZ, MX, MY, MZ) are also left in ``cax`` for the rig's own
    channels (load cells).
    """
    c_axis_loads(cx, cy, cz, ax, ay, az, f, cax)
    o[0] = t
    o[1] = dist
    for k in range(6):
        o[2 + k] = cax[k]
    o[8] = f[11]
    o[9] = f[12]
    o[10] = f[13]
    o[11] = cx
    o[12] = cy
    o[13] = cz
    o[14] = vx
    o[15] = vy
    o[16] = vz
    o[17] = omega
    # inclination: angle of the wheel plane to the road normal (TYDEX, sin g = a . n)
    o[18] = math.asin(max(-1.0, min(1.0, ax * f[6] + ay * f[7] + az * f[8])))
    o[19] = f[9] if f[9] > 0.0 else 0.0
    o[20] = f[3]
    o[21] = f[4]
    o[22] = f[5]
    o[23] = f[17]
    o[24] = f[18]
