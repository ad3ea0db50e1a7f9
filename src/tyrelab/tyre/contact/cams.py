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
measured deflection-to-half-width table, as the thesis asks for in 4.4).

Python builds the cam tables once; the compiled functions evaluate one cam.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ...road.grid import grid_height
from .shape import _x_height, section_walk

#: points in each cam table
TABLE_POINTS = 1025


def cam_drop(s, ae, be, ce):
    """Rise e(s) [m] of the cam contour above its lowest point (eq. 2.5), vectorised."""
    t = np.minimum(np.abs(np.asarray(s, float)) / ae, 1.0)
    return be * (1.0 - (1.0 - t ** ce) ** (1.0 / ce))


def cam_tables(ae, be, ce, n=TABLE_POINTS) -> np.ndarray:
    """``[drop, window, touch]`` tables of a cam, each ``n`` long, concatenated.

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
    return np.r_[drop, window, touch]


@nb.njit(cache=True, inline="always")
def table_drop(ct, off, n, ae, s):
    """e(|s|) by linear interpolation in the drop table; 1e30 beyond the cam."""
    x = abs(s) * (n - 1) / ae
    if x >= n - 1:
        return 1e30
    i = int(x)
    f = x - i
    return ct[off + i] * (1.0 - f) + ct[off + i + 1] * f


@nb.njit(cache=True, inline="always")
def table_window(ct, off, n, ae, be, rise):
    """Distance beyond which the contour has risen more than ``rise`` (rounded up)."""
    if rise >= be:
        return ae
    if rise <= 0.0:
        return 0.0
    x = math.sqrt(rise / be) * (n - 1)
    i = min(int(math.ceil(x)), n - 1)
    return ct[off + n + i]


def block_maxima(z: np.ndarray, per: int) -> np.ndarray:
    """Maxima of the road over blocks of ``per`` x cells, for each pair of grid rows.

    Block b spans x nodes ``b per .. (b+1) per`` (both ends: a cell between two
    nodes lies in one block) and rows j, j+1, so it bounds the bilinear road
    on any line between those rows. Shape ``(n_blocks, ny - 1)``, row-major.
    """
    nx = z.shape[0]
    pair = np.maximum(z[:, :-1], z[:, 1:])
    n_blocks = -(-(nx - 1) // per)
    ends = np.minimum(np.arange(1, n_blocks + 1) * per, nx - 1)
    out = np.maximum.reduceat(pair, np.arange(n_blocks) * per, axis=0)
    return np.maximum(out, pair[ends])


@nb.njit(cache=True, inline="always")
def touch_point(ct, off, n, ae, m):
    """Where (s) the cam's contour has slope m: the cam touches a road of slope m there."""
    x = abs(m) / (1.0 + abs(m)) * (n - 1)
    i = min(int(x), n - 2)
    f = x - i
    base = off + 2 * n
    return math.copysign(ct[base + i] * (1.0 - f) + ct[base + i + 1] * f, m)


@nb.njit(cache=True, inline="always")
def slope_support(ct, off, n, ae, m):
    """Height of a cam's lowest point above a straight road of slope m, under it.

    A cam resting on a uniform slope touches it at ``s*`` (contour slope m)
    and its lowest point stands ``m s* - e(s*)`` above the road below it;
    subtracting this makes a uniformly inclined road its own effective plane.
    """
    s = touch_point(ct, off, n, ae, m)
    return m * s - table_drop(ct, off, n, ae, s)


@nb.njit(cache=True, inline="always")
def _cam_side(ct, off, n, ae, be, cap, cp, brk, step, gp, z, x0, y0, fx, fy, top, best, reach):
    """Walk from the cam's centre outwards along (fx, fy); returns (best, reach).

    Each grid node lifts the cam to ``h - e(s)``; a straight piece between
    two nodes can lift it more only inside, where the contour's slope equals
    the piece's: that point is found (:func:`touch_point`) only when the
    piece's highest end minus the contour's rise at its near end could beat
    the current height. The walk stops where the contour has risen more
    than ``top - best``.
    """
    if reach <= 0.0:
        return best, reach
    sb = cap
    aligned, j, wy, a, b, k, k_end, kdir, h0, h_b = section_walk(gp, z, x0, y0, fx, fy, 0.0, sb, step)
    if h0 > best:  # the centre itself (first side only)
        best = h0
        reach = min(table_window(ct, off, n, ae, be, top - best), cap)
    jump = aligned and brk > 0 and kdir > 0
    s0 = 0.0
    e0 = 0.0
    while True:
        last = (k - k_end) * kdir > 0
        if last:
            s1 = sb
            h1 = h_b
        else:
            s1 = a + k * b
            h1 = z[k, j] * (1.0 - wy) + z[k, j + 1] * wy if aligned else grid_height(
                gp, z, x0 + s1 * fx, y0 + s1 * fy)
        if s1 > s0:
            e1 = table_drop(ct, off, n, ae, s1)
            if h1 - e1 > best:
                best = h1 - e1
                reach = min(table_window(ct, off, n, ae, be, top - best), cap)
            if max(h0, h1) - e0 > best:  # the piece's inside might lift the cam higher
                m = (h1 - h0) / (s1 - s0)
                s = min(max(touch_point(ct, off, n, ae, m), s0), s1)
                w = h0 + m * (s - s0) - table_drop(ct, off, n, ae, s)
                if w > best:
                    best = w
                    reach = min(table_window(ct, off, n, ae, be, top - best), cap)
            s0 = s1
            h0 = h1
            e0 = e1
        if last or s1 >= reach:
            return best, reach
        if jump:
            nxt = int(cp[brk + k])
            k = nxt if nxt > k else k + 1
        else:
            k += kdir


@nb.njit(cache=True, inline="always")
def _cam_along_x(ct, off, n, ae, be, cap, cp, brk, gp, z, j, wy, x0, step_dir, top, best, reach, h_c,
                 cm, per, xt):
    """:func:`_cam_side` for a row along grid x (row j, weight wy): walks the x nodes
    from x0 in direction ``step_dir`` (+1/-1); returns (best, reach, xt), xt the x
    of the road point the cam rests on (kept from the input while not improved).

    With ``cm`` > 0, ``cp[cm:]`` holds the road's maxima over blocks of ``per``
    x cells for each pair of grid rows (:func:`block_maxima`): a block whose
    maximum, minus the contour's rise at its near end, cannot beat the
    current height is stepped over without reading its nodes.
    """
    u = (x0 - gp[0]) * gp[4]
    nx = z.shape[0]
    if step_dir > 0:
        k = int(math.floor(u)) + 1
        if k < 0:
            k = 0
    else:
        k = int(math.ceil(u)) - 1
        if k > nx - 1:
            k = nx - 1
    jump = brk > 0 and step_dir > 0
    s0 = 0.0
    h0 = h_c
    e0 = 0.0
    nrows = z.shape[1] - 1
    # the block holding the segment that ends at node k, and the node where it ends
    block = 0
    if cm > 0:  # (k - 1) // per or k // per, without an integer division
        kk = k - 1 if step_dir > 0 else k
        block = int(kk * (1.0 / per))
        if (block + 1) * per <= kk:
            block += 1
        elif block * per > kk:
            block -= 1
    k_far = min((block + 1) * per, nx - 1) if step_dir > 0 else block * per
    fresh = True
    while 0 <= k < nx:
        if cm > 0:
            if (k - k_far) * step_dir > 0:  # walked into the next block
                block += step_dir
                k_far = min((block + 1) * per, nx - 1) if step_dir > 0 else block * per
                fresh = True
            if fresh:
                fresh = False
                if cp[cm + block * nrows + j] - e0 <= best:  # nothing in it can lift the cam
                    s_far = abs(gp[0] + k_far * gp[2] - x0)
                    if s_far >= reach:
                        return best, reach, xt
                    s0 = s_far
                    h0 = z[k_far, j] * (1.0 - wy) + z[k_far, j + 1] * wy
                    e0 = table_drop(ct, off, n, ae, s0)
                    k = k_far + step_dir
                    continue
        s1 = abs(gp[0] + k * gp[2] - x0)
        if s1 >= reach:
            # the piece up to the window's edge: only its inside can still matter
            if s1 > s0 and max(h0, z[k, j] * (1.0 - wy) + z[k, j + 1] * wy) - e0 > best:
                h1 = z[k, j] * (1.0 - wy) + z[k, j + 1] * wy
                m = (h1 - h0) / (s1 - s0)
                sp = min(max(touch_point(ct, off, n, ae, m), s0), min(s1, reach))
                w = h0 + m * (sp - s0) - table_drop(ct, off, n, ae, sp)
                if w > best:
                    best = w
                    xt = x0 + step_dir * sp
                    reach = min(table_window(ct, off, n, ae, be, top - best), cap)
            return best, reach, xt
        h1 = z[k, j] * (1.0 - wy) + z[k, j + 1] * wy
        if h1 == h0 and s1 > s0:  # level road: lower than its near end (e grows outwards)
            s0 = s1
        elif s1 > s0:
            e1 = table_drop(ct, off, n, ae, s1)
            if h1 - e1 > best:
                best = h1 - e1
                xt = x0 + step_dir * s1
                reach = min(table_window(ct, off, n, ae, be, top - best), cap)
            if max(h0, h1) - e0 > best:  # the piece's inside might lift the cam higher
                m = (h1 - h0) / (s1 - s0)
                sp = min(max(touch_point(ct, off, n, ae, m), s0), s1)
                w = h0 + m * (sp - s0) - table_drop(ct, off, n, ae, sp)
                if w > best:
                    best = w
                    xt = x0 + step_dir * sp
                    reach = min(table_window(ct, off, n, ae, be, top - best), cap)
            s0 = s1
            h0 = h1
            e0 = e1
        if jump:
            nxt = int(cp[brk + k])
            k = nxt if nxt > k else k + 1
        else:
            k += step_dir
    return best, reach, xt  # beyond the grid the road stays level: it cannot lift the cam more


@nb.njit(cache=True, inline="always")
def cam_height(ct, off, n, ae, be, window_cap, cp, brk, step, gp, z, x0, y0, fx, fy, zmax, cm=0,
               per=1, lower=-1e300, x_lower=0.0):
    """Height w of the lowest point of one cam resting on the road (basic function).

    The cam sits at (x0, y0) and looks along the horizontal direction
    (fx, fy). Only road within the distance where the contour has risen
    ``zmax - w`` can lift it (``zmax`` bounds the road around), so the walks
    outwards, ahead and behind, shrink as w grows; ``window_cap`` limits them
    further (MF-Swift ELLIPS_MAX_STEP). Each straight piece of the road lifts
    the cam to its best point exactly. ``cm``, ``per``: block maxima of the
    road (see :func:`_cam_along_x`), 0 when there are none. ``lower``: a
    height the cam certainly reaches, resting on the road point at x =
    ``x_lower`` (from the neighbouring cam; it only shortens the walk).

    Returns ``(w, xt)``: the height and, along grid x, the x of the road point
    the cam rests on.
    """
    aligned = abs(fy) < 0.01  # along grid x: walk the nodes of one grid row directly
    j, wy = 0, 0.0
    best = -1e300
    reach = window_cap
    if aligned:
        jf = (y0 - gp[1]) * gp[5]
        ny = z.shape[1]
        if jf >= ny - 1:
            j, wy = ny - 2, 1.0
        elif jf > 0.0:
            j = min(int(jf), ny - 2)
            wy = jf - j
        best = _x_height(gp, z, x0, j, wy)
        h_c = best
        xt = x0
        if lower > best:
            best = lower
            xt = x_lower
        reach = min(table_window(ct, off, n, ae, be, zmax - best), window_cap)
    else:
        h_c = best
        xt = x0
    for side in range(2):
        d = 1.0 if side == 0 else -1.0
        if reach <= 0.0:
            break
        if aligned:
            best, reach, xt = _cam_along_x(ct, off, n, ae, be, window_cap, cp, brk, gp, z, j, wy,
                                           x0, 1 if d * fx > 0.0 else -1, zmax, best, reach, h_c,
                                           cm, per, xt)
        else:
            best, reach = _cam_side(ct, off, n, ae, be, window_cap, cp, brk, step, gp, z, x0, y0,
                                    d * fx, d * fy, zmax, best, reach)
    return best, xt


@nb.njit(cache=True, inline="always")
def row_max(cp, brk, step, gp, z, x0, y0, fx, fy, sa, sb):
    """Highest road point on the line (x0, y0) + s (fx, fy), s in [sa, sb]."""
    aligned, j, wy, a, b, k, k_end, kdir, h_a, h_b = section_walk(gp, z, x0, y0, fx, fy, sa, sb, step)
    top = max(h_a, h_b)
    if aligned:
        lo, hi = (k, k_end) if kdir > 0 else (k_end, k)
        for i in range(lo, hi + 1):
            h = z[i, j] * (1.0 - wy) + z[i, j + 1] * wy
            if h > top:
                top = h
        return top
    for i in range(k, k_end + 1):
        s = a + i * b
        h = grid_height(gp, z, x0 + s * fx, y0 + s * fy)
        if h > top:
            top = h
    return top


@nb.njit(cache=True)
def half_length(mode, c1, c2, r0, rho):
    """Half contact length a [m]: eq. 2.3 (mode 0) or MF-Swift (mode 1)."""
    if rho <= 0.0:
        return 0.0
    x = rho / r0
    if mode == 0:
        return c1 * r0 * (x + c2 * math.sqrt(x))  # eq. 2.3: PA1, PA2
    return r0 * (c2 * x + c1 * math.sqrt(x))  # MF-Swift: Q_RA1, Q_RA2


@nb.njit(cache=True)
def half_width(mode, c1, c2, c3, w0, r0, rho, cp, off, rows, b_max):
    """Half contact width b [m], at most ``b_max``.

    mode 0: eq. 2.4 (PB1-PB3); 1: MF-Swift (Q_RB1, Q_RB2); 2: a table of
    (deflection, half width) rows at ``cp[off:]``, linear, clamped at its ends.
    """
    if mode == 2:
        if rho <= cp[off]:
            b = cp[off + 1]
        elif rho >= cp[off + 2 * (rows - 1)]:
            b = cp[off + 2 * (rows - 1) + 1]
        else:
            i = 0
            while cp[off + 2 * (i + 1)] < rho:
                i += 1
            d0 = cp[off + 2 * i]
            d1 = cp[off + 2 * (i + 1)]
            f = (rho - d0) / (d1 - d0)
            b = cp[off + 2 * i + 1] * (1.0 - f) + cp[off + 2 * i + 3] * f
    elif rho <= 0.0:
        b = 0.0
    else:
        x = rho / r0
        if mode == 0:
            b = c1 * w0 * (x + c2 * math.sqrt(x) + c3 * x * math.sqrt(x))  # eq. 2.4
        else:
            b = w0 * (c2 * x + c1 * x ** (1.0 / 3.0))  # MF-Swift
    return min(max(b, 0.0), b_max)
