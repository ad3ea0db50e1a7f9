"""Contact-patch size laws of the 3D enveloping model from footprints (thesis 3.3.3, 4.4).

Half length (eq. 2.3 / 4.2) and half width (eq. 2.4 / 4.3), ``x = rho / R0``::

    a = PA1 R0 (x + PA2 sqrt(x))
    b = PB1 W0 (x + PB2 sqrt(x) + PB3 x sqrt(x))

Both are linear in the products of their parameters (``a / R0 = PA1 x +
(PA1 PA2) sqrt(x)``), so the least-squares fit is a linear one and exact
when the data follow the law. The thesis found PA1 = 0.15, PA2 = 7.06 and
PB1 = 0.0017, PB2 = 16006.5, PB3 = -77819.1, and that eq. 2.4 cannot follow
the width of a large off-road tyre, which hardly changes with deflection; it
recommends a straight line or a table of half width against deflection
instead: :func:`contact_width_table` (tyrelab's ``[CONTACT_WIDTH_CURVE]``,
which the enveloping model uses instead of eq. 2.4 when present).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..errors import InputError


def _points(deflection, size, unloaded_radius, what):
    d = np.asarray(deflection, float)
    s = np.asarray(size, float)
    keep = np.isfinite(d) & np.isfinite(s)
    d, s = d[keep], s[keep]
    if d.size < 2 or np.unique(np.round(d, 6)).size < 2:
        raise InputError(f"the {what} fit needs patch sizes at two or more deflections, got {d.size}",
                         field=what)
    if np.any(d <= 0) or np.any(s <= 0) or not unloaded_radius > 0:
        raise InputError(f"deflections, {what}s and the radius must be positive", field=what)
    return d, s


def contact_half_length(deflection, pa1, pa2, unloaded_radius):
    """Half contact length a [m] of eq. 2.3 at ``deflection`` [m]."""
    x = np.maximum(np.asarray(deflection, float), 0.0) / unloaded_radius
    return pa1 * unloaded_radius * (x + pa2 * np.sqrt(x))


def contact_half_width(deflection, pb1, pb2, pb3, unloaded_radius, width, clip=True):
    """Half contact width b [m] of eq. 2.4 at ``deflection`` [m]; with ``clip`` limited to
    [0, W0/2] as the enveloping model does."""
    x = np.maximum(np.asarray(deflection, float), 0.0) / unloaded_radius
    b = pb1 * width * (x + pb2 * np.sqrt(x) + pb3 * x * np.sqrt(x))
    return np.clip(b, 0.0, 0.5 * width) if clip else b


class LengthFit(NamedTuple):
    """Result of :func:`fit_contact_length`."""

    pa1: float
    pa2: float
    #: RMS of the half length [m] over the points
    rms: float
    points: int


def fit_contact_length(deflection, half_length, unloaded_radius) -> LengthFit:
    """PA1, PA2 of eq. 2.3 by least squares on the half length (thesis 4.4: 0.15, 7.06).

    ``a / R0 = c1 x + c2 sqrt(x)`` is solved for ``(c1, c2)`` by linear least
    squares; ``PA1 = c1``, ``PA2 = c2 / c1``.

    Parameters
    ----------
    deflection, half_length : array_like
        Tyre deflection [m] and half contact length a [m] of each footprint.
    unloaded_radius : float
        R0 [m].
    """
    d, a = _points(deflection, half_length, unloaded_radius, "contact length")
    x = d / unloaded_radius
    basis = np.column_stack([x, np.sqrt(x)])
    (c1, c2), *_ = np.linalg.lstsq(basis, a / unloaded_radius, rcond=None)
    if c1 == 0:
        raise InputError("the half lengths give PA1 = 0; eq. 2.3 cannot describe them", field="PA1")
    pa1, pa2 = float(c1), float(c2 / c1)
    # a patch grows as the tyre is pressed: eq. 2.3 must rise over the deflections measured
    grid = np.linspace(0.0, float(d.max()), 201)[1:]
    law = contact_half_length(grid, pa1, pa2, unloaded_radius)
    bad = np.flatnonzero((law <= 0) | (np.diff(np.r_[0.0, law]) < 0))
    if bad.size:
        lo, hi = int(np.argmin(d)), int(np.argmax(d))
        raise InputError(f"eq. 2.3 fitted to these sizes (PA1 = {pa1:.4g}, PA2 = {pa2:.4g}) gives a contact "
                         f"length that does not grow with deflection (from {1e3 * grid[bad[0]]:.0f} mm on): "
                         f"the lengths measured go from {2e3 * a[lo]:.0f} mm at {1e3 * d[lo]:.0f} mm to "
                         f"{2e3 * a[hi]:.0f} mm at {1e3 * d[hi]:.0f} mm; is the deflection (or load) "
                         "column the right one?", field="contact length")
    rms = float(np.sqrt(np.mean((contact_half_length(d, pa1, pa2, unloaded_radius) - a) ** 2)))
    return LengthFit(pa1, pa2, rms, int(d.size))


class WidthFit(NamedTuple):
    """Result of :func:`fit_contact_width`."""

    pb1: float
    pb2: float
    pb3: float
    #: RMS of the half width [m] over the points, of eq. 2.4 as written (unclipped)
    rms: float
    points: int


def fit_contact_width(deflection, half_width, unloaded_radius, width) -> WidthFit:
    """PB1, PB2, PB3 of eq. 2.4 by least squares on the half width (thesis 4.4: 0.0017,
    16006.5, -77819.1).

    ``b / W0 = c1 x + c2 sqrt(x) + c3 x sqrt(x)`` by linear least squares;
    ``PB1 = c1``, ``PB2 = c2 / c1``, ``PB3 = c3 / c1``. With fewer than three
    deflections ``PB3`` is 0 (two terms).
    """
    d, b = _points(deflection, half_width, unloaded_radius, "contact width")
    if not width > 0:
        raise InputError("the tyre width W0 must be positive", field="WIDTH")
    x = d / unloaded_radius
    columns = [x, np.sqrt(x), x * np.sqrt(x)]
    if np.unique(np.round(d, 6)).size < 3:
        columns = columns[:2]
    coef, *_ = np.linalg.lstsq(np.column_stack(columns), b / width, rcond=None)
    coef = np.r_[coef, np.zeros(3 - coef.size)]
    if coef[0] == 0:
        raise InputError("the half widths give PB1 = 0; eq. 2.4 cannot describe them", field="PB1")
    pb1, pb2, pb3 = float(coef[0]), float(coef[1] / coef[0]), float(coef[2] / coef[0])
    fitted = contact_half_width(d, pb1, pb2, pb3, unloaded_radius, width, clip=False)
    return WidthFit(pb1, pb2, pb3, float(np.sqrt(np.mean((fitted - b) ** 2))), int(d.size))


class WidthTable(NamedTuple):
    """Result of :func:`contact_width_table`."""

    #: (deflection [m], half width [m]) rows, deflection increasing: ``[CONTACT_WIDTH_CURVE]``
    table: np.ndarray
    #: straight line b = intercept + slope rho [m, -] by least squares
    intercept: float
    slope: float
    #: RMS of the half width [m] of the table (linear between rows, as the model reads it) and
    #: of the line, over the points
    rms: float
    rms_line: float


def contact_width_table(deflection, half_width, resolution=1e-3) -> WidthTable:
    """The half-width table the thesis recommends instead of eq. 2.4 (4.4), and its straight line.

    Points whose deflections lie within ``resolution`` [m] of each other are
    one row (their mean); the enveloping model interpolates linearly between
    rows and holds the end values beyond them.
    """
    d = np.asarray(deflection, float)
    b = np.asarray(half_width, float)
    keep = np.isfinite(d) & np.isfinite(b)
    d, b = d[keep], b[keep]
    if d.size < 1 or np.any(d <= 0) or np.any(b <= 0):
        raise InputError("a width table needs positive deflections and half widths", field="width")
    order = np.argsort(d, kind="stable")
    d, b = d[order], b[order]
    groups = np.r_[0, np.cumsum(np.diff(d) > resolution)]
    rows = np.array([[d[groups == g].mean(), b[groups == g].mean()] for g in np.unique(groups)])
    if rows.shape[0] >= 2:
        slope, intercept = np.polyfit(d, b, 1)
    else:
        slope, intercept = 0.0, float(rows[0, 1])
    table_at = np.interp(d, rows[:, 0], rows[:, 1])
    return WidthTable(rows, float(intercept), float(slope),
                      float(np.sqrt(np.mean((table_at - b) ** 2))),
                      float(np.sqrt(np.mean((intercept + slope * d - b) ** 2))))


def width_from_table(table, deflection):
    """Half width [m] of a ``[CONTACT_WIDTH_CURVE]`` table at ``deflection`` [m], as the enveloping
    model reads it (linear between rows, end values held)."""
    t = np.asarray(table, float)
    return np.interp(np.asarray(deflection, float), t[:, 0], t[:, 1])
