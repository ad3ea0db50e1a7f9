"""A one-dimensional least-squares search, coarse to fine (the touch of a press, the release of a
drop): the sum of squares is evaluated on a grid, and the grid is narrowed round its smallest
value until its spacing is the resolution asked for; at each candidate the rest of the model is
a few terms fitted linearly (:func:`term_sse`). Memory stays at ``points`` times the
samples, whatever the range: a slow press logged at 100 Hz has thousands of samples over the
range searched."""

from __future__ import annotations

import numpy as np

#: grid points per pass
POINTS = 201


def refine_minimum(sse, lo: float, hi: float, resolution: float, points: int = POINTS) -> float:
    """The ``x`` in ``[lo, hi]`` where ``sse(x_array) -> array`` is least, to ``resolution``.

    Each pass evaluates ``points`` values and keeps two grid steps either side of the
    smallest; a minimum narrower than the first grid's step could be missed, so the first
    grid should resolve the feature sought (the callers' sums of squares vary over the
    whole fall or rise they fit)."""
    lo, hi = float(lo), float(hi)
    if not hi > lo:
        return lo
    while True:
        xs = np.linspace(lo, hi, points)
        k = int(np.argmin(sse(xs)))
        step = xs[1] - xs[0]
        if step <= resolution:
            return float(xs[k])
        lo, hi = xs[max(k - 2, 0)], xs[min(k + 2, points - 1)]


def term_sse(terms, y) -> np.ndarray:
    """Per row, the least sum of squares of ``y ~ sum_k c_k terms[..., k]`` (``terms`` of shape
    ``(rows, samples, k)``):
    the normal equations of each row solved together. A row whose terms are linearly dependent
    on its samples (no fit to choose between them) is infinite."""
    terms = np.asarray(terms, float)
    y = np.asarray(y, float)
    gram = np.einsum("rsk,rsl->rkl", terms, terms)
    rhs = np.einsum("rsk,s->rk", terms, y)
    scale = np.prod(np.maximum(np.einsum("rkk->rk", gram), 1e-300), axis=1)
    ok = np.abs(np.linalg.det(gram)) > 1e-24 * scale
    out = np.full(terms.shape[0], np.inf)
    if np.any(ok):
        coef = np.linalg.solve(gram[ok], rhs[ok][..., None])[..., 0]
        out[ok] = ((np.einsum("rsk,rk->rs", terms[ok], coef) - y[None, :]) ** 2).sum(1)
    return out
