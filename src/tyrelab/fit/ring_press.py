"""The flexible ring pressed on a flat plate, as the identification sees it (thesis 4.5):
its plate loads at a series of deflections and its contact half-length, beside the length
of thesis eq. 2.3 the tyre's PA1, PA2 give (:mod:`tyrelab.fit.ring`).
"""

from __future__ import annotations

import numpy as np

from ..road.obstacles import Flat
from ..tyre.ring.model import RELAX_RATE, nominal_state, ring_params
from ..tyre.ring.static import block_positions, settle
from ..tyre.static import PC
from .patch import contact_half_length as patch_half_length


def contact_half_length_eq23(tyre, deflection):
    """Half contact length [m] of thesis eq. 2.3 with the tyre's PA1, PA2
    (:func:`tyrelab.fit.patch.contact_half_length`)."""
    pa1 = tyre.tir.number("CONTACT_PATCH", "PA1", required=True)
    pa2 = tyre.tir.number("CONTACT_PATCH", "PA2", required=True)
    return patch_half_length(np.asarray(deflection, float), pa1, pa2, tyre.unloaded_radius)


def press_plate(tyre, rp, deflections):
    """Model plate loads [N] at increasing press ``deflections`` [m], and the
    half contact length [m] at the last one (blocks in contact, plus half a
    segment pitch at each end)."""
    grid = Flat().grid()
    params = ring_params(tyre, grid, parameters=rp, relax=RELAX_RATE)
    state = nominal_state(params)
    d = np.asarray(deflections, float)
    res = settle(params, state, grid.surface(), tyre.unloaded_radius - d)
    return res[:, PC.FZ], contact_half_length_of_state(params, state, tyre.unloaded_radius - d[-1])


def contact_half_length_of_state(params, state, height):
    """Half contact length [m] of a pressed state along the tread centre.

    For the block columns nearest the centre line, the contact edges are
    where the block tips' height over the plate crosses zero, interpolated
    linearly between the last block in contact and the first one out
    (smooth in the parameters, unlike counting blocks).
    """
    n, nb = params.n_segments, params.n_blocks
    x, y, zt = block_positions(params, state)
    x = x.reshape(n, nb)
    gap = (zt + height).reshape(n, nb)  # tip height over the plate (rim centre at height)
    y1 = np.abs(params.block_y[:nb])
    cols = np.flatnonzero(np.isclose(y1, y1.min()))
    halves = []
    for j in cols:
        g, xx = gap[:, j], x[:, j]
        bottom = int(np.argmin(g))
        if g[bottom] >= 0:
            halves.append(0.0)
            continue
        edges = []
        for step in (1, -1):
            k = bottom
            while g[(k + step) % n] < 0:
                k = (k + step) % n
            k2 = (k + step) % n
            f = g[k] / (g[k] - g[k2])
            edges.append(xx[k] + f * (xx[k2] - xx[k]))
        halves.append(0.5 * abs(edges[0] - edges[1]))
    return float(np.mean(halves))


def contact_half_length(tyre, rp, deflection):
    """Half contact length [m] of the model pressed to ``deflection`` on a plate."""
    _, half = press_plate(tyre, rp, [deflection])
    return float(half)
