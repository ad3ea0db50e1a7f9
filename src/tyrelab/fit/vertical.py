"""Vertical stiffness from the flat-plate press (thesis 3.3.1, 4.2).

Two descriptions of the same test, as the thesis made them:

* a linear spring, the static part of eq. 4.1 (``Fz = k_z rho``), fitted by
  least squares through the origin to every sample (thesis: 659.6 N/mm with
  an RMS error of 2938.4 N on the raw hysteresis loop at 300 kPa);
* the load-deflection table ``[DEFLECTION_LOAD_CURVE]``: at every step of
  deflection, the mean of the loading and the unloading branch of the loop
  (Table 3-2: 10 mm steps; section 4.2: 5 mm in the property file), which the
  vertical law turns into a cubic spline (eq. 2.2).
"""

from __future__ import annotations

import warnings
from typing import NamedTuple

import numpy as np
from scipy.signal import find_peaks

from ..errors import InputError, naming
from .search import refine_minimum, term_sse

#: largest number of rows of a load-deflection table (ADAMS/Tire: 100 points, thesis 2.3.1)
MAX_TABLE_ROWS = 100


class LinearStiffness(NamedTuple):
    """Result of :func:`linear_stiffness`."""

    #: k_z [N/m]
    stiffness: float
    #: root-mean-square of F - k rho over the samples [N]
    rms: float
    #: samples fitted
    samples: int


def linear_stiffness(deflection, load) -> LinearStiffness:
    """Linear vertical stiffness of eq. 4.1, ``F = k_z rho``, fitted through the origin (thesis 4.2).

    Least squares over every sample: ``k_z = sum(rho_i F_i) / sum(rho_i^2)``,
    ``RMS = sqrt(mean((F_i - k_z rho_i)^2))``.

    Parameters
    ----------
    deflection, load : array_like
        Plate deflection [m] (from first touch, positive in compression) and
        load [N]: the raw loading/unloading samples, or the rows of a table.
    """
    d = np.asarray(deflection, float)
    f = np.asarray(load, float)
    if d.shape != f.shape or d.ndim != 1 or d.size < 2 or not np.all(np.isfinite(d) & np.isfinite(f)):
        raise InputError("a stiffness fit needs finite deflections and loads of equal length (>= 2)",
                         field="load_deflection")
    dd = float(d @ d)
    if not dd > 0:
        raise InputError("every deflection is zero: no stiffness to fit", field="deflection")
    k = float(d @ f) / dd
    return LinearStiffness(k, float(np.sqrt(np.mean((f - k * d) ** 2))), int(d.size))


#: a press record whose load rises from zero this far [m] (or this share of its deepest deflection,
#: if more) into it has travel before the touch, which is taken off
TOUCH_TRAVEL = 1e-3
TOUCH_SHARE = 0.02


def first_touch(deflection, load) -> float:
    """The deflection [m] of a press record at which the tyre touches the plate: 0 for a record
    counted from first touch (as Table 3-2), else the ram's travel before it.

    A press logs its ram from where it starts, above the plate, so a raw
    record may carry travel with no load before the tyre touches. On the
    loading samples below 15 % of the peak load the touch ``d0`` is fitted as
    a hinge: ``F = 0`` before it, ``F = a u + b u^2 + c u^3`` after, ``u = d - d0``
    (a tyre's curve may start softly, as the plate flattens the tread: the cubic
    term follows such a start; with ``a u + b u^2`` only, the touch came 0.7-0.8 mm
    late on the XZL's curve, 155 N at 1 mm, and 1.1-1.2 mm on a ``u^1.5`` start).
    For each candidate ``d0`` the coefficients follow by linear least squares;
    the candidate with the smallest residual, to a quarter of a sample step
    (:func:`~tyrelab.fit.search.refine_minimum`), is the touch. The unloaded
    samples pin it from one side, the rising ones from the other. A touch
    under :data:`TOUCH_TRAVEL` (or :data:`TOUCH_SHARE` of the deepest
    deflection) is the record's own noise: 0. A table's rows (as Table 3-2)
    are used alike. On a 0.5 mm stepped press 20 mm above the plate, with
    30 N of noise, the XZL's touch is found within 0.2 mm; a softer start is
    found late still (a ``u^1.5`` start 0.3-0.8 mm: near the touch its load
    is below the noise).
    """
    d = np.asarray(deflection, float)
    f = np.asarray(load, float)
    peak = float(np.max(f))
    if d.size < 4 or not peak > 0:
        return 0.0
    loading = np.zeros(d.size, bool)
    if is_table(d):
        loading[:] = True
    else:
        for part, direction in loop_branches(d):
            loading[part] |= direction > 0
        if not loading.any():
            loading[:] = True
    low = loading & (f < 0.15 * peak)
    if np.count_nonzero(low) < 4:
        return 0.0
    dl, fl = d[low], f[low]
    steps = np.diff(np.sort(dl))
    step = float(np.median(steps[steps > 0])) if np.any(steps > 0) else 0.0
    if not step > 0:
        return 0.0

    def sse(candidates):   # the hinge a u + b u^2 + c u^3, u = d - d0 past the touch, 0 before it
        u = np.clip(dl[None, :] - candidates[:, None], 0.0, None)       # (candidates, samples)
        return term_sse(np.stack([u, u * u, u * u * u], axis=2), fl)

    touch = refine_minimum(sse, float(dl.min()), float(dl.max()), 0.25 * step)
    if touch < max(TOUCH_TRAVEL, TOUCH_SHARE * float(np.max(d))):
        return 0.0
    return touch


def loop_branches(deflection, prominence=None) -> list[tuple[slice, int]]:
    """Monotone branches of a press record: ``[(slice, +1 loading / -1 unloading), ...]``.

    Turning points are the extremes of the deflection standing out by at least
    ``prominence`` [m] (default a tenth of its range), so noise on a branch
    does not cut it. A turning sample belongs to the branch that reached it,
    not to the one leaving it: where the hysteresis does not vanish as the
    press slows (a tyre's rubber and cords: loading above unloading by a
    share of the load), the sample at the top is a loading value, and read
    as the unloading branch's own it set the table's deepest row to the
    loading branch (+8 % on a stepped press with +-8 % hysteresis).
    """
    d = np.asarray(deflection, float)
    if prominence is None:
        prominence = 0.1 * float(np.ptp(d))
    turns = np.r_[find_peaks(d, prominence=prominence)[0], find_peaks(-d, prominence=prominence)[0]]
    cuts = np.unique(np.r_[0, turns, d.size - 1])
    out = []
    for a, b in zip(cuts[:-1], cuts[1:]):
        if b - a >= 2:
            first = int(a) if a == 0 else int(a) + 1
            out.append((slice(first, int(b) + 1), 1 if d[b] > d[a] else -1))
    return out


def _branch_at(d, f, grid, half):
    """Load of one branch at each grid deflection: a parabola fitted to the samples within
    ``half`` of it (the branch's own noise averages out; a straight line would be biased by the
    curve's bend, f'' E[u^2] / 2), else linear interpolation; NaN more than ``half`` beyond
    the branch's ends. Within ``half`` beyond an end a straight line through the window's
    samples extrapolates (its bend bias over so short a reach is a few newtons): a branch
    leaving a turning point does not hold the turning sample (:func:`loop_branches`)."""
    order = np.argsort(d, kind="stable")
    d, f = d[order], f[order]
    out = np.full(grid.size, np.nan)
    for j, g in enumerate(grid):
        if g < d[0] - half or g > d[-1] + half:
            continue
        near = np.abs(d - g) <= half * (1.0 + 1e-9)  # a sample on the window's edge, as on a stepped press
        count, spread = np.count_nonzero(near), np.ptp(d[near]) if near.any() else 0.0
        inside = d[0] <= g <= d[-1]
        if inside and count >= 6 and spread > 0.5 * half:
            out[j] = np.polyfit((d[near] - g) / half, f[near], 2)[-1]
        elif not inside and count >= 2 and spread > 0.0:
            out[j] = np.polyfit((d[near] - g) / half, f[near], 1)[-1]
        else:
            out[j] = np.interp(g, d, f)
    return out


class LoadDeflectionTable(NamedTuple):
    """Result of :func:`load_deflection_table` (SI)."""

    #: deflections [m] of the rows, from 0
    deflection: np.ndarray
    #: table load [N]: the mean of the loading and unloading branches (non-decreasing)
    load: np.ndarray
    #: mean loading and unloading branch at each row [N] (NaN where none reaches)
    loading: np.ndarray
    unloading: np.ndarray
    #: branches of the loop used (0: the file was a table, used as it is)
    branches: int
    #: rows raised to the previous row's load so that the table never falls
    raised: int


def is_table(deflection) -> bool:
    """True when the deflections rise strictly and there are at most :data:`MAX_TABLE_ROWS` of them
    (a table as the thesis's Table 3-2), False for a raw record (a loop or a ramp to average)."""
    d = np.asarray(deflection, float)
    return d.size <= MAX_TABLE_ROWS and bool(np.all(np.diff(d) > 0))


def load_deflection_table(deflection, load, step=0.005) -> LoadDeflectionTable:
    """The ``[DEFLECTION_LOAD_CURVE]`` of a plate press (thesis 3.3.1 Table 3-2, 4.2).

    A raw record is cut into loading and unloading branches
    (:func:`loop_branches`); at each multiple of ``step`` [m] from zero up to
    the deepest deflection every branch's load is read (a local parabola
    through its samples within half a step), the branches of each direction
    averaged, and the row is the mean of loading and unloading::

        F_table(rho_j) = (F_loading(rho_j) + F_unloading(rho_j)) / 2

    so a hysteresis symmetric about the elastic curve (a viscous one,
    ``c rho_dot``) cancels. A record that is already a table (:func:`is_table`)
    is used row by row. The table starts at (0, 0) (deflection is counted
    from first touch) and never falls (a row below the one before is raised
    to it and counted in ``raised``).
    """
    d = np.asarray(deflection, float)
    f = np.asarray(load, float)
    if d.shape != f.shape or d.ndim != 1 or d.size < 2 or not np.all(np.isfinite(d) & np.isfinite(f)):
        raise InputError("a load-deflection table needs finite deflections and loads of equal length",
                         field="load_deflection")
    if not step > 0:
        raise InputError(f"the table step must be positive, got {step}", field="step")
    if is_table(d):
        rows_d, rows_f = d[d > 0], f[d > 0]
        loading, unloading, branches = rows_f.copy(), np.full(rows_f.size, np.nan), 0
        rows_d, rows_f = np.r_[0.0, rows_d], np.r_[0.0, rows_f]
        loading, unloading = np.r_[0.0, loading], np.r_[0.0, unloading]
    else:
        parts = loop_branches(d)
        top = float(np.max(d))
        n = int(np.floor(top / step + 1e-9))
        if n > MAX_TABLE_ROWS - 1:
            raise InputError(f"a step of {step * 1e3:g} mm over {top * 1e3:g} mm gives more than "
                             f"{MAX_TABLE_ROWS} rows; choose a larger step", field="step")
        grid = step * np.arange(n + 1)
        sums = {1: [], -1: []}
        for part, direction in parts:
            sums[direction].append(_branch_at(d[part], f[part], grid, 0.5 * step))
        with warnings.catch_warnings():  # "mean of empty slice" where no branch reaches a row
            warnings.simplefilter("ignore", RuntimeWarning)
            loading = np.nanmean(sums[1], axis=0) if sums[1] else np.full(grid.size, np.nan)
            unloading = np.nanmean(sums[-1], axis=0) if sums[-1] else np.full(grid.size, np.nan)
            rows_f = np.nanmean(np.vstack([loading, unloading]), axis=0)
        keep = np.isfinite(rows_f)
        keep[0] = True
        rows_d, rows_f = grid[keep], np.where(np.isfinite(rows_f[keep]), rows_f[keep], 0.0)
        loading, unloading, branches = loading[keep], unloading[keep], len(parts)
        rows_f[0] = 0.0
    rows_f = np.maximum(rows_f, 0.0)
    monotone = np.maximum.accumulate(rows_f)
    raised = int(np.count_nonzero(monotone > rows_f))
    if rows_d.size < 2 or not monotone[-1] > 0:
        raise InputError("the press record gives no load-deflection table (no load above zero)",
                         field="load_deflection")
    return LoadDeflectionTable(rows_d, monotone, loading, unloading, branches, raised)


def press_table(test) -> LoadDeflectionTable:
    """:func:`load_deflection_table` of a campaign's plate press (a
    :class:`~tyrelab.fit.lab_files.LoadDeflection`); a record it refuses is named by its file."""
    with naming(test.source):
        return load_deflection_table(test.deflection, test.load, test.step)


def hysteresis(table: LoadDeflectionTable) -> float:
    """Largest half difference of the loading and unloading branches [N] (0 for a table)."""
    gap = 0.5 * np.abs(table.loading - table.unloading)
    gap = gap[np.isfinite(gap)]
    return float(gap.max()) if gap.size else 0.0


def table_rms(table_deflection, table_load, deflection, load) -> float:
    """RMS [N] of a measured record against the cubic spline of a table (the vertical law,
    eq. 2.2, as the models evaluate it)."""
    from ..tyre.vertical import VerticalLaw
    law = VerticalLaw.table(np.asarray(table_deflection, float), np.asarray(table_load, float), 0.0)
    predicted = law.static_load(np.maximum(np.asarray(deflection, float), 0.0))
    return float(np.sqrt(np.mean((predicted - np.asarray(load, float)) ** 2)))
