"""3D enveloping contact: Schmeitz's elliptical cams (thesis 2.3.3, 4.4).

``N_LENGTH x N_WIDTH`` cams (:mod:`tyrelab.tyre.contact.cams`, eq. 2.5) sit
on a grid over the contact patch: along the wheel's heading, equally spaced
over the base length ``ls = 2 PLS a`` (eq. 2.6), and across it over the
contact width ``2 b`` (outer cams on its edges), with the half length ``a``
(eq. 2.3) and half width ``b`` (eq. 2.4, or a ``[CONTACT_WIDTH_CURVE]``
table) taken at the deflection estimated from a single cam under the wheel
centre, but at no less than ``min_patch_deflection`` (no state is kept
between calls; see *The shortest patch* below). Each cam rests on the road
at a height ``w_ij`` (Schmeitz's basic function); a least-squares plane
through the cam heights gives

* the effective road height (the mean cam height, which is Schmeitz's
  tandem average when there are two cams), corrected for the offset of a cam
  resting on a slope so that an inclined road is its own effective plane;
* the effective forward slope (tilt along the heading: an obstacle ahead
  lifts the front cams and the normal force also pushes the wheel back);
* the effective road camber (tilt across);
* the effective road curvature (quadratic term along the heading;
  :attr:`ContactGeometry.curvature <tyrelab.tyre.wheel.ContactGeometry>`, not
  used by the vertical law).

The vertical law (eq. 2.2) acts along the effective plane's normal; the
deflection is measured to the effective plane as for a rigid disc
(:func:`tyrelab.tyre.contact.volume.plane_contact`).

Because every cam envelops the road over about its own length, the
effective height rises over about the contact length when the tyre meets a
step (lengthening) and a short cleat lifts it less than it lifts a rigid disc
(swallowing).

*The shortest patch.* The one-cam estimate falls to zero while the tyre still
rests, loaded, on an obstacle off its centre (riding onto or off a cleat, the
wheel's bottom above the cam under its centre). Sized at zero, the cams met at
the centre, their plane took one cam's slope through the corner it rests on
(a rigid disc sinks deeper into that plane than into the corner), and at zero,
with no slope, fell to that cam's height: the load was lost in one step. The
patch is therefore sized at no less than ``min_patch_deflection`` (default
:data:`MIN_PATCH_DEFLECTION` R0: 10 mm on the XZL, a quarter of its static
deflection at the lightest thesis load), so the cams stay apart and the plane
is as continuous in the wheel's position as every cam height is.

*Cam layouts.* ``cam_layout="outline"`` lets only the cams on the patch's outline
make the plane, as the thesis describes its ADAMS implementation: the contact model
``enveloping-edge`` (:mod:`.enveloping_edge`, where the reasons are written down).

Property-file keys, ``[CONTACT_PATCH]`` (ADAMS PAC2002 names first, then the
MF-Swift names that mean the same thing on these cams):

=============  ================  ===========================================
ADAMS          MF-Swift          meaning here
=============  ================  ===========================================
PA1, PA2       Q_RA1, Q_RA2      half length: eq. 2.3, or ``R0 (Q_RA2 x + Q_RA1 sqrt x)``
PB1-PB3        Q_RB1, Q_RB2      half width: eq. 2.4, or ``W (Q_RB2 x + Q_RB1 x^(1/3))``
PAE            ELLIPS_LENGTH     cam half length / R0
PBE            ELLIPS_HEIGHT     cam half height / R0
PCE            ELLIPS_ORDER      cam exponent
PLS            ELLIPS_SHIFT      base length factor, ``ls = 2 PLS a``
N_WIDTH        ELLIPS_NWIDTH     cams across the width
N_LENGTH       ELLIPS_NLENGTH    cams along the length
--             ELLIPS_MAX_STEP   [m] a cam sees road only where its contour
                                 is within this height of its bottom
=============  ================  ===========================================

(x = deflection / R0.) The half width is clipped to half the tyre width: the
thesis's PB fit (0.0017, 16006.5, -77819.1) gives about 1.9 m for the XZL
(section 4.4 found the formula unfit), so with it the cams span the tread.

:func:`effective_road` tabulates the effective road (height, slope, camber,
curvature) and the patch size at wheel positions; :func:`enveloping_geometry`
the contact geometry.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from ...core.vec3 import unit, wheel_axes
from ...errors import InputError
from ...road.terrain import terrain_range, terrain_zmax
from ..model import PO, TyreModel, contact_geometry_table, positions_table, wheel_positions
from ..registry import ContactModel, register_contact
from ..wheel import ContactGeometry, WheelPose
from .cams import cam_tables
from .patch_laws import half_length, half_width, length_law, patch_key, warn_assumed_patch, width_law
from .enveloping_params import (_DATA, _OTHER_OPTIONS, _USER_OPTIONS, BLOCK, CAM_LAYOUTS, FIT_STEPS,
                                cam_option_values, check_width, swift_coefficients,
                                MIN_PATCH_DEFLECTION, EnvelopingParams)
from .enveloping_plane import cam_plane
from .volume import DEFAULT_STEP, no_contact, plane_contact


class EffectiveRoad(NamedTuple):
    """The effective road the cams give under a wheel (:func:`effective_road`).

    ``height`` [m] of the effective plane at the patch centre (the wheel
    plane's trace below the centre: at the centre's x, y for an upright
    wheel), ``slope`` its rise per metre along the heading, ``camber`` its rise
    per metre across (to the wheel's left), ``curvature`` [1/m] of the
    quadratic fit along the heading; ``deflection`` [m] to the effective plane
    (the contact's; <= 0: no contact); ``half_length`` and ``half_width`` [m] of the contact patch the
    cams were spread over (sized at the deflection of the one cam under the
    centre, at least ``min_patch_deflection``).
    """

    height: float
    slope: float
    camber: float
    curvature: float
    deflection: float
    half_length: float
    half_width: float


def enveloping_params(tyre, grid, width_table=None, n_width=None, n_length=None,
                      step=DEFAULT_STEP, min_patch_deflection=None, cam_layout="grid",
                      **options) -> EnvelopingParams:
    """The enveloping model's record: contact-patch laws, cam tables, the road's block maxima.

    Parameters
    ----------
    tyre : Tyre
        ``[CONTACT_PATCH]`` keys as in the module docstring.
    grid : RoadGrid
        The ground (:class:`~tyrelab.road.terrain.Ground`): its block bounds per row
        and whether it varies across are kept in the record.
    width_table : bool, optional
        True: use the ``[CONTACT_WIDTH_CURVE]`` table (error if absent);
        False: use the formula; None (default): the table when present.
    n_width, n_length : int, optional
        Override the number of cams.
    step : float
        Sampling step [m] along cam rows that do not run along x.
    min_patch_deflection : float, optional
        The patch is sized at no less than this deflection [m] (default
        :data:`MIN_PATCH_DEFLECTION` R0; 0 lets it shrink to a point, see the
        module docstring).
    cam_layout : {"grid", "outline"}
        Which cams make the effective plane: every cam of the grid (default), or
        only those on the patch's outline, as the thesis describes its ADAMS model
        (the contact model ``enveloping-edge``, :mod:`.enveloping_edge`).
    """
    unknown = set(options) - set(_OTHER_OPTIONS)
    if unknown:
        raise InputError(f"unknown enveloping-model option(s) {', '.join(sorted(unknown))}; "
                         "expected width_table, n_width, n_length, step, min_patch_deflection, "
                         "cam_layout", field="options")
    if cam_layout not in CAM_LAYOUTS:
        raise InputError(f"cam_layout must be one of {', '.join(CAM_LAYOUTS)}, got '{cam_layout}'",
                         field="cam_layout")
    tir = tyre.tir
    warn_assumed_patch(tir, [k for k, v in (("n_width", n_width), ("n_length", n_length)) if v is not None])
    r0, w0 = float(check_width(tyre).unloaded_radius), float(tyre.width)
    bounded = cam_option_values({"n_width": n_width, "n_length": n_length, "step": step,
                                 "min_patch_deflection": min_patch_deflection})
    n_width, n_length = bounded.get("n_width"), bounded.get("n_length")
    step = bounded.get("step", DEFAULT_STEP)
    rho_min = bounded.get("min_patch_deflection", MIN_PATCH_DEFLECTION * r0)
    b_max = 0.5 * w0
    lmode, (a1, a2) = length_law(tir)
    wmode, (b1, b2, b3), wtable = width_law(tir, width_table, b_max)
    ae, be, ce = (patch_key(tir, k) * f for k, f in (("PAE", r0), ("PBE", r0), ("PCE", 1.0)))
    pls = patch_key(tir, "PLS")
    nw = int(n_width if n_width is not None else patch_key(tir, "N_WIDTH"))
    nl = int(n_length if n_length is not None else patch_key(tir, "N_LENGTH"))
    if not (ae > 0 and be > 0 and ce >= 1.0 and pls >= 0 and nw >= 1 and nl >= 1):
        raise InputError("cams need PAE, PBE > 0, PCE >= 1, PLS >= 0 and at least one cam "
                         f"each way (got {ae / r0:g}, {be / r0:g}, {ce:g}, {pls:g}, {nw}, {nl})",
                         source=tir.source, field="CONTACT_PATCH")
    cap = ae
    if tir.has("CONTACT_PATCH", "ELLIPS_MAX_STEP"):
        rise = tir.number("CONTACT_PATCH", "ELLIPS_MAX_STEP")
        if rise < be:  # where the contour has risen ELLIPS_MAX_STEP
            cap = ae * (1.0 - (1.0 - rise / be) ** ce) ** (1.0 / ce)
    drop, window, touch = cam_tables(ae, be, ce)
    if wtable is None:
        wtable = np.zeros((0, 2))
    wtable = np.ascontiguousarray(wtable, np.float64)
    per, maxima = grid.row_maxima(BLOCK)  # the ground's bounds per block and row
    return EnvelopingParams(
        unloaded_radius=r0, width=w0, min_patch_deflection=rho_min, length_law=int(lmode),
        length_c1=float(a1), length_c2=float(a2), width_law=int(wmode), width_c1=float(b1),
        width_c2=float(b2), width_c3=float(b3), max_half_width=float(b_max), cam_half_length=float(ae),
        cam_half_height=float(be), cam_exponent=float(ce), base_length_factor=float(pls),
        n_width=nw, n_length=nl, cam_reach=float(cap), step=float(step),
        # a 2D road: every row of cams sees the same road
        profile_road=grid.uniform_across(),
        cam_drop=drop, cam_window=window, cam_touch=touch, width_table=wtable,
        block_per=per, row_block_max=maxima, outline_only=cam_layout == "outline",
        **dict(zip(("swift_c1", "swift_c2"), swift_coefficients(tyre))))


def contact_patch(params: EnvelopingParams, deflection: float):
    """``(a, b)`` half length and half width [m] by the patch laws at ``deflection`` [m] (the
    model sizes its patch at no less than ``params.min_patch_deflection``)."""
    return half_length(params, float(deflection)), half_width(params, float(deflection))


@nb.njit(cache=True, inline="always")
def enveloping_contact(params, road, pose):
    """Deflection, contact point and effective-plane normal from the cams.

    ``params`` an :class:`EnvelopingParams`, ``road`` a terrain record, ``pose`` a
    WheelPose (only its centre and spin axis are used). Returns a
    :class:`ContactGeometry` as :func:`tyrelab.tyre.contact.point.point_contact`,
    on the cams' effective plane, with the effective road curvature [1/m].
    """
    r0 = params.unloaded_radius
    cx, cy, cz = pose.cx, pose.cy, pose.cz
    ax, ay, az = pose.ax, pose.ay, pose.az
    fx, fy, fz, dx, dy, dz = wheel_axes(ax, ay, az)
    cosg = -dz
    if cosg < 1e-3:
        return no_contact(r0, cx, cy, cz, 1.0)
    reach = (r0 + params.cam_half_length) * abs(fx) + params.max_half_width * abs(fy) + 1e-9
    zmax = terrain_zmax(road, cx - reach, cx + reach)
    if (cz - zmax) * cosg >= r0:
        return no_contact(r0, cx, cy, cz, (cz - zmax) * cosg - r0)
    zlo, zhi = terrain_range(road)
    if zhi == zlo:  # one level plane everywhere
        return plane_contact(r0, cx, cy, cz, ax, ay, az, cx, cy, zlo, 0.0, 0.0, 1.0, 0.0)
    px, py, w0, su, sv, curvature, _, _ = cam_plane(params, road, cx, cy, cz, fx, fy, dx, dy,
                                                    cosg, zmax)
    lx, ly = -fy, fx
    nx, ny, nz = unit(-(su * fx + sv * lx), -(su * fy + sv * ly), 1.0)
    g = plane_contact(r0, cx, cy, cz, ax, ay, az, px, py, w0, nx, ny, nz, 0.0)
    return ContactGeometry(g.deflection, g.px, g.py, g.pz, g.nx, g.ny, g.nz, curvature)


@nb.njit(cache=True)
def effective_road_at(params, road, pose):
    """:class:`EffectiveRoad` under a wheel at ``pose`` (compiled; see :func:`effective_road`).

    The plane is the one :func:`enveloping_contact` uses. It is found also
    when the tyre does not touch the road: the patch then has its size at
    ``params.min_patch_deflection``; on a road level everywhere it is that
    level. A wheel lying (nearly) flat has none: NaN.
    """
    deflection = enveloping_contact(params, road, pose).deflection
    r0 = params.unloaded_radius
    cx, cy, cz = pose.cx, pose.cy, pose.cz
    fx, fy, fz, dx, dy, dz = wheel_axes(pose.ax, pose.ay, pose.az)
    cosg = -dz
    if cosg < 1e-3:
        return EffectiveRoad(math.nan, math.nan, math.nan, math.nan, deflection, 0.0, 0.0)
    zlo, zhi = terrain_range(road)
    if zhi == zlo:
        rho0 = max(r0 - (cz - zlo) / cosg, params.min_patch_deflection)
        return EffectiveRoad(zlo, 0.0, 0.0, 0.0, deflection, half_length(params, rho0),
                             half_width(params, rho0))
    reach = (r0 + params.cam_half_length) * abs(fx) + params.max_half_width * abs(fy) + 1e-9
    zmax = terrain_zmax(road, cx - reach, cx + reach)
    _, _, w0, su, sv, curvature, a, b = cam_plane(params, road, cx, cy, cz, fx, fy, dx, dy,
                                                  cosg, zmax)
    return EffectiveRoad(w0, su, sv, curvature, deflection, a, b)


#: number of fields of an :class:`EffectiveRoad`
N_EFFECTIVE = len(EffectiveRoad._fields)


@nb.njit(cache=True)
def _effective_many(params, road, poses, out):
    for k in range(poses.shape[0]):  # rows of wheel_positions: centre and spin axis (PO)
        p = poses[k]
        e = effective_road_at(params, road, WheelPose(p[PO.CX], p[PO.CY], p[PO.CZ], p[PO.AX],
                                                      p[PO.AY], p[PO.AZ], 0.0, 0.0, 0.0, 0.0))
        for j in range(N_EFFECTIVE):
            out[k, j] = e[j]


def effective_road(tyre, road, x, y=0.0, z=None, axis=(0.0, 1.0, 0.0), **options):
    """The effective road of the enveloping model under wheel centres ``(x, y, z)``.

    The least-squares plane through the heights of the cams (eq. 2.5) spread over
    the contact patch (eqs. 2.3, 2.4, 2.6), which the vertical law (eq. 2.2) acts
    on: :func:`effective_road_at` runs the contact model's own code, so the values
    are exact, not recovered from the contact normal.

    Parameters
    ----------
    tyre : Tyre
        ``[CONTACT_PATCH]`` keys as in the module docstring.
    road, x, y, z, axis
        As :func:`tyrelab.tyre.model.contact_geometry_table`: road name, road or
        grid; wheel centres [m] (broadcast; ``z`` by default the unloaded radius
        above the road below the centre); unit spin axis (default heading +x).
    **options
        Options of :func:`enveloping_params` (``n_width``, ``n_length``,
        ``width_table``, ``step``, ``min_patch_deflection``).

    Returns
    -------
    pandas.DataFrame
        One row per position: ``x, y, z`` and the :class:`EffectiveRoad` fields
        (``height``, ``slope``, ``camber``, ``curvature``, ``deflection``,
        ``half_length``, ``half_width``).
    """
    grid, poses = wheel_positions(road, x, y, z, axis, tyre.unloaded_radius)
    out = np.empty((poses.shape[0], N_EFFECTIVE))
    _effective_many(enveloping_params(tyre, grid, **options), grid.surface(), poses, out)
    return positions_table(poses, out, EffectiveRoad._fields)


def enveloping_geometry(tyre, road, x, y=0.0, z=None, axis=(0.0, 1.0, 0.0), **options):
    """Deflection, contact point, normal and curvature of the enveloping model at wheel
    centres ``(x, y, z)``.

    See :func:`tyrelab.tyre.model.contact_geometry_table` for the arguments
    and the returned table; ``options`` are those of :func:`enveloping_params`.
    """
    return contact_geometry_table(TyreModel(tyre, "enveloping", options=dict(options)), road,
                                  x, y, z, axis)


register_contact(ContactModel("enveloping", EnvelopingParams, enveloping_params,
                              geometry=enveloping_contact,
                              summary="3D enveloping contact (tandem elliptical cams), "
                                      "thesis 2.3.3",
                              options={**_USER_OPTIONS, "cam_layout": str}, cost=0.022,
                              parameterization=_DATA, fit_steps=FIT_STEPS, terrains=("rigid", "soil"),
                              check_values=cam_option_values, check_tyre=check_width))

