"""Modal analysis of the ring: linearisation, natural frequencies, damping ratios.

The belt's equations of motion (rim held, no spin unless given) are
linearised numerically about a state ``ts`` -- the free, inflated belt, or a
belt pressed on a plate (``load`` > 0: the tread blocks in contact then add
their stiffness) -- by central differences of the compiled force function::

    M q'' + C q' + K q = 0,   K = -dF/dq,  C = -dF/dq'

and the damped eigenproblem of the first-order form gives frequencies
``f = |lambda| / 2 pi`` and damping ratios ``zeta = -Re(lambda)/|lambda|``.
Each mode is named by its shape as thesis Table 3-3 (after Gipser) does:
in-plane or out-of-plane, and its circumferential wave number n (the
dominant Fourier harmonic of the segment displacements):

1. in-plane rotation (in-plane, n = 0, tangential),
2. vertical/longitudinal translation (in-plane, n = 1),
3. lateral translation (out-of-plane, n = 0),
4. out-of-plane rotation, tilt (out-of-plane, n = 1),
5. third in-plane mode (in-plane, n = 2),
6. third out-of-plane mode (out-of-plane, n = 2).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np
import pandas as pd

from .belt import belt_forces
from .records import VELOCITIES, copy_state

MODE_NAMES = {
    1: "in-plane rotation about the spin axis",
    2: "vertical/longitudinal translation",
    3: "lateral translation",
    4: "out-of-plane rotation",
    5: "third in-plane",
    6: "third out-of-plane",
}
#: (in_plane, wave number) of each Table 3-3 mode
MODE_SHAPES = {1: (True, 0), 2: (True, 1), 3: (False, 0), 4: (False, 1), 5: (True, 2), 6: (False, 2)}


@nb.njit(cache=True)
def generalized_forces(params, state, omega, q):
    """Forces on the 4N DOFs (p1, p2, y, beta) of the free belt spinning at omega.

    Centrifugal force included, Coriolis not (see :func:`linearize`).
    """
    n = params.n_segments
    belt_forces(params, state)
    m = params.segment_mass
    for i in range(n):
        q[i] = state.f1[i] + m * omega * omega * state.p1[i]
        q[n + i] = state.f2[i] + m * omega * omega * state.p2[i]
        q[2 * n + i] = state.fy[i]
        q[3 * n + i] = state.fb[i]


@nb.njit(cache=True)
def _difference_matrices(params, state, omega, K, C):
    """Central differences of :func:`generalized_forces` in positions and velocities.

    DOF k is entry ``k % N`` of ``p1, p2, y, beta`` (positions) or ``v1,
    v2, vy, vbeta`` (velocities) for ``k // N`` = 0, 1, 2, 3.
    """
    n = params.n_segments
    ndof = 4 * n
    pos = (state.p1, state.p2, state.y, state.beta)
    vel = (state.v1, state.v2, state.vy, state.vbeta)
    fp = np.empty(ndof)
    fm = np.empty(ndof)
    eps_p = 1e-6 * params.belt_radius
    eps_v = 1e-4
    for k in range(ndof):
        for which in range(2):
            arr = pos[k // n] if which == 0 else vel[k // n]
            idx = k % n
            eps = eps_p if which == 0 else eps_v
            x0 = arr[idx]
            arr[idx] = x0 + eps
            generalized_forces(params, state, omega, fp)
            arr[idx] = x0 - eps
            generalized_forces(params, state, omega, fm)
            arr[idx] = x0
            for r in range(ndof):
                d = -(fp[r] - fm[r]) / (2.0 * eps)
                if which == 0:
                    K[r, k] = d
                else:
                    C[r, k] = d


def linearize(params, state, omega=0.0, contact=None):
    """``(M, C, K)`` of the belt about ``state`` (4N DOFs: p1, p2, y, beta per segment).

    ``contact`` optionally adds a stiffness matrix of the tread contact.
    With spin ``omega`` the Coriolis term adds ``2 m omega J`` to C.
    """
    n = params.n_segments
    state = copy_state(state)
    ndof = 4 * n
    K = np.empty((ndof, ndof))
    C = np.empty((ndof, ndof))
    _difference_matrices(params, state, float(omega), K, C)
    if contact is not None:
        K = K + contact
    m = params.segment_mass
    M = np.diag(np.r_[np.full(3 * n, m), np.full(n, params.segment_twist_inertia)])
    if omega != 0.0:
        # Coriolis -2 m Omega x v: on (v1, v2) it is 2 m omega (v2, -v1) as a damping-like term
        i = np.arange(n)
        C[i, n + i] += 2 * m * omega
        C[n + i, i] -= 2 * m * omega
    return M, C, K


def eigenmodes(M, C, K):
    """Frequencies [Hz], damping ratios [-] and DOF shapes of the damped system."""
    ndof = M.shape[0]
    Minv = np.diag(1.0 / np.diag(M))
    A = np.zeros((2 * ndof, 2 * ndof))
    A[:ndof, ndof:2 * ndof] = np.eye(ndof)
    A[ndof:2 * ndof, :ndof] = -Minv @ K
    A[ndof:2 * ndof, ndof:2 * ndof] = -Minv @ C
    lam, vec = np.linalg.eig(A)
    keep = lam.imag > 1e-6
    lam = lam[keep]
    vec = vec[:ndof, keep]
    order = np.argsort(np.abs(lam))
    lam = lam[order]
    vec = vec[:, order]
    freq = np.abs(lam) / (2 * np.pi)
    zeta = -lam.real / np.abs(lam)
    return freq, zeta, vec


def classify(params, shape):
    """``(in_plane, n, tangential)`` of a mode shape over the 4N DOFs."""
    n = params.n_segments
    rb = params.belt_radius
    th = 2 * np.pi * np.arange(n) / n
    s = np.real(shape * np.exp(-1j * np.angle(shape[np.argmax(np.abs(shape))])))
    p1, p2, y, b = s[:n], s[n:2 * n], s[2 * n:3 * n], s[3 * n:]
    ur = p1 * np.cos(th) + p2 * np.sin(th)
    ut = -p1 * np.sin(th) + p2 * np.cos(th)
    e_in = np.sum(ur ** 2 + ut ** 2)
    e_out = np.sum(y ** 2 + (rb * b) ** 2)
    in_plane = e_in >= e_out
    comps = (ur, ut) if in_plane else (y, rb * b)
    power = sum(np.abs(np.fft.rfft(c)) ** 2 for c in comps)
    wave = int(np.argmax(power[:n // 2]))
    tangential = np.sum(ut ** 2) > np.sum(ur ** 2)
    return bool(in_plane), wave, bool(tangential)


def table_modes(params, freq, zeta, vec) -> pd.DataFrame:
    """The six modes of thesis Table 3-3 picked from the eigen-solution."""
    found = {}
    for k in range(freq.size):
        in_plane, wave, tangential = classify(params, vec[:, k])
        for mode, (ip, nw) in MODE_SHAPES.items():
            if mode in found or ip != in_plane or nw != wave:
                continue
            if mode == 1 and not tangential:
                continue
            n = params.n_segments
            if mode == 3 and np.sum(np.abs(vec[2 * n:3 * n, k])) == 0:
                continue
            found[mode] = (freq[k], zeta[k])
    rows = []
    for m in sorted(MODE_NAMES):
        freq_m, zeta_m = found.get(m, (np.nan, np.nan))
        rows.append({"mode": m, "description": MODE_NAMES[m], "freq_Hz": freq_m,
                     "damping_pct": 100 * zeta_m})
    return pd.DataFrame(rows)


def ring_modal(tyre, pressure=None, load=0.0, omega=0.0, **options) -> pd.DataFrame:
    """Natural frequencies and damping ratios of the Table 3-3 modes.

    ``tyre`` a :class:`~tyrelab.tyre.params.Tyre` (its pressure unless
    ``pressure`` [Pa] is given); ``load`` > 0 linearises about the belt
    pressed on a flat plate at the static deflection of that load (the
    contact's normal and stick stiffness then enter through the blocks in
    contact, :func:`contact_stiffness`).
    """
    import copy
    from .model import nominal_state, ring_initial_state, ring_params
    if pressure is not None:
        tyre = copy.copy(tyre)
        tyre.pressure = float(pressure)
    params = ring_params(tyre, None, **options)
    contact = None
    if load > 0:
        state = ring_initial_state(tyre, load, params, **options)
        contact = contact_stiffness(tyre, params, state, load, options)
    else:
        state = nominal_state(params)
    M, C, K = linearize(params, state, omega, contact)
    freq, zeta, vec = eigenmodes(M, C, K)
    return table_modes(params, freq, zeta, vec)


#: the fields of :class:`~.records.RingParams` zeroed to isolate the tread contact
STRUCTURE = ("radial_stiffness", "tangential_stiffness", "lateral_stiffness",
             "torsion_stiffness", "radial_damping", "tangential_damping", "lateral_damping",
             "torsion_damping", "pretension", "extension_stiffness",
             "extension_damping",
             "bending_stiffness", "lateral_bending_stiffness", "belt_torsion_stiffness",
             "pressure_load", "tread_damping", "tread_shear_damping", "relax_rate")


def contact_stiffness(tyre, params, state, load, options):
    """Stiffness of the tread contact about a pressed state (blocks in stick).

    For each belt DOF of a segment in contact, the DOF is moved by +-eps
    through one tiny kernel step with velocity eps/h -- so the stuck blocks'
    tangential deflections move with it, as in stick -- and the contact
    forces of a following step at rest are differenced. The structure and
    all dampers are switched off in a copy of ``params``.
    """
    from ...road.obstacles import Flat
    from ..wheel import WheelPose
    from .kernel import ring_advance
    n = params.n_segments
    road = Flat().grid().surface()
    height = tyre.unloaded_radius - tyre.static_deflection(float(load))
    h = 1e-7
    bare = params._replace(max_step=h, **{name: 0.0 for name in STRUCTURE})
    mass = np.r_[np.full(3 * n, params.segment_mass), np.full(n, params.segment_twist_inertia)]
    at = WheelPose(0.0, 0.0, height, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0)

    def velocities(st):
        return [getattr(st, name) for name in VELOCITIES]

    def forces_after(k, eps):
        st = copy_state(state)
        for v in velocities(st):
            v[:] = 0.0
        if k >= 0:
            velocities(st)[k // n][k % n] = eps / h
        ring_advance(bare, st, road, at, h)   # moves DOF k by eps, the stuck tips with it
        for v in velocities(st):
            v[:] = 0.0
        ring_advance(bare, st, road, at, h)   # contact forces at rest in the moved state
        return np.concatenate(velocities(st)) * mass / h

    base = forces_after(-1, 0.0)
    segs = np.unique(np.flatnonzero(np.abs(base) > 0) % n)
    cols = np.r_[segs, n + segs, 2 * n + segs, 3 * n + segs]
    Kc = np.zeros((4 * n, 4 * n))
    for k in cols:
        eps = 1e-6 if k < 3 * n else 1e-5
        Kc[:, k] = -(forces_after(k, eps) - forces_after(k, -eps)) / (2 * eps)
    return Kc


def ring_frequencies_analytic(n_max, radius, mass_per_length, kr, kt, tension, ea, ei=0.0):
    """In-plane natural frequencies [Hz] of a pre-tensioned ring on an elastic foundation.

    Continuum ring of radius R, mass per length m', radial and tangential
    foundation stiffness per length k_r, k_t, hoop pre-tension T0 held by
    the inflation pressure as a follower load (T0 = p b R), extension
    stiffness EA, bending EI. For displacements ``w = W cos n th``,
    ``v = V sin n th`` the second variation of the energy gives (per length)::

        K_n = [[k_r + T0 (n^2 - 1)/R^2 + EA/R^2 + EI (n^2 - 1)^2 / R^4,  n EA/R^2],
               [n EA/R^2,                                     k_t + n^2 EA/R^2]]
        omega^2 = eig(K_n) / m'

    (pressure work and pre-tension together give ``T0 (w'^2 - w^2) / 2R``, so
    rigid translation n = 1 is unaffected by them). For n = 0 the
    tangential (rotation) and radial (breathing) modes decouple:
    ``k_t / m'`` and ``(k_r + (EA - T0)/R^2) / m'``. Returns a list of
    ``(n, f_low, f_high)``.
    """
    out = []
    R = radius
    for n in range(n_max + 1):
        a = kr + tension * (n * n - 1) / R ** 2 + ea / R ** 2 + ei * (n * n - 1) ** 2 / R ** 4
        b = n * ea / R ** 2
        d = kt + n * n * ea / R ** 2
        ev = np.linalg.eigvalsh(np.array([[a, b], [b, d]]))
        f = np.sqrt(np.maximum(ev, 0) / mass_per_length) / (2 * math.pi)
        out.append((n, float(f[0]), float(f[1])))
    return out
