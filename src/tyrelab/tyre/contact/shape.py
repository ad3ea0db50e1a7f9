"""The tyre's cross-section as discs across its width (thesis 2.3.2, 4.3, Table 4-1).

ADAMS/Tire describes the carcass by up to ten points (radius ratio, width
ratio) over half the section, symmetric about the centreline, width ratio 0
at the centreline and 1 at the shoulder. Unequally spaced points are
resampled to the same number of equally spaced ones; the intervals between
them are the discs of the equivalent volume model, whose widths add up to
the tyre width. Without a table the section is square (all radii R0).

The compiled part intersects one disc with the ground, through the terrain
interface only (:mod:`tyrelab.road.terrain`): the ground's section in the
disc plane is walked as straight pieces (exact between the ground's break
lines when driven along x: :func:`section_walk`, shared with the enveloping
model's cams), each piece is clipped to the disc's circle in closed form, and
the area and first moments of the region inside the disc and below the ground
are integrated exactly (:func:`disc_intersection`).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from ...errors import InputError
from ...road.terrain import profile_breaks  # noqa: F401  (its callers import it from here)
from ...road.terrain import (terrain_height, terrain_line_height, terrain_lines, terrain_row,
                             terrain_row_height)


#: discs per half width for a square section (no [SHAPE] table)
SQUARE_DISCS_PER_HALF = 4


def resample_shape(shape: np.ndarray) -> np.ndarray:
    """The carcass table at equally spaced width ratios, as many points as given.

    Parameters
    ----------
    shape : ndarray, shape (n, 2)
        Radius ratio, width ratio (Table 4-1), 2 <= n <= 10.

    Returns
    -------
    ndarray, shape (n, 2)
        Radius ratio (linear interpolation) at width ratios ``linspace(0, 1, n)``.
    """
    shape = np.asarray(shape, float)
    if shape.ndim != 2 or shape.shape[1] != 2 or not 2 <= shape.shape[0] <= 10:
        raise InputError("[SHAPE] needs 2 to 10 rows of (radius ratio, width ratio)", field="SHAPE")
    order = np.argsort(shape[:, 1], kind="stable")
    radius, width = shape[order, 0], shape[order, 1]
    if np.any(np.diff(width) <= 0) or width[0] < 0 or width[-1] <= 0:
        raise InputError("[SHAPE] width ratios must be distinct and non-negative", field="SHAPE")
    if np.any(radius <= 0) or np.any(radius > 1.0 + 1e-9):
        raise InputError("[SHAPE] radius ratios must lie in (0, 1]", field="SHAPE")
    # the table may not start at the centreline or end at the shoulder: rescale to [0, 1]
    # as ADAMS does (ratios are fractions of the half width)
    grid = np.linspace(0.0, 1.0, shape.shape[0])
    return np.column_stack([np.interp(grid * width[-1], width, radius), grid])


def carcass_discs(tyre, discs_per_half: int | None = None):
    """Lateral offsets, radii and widths [m] of the discs across the tyre.

    Parameters
    ----------
    tyre : Tyre
        ``unloaded_radius``, ``width`` and ``shape`` (or None: square section).
    discs_per_half : int, optional
        Override the number of discs on each side of the centreline (default:
        one per interval of the resampled table, or
        :data:`SQUARE_DISCS_PER_HALF` for a square section).

    Returns
    -------
    offsets, radii, widths : ndarray
        Disc centres along the spin axis from the wheel plane (symmetric),
        their radii and their widths. A tyre of zero width is one disc of
        unit weight in the wheel plane.
    """
    r0 = float(tyre.unloaded_radius)
    half = 0.5 * float(tyre.width)
    if half <= 0.0:
        return np.zeros(1), np.array([r0]), np.ones(1)
    table = None if tyre.shape is None else resample_shape(tyre.shape)
    if discs_per_half is None:
        n = SQUARE_DISCS_PER_HALF if table is None else table.shape[0] - 1
    else:
        n = int(discs_per_half)
        if n < 1:
            raise InputError(f"discs per half width must be >= 1, got {discs_per_half}",
                             field="discs")
    centres = (np.arange(n) + 0.5) / n  # width ratio of each disc centre
    ratio = np.ones(n) if table is None else np.interp(centres, table[:, 1], table[:, 0])
    offsets = np.r_[-centres[::-1], centres] * half
    radii = np.r_[ratio[::-1], ratio] * r0
    widths = np.full(2 * n, half / n)
    return offsets, radii, widths


# --- one disc against one straight piece of road ------------------------------

@nb.njit(cache=True, inline="always")
def _circle_primitives(r, s):
    """Primitives at s of the lower arc c(s) = sqrt(r^2 - s^2): (int c, int s c, int c^2/2)."""
    if s > r:
        s = r
    elif s < -r:
        s = -r
    c = math.sqrt(max(r * r - s * s, 0.0))
    return (0.5 * (s * c + r * r * math.asin(s / r)), -c * c * c / 3.0,
            0.5 * (r * r * s - s * s * s / 3.0))


@nb.njit(cache=True, inline="always")
def _chord(r, s0, q0, s1, q1):
    """Part ``[u0, u1]`` of the segment (s0,q0)-(s1,q1) inside the circle of radius r.

    Returns (u0, u1, inside) with s0 <= u0 <= u1 <= s1.
    """
    r2 = r * r
    in0 = s0 * s0 + q0 * q0 < r2
    in1 = s1 * s1 + q1 * q1 < r2
    if in0 and in1:
        return s0, s1, True
    es = s1 - s0
    eq = q1 - q0
    a = es * es + eq * eq
    if a <= 0.0:
        return s0, s0, False
    b = s0 * es + q0 * eq
    c = s0 * s0 + q0 * q0 - r2
    disc = b * b - a * c
    if disc <= 0.0:
        return s0, s0, False
    root = math.sqrt(disc)
    t0 = (-b - root) / a
    t1 = (-b + root) / a
    if in0:
        t0 = 0.0
    if in1:
        t1 = 1.0
    if t0 < 0.0:
        t0 = 0.0
    if t1 > 1.0:
        t1 = 1.0
    if t1 <= t0:
        return s0, s0, False
    return s0 + t0 * es, s0 + t1 * es, True


@nb.njit(cache=True)
def segment_area(depth, r):
    """Area cut from a disc of radius ``r`` by a flat chord ``depth`` deep (circular segment)."""
    if depth <= 0.0:
        return 0.0
    if depth >= 2.0 * r:
        return math.pi * r * r
    c = r - depth
    return r * r * math.acos(c / r) - c * math.sqrt(max(r * r - c * c, 0.0))


@nb.njit(cache=True)
def segment_depth(area, r):
    """Depth d of a flat cut that removes ``area`` from a disc of radius ``r``.

    Circular segment: ``A = r^2/2 (theta - sin theta)``, ``d = r (1 - cos(theta/2))``.
    theta from the inverse series of ``theta - sin theta`` in ``s = (12 A / r^2)^(1/3)``
    (``theta = s + s^3/60 + s^5/1400 + s^7/25200 + ...``, relative error < 1e-10
    for theta <= 0.4), polished by Newton steps for larger angles.
    """
    k = 2.0 * area / (r * r)
    if k <= 0.0:
        return 0.0
    if k >= 2.0 * math.pi:
        return 2.0 * r
    s = np.cbrt(6.0 * k)
    s2 = s * s
    th = s * (1.0 + s2 * (1.0 / 60.0 + s2 * (1.0 / 1400.0 + s2 * (1.0 / 25200.0
                                                              + s2 * 43.0 / 17248000.0))))
    if th > 0.4:
        if th > 2.0 * math.pi:
            th = 2.0 * math.pi
        for _ in range(8):
            step = (th - math.sin(th) - k) / max(1.0 - math.cos(th), 1e-300)
            th -= step
            # quadratic convergence: after a step below 1e-6 th the error is ~1e-12 th
            if abs(step) < 1e-6 * th:
                break
    sq = math.sin(0.25 * th)
    return 2.0 * r * sq * sq


# --- the road's section along a line, as maximal straight pieces ------------------

class SectionWalk(NamedTuple):
    """A walk along a section of the ground (:func:`section_walk`).

    ``aligned``: the line runs along x and the samples are the ground's break
    lines on the row handle ``(row, weight)``; sample k lies at ``s = a + k b``,
    k from ``k`` to ``k_end`` in steps of ``kdir``; ``h_a``, ``h_b`` the
    heights at the walk's ends.
    """

    aligned: bool
    row: int
    weight: float
    a: float
    b: float
    k: int
    k_end: int
    kdir: int
    h_a: float
    h_b: float


@nb.njit(cache=True, inline="always")
def section_walk(road, x0, y0, fx, fy, sa, sb, step):
    """Set up a walk along the line (x0, y0) + s (fx, fy), s from sa to sb.

    ``road`` is a terrain record (:mod:`tyrelab.road.terrain`). Returns a
    :class:`SectionWalk`. When the line runs along x (|fy| < 0.01; the rigs
    drive along x) the samples are the ground's break lines
    (:func:`~tyrelab.road.terrain.terrain_lines`) strictly inside (sa, sb) on
    the row of y0 (exact: the ground is linear between them; the small drift
    of y along the line is ignored); otherwise samples every ``step``.
    """
    if abs(fy) < 0.01:
        j, wy = terrain_row(road, y0)
        line0, spacing, inv_spacing, nx = terrain_lines(road)
        u0 = (x0 + sa * fx - line0) * inv_spacing
        u1 = (x0 + sb * fx - line0) * inv_spacing
        if fx > 0.0:
            k, k_end, kdir = max(int(math.floor(u0)) + 1, 0), min(int(math.ceil(u1)) - 1, nx - 1), 1
        else:
            k, k_end, kdir = min(int(math.ceil(u0)) - 1, nx - 1), max(int(math.floor(u1)) + 1, 0), -1
        return SectionWalk(True, j, wy, (line0 - x0) / fx, spacing / fx, k, k_end, kdir,
                           terrain_row_height(road, j, wy, x0 + sa * fx),
                           terrain_row_height(road, j, wy, x0 + sb * fx))
    n = max(int(math.ceil((sb - sa) / step)), 1)
    return SectionWalk(False, 0, 0.0, sa, (sb - sa) / n, 1, n - 1, 1,
                       terrain_height(road, x0 + sa * fx, y0 + sa * fy),
                       terrain_height(road, x0 + sb * fx, y0 + sb * fy))


@nb.njit(cache=True, inline="always")
def _height(road, walk, x0, y0, fx, fy, k, s):
    """Height of the walk's sample k at s."""
    if walk.aligned:
        return terrain_line_height(road, walk.row, walk.weight, k)
    return terrain_height(road, x0 + s * fx, y0 + s * fy)


@nb.njit(cache=True, inline="always")
def road_piece(road, breaks, x0, y0, fx, fy, sb, walk, k, s0, h0):
    """The maximal straight piece of the section that starts at (s0, h0).

    Consecutive samples on one line are merged (a flat block top is one
    piece); on grounds uniform across (``breaks``, the ground's
    :meth:`~tyrelab.road.terrain.Ground.profile_breaks`, not empty) the walk
    jumps from kink to kink. Returns ``(s1, h1, k, done)``: the piece's end,
    the index of the next unused sample and whether the end ``sb`` was reached.
    """
    a, b, k_end, kdir, h_b = walk.a, walk.b, walk.k_end, walk.kdir, walk.h_b
    jump = walk.aligned and breaks.shape[0] > 0 and kdir > 0
    if (k - k_end) * kdir > 0:
        return sb, h_b, k, True
    s1 = a + k * b
    h1 = _height(road, walk, x0, y0, fx, fy, k, s1)
    m = (h1 - h0) / (s1 - s0)
    while True:
        if jump:
            nxt = breaks[k]
            k = nxt if nxt > k else k + 1
        else:
            k += kdir
        if (k - k_end) * kdir > 0:
            if abs(h_b - (h1 + m * (sb - s1))) <= 1e-10:
                return sb, h_b, k, True
            return s1, h1, k, False
        s2 = a + k * b
        h2 = _height(road, walk, x0, y0, fx, fy, k, s2)
        if abs(h2 - (h1 + m * (s2 - s1))) > 1e-10:
            return s1, h1, k, False
        s1 = s2
        h1 = h2


@nb.njit(cache=True, inline="always")
def disc_intersection(road, breaks, step, r, xc, yc, zc, fx, fy, cosg, sa, sb):
    """Area and first moments of a disc's intersection with the road.

    ``road`` is a terrain record (:mod:`tyrelab.road.terrain`), ``breaks``
    its profile breakpoints (:func:`~tyrelab.road.terrain.profile_breaks`;
    empty when the ground varies across), ``step`` the sampling step [m]
    along sections that do not run along x. The disc (radius r, centre (xc, yc, zc)) lies in a plane with
    horizontal forward direction (fx, fy); s runs along it, q is the depth
    below the centre measured in the plane, ``(zc - h) / cos(camber)``.
    Returns ``(A, Ms, Mq)``: the area of the region inside the disc and
    below the road, ``int s dA`` and ``int q dA``. Each straight piece of
    the section is clipped to the circle exactly (:func:`_chord`); the
    road's integrals are added per piece, the arc's closed-form integrals
    once per run of contiguous inside pieces (they telescope).
    """
    area = 0.0
    ms = 0.0
    mq = 0.0
    run_open = False
    run_start = 0.0
    run_end = 0.0
    walk = section_walk(road, xc, yc, fx, fy, sa, sb, step)
    k = walk.k
    inv_cosg = 1.0 / cosg
    sixth = 1.0 / 6.0
    s0 = sa
    h0 = walk.h_a
    q0 = (zc - h0) * inv_cosg
    done = False
    while not done:
        s1, h1, k, done = road_piece(road, breaks, xc, yc, fx, fy, sb, walk, k, s0, h0)
        q1 = (zc - h1) * inv_cosg
        if s1 > s0:
            u0, u1, inside = _chord(r, s0, q0, s1, q1)
            if inside:
                if run_open and u0 != run_end:  # a gap: close the previous run
                    a1, m1, n1 = _circle_primitives(r, run_end)
                    a0, m0, n0 = _circle_primitives(r, run_start)
                    area += a1 - a0
                    ms += m1 - m0
                    mq += n1 - n0
                    run_open = False
                if not run_open:
                    run_open = True
                    run_start = u0
                run_end = u1
                qa = q0
                qb = q1
                if u0 != s0 or u1 != s1:  # clipped by the circle
                    m = (q1 - q0) / (s1 - s0)
                    qa = q0 + m * (u0 - s0)
                    qb = q0 + m * (u1 - s0)
                w = u1 - u0
                area -= 0.5 * w * (qa + qb)
                ms -= w * (qa * (2.0 * u0 + u1) + qb * (u0 + 2.0 * u1)) * sixth
                mq -= w * (qa * qa + qa * qb + qb * qb) * sixth
        s0 = s1
        h0 = h1
        q0 = q1
    if run_open:
        a1, m1, n1 = _circle_primitives(r, run_end)
        a0, m0, n0 = _circle_primitives(r, run_start)
        area += a1 - a0
        ms += m1 - m0
        mq += n1 - n0
    return area, ms, mq
