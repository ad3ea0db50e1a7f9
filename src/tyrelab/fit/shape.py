"""The carcass ``[SHAPE]`` table from the measured outer contour (thesis 3.3.2, 4.3, Table 4-1).

ADAMS/Tire (and tyrelab's volume model, :func:`tyrelab.tyre.contact.shape.resample_shape`)
takes up to ten points (radius ratio, width ratio) over half the section,
assumes the carcass symmetric, and *resamples the points to the same number
of equally spaced width ratios* before it cuts the discs. The shape a model
sees is therefore the polyline through equally spaced points; the best table
of ``n`` points is that polyline fitted to the contour, with its knots at
``w_k = k / (n - 1)``::

    r(w) / R0 = sum_k v_k phi_k(w)         (phi_k: the hat function of knot k)

``v`` by linear least squares over every measured point, both halves folded
onto one (``w = |y| / (W0 / 2)``), with a faint second-difference penalty
so that an interval holding no point is bridged straight. Thesis Table 4-1's
nine unequally spaced points are, as the models resample them, a different
polyline from the one printed; :func:`shape_rms` measures both against the
contour.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..errors import InputError

#: most points of a [SHAPE] table (ADAMS/Tire, thesis 4.3)
MAX_POINTS = 10
#: weight of the second-difference penalty relative to the data's own weight
SMOOTHING = 1e-6


class FoldedProfile(NamedTuple):
    """Contour points folded onto one half and normalised."""

    width_ratio: np.ndarray
    radius_ratio: np.ndarray
    #: R0 and half width [m] used to normalise
    unloaded_radius: float
    half_width: float
    #: RMS [-] of the radius ratio between the two halves where both were measured (NaN: one side)
    asymmetry: float
    #: the centre line's ``y`` [m] in the points as given (:func:`profile_centre`; 0: measured from it)
    centre: float = 0.0


def profile_centre(y, radius) -> float:
    """The centre line's ``y`` [m] of a contour measured across the whole section from one side.

    A scan across the tyre from one sidewall to the other gives ``y`` of one
    sign (0 to W0, say) with the crown in the middle; read as distances from
    the centre line, its sidewall would become the crown. Such a contour --
    all ``y`` of one sign, and both of its ends below half way from the
    lowest to the highest radius -- is centred on the midpoint of the two
    places where it crosses that half-way level (the shoulders). Any other
    contour (both signs, or one half with its crown at ``y = 0``) is taken as
    measured from the centre line: 0.
    """
    y = np.asarray(y, float)
    r = np.asarray(radius, float)
    if y.size < 3 or not (np.all(y >= 0) or np.all(y <= 0)):
        return 0.0
    order = np.argsort(y, kind="stable")
    y, r = y[order], r[order]
    level = r.min() + 0.5 * (r.max() - r.min())
    above = np.flatnonzero(r >= level)
    if not (r[0] < level and r[-1] < level and above.size):
        return 0.0
    i, j = int(above[0]), int(above[-1])
    # where the contour crosses the level, interpolated on each side
    rise = y[i - 1] + (level - r[i - 1]) * (y[i] - y[i - 1]) / (r[i] - r[i - 1])
    fall = y[j] + (level - r[j]) * (y[j + 1] - y[j]) / (r[j + 1] - r[j])
    return float(0.5 * (rise + fall))


def fold_profile(y, radius, unloaded_radius=None, half_width=None) -> FoldedProfile:
    """Contour points ``(y, radius)`` [m] as (width ratio, radius ratio) of one half.

    ``unloaded_radius`` defaults to the largest radius measured and
    ``half_width`` to the largest ``|y|``; points beyond the half width are
    dropped. A whole section scanned from one side is centred first
    (:func:`profile_centre`).
    """
    y = np.asarray(y, float)
    r = np.asarray(radius, float)
    if y.shape != r.shape or y.size < 3 or not np.all(np.isfinite(y) & np.isfinite(r)) or np.any(r <= 0):
        raise InputError("a carcass profile needs at least 3 finite points with positive radii",
                         field="carcass_profile")
    centre = profile_centre(y, r)
    y = y - centre
    r0 = float(unloaded_radius) if unloaded_radius else float(r.max())
    hw = float(half_width) if half_width else float(np.abs(y).max())
    if not (r0 > 0 and hw > 0):
        raise InputError("the radius and half width to normalise by must be positive", field="SHAPE")
    w = np.abs(y) / hw
    keep = w <= 1.0 + 1e-9
    asym = float("nan")
    left, right = y < 0, y > 0
    if left.sum() >= 2 and right.sum() >= 2:
        lo = max(w[left].min(), w[right].min())
        hi = min(w[left].max(), w[right].max())
        if hi > lo:
            grid = np.linspace(lo, hi, 50)
            ol, orr = np.argsort(w[left]), np.argsort(w[right])
            a = np.interp(grid, w[left][ol], r[left][ol] / r0)
            b = np.interp(grid, w[right][orr], r[right][orr] / r0)
            asym = float(np.sqrt(np.mean((a - b) ** 2)))
    return FoldedProfile(np.minimum(w[keep], 1.0), r[keep] / r0, r0, hw, asym, centre)


def hat_basis(width_ratio, n) -> np.ndarray:
    """Hat functions of ``n`` equally spaced knots on [0, 1] at ``width_ratio``: ``(points, n)``."""
    w = np.clip(np.asarray(width_ratio, float), 0.0, 1.0)
    knots = np.linspace(0.0, 1.0, n)
    return np.clip(1.0 - np.abs(w[:, None] - knots[None, :]) * (n - 1), 0.0, None)


def shape_rms(table, width_ratio, radius_ratio, resampled=True) -> float:
    """RMS [-] of a ``[SHAPE]`` table (radial, width rows) against folded contour points; with
    ``resampled`` the table as the models see it (resampled to equal steps), else as printed."""
    t = np.asarray(table, float)
    if resampled:
        from ..tyre.contact.shape import resample_shape
        t = resample_shape(t)
    order = np.argsort(t[:, 1])
    model = np.interp(width_ratio, t[order, 1], t[order, 0])
    return float(np.sqrt(np.mean((model - np.asarray(radius_ratio, float)) ** 2)))


class ShapeFit(NamedTuple):
    """Result of :func:`fit_carcass_shape`."""

    #: ``[SHAPE]`` rows (radius ratio, width ratio), width 0 to 1 in equal steps
    table: np.ndarray
    #: RMS of the radius ratio over the folded points [-] (times R0: [m])
    rms: float
    profile: FoldedProfile


def fit_carcass_shape(y, radius, unloaded_radius=None, half_width=None, points=None) -> ShapeFit:
    """The ``[SHAPE]`` table of a measured contour (module docstring; thesis 4.3).

    Parameters
    ----------
    y, radius : array_like
        Lateral position [m] from the centre line (either side) and radius
        [m] from the spin axis of each contour point (a whole section scanned
        from one side is centred first: :func:`profile_centre`).
    unloaded_radius, half_width : float, optional
        R0 and W0 / 2 [m] the ratios are taken of (default: the contour's own
        largest radius and |y|).
    points : int, optional
        Rows of the table, 2 to 10; default: of 3 to 10 rows, the table with the
        smallest RMS (equal steps of a different size meet the contour's bends
        differently, so more rows are not always closer), the fewer rows on a tie.
    """
    prof = fold_profile(y, radius, unloaded_radius, half_width)
    if points is None:
        fits = [_fit(prof, n) for n in range(3, MAX_POINTS + 1)]
        return min(fits, key=lambda f: (round(f.rms, 9), f.table.shape[0]))
    if not (isinstance(points, (int, np.integer)) and 2 <= points <= MAX_POINTS):
        raise InputError(f"a [SHAPE] table has 2 to {MAX_POINTS} points, got {points}", field="points")
    return _fit(prof, int(points))


def _fit(prof: FoldedProfile, points: int) -> ShapeFit:
    a = hat_basis(prof.width_ratio, points)
    d2 = np.diff(np.eye(points), 2, axis=0) * np.sqrt(SMOOTHING * len(prof.width_ratio))
    lhs = np.vstack([a, d2])
    rhs = np.r_[prof.radius_ratio, np.zeros(d2.shape[0])]
    v, *_ = np.linalg.lstsq(lhs, rhs, rcond=None)
    v = np.clip(v, 1e-3, 1.0)  # radius ratios lie in (0, 1]
    table = np.column_stack([v, np.linspace(0.0, 1.0, points)])
    rms = float(np.sqrt(np.mean((a @ v - prof.radius_ratio) ** 2)))
    return ShapeFit(table, rms, prof)
