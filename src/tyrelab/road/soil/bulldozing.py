"""Bulldozing: the soil a wheel presses down flows beside and ahead of the rut (compiled).

Optional (a soil file's ``[bulldozing]`` table), after the scheme of Project Chrono's
SCMTerrain (its ``SetBulldozingParameters``), written anew on the bed's arrays:

1. **Displaced volume.** In a step, every node in contact that yields sinks plastically
   by ``d sp``; the volume ``flow_factor * sum(d sp) * dx dy`` is displaced (elastic
   sinkage displaces nothing: it springs back).
2. **Raised at the rut's edge.** The nodes out of contact that border the contact (a
   4-neighbour in contact: beside and ahead of the wheel, and behind it where the rut ends)
   each take an equal share: their surface *and* their undisturbed height ``h0`` rise by
   it, so the new soil is loose soil whose later sinkage counts from its own top (as
   Chrono raises a node's level and initial level together), while ``base``, the surface
   as laid, stays -- the reference of the single-wheel tester's ``SINKAGE``.
3. **Erosion.** The raised nodes stand one cell wide; ``erosion_iterations`` sweeps over
   the nodes out of contact within ``erosion_propagations`` nodes of the box around the
   step's nodes in contact move soil from each node to any 4-neighbour (out of contact) lower by more than the
   angle of repose allows, ``(dz - dx tan(angle)) / 8`` at a time (half the excess, shared
   among four neighbours), surface and ``h0`` together.

Volume is conserved by steps 2 and 3 exactly (to rounding) with ``flow_factor`` 1, except
where a node would rise above the surface as laid by more than
:data:`~tyrelab.road.soil.scm.PILE_LIMIT` (the bounds the contact models' searches take):
it rises no further and the rest is lost. Chrono differs in three ways: it erodes a domain
grown ring by ring from the boundary (here the contact box widened, a superset), keeps soil
that cannot rise in a hidden store, and sweeps its nodes in hash order (here row by row:
deterministic).
"""

from __future__ import annotations

import numba as nb

from .scm import PILE_LIMIT


@nb.njit(cache=True)
def _in_contact(bed, i, k):
    nx, ny = bed.h0.shape
    return 0 <= i < nx and 0 <= k < ny and bed.sigma[i, k] > 0.0


@nb.njit(cache=True)
def _borders_contact(bed, i, k):
    """Whether node ``(i, k)`` is out of contact with a 4-neighbour in contact."""
    return (bed.sigma[i, k] <= 0.0
            and (_in_contact(bed, i - 1, k) or _in_contact(bed, i + 1, k)
                 or _in_contact(bed, i, k - 1) or _in_contact(bed, i, k + 1)))


@nb.njit(cache=True)
def _raise(bed, i, k, amount):
    """Node ``(i, k)``'s surface and undisturbed height up by ``amount`` [m] (down, when
    negative), no higher than :data:`PILE_LIMIT` above the surface as laid; the rise made."""
    amount = min(amount, bed.base[i, k] + PILE_LIMIT - bed.h0[i, k])
    bed.h0[i, k] += amount
    bed.ground.z[i, k] += amount
    return amount


@nb.njit(cache=True)
def bulldoze(bed, i0, i1, k0, k1, pressed):
    """Move the soil pressed down in a step to the rut's edge and erode it (module docstring):
    ``pressed`` the sum of the plastic sinkage increments [m] of the nodes in contact in the
    step (``sigma > 0`` marks them), all within rows ``i0..i1`` and columns ``k0..k1``."""
    soil = bed.soil
    nx, ny = bed.h0.shape
    a0, a1 = max(0, i0 - 1), min(nx - 1, i1 + 1)
    b0, b1 = max(0, k0 - 1), min(ny - 1, k1 + 1)
    edge = 0
    for i in range(a0, a1 + 1):
        for k in range(b0, b1 + 1):
            if _borders_contact(bed, i, k):
                edge += 1
    if edge == 0 or pressed <= 0.0:
        return
    share = soil.flow_factor * pressed / edge
    for i in range(a0, a1 + 1):
        for k in range(b0, b1 + 1):
            if _borders_contact(bed, i, k):
                _raise(bed, i, k, share)
    # erosion to the angle of repose, over the nodes out of contact near the contact
    p = soil.erosion_propagations
    e0, e1 = max(0, i0 - 1 - p), min(nx - 1, i1 + 1 + p)
    f0, f1 = max(0, k0 - 1 - p), min(ny - 1, k1 + 1 + p)
    for _ in range(soil.erosion_iterations):
        for i in range(e0, e1 + 1):
            for k in range(f0, f1 + 1):
                if bed.sigma[i, k] > 0.0:
                    continue
                for di, dk, step in ((-1, 0, bed.dx), (1, 0, bed.dx), (0, -1, bed.dy),
                                     (0, 1, bed.dy)):
                    m, n = i + di, k + dk
                    if m < e0 or m > e1 or n < f0 or n > f1 or bed.sigma[m, n] > 0.0:
                        continue
                    excess = bed.ground.z[i, k] - bed.ground.z[m, n] - step * soil.erosion_slope
                    if excess > 0.0:
                        moved = _raise(bed, m, n, 0.125 * excess)
                        _raise(bed, i, k, -moved)
