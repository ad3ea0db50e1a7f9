"""Static states of the ring (thesis 3.3): relaxation to equilibrium, footprints.

The rim is held level (spin axis along y, no spin) and moved down onto a
plate or cleat in small ramps; after each ramp the belt relaxes to static
equilibrium with an extra velocity damping (dynamic relaxation,
``ring_params(..., relax=rate)``). The ramps and holds are the one press
loop of every model (:func:`tyrelab.tyre.static.press_path`); the static
press and footprint rig (:mod:`tyrelab.rig.static_press`) drives it for
users, :func:`settle` here for the ring's own initial states and its
identification.
"""

from __future__ import annotations

import numpy as np

from ...road.terrain import ground_range
from ..handling.none import NoHandling
from ..handling.relaxation import no_lag
from ..static import DT, HOLD, PRESS_COLUMNS, PRESS_RATE, WINDOW, press_path
from ..vertical import VerticalLaw
from ..wheel import Wheel

#: the ring carries its own vertical stiffness: the wheel's law is not used
_UNUSED_LAW = VerticalLaw.linear(0.0, 0.0)


def settle(params, state, road, heights, start=None, rate=PRESS_RATE, hold=HOLD):
    """Press the ring (``state``, relaxed ``params``) through centre ``heights``
    [m] on ``road`` (a terrain record, :mod:`tyrelab.road.terrain`); returns the
    ``(k, 7)`` result table of :func:`~tyrelab.tyre.static.press_path`;
    ``state`` is left in the last pressed state (``state.block_force`` its
    blocks' normal forces).

    Starts 2 mm above the touch of the road's highest point unless
    ``start`` [m] is given.
    """
    heights = np.asarray(heights, float)
    r0 = params.unloaded_radius
    z0 = ground_range(road)[1] + r0 + 0.002 if start is None else float(start)
    res = np.zeros((heights.size, len(PRESS_COLUMNS)))
    press_path(Wheel(_UNUSED_LAW, params, NoHandling(), road, state, no_lag()), z0, heights, rate,
               hold, WINDOW, DT, res)
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


def footprint_from_blocks(params, state, force, load, deflection, pressure) -> dict:
    """The footprint of a pressed ring from its blocks' normal forces ``force`` [N].

    Returns a dict: ``x, y`` block-tip positions on the plate [m], ``force``,
    ``pressure`` [Pa] (force / block area), ``outline`` (closed polygon
    ``(k, 2)`` around the contacting blocks, extended by half a block pitch),
    ``length``, ``width`` [m], ``cell`` (block cell length and width [m]),
    ``load`` [N] (plate force), ``deflection`` [m], ``pressure_inflation`` [Pa].
    """
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
