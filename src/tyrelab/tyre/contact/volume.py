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
acts along the effective normal (:func:`tyrelab.tyre.wheel.analytic_wheel_step`).

The model reads the ground through the terrain interface only
(:mod:`tyrelab.road.terrain`). Driven along x, each section is piecewise
linear between the ground's break lines (the grid's x nodes), and each piece
is intersected with the disc's circle exactly (line-circle intersection,
closed-form integrals), so no sampling error arises and a sharp edge stays
sharp. Consecutive collinear pieces are merged, and for grounds that do not
vary across (2D profiles) the breakpoints of the profile are precomputed
(:meth:`~tyrelab.road.terrain.Ground.profile_breaks`), so a flat road costs
a few operations per disc.
"""

from __future__ import annotations

import math
from functools import partial
from typing import NamedTuple

import numba as nb
import numpy as np

from ...core.vec3 import unit, wheel_axes
from ...errors import InputError
from ...limits import MAX_DISCS, SAMPLING_STEP, Bound, bounded_options
from ...road.terrain import terrain_height, terrain_range, terrain_zmax
from ..model import TyreModel, contact_geometry_table
from ..params import Tyre
from ..registry import ContactModel, register_contact
from ..wheel import ContactGeometry
from .shape import carcass_discs, disc_intersection, segment_area, segment_depth

#: what needs the tyre's width, as a refusal names it (:meth:`~tyrelab.tyre.params.Tyre.require_width`)
WHAT = "the volume model"
#: default sampling step [m] along sections not aligned with the grid
DEFAULT_STEP = 0.005
#: options the enveloping model takes (accepted and ignored here)
_OTHER_OPTIONS = ("width_table", "n_width", "n_length")


class VolumeParams(NamedTuple):
    """Parameters of the equivalent volume model.

    ``unloaded_radius`` R0 [m]; ``step`` [m] the sampling step along road
    sections not aligned with the grid; ``disc_offsets``, ``disc_radii``,
    ``disc_widths`` [m] the discs across the tyre
    (:func:`~tyrelab.tyre.contact.shape.carcass_discs`: centres along the
    spin axis from the wheel plane, symmetric and increasing, their radii and
    widths); ``profile_breaks`` (int) for a ground that does not vary across,
    the next kink's break line for every break line
    (:meth:`~tyrelab.road.terrain.Ground.profile_breaks`), empty when the
    ground varies across.
    """

    unloaded_radius: float
    step: float
    disc_offsets: np.ndarray
    disc_radii: np.ndarray
    disc_widths: np.ndarray
    profile_breaks: np.ndarray


#: the bounded options of the volume model: ``discs`` per half width, the sampling ``step``
VOLUME_BOUNDS = {"discs": Bound("discs per half width", 1, MAX_DISCS, whole=True), "step": SAMPLING_STEP}
#: the volume model's option values, checked (``ContactModel.check_values``)
volume_option_values = partial(bounded_options, bounds=VOLUME_BOUNDS)


def volume_params(tyre, grid, discs=None, step=DEFAULT_STEP, **options) -> VolumeParams:
    """The volume model's record: the disc set and the road's profile breakpoints.

    Parameters
    ----------
    tyre : Tyre
        Radius, width and carcass shape (``[SHAPE]``, Table 4-1).
    grid : RoadGrid
        The ground the tyre will run on (:class:`~tyrelab.road.terrain.Ground`).
    discs : int, optional
        Discs per half width (default: from the shape table, see
        :func:`~tyrelab.tyre.contact.shape.carcass_discs`).
    step : float
        Sampling step [m] along sections that are not aligned with a grid
        axis (a wheel heading obliquely across the grid).
    **options
        The enveloping model's options (``width_table``, ``n_width``,
        ``n_length``) are accepted and ignored; any other is an error.

    Returns
    -------
    VolumeParams
    """
    unknown = set(options) - set(_OTHER_OPTIONS)
    if unknown:
        raise InputError(f"unknown volume-model option(s) {', '.join(sorted(unknown))}; "
                         "expected discs, step", field="options")
    step = volume_option_values({"step": step})["step"]
    tyre.require_width(WHAT)
    offsets, radii, widths = carcass_discs(tyre, discs)
    breaks = grid.profile_breaks()
    if breaks is None:
        breaks = np.zeros(0, np.int64)

    def floats(a):
        return np.ascontiguousarray(a, dtype=np.float64)

    return VolumeParams(float(tyre.unloaded_radius), float(step), floats(offsets), floats(radii),
                        floats(widths), np.ascontiguousarray(breaks, dtype=np.int64))


# --- the effective plane ---------------------------------------------------------

@nb.njit(cache=True)
def plane_contact(r0, cx, cy, cz, ax, ay, az, px, py, pz, nx, ny, nz, lateral):
    """:class:`ContactGeometry` of a wheel on a plane.

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
    if wn < 1e-9:  # wheel lying flat on the plane: no contact the laws describe
        return ContactGeometry(-1.0, cx, cy, cz - r0, 0.0, 0.0, 1.0, 0.0)
    dist = (cx - px) * nx + (cy - py) * ny + (cz - pz) * nz
    q = dist / wn
    t = (dist + lateral * na) / wn  # distance along -n_w to the plane at the lateral offset
    return ContactGeometry(r0 - q, cx + lateral * ax - t * wx / wn,
                           cy + lateral * ay - t * wy / wn, cz + lateral * az - t * wz / wn,
                           nx, ny, nz, 0.0)


@nb.njit(cache=True)
def no_contact(r0, cx, cy, cz, gap):
    """No contact: deflection ``-gap`` (<= 0), point below the centre, normal up."""
    return ContactGeometry(-gap if gap > 0.0 else 0.0, cx, cy, cz - r0, 0.0, 0.0, 1.0, 0.0)


@nb.njit(cache=True)
def volume_contact(params, road, pose):
    """Deflection, contact point and effective normal of the equivalent volume model.

    Parameters
    ----------
    params : VolumeParams
    road : a terrain record (:mod:`tyrelab.road.terrain`)
    pose : WheelPose
        Only the centre and the spin axis are used.

    Returns
    -------
    ContactGeometry
        Deflection ``R0`` minus the distance from the centre to the
        effective plane in the wheel plane (<= 0: no contact), the contact
        point on the effective plane at the volume centroid's lateral
        offset, the effective plane's unit normal; curvature 0.
    """
    r0 = params.unloaded_radius
    offsets = params.disc_offsets
    radii = params.disc_radii
    widths = params.disc_widths
    nd = offsets.shape[0]
    cx, cy, cz = pose.cx, pose.cy, pose.cz
    ax, ay, az = pose.ax, pose.ay, pose.az
    fx, fy, fz, dx, dy, dz = wheel_axes(ax, ay, az)
    cosg = -dz
    if cosg < 1e-3:
        return no_contact(r0, cx, cy, cz, 1.0)
    half_width = abs(offsets[nd - 1])
    reach = r0 * abs(fx) + half_width * abs(ax) + 1e-9
    zmax = terrain_zmax(road, cx - reach, cx + reach)
    if (cz - half_width * abs(az) - zmax) * cosg >= r0:
        return no_contact(r0, cx, cy, cz, (cz - zmax) * cosg - r0)
    breaks = params.profile_breaks
    step = params.step
    zlo, zhi = terrain_range(road)
    flat = zhi == zlo  # one level plane everywhere (e.g. the trailer's other wheel)
    lever = (cz - terrain_height(road, cx, cy)) / cosg
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
        e = offsets[k]
        r = radii[k]
        width = widths[k]
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
            area, ms, mq = disc_intersection(road, breaks, step, r, cx + e * ax + hx,
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
        return no_contact(r0, cx, cy, cz, 0.0)
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
    return plane_contact(r0, cx, cy, cz, ax, ay, az, cx + q0 * ux, cy + q0 * uy, cz + q0 * uz,
                         nx, ny, nz, se / sw)


def volume_geometry(tyre, road, x, y=0.0, z=None, axis=(0.0, 1.0, 0.0), discs=None):
    """Contact geometry of the 3D equivalent volume model (thesis 2.3.2, 4.3).

    The tyre is a row of discs across its width (its ``[SHAPE]`` carcass
    table); each disc is intersected with the road's section in its plane,
    and the discs' intersected areas, weighted by their widths, give an
    effective road plane: the deflection is ``R0`` minus the distance from
    the wheel centre to that plane in the wheel plane, the normal is the
    plane's (tilted back at a step edge, sideways on an oblique cleat or a
    banked road), the contact point lies on it at the intersected volume's
    centroid across the width.

    Parameters
    ----------
    tyre : Tyre
        Radius, width and carcass shape (from a ``.tir`` or
        :func:`tyrelab.tyre.library.load_tyre`).
    road : str, Road or RoadGrid
        A road name (:func:`tyrelab.road.spec.road_from_spec`), road or grid.
    x, y : array_like
        Wheel-centre positions [m] (broadcast).
    z : array_like, optional
        Wheel-centre heights [m]; default: the unloaded radius above the
        road straight below the centre.
    axis : 3 floats
        Unit spin axis (default level, heading +x).
    discs : int, optional
        Discs per half width (default: from the shape table, see
        :func:`~tyrelab.tyre.contact.shape.carcass_discs`).

    Returns
    -------
    pandas.DataFrame
        One row per position: ``x, y, z`` and the
        :class:`~tyrelab.tyre.wheel.ContactGeometry` fields: ``deflection``
        [m] (<= 0: no contact), ``px, py, pz`` the contact point [m], ``nx,
        ny, nz`` the effective plane's unit normal, ``curvature`` (0 for
        this model).

    See Also
    --------
    tyrelab.tyre.model.contact_geometry_table
    tyrelab.tyre.contact.point.point_geometry
    """
    options = {} if discs is None else {"discs": discs}
    return contact_geometry_table(TyreModel(tyre, "volume", options=options), road, x, y, z, axis)


register_contact(ContactModel("volume", VolumeParams, volume_params, geometry=volume_contact,
                              summary="3D equivalent volume contact, thesis 2.3.2",
                              options={"discs": int, "step": float}, cost=0.017,
                              check_values=volume_option_values,
                              check_tyre=partial(Tyre.require_width, what=WHAT),
                              parameterization="load-deflection curve + carcass cross-section shape",
                              terrains=("rigid", "soil"), fit_steps=("vertical", "damping", "shape")))
