"""The ring's records: its parameters (:class:`RingParams`) and its state (:class:`RingState`).

:class:`RingParams` is the contact record of the "ring" and "ring-tp"
models (built by :func:`tyrelab.tyre.ring.model.ring_params`), SI, per belt
segment where it says so. :class:`RingState` is the belt's state relative to
the rim, in the rim-fixed axes that spin with it (see
:mod:`tyrelab.tyre.ring.belt`), plus the scratch arrays a time step writes
into, so that a step allocates nothing; the compiled step
(:func:`tyrelab.tyre.ring.kernel.ring_step`) mutates its arrays in place.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ...core.named_index import named_index
from .tread import ACC_SIZE

# --- the out-of-plane factor (tyre/ring/implicit.py) kept in RingState ------------
#: half bandwidth of the interleaved out-of-plane matrix (y_i couples y_{i+-2})
LATERAL_BAND = 4
#: rows of the dense border the ring's closure puts at the end of its factor
LATERAL_BORDER = 4

# --- RingState.kinematics: the rim's motion as the state last saw it -------------
#: belt rotation angle psi [rad] (integral of the spin)
KIN_PSI = 0
#: rim-centre velocity at the previous step [m/s]
KIN_VX = 1
KIN_VY = 2
KIN_VZ = 3
#: spin rate at the previous step [rad/s]
KIN_OMEGA = 4
#: time the state has been advanced [s]
KIN_TIME = 5
#: how long the rim has turned at the spin ``KIN_OMEGA`` [s], and the slope of the moment on it
#: in its spin that the last step gave the rig [N m s/rad] (:func:`~.kernel.rim_spin_change`)
KIN_HELD = 6
KIN_SLOPE = 7
KIN_SIZE = 8

# --- RingState.lateral_key: what the out-of-plane factor was made for -----------------
#: the key's entries: the internal step [s] and the matrix checksum; their positions (``LK``)
LATERAL_KEY = ("STEP", "CHECKSUM")
LK = named_index("LateralKeyIndex", LATERAL_KEY)


class RingParams(NamedTuple):
    """Parameters of the flexible ring at one inflation pressure (SI).

    Counts: ``n_segments`` N belt segments, ``n_blocks`` NB tread blocks per
    segment, ``lateral_samples`` samples across a block's width where the
    road is uneven under it (:mod:`.tread`). Foundation stiffnesses and
    dampers are per segment (per-length values times the segment arc).
    Tables: ``cos_theta``, ``sin_theta`` (N) of the segments' nominal angles;
    ``block_y`` lateral offset, ``block_s`` circumferential offset,
    ``block_h`` height above the belt and ``block_area`` footprint area of
    each block (N*NB, segment-major).
    """

    n_segments: int
    n_blocks: int
    lateral_samples: int
    #: R0 [m]
    unloaded_radius: float
    #: Rb = R0 - tread depth [m]
    belt_radius: float
    #: inflation pressure [Pa]
    pressure: float
    #: mass of one segment [kg]
    segment_mass: float
    #: twist inertia of one segment about the belt tangent [kg m^2]
    segment_twist_inertia: float
    #: foundation springs [N/m], torsion [N m/rad], per segment
    radial_stiffness: float
    tangential_stiffness: float
    lateral_stiffness: float
    torsion_stiffness: float
    #: foundation dampers [N s/m], torsion [N m s/rad], per segment
    radial_damping: float
    tangential_damping: float
    lateral_damping: float
    torsion_damping: float
    #: contact patch's Maxwell element (road to rim): gain g [-] (its force is
    #: g (Fn - r), Fn the patch's normal force, r its relaxed value; 0 in
    #: static builds) and relaxation time [s] of r
    patch_hysteresis_gain: float
    patch_hysteresis_time: float
    #: belt pre-tension T0 [N] (in equilibrium with the pressure on the polygon)
    pretension: float
    #: EA [N] and its damping [N s]
    extension_stiffness: float
    extension_damping: float
    #: EI in plane [N m^2]
    bending_stiffness: float
    #: EI out of plane [N m^2]
    lateral_bending_stiffness: float
    #: GJ of the belt [N m^2]
    belt_torsion_stiffness: float
    #: pressure times effective width, p b [N/m]
    pressure_load: float
    #: radial block stiffness per area [N/m^3], progression q [-], damping [N s/m^3]
    tread_stiffness: float
    tread_progression: float
    tread_damping: float
    #: tangential block stiffness [N/m^3] and damping [N s/m^3] per area
    tread_shear_stiffness: float
    tread_shear_damping: float
    #: tread-road friction coefficient [-]
    friction: float
    #: largest internal step [s]
    max_step: float
    #: extra velocity damping rate [1/s] (static relaxation; 0 when rolling)
    relax_rate: float
    #: nominal chord length L0 = 2 Rb sin(dth/2) [m]
    chord_length: float
    #: segment angle dth = 2 pi / N [rad]
    segment_angle: float
    #: tallest block [m]
    max_block_height: float
    #: half width of the tread [m]
    tread_half_width: float
    cos_theta: np.ndarray
    sin_theta: np.ndarray
    block_y: np.ndarray
    block_s: np.ndarray
    block_h: np.ndarray
    block_area: np.ndarray
    #: the constant stiffness matrix of the out-of-plane degrees of freedom
    #: (y, beta interleaved, 2N x 2N; :mod:`.implicit`) and a checksum of it
    lateral_matrix: np.ndarray
    lateral_checksum: float
    #: the effective rolling radius [m] the wheel's kinematic slip (``LONGSLIP``) is measured
    #: against: its free-rolling ``V / omega``, set from a rig's rolling equilibrium
    #: (:meth:`tyrelab.tyre.model.TyreModel.wheel`); the unloaded radius until then
    rolling_radius: float


class RingState(NamedTuple):
    """State of the belt relative to the rim, and a time step's scratch.

    Per segment (N): in-plane centre ``p1, p2`` [m] and velocity ``v1, v2``
    [m/s] in the rotating wheel-plane axes, lateral displacement ``y`` [m]
    and velocity ``vy``, twist ``beta`` [rad] and its rate ``vbeta``;
    ``patch_relaxed[0]`` [N], the relaxed normal force ``r`` of the
    contact patch's Maxwell element (:func:`~.road_forces.patch_hysteresis`).
    Per block (N*NB): tangential tip deflections ``s1, s2`` [m] in the road
    plane, and ``block_force`` [N], each block's normal force at the end of
    the last step (footprints, pressure maps). ``kinematics`` holds the
    rim's motion as last seen (indices ``KIN_*``), ``initialised[0]`` is
    False until the first step (no rim acceleration can be estimated yet).
    ``in_reach[i]`` (N, bool) is False only when segment i's blocks are
    known to be clear (out of the road's reach at the last internal step:
    no deflection, no force), so they need not be cleared again.
    Scratch: ``f1, f2, fy, fb`` the forces on the segments, ``patch`` the
    contact-patch sums of the last step (indices ``ACC_*`` of :mod:`.tread`);
    for the implicit terms (:mod:`.implicit`): ``chord_1, chord_2`` the chord
    directions, ``chord_rate`` their extension rates at the step's start,
    ``chord_tension, chord_work, chord_aux`` the tridiagonal solve;
    ``lateral_key`` (step length, matrix checksum) of the out-of-plane factor
    in ``lateral_band`` (2N x (band + 1)) and ``lateral_border``
    (border x 2N), ``lateral_work`` (2N) its solve.
    """

    p1: np.ndarray
    p2: np.ndarray
    v1: np.ndarray
    v2: np.ndarray
    y: np.ndarray
    vy: np.ndarray
    beta: np.ndarray
    vbeta: np.ndarray
    patch_relaxed: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    block_force: np.ndarray
    kinematics: np.ndarray
    initialised: np.ndarray
    in_reach: np.ndarray
    f1: np.ndarray
    f2: np.ndarray
    fy: np.ndarray
    fb: np.ndarray
    patch: np.ndarray
    chord_1: np.ndarray
    chord_2: np.ndarray
    chord_rate: np.ndarray
    chord_tension: np.ndarray
    chord_work: np.ndarray
    chord_aux: np.ndarray
    lateral_key: np.ndarray
    lateral_band: np.ndarray
    lateral_border: np.ndarray
    lateral_work: np.ndarray


#: the velocity arrays of :class:`RingState`, in the order of the positions p1, p2, y, beta
VELOCITIES = ("v1", "v2", "vy", "vbeta")


def empty_state(n: int, nb: int) -> RingState:
    """A zeroed :class:`RingState` for ``n`` segments of ``nb`` blocks."""
    seg = [np.zeros(n) for _ in range(8)]
    return RingState(*seg, np.zeros(1), np.zeros(n * nb), np.zeros(n * nb), np.zeros(n * nb),
                     np.zeros(KIN_SIZE), np.zeros(1, np.bool_), np.ones(n, np.bool_),
                     np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(ACC_SIZE),
                     *[np.zeros(n) for _ in range(6)], np.zeros(len(LATERAL_KEY)),
                     np.zeros((2 * n, LATERAL_BAND + 1)), np.zeros((LATERAL_BORDER, 2 * n)),
                     np.zeros(2 * n))


def copy_state(state: RingState) -> RingState:
    """A deep copy (every array copied)."""
    return RingState(*(a.copy() for a in state))


def params_key(params: RingParams) -> tuple:
    """A hashable key of a parameter record (arrays by their bytes)."""
    return tuple(v.tobytes() if isinstance(v, np.ndarray) else v for v in params)
