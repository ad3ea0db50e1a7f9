"""3-vector helpers for compiled kernels (inlined by numba)."""

import math

import numba as nb


@nb.njit(cache=True, inline="always")
def cross(a0, a1, a2, b0, b1, b2):
    """a x b."""
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@nb.njit(cache=True, inline="always")
def dot(a0, a1, a2, b0, b1, b2):
    return a0 * b0 + a1 * b1 + a2 * b2


@nb.njit(cache=True, inline="always")
def unit(a0, a1, a2):
    """a / |a| (a zero vector stays zero)."""
    n = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
    if n == 0.0:
        return 0.0, 0.0, 0.0
    return a0 / n, a1 / n, a2 / n


@nb.njit(cache=True, inline="always")
def wheel_axes(ax, ay, az):
    """Forward and in-plane downward unit vectors of a wheel with spin axis a.

    forward = a x e_z normalised (in the wheel plane, parallel to the ground:
    the TYDEX C-axis x); down = a x forward (in the wheel plane, pointing
    from the centre towards the ground).
    """
    fx, fy, fz = unit(ay, -ax, 0.0)  # a x (0, 0, 1)
    dx, dy, dz = cross(ax, ay, az, fx, fy, fz)
    return fx, fy, fz, dx, dy, dz
