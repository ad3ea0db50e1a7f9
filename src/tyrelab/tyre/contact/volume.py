"""3D equivalent volume contact (thesis 2.3.2, 4.3).

The undeflected tyre is a row of discs across its width
(:func:`tyrelab.tyre.contact.shape.carcass_discs`). Each disc, in a plane
parallel to the wheel plane, is intersected with the road's section in that
plane; the intersection region (inside the disc, below the road surface)
gives three numbers per disc: its area ``A`` and its first moments about the
disc centre. From them:

* the disc's *equivalent penetration* ``d``: the depth of a flat road that
  cuts the same area from the disc (circular segment, inverted exactly);
* the disc's *push direction*: from the region's centroid to the disc centre
  (for a flat road, straight up along the wheel plane; at a step edge,
  tilted back, so the obstacle also pushes the wheel back);

and over the discs, weighted by the intersected volume ``A * width``:

* the in-plane direction of the effective normal (mean push direction);
* a weighted least-squares line of the disc's equivalent chord distance
  ``R_k - d_k`` against the disc's lateral offset, whose slope tilts the
  effective plane about the wheel's forward axis (effective road camber,
  which an oblique cleat or a banked road produces) and whose intercept is
  the distance from the wheel centre to the effective plane in the wheel
  plane: the deflection is ``R0`` minus it;
* the contact point: on the effective plane, in the wheel's radial line,
  shifted along the axis to the volume centroid.

On a flat or uniformly inclined road every contacting disc sees the same
plane, so the effective plane is the road plane and the deflection is the
one of a rigid disc (the point model's). The vertical law (eq. 2.2) then
acts along the effective normal (:func:`tyrelab.tyre.kernel.wheel_force`).

The road is bilinear on its grid; driven along a grid axis, each section is
piecewise linear between grid nodes, and each piece is intersected with the
disc's circle exactly (line-circle intersection, closed-form integrals), so
no sampling error arises and a sharp edge stays sharp. Consecutive collinear
pieces are merged, and for roads that do not vary across (2D profiles) the
breakpoints of the profile are precomputed, so a flat road costs a few
operations per disc.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ...core.vec3 import unit, wheel_axes
from ...errors import InputError
from ...road.grid import grid_height
from .point import GEO_NX, GEO_NY, GEO_NZ, GEO_PX, GEO_PY, GEO_PZ, GEO_RHO, local_zmax
from .shape import (carcass_discs, disc_intersection, profile_breaks,
                    segment_area, segment_depth)

#: cp layout: header, then (offset, radius, weight) per disc, then the profile breakpoints
CP_R0, CP_NDISC, CP_STEP, CP_BREAKS, CP_NX = range(5)
CP_HEADER = 5
#: default sampling step [m] along sections not aligned with the grid
DEFAULT_STEP = 0.005
#: options the enveloping model takes (accepted and ignored here)
_OTHER_OPTIONS = ("width_table", "n_width", "n_length")


def volume_params(tyre, grid, discs=None, step=DEFAULT_STEP, **options) -> np.ndarray:
    """Pack the disc set and the road's profile breakpoints for :func:`volume_contact`.

    Parameters
    ----------
    tyre : Tyre
        Radius, width and carcass shape (``[SHAPE]``, Table 4-1).
    grid : RoadGrid
        The road the tyre will run on.
    discs : int, optional
        Discs per half width (default: from the shape table, see
        :func:`~tyrelab.tyre.contact.shape.carcass_discs`).
    step : float
        Sampling step [m] along sections that are not aligned with a grid
        axis (a wheel heading obliquely across the grid).
    """
    unknown = set(options) - set(_OTHER_OPTIONS)
    if unknown:
        raise InputError(f"unknown volume-model option(s) {', '.join(sorted(unknown))}; "
                         "expected discs, step", field="options")
    if not (step > 0):
        raise InputError(f"sampling step must be positive, got {step}", field="step")
    offsets, radii, widths = carcass_discs(tyre, discs)
    breaks = profile_breaks(grid.z)
    n = offsets.size
    head = np.zeros(CP_HEADER)
    head[CP_R0] = tyre.unloaded_radius
    head[CP_NDISC] = n
    head[CP_STEP] = step
    head[CP_NX] = grid.z.shape[0]
    discs_packed = np.column_stack([offsets, radii, widths]).ravel()
    if breaks is None:
        return np.r_[head, discs_packed]
    head[CP_BREAKS] = CP_HEADER + 3 * n
    return np.r_[head, discs_packed, breaks]


# --- the effective plane ---------------------------------------------------------

@nb.njit(cache=True)
def plane_contact(r0, cx, cy, cz, ax, ay, az, px, py, pz, nx, ny, nz, lateral, geo):
    """Write deflection, contact point and normal of a wheel on a plane into ``geo``.

    The plane passes through (px, py, pz) with unit normal n (pointing out of
    the road). As for a rigid disc (the point model), the deflection is
    ``r0`` minus the distance, *within the wheel plane*, from the centre to
    the line where the wheel plane cuts the road plane; the contact point is
    the foot of that distance, moved ``lateral`` metres along the spin axis
    and back onto the plane.
    """
    na = nx * ax + ny * ay + nz * az
    wx, wy, wz = nx - na * ax, ny - na * ay, nz - na * az  # n projected on the wheel plane
    wn = math.sqrt(wx * wx + wy * wy + wz * wz)
    if wn < 1e-9:  # wheel lying flat on the plane
        geo[GEO_RHO] = -1.0
        return
    dist = (cx - px) * nx + (cy - py) * ny + (cz - pz) * nz
    q = dist / wn
    t = (dist + lateral * na) / wn  # distance along -n_w to the plane at the lateral offset
    geo[GEO_RHO] = r0 - q
    geo[GEO_PX] = cx + lateral * ax - t * wx / wn
    geo[GEO_PY] = cy + lateral * ay - t * wy / wn
    geo[GEO_PZ] = cz + lateral * az - t * wz / wn
    geo[GEO_NX] = nx
    geo[GEO_NY] = ny
    geo[GEO_NZ] = nz


@nb.njit(cache=True)
def no_contact(r0, cx, cy, cz, gap, geo):
    """No contact: deflection ``-gap`` (<= 0), point below the centre, normal up."""
    geo[GEO_RHO] = -gap if gap > 0.0 else 0.0
    geo[GEO_PX] = cx
    geo[GEO_PY] = cy
    geo[GEO_PZ] = cz - r0
    geo[GEO_NX] = 0.0
    geo[GEO_NY] = 0.0
    geo[GEO_NZ] = 1.0


@nb.njit(cache=True)
def volume_contact(cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
    """Deflection, contact point and effective normal of the equivalent volume model.

    Parameters as :func:`tyrelab.tyre.contact.point.point_contact`, with
    ``cp`` from :func:`volume_params`.
    """
    r0 = cp[CP_R0]
    nd = int(cp[CP_NDISC])
    fx, fy, fz, dx, dy, dz = wheel_axes(ax, ay, az)
    cosg = -dz
    if cosg < 1e-3:
        no_contact(r0, cx, cy, cz, 1.0, geo)
        return
    half_width = abs(cp[CP_HEADER + 3 * (nd - 1)])
    reach = r0 * abs(fx) + half_width * abs(ax) + 1e-9
    zmax = local_zmax(zinfo, cx - reach, cx + reach)
    if (cz - half_width * abs(az) - zmax) * cosg >= r0:
        no_contact(r0, cx, cy, cz, (cz - zmax) * cosg - r0, geo)
        return
    brk = int(cp[CP_BREAKS])
    step = cp[CP_STEP]
    flat = zinfo[1] == zinfo[0]  # one level plane everywhere (e.g. the trailer's other wheel)
    lever = (cz - grid_height(gp, z, cx, cy)) / cosg
    hx = dx * lever
    hy = dy * lever
    sw = 0.0  # sums over discs, weighted by intersected volume
    se = 0.0
    see = 0.0
    sq = 0.0
    seq = 0.0
    sus = 0.0
    suq = 0.0
    for k in range(nd):
        e = cp[CP_HEADER + 3 * k]
        r = cp[CP_HEADER + 3 * k + 1]
        width = cp[CP_HEADER + 3 * k + 2]
        zk = cz + e * az
        q_top = (zk - zmax) / cosg
        if q_top >= r:
            continue
        if flat:  # the section is a straight line at depth q_top: a circular segment
            area = segment_area(r - q_top, r)
            chord = q_top
            us_k = 0.0
            uq_k = 1.0
        else:
            half = r if q_top <= 0.0 else math.sqrt(r * r - q_top * q_top)
            area, ms, mq = disc_intersection(cp, brk, step, gp, z, r, cx + e * ax + hx,
                                             cy + e * ay + hy, zk, fx, fy, cosg, -half, half)
            mn = math.sqrt(ms * ms + mq * mq)
            if not (area > 1e-14 * r * r) or mn <= 0.0:
                continue
            us_k = ms / mn
            uq_k = mq / mn
            chord = r - segment_depth(area, r)  # centre to the equivalent flat chord
        wk = area * width
        sw += wk
        se += wk * e
        see += wk * e * e
        sq += wk * chord
        seq += wk * e * chord
        sus += wk * us_k
        suq += wk * uq_k
    if sw <= 0.0:
        no_contact(r0, cx, cy, cz, 0.0, geo)
        return
    # weighted least-squares line chord = q0 + g * e across the discs
    den = sw * see - se * se
    g = 0.0
    if den > 1e-12 * sw * sw * max(see / sw, 1e-12):
        g = (sw * seq - se * sq) / den
    q0 = (sq - g * se) / sw
    us, uq = sus, suq
    un = math.sqrt(us * us + uq * uq)
    us /= un
    uq /= un
    ux, uy, uz = us * fx + uq * dx, us * fy + uq * dy, us * fz + uq * dz  # centre -> road
    nx, ny, nz = unit(g * ax - ux, g * ay - uy, g * az - uz)
    plane_contact(r0, cx, cy, cz, ax, ay, az, cx + q0 * ux, cy + q0 * uy, cz + q0 * uz,
                  nx, ny, nz, se / sw, geo)
