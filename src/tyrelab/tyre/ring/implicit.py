"""The belt's stiffest terms, integrated implicitly (docs/ring.md, "Performance").

Explicit (symplectic) Euler is stable only for steps below ``2/omega_max``.
Two groups of belt terms are far stiffer than the physics of interest (thesis
Figure 1-2: below 100 Hz) and would alone set the step:

* the chords' axial stiffness ``EA/L0`` and damping ``c_EA/L0`` (a nearly
  inextensible steel belt): omega^2 ~ 4 EA / (L0 m), growing as N^2;
* the belt's lateral bending ``EI_o`` and torsion ``GJ``: linear with
  constant coefficients, the bending growing as N^4.

Both are made linearly implicit after the explicit kick of every force at
the step's start: the increment of these forces over the step is taken at
``x_n + theta h v_new`` (``theta`` = :data:`THETA` = 1/2, the least that is
unconditionally stable with the symplectic drift ``x_new = x_n + h v_new``
that every other term keeps):

* chords: the tension increment of chord c = (i, i+1),
  ``lambda_c = (EA/L0) theta h e_c(v_new) + (c_EA/L0) (e_c(v_new) - e_c(v_old))``
  (``e_c = d_c . (v_{i+1} - v_i)``, its extension rate along its direction
  ``d_c`` at the step's start), solves the cyclic tridiagonal system
  ``(1 + 2a) lambda_c - a (d_{c-1}.d_c) lambda_{c-1} - a (d_c.d_{c+1})
  lambda_{c+1} = k e*_c - (c_EA/L0) e_c(v_old)``, ``k = theta h EA/L0 + c_EA/L0``,
  ``a = k h / m``, with ``e*`` from the explicit velocities (Thomas with the
  Sherman-Morrison correction for the two corner terms, O(N));
* out of plane: ``(M + theta h^2 K) v_new = M v*``, K the constant stiffness
  matrix of lateral bending and torsion on the (y, beta) degrees of freedom, interleaved
  ``(y_0, beta_0, y_1, ...)``, which makes it a band of half-width 4 with
  the ring's closure in the last rows. Its Cholesky factor keeps that form
  (a band and a dense border of the last rows), is computed once per step
  length and stored compactly; each step solves in O(N).
"""

from __future__ import annotations


import numba as nb
import numpy as np

from .records import LK, empty_state

#: weight of the new velocities in the implicit terms: 1/2 is the least that is
#: stable for every step; it damps a mode by about THETA h omega_K^2 / (2 omega)
#: (omega_K^2 the implicit terms' share of its stiffness), the stiffest most
THETA = 0.5


def lateral_stiffness_matrix(params) -> np.ndarray:
    """The constant stiffness matrix K [2N x 2N] of the belt's lateral bending
    and torsion, on the (y, beta) degrees of freedom interleaved, as
    :func:`~.belt.out_of_plane_forces` gives it without the pre-tension's
    string term (``K = -dF/dx``, found column by column; the forces are
    linear). Rigid motions of the ring strain neither, so the low lateral
    modes (the belt on its foundation) see none of the implicit treatment."""
    from .belt import out_of_plane_forces

    n, nb_ = params.n_segments, params.n_blocks
    params = params._replace(pretension=0.0)
    state = empty_state(n, nb_)
    state.p1[:] = params.belt_radius * params.cos_theta
    state.p2[:] = params.belt_radius * params.sin_theta
    k = np.zeros((2 * n, 2 * n))
    for col in range(2 * n):
        state.y[:] = 0.0
        state.beta[:] = 0.0
        (state.y if col % 2 == 0 else state.beta)[col // 2] = 1.0
        state.fy[:] = 0.0
        state.fb[:] = 0.0
        out_of_plane_forces(params, state)
        k[0::2, col] = -state.fy
        k[1::2, col] = -state.fb
    return 0.5 * (k + k.T)


def lateral_checksum(k: np.ndarray) -> float:
    """A number that changes when K does (identifies the factor a state holds)."""
    w = np.arange(1, k.size + 1, dtype=np.float64).reshape(k.shape)
    return float(np.sum(k * w)) + 1.0


@nb.njit(cache=True)
def chord_implicit(params, state, h):
    """Correct the kicked in-plane velocities for the chords' implicit tension
    increment (module doc); the chord directions and extension rates at the
    step's start are those :func:`~.belt.membrane_forces` kept before the kick."""
    n = params.n_segments
    l0 = params.chord_length
    ka = params.extension_stiffness / l0
    ca = params.extension_damping / l0
    kk = THETA * ka * h + ca
    if kk == 0.0:
        return
    m = params.segment_mass
    a = kk * h / m
    v1, v2 = state.v1, state.v2
    d1, d2, rate = state.chord_1, state.chord_2, state.chord_rate
    lam, gam, z = state.chord_tension, state.chord_work, state.chord_aux
    for c in range(n):
        j = c + 1 if c + 1 < n else 0
        lam[c] = kk * (d1[c] * (v1[j] - v1[c]) + d2[c] * (v2[j] - v2[c])) - ca * rate[c]
    diag = 1.0 + 2.0 * a
    corner = -a * (d1[n - 1] * d1[0] + d2[n - 1] * d2[0])   # A[0, n-1] = A[n-1, 0]
    # Sherman-Morrison (A = T + u v^T, u = (g, 0, .., corner), v = (1, 0, .., corner/g))
    g = -diag
    inv = 1.0 / (diag - g)
    gam[0] = -a * (d1[0] * d1[1] + d2[0] * d2[1]) * inv
    lam[0] = lam[0] * inv
    z[0] = g * inv
    for c in range(1, n):
        sub = -a * (d1[c - 1] * d1[c] + d2[c - 1] * d2[c])
        bc = diag - corner * corner / g if c == n - 1 else diag
        inv = 1.0 / (bc - sub * gam[c - 1])
        if c < n - 1:
            gam[c] = -a * (d1[c] * d1[c + 1] + d2[c] * d2[c + 1]) * inv
        uc = corner if c == n - 1 else 0.0
        lam[c] = (lam[c] - sub * lam[c - 1]) * inv
        z[c] = (uc - sub * z[c - 1]) * inv
    for c in range(n - 2, -1, -1):
        lam[c] -= gam[c] * lam[c + 1]
        z[c] -= gam[c] * z[c + 1]
    factor = (lam[0] + corner * lam[n - 1] / g) / (1.0 + z[0] + corner * z[n - 1] / g)
    hm = h / m
    for c in range(n):
        lam[c] -= factor * z[c]
    for i in range(n):
        k = i - 1 if i > 0 else n - 1
        v1[i] += hm * (lam[i] * d1[i] - lam[k] * d1[k])
        v2[i] += hm * (lam[i] * d2[i] - lam[k] * d2[k])


@nb.njit(cache=True)
def lateral_factorize(params, state, h):
    """Cholesky factor of ``M + theta h^2 K`` into ``state.lateral_band`` /
    ``lateral_border`` (compact: ``band[i, k] = L[i, i-k]`` for the rows
    before the border, ``border[r] = L[2N - W + r]``) for step ``h``."""
    k = params.lateral_matrix
    n2 = k.shape[0]
    a = THETA * h * h * k
    for i in range(n2 // 2):
        a[2 * i, 2 * i] += params.segment_mass
        a[2 * i + 1, 2 * i + 1] += params.segment_twist_inertia
    low = np.linalg.cholesky(a)
    band = state.lateral_band
    border = state.lateral_border
    w = border.shape[0]
    for i in range(n2):
        # the diagonal as its reciprocal: the solve multiplies (no division on its chain)
        band[i, 0] = 1.0 / low[i, i]
        for q in range(1, band.shape[1]):
            band[i, q] = low[i, i - q] if i - q >= 0 and i < n2 - w else 0.0
    for r in range(w):
        for j in range(n2):
            border[r, j] = low[n2 - w + r, j]
    state.lateral_key[LK.STEP] = h
    state.lateral_key[LK.CHECKSUM] = params.lateral_checksum


@nb.njit(cache=True)
def lateral_implicit(params, state, h):
    """Solve ``(M + theta h^2 K) v_new = M v*`` for the out-of-plane velocities
    (``state.vy``, ``vbeta`` hold ``v*`` and receive ``v_new``); the factor is
    made again when the step or the matrix changed."""
    if (state.lateral_key[LK.STEP] != h
            or state.lateral_key[LK.CHECKSUM] != params.lateral_checksum):
        lateral_factorize(params, state, h)
    band = state.lateral_band
    border = state.lateral_border
    x = state.lateral_work
    vy, vb = state.vy, state.vbeta
    n = params.n_segments
    n2 = 2 * n
    w = border.shape[0]
    start = n2 - w
    m = params.segment_mass
    jt = params.segment_twist_inertia
    for i in range(n):
        x[2 * i] = m * vy[i]
        x[2 * i + 1] = jt * vb[i]
    # forward: L z = r (the band unrolled: LATERAL_BAND = 4)
    for i in range(min(4, start)):
        s = x[i]
        for q in range(1, i + 1):
            s -= band[i, q] * x[i - q]
        x[i] = s * band[i, 0]
    for i in range(4, start):
        x[i] = (x[i] - band[i, 1] * x[i - 1] - band[i, 2] * x[i - 2] - band[i, 3] * x[i - 3]
                - band[i, 4] * x[i - 4]) * band[i, 0]
    for r in range(w):
        i = start + r
        s = x[i]
        for j in range(i):
            s -= border[r, j] * x[j]
        x[i] = s * band[i, 0]
    # backward: L^T v = z (the border's columns first, then the band)
    for r in range(w - 1, -1, -1):
        i = start + r
        s = x[i]
        for rr in range(r + 1, w):
            s -= border[rr, i] * x[start + rr]
        x[i] = s * band[i, 0]
    for r in range(w):
        xr = x[start + r]
        for i in range(start):
            x[i] -= border[r, i] * xr
    for i in range(start - 1, start - 5, -1):
        s = x[i]
        for q in range(1, start - i):
            s -= band[i + q, q] * x[i + q]
        x[i] = s * band[i, 0]
    for i in range(start - 5, -1, -1):
        x[i] = (x[i] - band[i + 1, 1] * x[i + 1] - band[i + 2, 2] * x[i + 2]
                - band[i + 3, 3] * x[i + 3] - band[i + 4, 4] * x[i + 4]) * band[i, 0]
    for i in range(n):
        vy[i] = x[2 * i]
        vb[i] = x[2 * i + 1]
