"""Static virtual tests of the ring (thesis 3.3): press, footprint.

The rim is held level (spin axis along y, no spin) and moved down onto a
plate or cleat in small ramps; after each ramp the belt relaxes to static
equilibrium with an extra velocity damping (dynamic relaxation,
``ring_params(..., relax=rate)``), and the mean rim load over the last part
of the hold is recorded -- as the lab press measured (rim fixed, hydraulic
actuator, sinusoidal displacement, load averaged).

The press over the generic wheel step (:func:`tyrelab.tyre.wheel.wheel_step`)
gives :func:`ring_static_press` bit for bit when it: takes the wheel of
``TyreModel.wheel(grid, 0.0, static=True)`` (relaxed parameters, strips
sampled across on a road that varies across, the inflated nominal belt);
starts the centre at ``top + R0 + 0.002`` (x = y = 0, axis y, no spin)
and visits the heights in order of increasing deflection; moves to each in
``n = ceil(|target - z| / (PRESS_RATE DT))`` steps of ``DT`` at ``vz = (target
- z) / (n DT)``, each step posed at the centre *before* the step with
velocity ``(0, 0, vz)``, then ``z += vz DT``, and ``z = target`` after the
ramp; holds ``ceil(HOLD / DT)`` steps at zero velocity; averages the loads
of the last ``ceil(WINDOW / DT)`` of them as ``sum(load / n_win)`` in step
order; and reports ``max(deflection of the hold's last step, 0)``. That
deflection is ``patch[ACC_DEFL]`` here and ``WheelLoads.deflection`` there:
they differ only where blocks press but no contact point is nearer the
centre than R0 (then 0 here, 1e-9 there; seen at deflection 0 on the
longitudinal cleat). ``wheel.state.block_force`` after the last hold step
is the footprint.
"""

from __future__ import annotations

import numba as nb
import numpy as np
import pandas as pd

from ...errors import InputError
from ..wheel import WheelPose
from .kernel import ring_advance
from .tread import ACC_DEFL

#: press rate [m/s], hold time [s] and averaging window [s]
PRESS_RATE = 0.25
HOLD = 0.12
WINDOW = 0.02
DT = 1e-3


@nb.njit(cache=True)
def press_path(params, state, road, z_start, heights, rate, hold, window, dt, res):
    """Lower the rim centre from ``z_start`` through ``heights``; returns the last height.

    The rim is held level at x = y = 0 (spin axis y, no spin). To each
    height it moves in steps of ``dt`` at the constant speed that reaches it
    in a whole number of steps no faster than ``rate``, then holds it for
    ``hold``. ``res[k] = (Fx, Fy, Fz, deflection, Mx, My, Mz)``: the loads
    averaged over the last ``window`` of the hold at height k, the
    deflection of the hold's last step. ``state.block_force`` then holds
    the blocks' normal forces at the end of the last hold.
    """
    zc = z_start
    for k in range(heights.shape[0]):
        target = heights[k]
        n_ramp = int(np.ceil(abs(target - zc) / (rate * dt)))
        if n_ramp > 0:
            vz = (target - zc) / (n_ramp * dt)
            for s in range(n_ramp):
                ring_advance(params, state, road,
                             WheelPose(0.0, 0.0, zc, 0.0, 1.0, 0.0, 0.0, 0.0, vz, 0.0), dt)
                zc += vz * dt
        zc = target
        n_hold = int(np.ceil(hold / dt))
        n_win = int(np.ceil(window / dt))
        for q in range(7):
            res[k, q] = 0.0
        at = WheelPose(0.0, 0.0, zc, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        for s in range(n_hold):
            _, fx, fy, fz, mx, my, mz = ring_advance(params, state, road, at, dt)
            if s >= n_hold - n_win:
                res[k, 0] += fx / n_win
                res[k, 1] += fy / n_win
                res[k, 2] += fz / n_win
                res[k, 3] = state.patch[ACC_DEFL]
                res[k, 4] += mx / n_win
                res[k, 5] += my / n_win
                res[k, 6] += mz / n_win
    return zc


def settle(params, state, road, heights, start=None, rate=PRESS_RATE, hold=HOLD):
    """Press the ring (``state``, relaxed ``params``) through centre ``heights``
    [m] on ``road`` (a :class:`~tyrelab.road.grid.RoadSurface`); returns the
    ``(k, 7)`` result table of :func:`press_path`.

    Starts 2 mm above the touch of the road's highest point unless
    ``start`` [m] is given.
    """
    heights = np.asarray(heights, float)
    r0 = params.unloaded_radius
    z0 = road.zmax + r0 + 0.002 if start is None else float(start)
    res = np.zeros((heights.size, 7))
    press_path(params, state, road, z0, heights, rate, hold, WINDOW, DT, res)
    return res


def block_positions(params, state):
    """World positions ``(x, y, z)`` of the block tips of a non-spinning ring
    whose rim centre is at the origin with spin axis y (psi = 0)."""
    n = params.n_segments
    nb_ = params.n_blocks
    p1, p2, y, b = state.p1, state.p2, state.y, state.beta
    d1 = np.roll(p1, -1) - np.roll(p1, 1)
    d2 = np.roll(p2, -1) - np.roll(p2, 1)
    dl = np.hypot(d1, d2)
    n1, n2 = d2 / dl, -d1 / dl
    t1, t2 = -n2, n1
    yj, sj, hj = (a.reshape(n, nb_) for a in (params.block_y, params.block_s, params.block_h))
    # psi = 0: E1 = x, E2 = z, a = y
    x = p1[:, None] + sj * t1[:, None] + (hj - yj * b[:, None]) * n1[:, None]
    zz = p2[:, None] + sj * t2[:, None] + (hj - yj * b[:, None]) * n2[:, None]
    yy = y[:, None] + yj
    return x.ravel(), yy.ravel(), zz.ravel()


def static_params(model, grid):
    """The relaxed :class:`~.records.RingParams` of a ring ``model`` for a static test on ``grid``.

    As the registry builds it for static tests (``static=True``): the
    model's options plus ``relax=RELAX_RATE``, and, where the road varies
    across the wheel, strips sampled across the blocks' width too
    (:func:`~.model.ring_params`).
    """
    return model.contact_params(grid, static=True)


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
    from .model import nominal_state
    d = np.atleast_1d(np.asarray(deflections, float))
    if np.any(~np.isfinite(d)) or np.any(d < 0):
        raise InputError("press deflections must be finite and >= 0", field="deflection")
    params = static_params(model, grid)
    state = nominal_state(params)
    order = np.argsort(d, kind="stable")
    r0 = model.tyre.unloaded_radius
    res = settle(params, state, grid.surface(), top + r0 - d[order], start=top + r0 + 0.002)
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
    from .model import nominal_state
    tyre = model.tyre
    d = tyre.static_deflection(float(load)) if deflection is None else float(deflection)
    grid = Flat().grid()
    params = static_params(model, grid)
    state = nominal_state(params)
    res = settle(params, state, grid.surface(), [tyre.unloaded_radius - d])
    return footprint_from_blocks(params, state, state.block_force.copy(), res[0, 2], d,
                                 tyre.pressure)


def footprint_from_blocks(params, state, force, load, deflection, pressure) -> dict:
    """Footprint dict (see :func:`ring_footprint`) from block forces of a pressed state."""
    n = params.n_segments
    nb_ = params.n_blocks
    x, y, _ = block_positions(params, state)
    area = params.block_area
    with np.errstate(invalid="ignore", divide="ignore"):
        p = np.where(area > 0, force / np.where(area > 0, area, 1.0), 0.0)
    on = force > 0
    dx = 0.5 * params.chord_length
    dy = params.tread_half_width / nb_
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
