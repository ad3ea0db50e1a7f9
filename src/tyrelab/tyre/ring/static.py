"""Static virtual tests of the ring (thesis 3.3): press, footprint.

The rim is held level (spin axis along y, no spin) and moved down onto a
plate or cleat in small ramps; after each ramp the belt relaxes to static
equilibrium with an extra velocity damping (dynamic relaxation,
``ring_params(..., relax=rate)``), and the mean rim load over the last part
of the hold is recorded -- as the lab press measured (rim fixed, hydraulic
actuator, sinusoidal displacement, load averaged).
"""

from __future__ import annotations

import numba as nb
import numpy as np
import pandas as pd

from ...errors import InputError
from . import layout as L
from .kernel import ring_advance
from .tread import ACC_DEFL, ACC_SIZE

#: press rate [m/s], hold time [s] and averaging window [s]
PRESS_RATE = 0.25
HOLD = 0.12
WINDOW = 0.02
DT = 1e-3


@nb.njit(cache=True)
def press_path(cp, ts, gp, z, zinfo, z_start, heights, rate, hold, window, dt, res, blocks):
    """Lower the rim centre from ``z_start`` through ``heights``.

    ``res[k] = (Fx, Fy, Fz, deflection, Mx, My, Mz)`` averaged over the last
    ``window`` of the hold at height k; if ``blocks`` has a row per height,
    it receives each block's normal force at the end of the hold.
    """
    rim = np.zeros(6)
    acc = np.zeros(ACC_SIZE)
    none = np.zeros(1)
    zc = z_start
    for k in range(heights.shape[0]):
        target = heights[k]
        n_ramp = int(np.ceil(abs(target - zc) / (rate * dt)))
        if n_ramp > 0:
            vz = (target - zc) / (n_ramp * dt)
            for s in range(n_ramp):
                ring_advance(cp, ts, gp, z, zinfo, 0.0, 0.0, zc, 0.0, 1.0, 0.0, 0.0, 0.0, vz,
                             0.0, dt, rim, acc, none)
                zc += vz * dt
        zc = target
        n_hold = int(np.ceil(hold / dt))
        n_win = int(np.ceil(window / dt))
        for q in range(7):
            res[k, q] = 0.0
        for s in range(n_hold):
            last = s == n_hold - 1 and blocks.shape[0] == heights.shape[0]
            ring_advance(cp, ts, gp, z, zinfo, 0.0, 0.0, zc, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0,
                         0.0, dt, rim, acc, blocks[k] if last else none)
            if s >= n_hold - n_win:
                res[k, 0] += rim[0] / n_win
                res[k, 1] += rim[1] / n_win
                res[k, 2] += rim[2] / n_win
                res[k, 3] = acc[ACC_DEFL]
                res[k, 4] += rim[3] / n_win
                res[k, 5] += rim[4] / n_win
                res[k, 6] += rim[5] / n_win
    return zc


def settle(cp, ts, grid, heights, start=None, rate=PRESS_RATE, hold=HOLD, blocks=None):
    """Press the ring (state ``ts``, relaxed ``cp``) through centre ``heights``
    [m] on ``grid``; returns the ``(k, 7)`` result table of :func:`press_path`
    (``blocks``, if given, an array ``(k, N*NB)`` for the block normal forces)."""
    from ..kernel import road_info
    heights = np.asarray(heights, float)
    r0 = cp[L.CP_R0]
    z_top = float(grid.z.max())
    z0 = z_top + r0 + 0.002 if start is None else float(start)
    res = np.zeros((heights.size, 7))
    if blocks is None:
        blocks = np.zeros((1, 1))
    press_path(cp, ts, grid.params, grid.z, road_info(grid), z0, heights, rate, hold, WINDOW,
               DT, res, blocks)
    return res


def block_positions(cp, ts):
    """World positions ``(x, y, z)`` of the block tips of a non-spinning ring
    whose rim centre is at the origin with spin axis y (psi = 0)."""
    n = int(cp[L.CP_N])
    nb_ = int(cp[L.CP_NB])
    o = L.TS_HEADER
    seg = lambda k: ts[o + k * n:o + (k + 1) * n]  # noqa: E731
    p1, p2, y, b = seg(L.S_P1), seg(L.S_P2), seg(L.S_Y), seg(L.S_B)
    d1 = np.roll(p1, -1) - np.roll(p1, 1)
    d2 = np.roll(p2, -1) - np.roll(p2, 1)
    dl = np.hypot(d1, d2)
    n1, n2 = d2 / dl, -d1 / dl
    t1, t2 = -n2, n1
    blk = lambda key: cp[int(cp[key]):int(cp[key]) + n * nb_].reshape(n, nb_)  # noqa: E731
    yj, sj, hj = blk(L.CP_OFF_BY), blk(L.CP_OFF_BC), blk(L.CP_OFF_BH)
    # psi = 0: E1 = x, E2 = z, a = y
    x = p1[:, None] + sj * t1[:, None] + (hj - yj * b[:, None]) * n1[:, None]
    zz = p2[:, None] + sj * t2[:, None] + (hj - yj * b[:, None]) * n2[:, None]
    yy = y[:, None] + yj
    return x.ravel(), yy.ravel(), zz.ravel()


def ring_static_press(model, grid, top, deflections) -> pd.DataFrame:
    """Load on a plate or cleat at each press deflection (rim held, belt relaxed).

    Parameters
    ----------
    model : TyreModel
        A ring model (``contact="ring"`` or ``"ring-tp"``).
    grid : RoadGrid
        The plate or cleat.
    top : float
        Height of the obstacle's top [m]; deflection is counted from first touch.
    deflections : array
        Press deflections [m], >= 0.

    Returns
    -------
    DataFrame with ``deflection, load, FX, FY, DEFLECT``.
    """
    from .model import RELAX_RATE, nominal_state, ring_params
    d = np.atleast_1d(np.asarray(deflections, float))
    if np.any(~np.isfinite(d)) or np.any(d < 0):
        raise InputError("press deflections must be finite and >= 0", field="deflection")
    opts = dict(model.options)
    opts["relax"] = RELAX_RATE
    if np.ptp(grid.z, axis=1).max() > 0 and "lateral_samples" not in opts:
        # the obstacle varies across the wheel (a longitudinal cleat): sample
        # the blocks' strips across their width too, every ~10 mm
        opts["lateral_samples"] = 4
    cp = ring_params(model.tyre, grid, tread_pattern=model.contact == "ring-tp", **opts)
    ts = nominal_state(cp)
    order = np.argsort(d, kind="stable")
    r0 = model.tyre.unloaded_radius
    res = settle(cp, ts, grid, top + r0 - d[order], start=top + r0 + 0.002)
    out = np.empty_like(res)
    out[order] = res
    return pd.DataFrame({"deflection": d, "load": out[:, 2], "FX": out[:, 0], "FY": out[:, 1],
                         "DEFLECT": np.maximum(out[:, 3], 0.0)})


def ring_footprint(model, load, deflection=None) -> dict:
    """Contact-pressure map and outline of the standing tyre on a flat plate.

    The rim is pressed onto the plate to the deflection of ``load`` [N] on the
    tyre's load-deflection law (or to ``deflection`` [m]) and the belt relaxes.

    Returns a dict: ``x, y`` block-tip positions on the plate [m], ``force``
    block normal forces [N], ``pressure`` [Pa] (force / block area),
    ``outline`` (closed polygon ``(k, 2)`` around the contacting blocks,
    extended by half a block pitch), ``length``, ``width`` [m], ``cell``
    (block cell length and width [m]), ``load``
    [N] (plate force), ``deflection`` [m], ``pressure_inflation`` [Pa].
    """
    from ...road.obstacles import Flat
    from .model import RELAX_RATE, nominal_state, ring_params
    tyre = model.tyre
    d = tyre.static_deflection(float(load)) if deflection is None else float(deflection)
    grid = Flat().grid()
    opts = dict(model.options)
    opts["relax"] = RELAX_RATE
    cp = ring_params(tyre, grid, tread_pattern=model.contact == "ring-tp", **opts)
    ts = nominal_state(cp)
    n = int(cp[L.CP_N])
    nb_ = int(cp[L.CP_NB])
    blocks = np.zeros((1, n * nb_))
    res = settle(cp, ts, grid, [tyre.unloaded_radius - d], blocks=blocks)
    return footprint_from_blocks(cp, ts, blocks[0], res[0, 2], d, tyre.pressure)


def footprint_from_blocks(cp, ts, force, load, deflection, pressure) -> dict:
    """Footprint dict (see :func:`ring_footprint`) from block forces of a pressed state."""
    n = int(cp[L.CP_N])
    nb_ = int(cp[L.CP_NB])
    x, y, _ = block_positions(cp, ts)
    area = cp[int(cp[L.CP_OFF_BK]):int(cp[L.CP_OFF_BK]) + n * nb_]
    with np.errstate(invalid="ignore", divide="ignore"):
        p = np.where(area > 0, force / np.where(area > 0, area, 1.0), 0.0)
    on = force > 0
    dx = 0.5 * cp[L.CP_L0]
    dy = cp[L.CP_HALFW] / nb_
    outline = np.zeros((0, 2))
    length = width = 0.0
    if on.any():
        xs, ys = x[on], y[on]
        js = (np.arange(n * nb_) % nb_)[on]
        length = xs.max() - xs.min() + 2 * dx
        width = ys.max() - ys.min() + 2 * dy
        # outline: for each lateral column of blocks the leading and trailing edge
        cols = np.unique(js)
        lead = [(xs[js == c].max() + dx, ys[js == c].mean()) for c in cols]
        trail = [(xs[js == c].min() - dx, ys[js == c].mean()) for c in cols[::-1]]
        pts = [(lead[0][0], lead[0][1] - dy)] + lead + [(lead[-1][0], lead[-1][1] + dy),
                                                        (trail[0][0], trail[0][1] + dy)] + \
            trail + [(trail[-1][0], trail[-1][1] - dy)]
        outline = np.array(pts + [pts[0]])
    return {"x": x, "y": y, "force": force, "pressure": p, "outline": outline,
            "length": float(length), "width": float(width), "load": float(load),
            "cell": (2.0 * dx, 2.0 * dy),
            "deflection": float(deflection), "pressure_inflation": float(pressure)}
