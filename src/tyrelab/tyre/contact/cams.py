"""Elliptical cams and the contact patch of the enveloping model (thesis 2.3.3, 4.4).

Schmeitz (2004) replaces the tyre rolling over a short obstacle by cams
("tandem eggs") that slide over the road and stay on top of it. One cam is
the curve of eq. 2.5::

    (x_e / (p_ae R0))^p_ce + (z_e / (p_be R0))^p_ce = 1

Its lower contour rises ``e(s) = b_e (1 - (1 - |s/a_e|^c_e)^(1/c_e))`` above its
lowest point at a distance s along the road; a cam at x rests at the height

    w(x) = max_s [ h(x + s) - e(s) ]

(Schmeitz's *basic function*: the road filtered by the cam). The contact
patch dimensions follow eqs. 2.3 and 2.4 (or the MF-Swift forms, or a
measured deflection-to-half-width table, as the thesis asks for in 4.4):
:mod:`.patch_laws`, which also reads the ``[CONTACT_PATCH]`` keys.

Python builds the cam tables and the road's block maxima once, into the
model's record (:class:`tyrelab.tyre.contact.enveloping.EnvelopingParams`);
the compiled functions here take that record (``params``) and the terrain
record (:mod:`tyrelab.road.terrain`, queried through that interface only) and
evaluate a row of cams along x (the rigs) or one cam in any direction.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ...road.terrain import (terrain_height, terrain_line_height, terrain_lines, terrain_row,
                             terrain_row_height)
from .shape import section_walk

#: points in each cam table
TABLE_POINTS = 1025


def cam_drop(s, ae, be, ce):
    """Rise e(s) [m] of the cam contour above its lowest point (eq. 2.5), vectorised."""
    t = np.minimum(np.abs(np.asarray(s, float)) / ae, 1.0)
    return be * (1.0 - (1.0 - t ** ce) ** (1.0 / ce))


def cam_tables(ae, be, ce, n=TABLE_POINTS):
    """``(drop, window, touch)``: the tables of a cam, each ``n`` long.

    * drop: e(s) at ``s = i ae / (n-1)``;
    * window: the distance at which the contour has risen ``be u^2``, at
      ``u = i / (n-1)`` (the inverse of e, sampled so that it is close to
      linear near the cam's bottom);
    * touch: where the contour's slope de/ds equals m, at
      ``m / (1 + m) = i / (n-1)`` (a cam on a straight road of slope m
      touches it there; an error ds in it changes the cam's height only by
      about e'' ds^2 / 2).
    """
    s = np.linspace(0.0, ae, 20 * (n - 1) + 1)
    t = s / ae
    drop = cam_drop(s[::20], ae, be, ce)
    u = np.linspace(0.0, 1.0, n)
    window = ae * (1.0 - (1.0 - u * u) ** ce) ** (1.0 / ce)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        slope = be / ae * t ** (ce - 1.0) * (1.0 - t ** ce) ** (1.0 / ce - 1.0)
    slope = np.maximum.accumulate(np.nan_to_num(slope, nan=np.inf, posinf=np.inf))
    slope[-1] = np.inf
    u_of_s = 1.0 - 1.0 / (1.0 + slope)  # m / (1 + m), 1 where m is infinite
    touch = np.interp(u, u_of_s, s)
    touch[-1] = ae
    return (np.ascontiguousarray(drop, np.float64), np.ascontiguousarray(window, np.float64),
            np.ascontiguousarray(touch, np.float64))


@nb.njit(cache=True, inline="always")
def table_drop(drop, ae, s):
    """e(|s|) by linear interpolation in the drop table ``drop`` of a cam of half
    length ``ae``; 1e30 beyond the cam."""
    n = drop.shape[0]
    x = abs(s) * ((n - 1) / ae)
    if x >= n - 1:
        return 1e30
    i = int(x)
    f = x - i
    return drop[i] * (1.0 - f) + drop[i + 1] * f


@nb.njit(cache=True, inline="always")
def table_window(window, ae, be, rise):
    """Distance beyond which the contour has risen more than ``rise`` (rounded up), from
    the window table ``window`` of a cam of half length ``ae`` and half height ``be``."""
    if rise >= be:
        return ae
    if rise <= 0.0:
        return 0.0
    n = window.shape[0]
    x = math.sqrt(rise / be) * (n - 1)
    i = min(int(math.ceil(x)), n - 1)
    return window[i]


@nb.njit(cache=True, inline="always")
def touch_point(touch, m):
    """Where (s) the cam's contour has slope m (from the touch table ``touch``): the cam
    touches a road of slope m there."""
    n = touch.shape[0]
    x = abs(m) / (1.0 + abs(m)) * (n - 1)
    i = min(int(x), n - 2)
    f = x - i
    return math.copysign(touch[i] * (1.0 - f) + touch[i + 1] * f, m)


@nb.njit(cache=True, inline="always")
def slope_support(params, m):
    """Height of a cam's lowest point above a straight road of slope m, under it.

    A cam resting on a uniform slope touches it at ``s*`` (contour slope m)
    and its lowest point stands ``m s* - e(s*)`` above the road below it;
    subtracting this makes a uniformly inclined road its own effective plane.
    """
    s = touch_point(params.cam_touch, m)
    return m * s - table_drop(params.cam_drop, params.cam_half_length, s)


@nb.njit(cache=True)
def _cam_side(params, road, x0, y0, fx, fy, top, best, reach):
    """Walk from the cam's centre outwards along (fx, fy), sampling the road every
    ``params.step``; returns (best, reach).

    Each sample lifts the cam to ``h - e(s)``; a straight piece between two
    samples can lift it more only inside, where the contour's slope equals
    the piece's: that point is found (:func:`touch_point`) only when the
    piece's highest end minus the contour's rise at its near end could beat
    the current height. The walk stops where the contour has risen more
    than ``top - best`` (or at ``params.cam_reach``).
    """
    if reach <= 0.0:
        return best, reach
    drop, window, touch = params.cam_drop, params.cam_window, params.cam_touch
    ae, be, cap = params.cam_half_length, params.cam_half_height, params.cam_reach
    sb = cap
    walk = section_walk(road, x0, y0, fx, fy, 0.0, sb, params.step)
    a, b, k, k_end, h0, h_b = walk.a, walk.b, walk.k, walk.k_end, walk.h_a, walk.h_b
    if h0 > best:  # the centre itself (first side only)
        best = h0
        reach = min(table_window(window, ae, be, top - best), cap)
    s0 = 0.0
    e0 = 0.0
    while True:
        last = k > k_end
        if last:
            s1 = sb
            h1 = h_b
        else:
            s1 = a + k * b
            h1 = terrain_height(road, x0 + s1 * fx, y0 + s1 * fy)
        if s1 > s0:
            e1 = table_drop(drop, ae, s1)
            if h1 - e1 > best:
                best = h1 - e1
                reach = min(table_window(window, ae, be, top - best), cap)
            if max(h0, h1) - e0 > best:  # the piece's inside might lift the cam higher
                m = (h1 - h0) / (s1 - s0)
                s = min(max(touch_point(touch, m), s0), s1)
                w = h0 + m * (s - s0) - table_drop(drop, ae, s)
                if w > best:
                    best = w
                    reach = min(table_window(window, ae, be, top - best), cap)
            s0 = s1
            h0 = h1
            e0 = e1
        if last or s1 >= reach:
            return best, reach
        k += 1


# no fastmath: its flags (fused multiply-add, reassociation) made the results depend on the
# CPU's floating-point features; without them the golden traces agree to 4e-12 on the
# machine that recorded them, and a run is the same number on any x86-64 (5 % slower)
@nb.njit(cache=True)
def cam_row(params, road, j, wy, x_first, pitch, count, top, out):
    """Heights of ``count`` cams on one line along x, into ``out[:count]``.

    The cams stand at ``x_first + i pitch`` (``pitch >= 0``) on the line of
    row handle ``(j, wy)`` of the ground ``road``
    (:func:`~tyrelab.road.terrain.terrain_row`; the grid: between node rows
    j and j+1 at weight wy). Cam i rests at

        w_i = max over |x - x_i| <= cap of [h(x) - e(x - x_i)]

    on the ground (straight between its break lines, level beyond the first
    and last: :func:`~tyrelab.road.terrain.terrain_lines`), with ``cap =
    params.cam_reach``. Three facts keep the work small, none
    changes the result:

    * a cam rests no further back than the cam behind it: for a convex
      contour ``e(t - x_1) - e(t - x_2)`` grows with t when x_1 < x_2, so a
      road point behind where cam i-1 rests, lower than that point for cam
      i-1, is lower for cam i too; the walk of cam i starts there, with that
      point's height for cam i as its first lower bound;
    * only road within the distance where the contour has risen
      ``top - best`` can lift the cam (``top`` bounds the road of the row);
    * when ``params.row_block_max`` is not empty it holds the ground's bounds
      over blocks of ``params.block_per`` break lines for each row handle
      (:meth:`~tyrelab.road.terrain.Ground.row_maxima`): a block whose
      maximum minus the contour's rise at its nearest point cannot beat the
      current height is stepped over unread.

    Each straight piece is searched exactly: the concave function
    ``h(x) - e(x - x_i)`` on it peaks where the contour's slope equals the
    piece's (:func:`touch_point`), clipped to the piece.
    """
    g0, gd, ginv, nx = terrain_lines(road)
    drop, window, touch = params.cam_drop, params.cam_window, params.cam_touch
    ae, be, cap = params.cam_half_length, params.cam_half_height, params.cam_reach
    blocks = params.row_block_max
    has_blocks = blocks.shape[0] > 0
    per = params.block_per
    h_prev = t_prev = 0.0
    for i in range(count):
        xc = x_first + i * pitch
        best = terrain_row_height(road, j, wy, xc)  # the road under the centre
        xt = xc
        ht = best  # height of the road point the cam rests on
        if i > 0:
            lower = h_prev - table_drop(drop, ae, t_prev - xc)
            if lower > best and abs(t_prev - xc) <= cap:
                best = lower
                xt = t_prev
                ht = h_prev
        reach = min(table_window(window, ae, be, top - best), cap)
        left = xc - reach if i == 0 else max(xc - reach, t_prev)
        # the piece that holds `left` starts at node k
        k = int(math.floor((left - g0) * ginv))
        k = min(max(k, 0), nx - 2)
        xa = g0 + k * gd
        ha = terrain_line_height(road, j, wy, k)
        ea = -1.0  # e at xa, computed when needed
        if ha > best:
            ea = table_drop(drop, ae, xa - xc)
            if abs(xa - xc) <= cap and ha - ea > best:
                best = ha - ea
                xt = xa
                ht = ha
                reach = min(table_window(window, ae, be, top - best), cap)
        block = k // per
        k_test = k  # piece at which the next block test is due
        while k < nx - 1 and xa < xc + reach:
            if has_blocks and k == k_test:
                if k >= (block + 1) * per:  # walked into the next block
                    block += 1
                k_test = min((block + 1) * per, nx - 1)  # the node that ends the block
                xe = g0 + k_test * gd
                top_b = blocks[block, j]
                if top_b <= best or top_b - table_drop(
                        drop, ae, xe - xc if xe < xc else (xa - xc if xa > xc else 0.0)) <= best:
                    # nothing on pieces k .. k_test - 1 can lift the cam
                    k = k_test
                    xa = xe
                    ha = terrain_line_height(road, j, wy, k)
                    ea = -1.0  # not computed
                    continue
            xb = g0 + (k + 1) * gd
            hb = terrain_line_height(road, j, wy, k + 1)
            eb = -1.0
            if max(ha, hb) > best:  # else nothing on this piece can lift the cam (e >= 0)
                eb = table_drop(drop, ae, xb - xc)
                if abs(xb - xc) <= cap and hb - eb > best:
                    best = hb - eb
                    xt = xb
                    ht = hb
                    reach = min(table_window(window, ae, be, top - best), cap)
                if hb != ha:  # a level piece peaks at an end or under the centre: done
                    if xa <= xc <= xb:
                        emin = 0.0
                    else:
                        if ea < 0.0:
                            ea = table_drop(drop, ae, xa - xc)
                        emin = min(ea, eb)
                    if max(ha, hb) - emin > best:  # the piece's inside might lift the cam higher
                        m = (hb - ha) * ginv
                        s = min(max(touch_point(touch, m), xa - xc, -cap), xb - xc, cap)
                        h = ha + m * (xc + s - xa)
                        w = h - table_drop(drop, ae, s)
                        if w > best:
                            best = w
                            xt = xc + s
                            ht = h
                            reach = min(table_window(window, ae, be, top - best), cap)
            k += 1
            xa = xb
            ha = hb
            ea = eb
        out[i] = best
        h_prev = ht
        t_prev = xt


@nb.njit(cache=True)
def cam_height(params, road, x0, y0, fx, fy, zmax):
    """Height w of the lowest point of one cam resting on the road (basic function).

    The cam sits at (x0, y0) and looks along the horizontal direction
    (fx, fy). Only road within the distance where the contour has risen
    ``zmax - w`` can lift it (``zmax`` bounds the road around), so the walks
    outwards, ahead and behind, shrink as w grows; ``params.cam_reach``
    limits them further (MF-Swift ELLIPS_MAX_STEP). Along x (the rigs) the
    cam is searched exactly on the ground's row (:func:`cam_row`, with the
    ground's block bounds when the record has them); otherwise the road is
    sampled every ``params.step`` and each straight piece between samples
    searched exactly.
    """
    if abs(fy) < 0.01:  # along x: one row (the small drift of y is ignored)
        j, wy = terrain_row(road, y0)
        out = np.empty(1)
        # one cam; np.int64, not the literal 1, so that cam_row compiles once for both callers
        cam_row(params, road, j, wy, x0, 0.0, np.int64(1), zmax, out)
        return out[0]
    best = -1e300
    reach = params.cam_reach
    for side in range(2):
        d = 1.0 if side == 0 else -1.0
        if reach <= 0.0:
            break
        best, reach = _cam_side(params, road, x0, y0, d * fx, d * fy, zmax, best, reach)
    return best
