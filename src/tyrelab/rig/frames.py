"""From road-frame forces to the TYDEX C-axis system of a wheel (compiled)."""

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
