"""The cams' least-squares effective plane of the enveloping model (:mod:`.enveloping`).

Compiled, on the ground through the terrain interface only
(:mod:`tyrelab.road.terrain`): :func:`cam_plane` spreads the cams over the
contact patch, rests each on the road (:mod:`.cams`) and fits the plane;
:func:`row_block_max` bounds the ground on a row of cams from the record's
block bounds. Split from :mod:`.enveloping` to keep each file short.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ...road.terrain import terrain_height, terrain_lines, terrain_row
from .cams import cam_height, cam_row, slope_support
from .patch_laws import half_length, half_width


@nb.njit(cache=True, inline="always")
def row_block_max(params, road, j, xa, xb):
    """An upper bound of the ground on row j between x = xa and xb: the largest of the
    record's block bounds (``params.row_block_max``) over the blocks that cover it.

    Only for a record whose ``row_block_max`` is not empty.
    """
    line0, _, inv_spacing, nx = terrain_lines(road)
    blocks = params.row_block_max
    per = params.block_per
    k_lo = min(max(int(math.floor((min(xa, xb) - line0) * inv_spacing)), 0), nx - 1)
    k_hi = min(max(int(math.ceil((max(xa, xb) - line0) * inv_spacing)), 0), nx - 1)
    n_blocks = blocks.shape[0]
    top = -1e300
    for b in range(max((k_lo - 1) // per, 0), min(k_hi // per, n_blocks - 1) + 1):
        h = blocks[b, j]
        if h > top:
            top = h
    return top


@nb.njit(cache=True, forceinline=True)
def cam_plane(params, road, cx, cy, cz, fx, fy, dx, dy, cosg, zmax):
    """The cams' least-squares effective plane under a wheel centre (cx, cy, cz).

    ``(fx, fy)`` the horizontal heading, ``(dx, dy)`` the horizontal part of
    the in-plane down vector, ``cosg`` minus its vertical part (the cosine of the
    wheel plane's tilt), ``zmax`` a bound of the road within reach. Returns
    ``(px, py, height, slope, camber, curvature, a, b)``: the patch centre,
    the plane's height there, its slopes along the heading and across (to
    the left), the curvature of the quadratic fit along the heading [1/m]
    (0 when the cams cannot fit one) and the half length and half width the
    cams were spread over.
    """
    r0 = params.unloaded_radius
    cap = params.cam_reach
    has_blocks = params.row_block_max.shape[0] > 0
    lever = (cz - terrain_height(road, cx, cy)) / cosg
    px = cx + dx * lever  # contact patch centre: the wheel plane's trace on the road
    py = cy + dy * lever
    lx, ly = -fy, fx  # horizontal, to the left of the heading
    # along x (the rigs), a row of cams lies on one row of the ground (the drift of y along
    # the heading, u fy, is ignored) and is searched row-wise: see cams.cam_row
    aligned = abs(fy) < 0.01
    nl, nw = params.n_length, params.n_width
    same_rows = params.profile_road and aligned  # a 2D profile: every row sees the same road
    rows = 1 if same_rows else nw
    mult = float(nw) if same_rows else 1.0
    # one cam under the centre: its height sizes the patch, never below the floor (a
    # patch of no length has no slope: the plane would jump; module docstring)
    w = cam_height(params, road, px, py, fx, fy, zmax)
    rho0 = max(r0 - (cz - w) / cosg, params.min_patch_deflection)
    a = half_length(params, rho0)
    b = half_width(params, rho0)
    ls = 2.0 * params.base_length_factor * a  # eq. 2.6
    du = ls / (nl - 1) if nl > 1 else 0.0
    dv = 2.0 * b / (nw - 1) if nw > 1 else 0.0
    u_first = -0.5 * ls if nl > 1 else 0.0
    v_first = -b if nw > 1 else 0.0
    sw = suw = svw = suu = svv = su2w = su4 = 0.0
    w_row = np.empty(nl)  # heights of one row's cams, in grid-x order
    outline = params.outline_only
    count = float(nl * nw)
    if outline:  # two whole outer rows, the first and last cam of each row between
        count = float(min(nw, 2) * nl + max(nw - 2, 0) * min(nl, 2))
    for jr in range(rows):
        v = 0.0 if same_rows else v_first + jr * dv
        # a row between the outline's two outer rows: only its first and last cam count
        inner_row = outline and not (same_rows or jr == 0 or jr == nw - 1)
        if aligned:
            j, wy = terrain_row(road, py + v * ly)
            x_a = px + u_first * fx + v * lx  # first and last cam of the row
            x_b = x_a + (nl - 1) * du * fx
            x_lo, x_hi = min(x_a, x_b), max(x_a, x_b)
            top = row_block_max(params, road, j, x_lo - cap, x_hi + cap) if has_blocks else zmax
            pitch = du * abs(fx)
            if inner_row and nl > 2:
                # rest just the row's first and last cam (the last at x_lo + (nl - 1) pitch,
                # where the whole row puts it), their heights into the row's two ends. The
                # last cam's search then starts where the first rests, not its neighbour
                # (cams.cam_row): the same maximum along another path, equal to rounding
                # (1e-15), not to the bit.
                # np.int64: one compiled cam_row for both counts (a literal is its own type)
                cam_row(params, road, j, wy, x_lo, (nl - 1) * pitch, np.int64(2), top, w_row)
                w_row[nl - 1] = w_row[1]
            else:
                cam_row(params, road, j, wy, x_lo, pitch, nl, top, w_row)
        for i in range(nl):
            u = u_first + i * du
            weight = mult
            if outline:  # the rows this cam stands for whose cam i lies on the outline
                end = i == 0 or i == nl - 1
                if same_rows:
                    weight = float(nw) if end else float(min(nw, 2))
                elif inner_row and not end:
                    continue  # inside the patch: not evaluated (thesis 5.4)
            if aligned:
                w = w_row[i] if fx > 0.0 else w_row[nl - 1 - i]
            else:
                w = cam_height(params, road, px + u * fx + v * lx, py + u * fy + v * ly, fx, fy,
                               zmax)
            sw += weight * w
            suw += weight * u * w
            svw += weight * v * w
            suu += weight * u * u
            svv += weight * v * v
            su2w += weight * u * u * w
            su4 += weight * u * u * u * u
    if same_rows:  # the rows' spread, for completeness of the sums (no tilt across)
        svv = 0.0
        for jr in range(nw):
            v = v_first + jr * dv
            in_row = nl if not outline or jr == 0 or jr == nw - 1 else min(nl, 2)
            svv += in_row * v * v
    su = suw / suu if suu > 0.0 else 0.0  # forward slope
    sv = svw / svv if svv > 0.0 and not same_rows else 0.0  # road camber
    mean_u2 = suu / count
    den = su4 - count * mean_u2 * mean_u2
    curvature = 0.0
    if den > 1e-30:
        curvature = 2.0 * (su2w - mean_u2 * sw) / den  # curvature of the quadratic fit along u
    w0 = sw / count - slope_support(params, su)
    return px, py, w0, su, sv, curvature, a, b
