"""3D enveloping contact: Schmeitz's elliptical cams (thesis 2.3.3, 4.4).

``N_LENGTH x N_WIDTH`` cams (:mod:`tyrelab.tyre.contact.cams`, eq. 2.5) sit
on a grid over the contact patch: along the wheel's heading, equally spaced
over the base length ``ls = 2 PLS a`` (eq. 2.6), and across it over the
contact width ``2 b`` (outer cams on its edges), with the half length ``a``
(eq. 2.3) and half width ``b`` (eq. 2.4, or a ``[CONTACT_WIDTH_CURVE]``
table) taken at the deflection estimated from a single cam under the wheel
centre (no state is kept between calls). Each cam rests on the road at a
height ``w_ij`` (Schmeitz's basic function); a least-squares plane through
the cam heights gives

* the effective road height (the mean cam height, which is Schmeitz's
  tandem average when there are two cams), corrected for the offset of a cam
  resting on a slope so that an inclined road is its own effective plane;
* the effective forward slope (tilt along the heading: an obstacle ahead
  lifts the front cams and the normal force also pushes the wheel back);
* the effective road camber (tilt across);
* the effective road curvature (quadratic term along the heading; written to
  ``geo[7]``, not used by the vertical law).

The vertical law (eq. 2.2) acts along the effective plane's normal; the
deflection is measured to the effective plane as for a rigid disc
(:func:`tyrelab.tyre.contact.volume.plane_contact`).

Because every cam envelops the road over about its own length, the
effective height rises over about the contact length when the tyre meets a
step (lengthening) and a short cleat lifts it less than it lifts a rigid disc
(swallowing).

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
"""

from __future__ import annotations


import numba as nb
import numpy as np

from ...core.vec3 import unit, wheel_axes
from ...errors import InputError
from ...road.grid import grid_height
from .cams import (TABLE_POINTS, block_maxima, cam_height, cam_row, cam_tables, grid_row,
                   half_length, half_width, row_block_max, slope_support)
from .point import local_zmax
from .volume import DEFAULT_STEP, no_contact, plane_contact

(R0, W0, LMODE, A1, A2, WMODE, B1, B2, B3, AE, BE, CE, PLS, NW, NL, CAP, STEP, YINV,
 TN, TOFF, WOFF, WROWS, BMAX, CM, PER) = range(25)
HEADER = 25
#: length of the road blocks whose maxima let cams skip road they cannot touch [m]
BLOCK = 0.05
#: values used when the property file has neither the ADAMS nor the MF-Swift key
DEFAULTS = {"PA1": 0.15, "PA2": 7.06, "PAE": 0.72, "PBE": 1.0, "PCE": 2.0, "PLS": 0.9,
            "N_WIDTH": 10, "N_LENGTH": 15}
#: ADAMS key -> MF-Swift key for the same cam quantity
SWIFT = {"PAE": "ELLIPS_LENGTH", "PBE": "ELLIPS_HEIGHT", "PCE": "ELLIPS_ORDER",
         "PLS": "ELLIPS_SHIFT", "N_WIDTH": "ELLIPS_NWIDTH", "N_LENGTH": "ELLIPS_NLENGTH"}
_OTHER_OPTIONS = ("discs",)


def _key(tir, name):
    """The ADAMS key, else its MF-Swift twin, else the default."""
    for k in (name, SWIFT.get(name)):
        if k is not None and tir.has("CONTACT_PATCH", k):
            return tir.number("CONTACT_PATCH", k)
    return DEFAULTS[name]


def _length_law(tir):
    if tir.has("CONTACT_PATCH", "PA1") or tir.has("CONTACT_PATCH", "PA2"):
        return 0, (tir.number("CONTACT_PATCH", "PA1", DEFAULTS["PA1"]),
                   tir.number("CONTACT_PATCH", "PA2", DEFAULTS["PA2"]))
    if tir.has("CONTACT_PATCH", "Q_RA1") or tir.has("CONTACT_PATCH", "Q_RA2"):
        return 1, (tir.number("CONTACT_PATCH", "Q_RA1", 0.0), tir.number("CONTACT_PATCH", "Q_RA2", 0.0))
    return 0, (DEFAULTS["PA1"], DEFAULTS["PA2"])


def _width_law(tir, width_table, b_max):
    """(mode, (c1, c2, c3), table rows) of the half-width law."""
    table = tir.table("CONTACT_WIDTH_CURVE")
    if width_table and table is None:
        raise InputError("width_table=True needs a [CONTACT_WIDTH_CURVE] table (deflection, "
                         "half width)", source=tir.source, field="CONTACT_WIDTH_CURVE")
    if table is not None and width_table is not False:
        if table.shape[1] != 2 or np.any(np.diff(table[:, 0]) <= 0) or np.any(table[:, 1] < 0):
            raise InputError("[CONTACT_WIDTH_CURVE] needs rows of increasing deflection and "
                             "non-negative half width", source=tir.source, field="CONTACT_WIDTH_CURVE")
        return 2, (0.0, 0.0, 0.0), table
    if tir.has("CONTACT_PATCH", "PB1"):
        return 0, tuple(tir.number("CONTACT_PATCH", k, 0.0) for k in ("PB1", "PB2", "PB3")), None
    if tir.has("CONTACT_PATCH", "Q_RB1") or tir.has("CONTACT_PATCH", "Q_RB2"):
        return 1, (tir.number("CONTACT_PATCH", "Q_RB1", 0.0),
                   tir.number("CONTACT_PATCH", "Q_RB2", 0.0), 0.0), None
    return 2, (0.0, 0.0, 0.0), np.array([[0.0, b_max]])  # no law: the whole tread


def enveloping_params(tyre, grid, width_table=None, n_width=None, n_length=None,
                      step=DEFAULT_STEP, **options) -> np.ndarray:
    """Pack the contact-patch laws, cam tables and the road's block maxima for the kernel.

    Parameters
    ----------
    tyre : Tyre
        ``[CONTACT_PATCH]`` keys as in the module docstring.
    grid : RoadGrid
    width_table : bool, optional
        True: use the ``[CONTACT_WIDTH_CURVE]`` table (error if absent);
        False: use the formula; None (default): the table when present.
    n_width, n_length : int, optional
        Override the number of cams.
    step : float
        Sampling step [m] along cam rows not aligned with the grid.
    """
    unknown = set(options) - set(_OTHER_OPTIONS)
    if unknown:
        raise InputError(f"unknown enveloping-model option(s) {', '.join(sorted(unknown))}; "
                         "expected width_table, n_width, n_length, step", field="options")
    tir = tyre.tir
    r0, w0 = float(tyre.unloaded_radius), float(tyre.width)
    b_max = 0.5 * w0
    lmode, (a1, a2) = _length_law(tir)
    wmode, (b1, b2, b3), wtable = _width_law(tir, width_table, b_max)
    ae, be, ce = (_key(tir, k) * f for k, f in (("PAE", r0), ("PBE", r0), ("PCE", 1.0)))
    pls = _key(tir, "PLS")
    nw = int(n_width if n_width is not None else _key(tir, "N_WIDTH"))
    nl = int(n_length if n_length is not None else _key(tir, "N_LENGTH"))
    if not (ae > 0 and be > 0 and ce >= 1.0 and pls >= 0 and nw >= 1 and nl >= 1):
        raise InputError("cams need PAE, PBE > 0, PCE >= 1, PLS >= 0 and at least one cam "
                         f"each way (got {ae / r0:g}, {be / r0:g}, {ce:g}, {pls:g}, {nw}, {nl})",
                         source=tir.source, field="CONTACT_PATCH")
    cap = ae
    if tir.has("CONTACT_PATCH", "ELLIPS_MAX_STEP"):
        rise = tir.number("CONTACT_PATCH", "ELLIPS_MAX_STEP")
        if rise < be:  # where the contour has risen ELLIPS_MAX_STEP
            cap = ae * (1.0 - (1.0 - rise / be) ** ce) ** (1.0 / ce)
    tables = cam_tables(ae, be, ce)
    head = np.zeros(HEADER)
    head[[R0, W0, LMODE, A1, A2, WMODE, B1, B2, B3, AE, BE, CE, PLS, NW, NL, CAP, STEP]] = (
        r0, w0, lmode, a1, a2, wmode, b1, b2, b3, ae, be, ce, pls, nw, nl, cap, step)
    head[BMAX] = b_max
    head[TN] = TABLE_POINTS
    head[TOFF] = HEADER
    parts = [head, tables]
    offset = HEADER + tables.size
    if wtable is not None:
        head[WOFF] = offset
        head[WROWS] = wtable.shape[0]
        parts.append(np.ascontiguousarray(wtable, float).ravel())
        offset += wtable.size
    if np.all(grid.z == grid.z[:, :1]):  # a 2D road: every row of cams sees the same road
        head[YINV] = 1.0
    if grid.z.shape[0] > 2:  # block maxima per pair of grid rows
        per = max(1, int(round(BLOCK / grid.dx)))
        head[CM] = offset
        head[PER] = per
        parts.append(block_maxima(grid.z, per).ravel())
    return np.concatenate(parts)


def contact_patch(cp, deflection):
    """``(a, b)`` half length and half width [m] the kernel uses at ``deflection`` [m]."""
    a = half_length(int(cp[LMODE]), cp[A1], cp[A2], cp[R0], deflection)
    b = half_width(int(cp[WMODE]), cp[B1], cp[B2], cp[B3], cp[W0], cp[R0], deflection, cp,
                   int(cp[WOFF]), int(cp[WROWS]), cp[BMAX])
    return a, b


@nb.njit(cache=True)
def enveloping_contact(cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
    """Deflection, contact point and effective-plane normal from the cams.

    Parameters as :func:`tyrelab.tyre.contact.point.point_contact`, with
    ``cp`` from :func:`enveloping_params`; ``geo[7]`` receives the effective
    road curvature [1/m].
    """
    r0 = cp[R0]
    fx, fy, fz, dx, dy, dz = wheel_axes(ax, ay, az)
    cosg = -dz
    if cosg < 1e-3:
        no_contact(r0, cx, cy, cz, 1.0, geo)
        return
    ae, be = cp[AE], cp[BE]
    reach = (r0 + ae) * abs(fx) + cp[BMAX] * abs(fy) + 1e-9
    zmax = local_zmax(zinfo, cx - reach, cx + reach)
    geo[7] = 0.0
    if (cz - zmax) * cosg >= r0:
        no_contact(r0, cx, cy, cz, (cz - zmax) * cosg - r0, geo)
        return
    if zinfo[1] == zinfo[0]:  # one level plane everywhere
        plane_contact(r0, cx, cy, cz, ax, ay, az, cx, cy, zinfo[0], 0.0, 0.0, 1.0, 0.0, geo)
        return
    n_tab, off, cap, step = int(cp[TN]), int(cp[TOFF]), cp[CAP], cp[STEP]
    cm, per = int(cp[CM]), int(cp[PER])
    lever = (cz - grid_height(gp, z, cx, cy)) / cosg
    px = cx + dx * lever  # contact patch centre: the wheel plane's trace on the road
    py = cy + dy * lever
    lx, ly = -fy, fx  # horizontal, to the left of the heading
    # along grid x (the rigs), a row of cams lies on one grid row (the drift of y along
    # the heading, u fy, is ignored) and is searched row-wise: see cams.cam_row
    aligned = abs(fy) < 0.01
    nl, nw = int(cp[NL]), int(cp[NW])
    same_rows = cp[YINV] != 0.0 and aligned  # a 2D profile: every row sees the same road
    rows = 1 if same_rows else nw
    mult = float(nw) if same_rows else 1.0
    # one cam under the centre: its height sizes the patch
    w = cam_height(cp, off, n_tab, ae, be, cap, cp, cm, per, step, gp, z, px, py, fx, fy, zmax)
    rho0 = max(r0 - (cz - w) / cosg, 0.0)
    a = half_length(int(cp[LMODE]), cp[A1], cp[A2], r0, rho0)
    b = half_width(int(cp[WMODE]), cp[B1], cp[B2], cp[B3], cp[W0], r0, rho0, cp,
                   int(cp[WOFF]), int(cp[WROWS]), cp[BMAX])
    ls = 2.0 * cp[PLS] * a  # eq. 2.6
    du = ls / (nl - 1) if nl > 1 else 0.0
    dv = 2.0 * b / (nw - 1) if nw > 1 else 0.0
    u_first = -0.5 * ls if nl > 1 else 0.0
    v_first = -b if nw > 1 else 0.0
    sw = suw = svw = suu = svv = su2w = su4 = 0.0
    w_row = np.empty(nl)  # heights of one row's cams, in grid-x order
    for jr in range(rows):
        v = 0.0 if same_rows else v_first + jr * dv
        if aligned:
            j, wy = grid_row(gp, z, py + v * ly)
            x_a = px + u_first * fx + v * lx  # first and last cam of the row
            x_b = x_a + (nl - 1) * du * fx
            x_lo, x_hi = min(x_a, x_b), max(x_a, x_b)
            top = row_block_max(cp, cm, per, gp, z, j, x_lo - cap, x_hi + cap) if cm > 0 else zmax
            cam_row(cp, off, n_tab, ae, be, cap, cp, cm, per, gp, z, j, wy, x_lo, du * abs(fx), nl,
                    top, w_row)
        for i in range(nl):
            u = u_first + i * du
            if aligned:
                w = w_row[i] if fx > 0.0 else w_row[nl - 1 - i]
            else:
                w = cam_height(cp, off, n_tab, ae, be, cap, cp, cm, per, step, gp, z,
                               px + u * fx + v * lx, py + u * fy + v * ly, fx, fy, zmax)
            sw += mult * w
            suw += mult * u * w
            svw += mult * v * w
            suu += mult * u * u
            svv += mult * v * v
            su2w += mult * u * u * w
            su4 += mult * u * u * u * u
    if same_rows:  # the rows' spread, for completeness of the sums (no tilt across)
        svv = 0.0
        for jr in range(nw):
            v = v_first + jr * dv
            svv += nl * v * v
    count = float(nl * nw)
    su = suw / suu if suu > 0.0 else 0.0  # forward slope
    sv = svw / svv if svv > 0.0 and not same_rows else 0.0  # road camber
    mean_u2 = suu / count
    den = su4 - count * mean_u2 * mean_u2
    if den > 1e-30:
        geo[7] = 2.0 * (su2w - mean_u2 * sw) / den  # curvature of the quadratic fit along u
    w0 = sw / count - slope_support(cp, off, n_tab, ae, su)
    nx, ny, nz = unit(-(su * fx + sv * lx), -(su * fy + sv * ly), 1.0)
    curvature = geo[7]
    plane_contact(r0, cx, cy, cz, ax, ay, az, px, py, w0, nx, ny, nz, 0.0, geo)
    geo[7] = curvature
