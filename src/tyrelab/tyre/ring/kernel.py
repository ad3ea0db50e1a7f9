"""Compiled time step of the flexible ring tyre: belt dynamics and hub loads.

:func:`ring_step` (the ring's step behind :func:`tyrelab.tyre.wheel.wheel_step`)
advances the belt state ``wheel.state`` (a :class:`~.records.RingState`,
relative to the rim) by ``dt`` while the rim centre moves with velocity
``pose.v`` and spins at ``pose.omega`` about ``pose.a``, and returns the
loads on the rim as :class:`~tyrelab.tyre.wheel.WheelLoads`.

Equations of motion of segment i in the rim-fixed axes that spin with the
rim (rotating frame, angular velocity ``Omega = omega a``)::

    m p'' = F_belt + F_tread - m a_rim - m Omega x (Omega x p) - 2 m Omega x p'
    m y'' = F_y - m a_rim . a,        J beta'' = M_beta

``a_rim`` is estimated from the change of the rim's velocity between calls; the
rim's spin is held over a call, and a change of it since the last call turns the
axes and the belt's coordinates in them at once (:func:`rim_spin_change`), so the
rigs can step a rim lighter than its belt (:func:`rim_spin_slope`). The belt's
weight is not applied: the rigs carry the whole wheel's weight.

Integrator: symplectic (semi-implicit) Euler with a fixed internal step
``h = dt / ceil(dt / h_max)``; the Coriolis term is applied as an exact
rotation of the in-plane velocity by ``2 omega h`` between two half kicks
(the Boris scheme), so it adds no energy drift. The belt's stiffest terms
(the chords' extension, its lateral bending and torsion) are linearly
implicit after the kick (:mod:`.implicit`), so ``h_max`` is the smaller of
the explicit terms' stability limit
(:func:`tyrelab.tyre.ring.parameters.stable_step`) and the accuracy cap
:data:`~.model.ACCURATE_STEP` (docs/ring.md, "Performance"). The hub loads written out are the
averages over the internal steps of the foundation forces on the rim
(``-sum F_foundation``) and their moment about the wheel centre.
"""

from __future__ import annotations

import math

import numba as nb

from ...road.terrain import terrain_height
from ..handling.slip import slip
from ..wheel import WheelLoads, WheelPose
from .belt import bending_forces, foundation_forces, membrane_forces, out_of_plane_forces
from .implicit import chord_implicit, lateral_implicit
from .records import (KIN_HELD, KIN_OMEGA, KIN_PSI, KIN_SLOPE, KIN_TIME, KIN_VX, KIN_VY,
                      KIN_VZ)
from .road_forces import patch_hysteresis, tread_contact
from .tread import (ACC_DEFL, ACC_FX, ACC_FY, ACC_FZ, ACC_NX, ACC_NY, ACC_NZ, ACC_PX, ACC_PY,
                    ACC_PZ, ACC_W)


# inlined into ring_advance: a call copies the records' several hundred fields
@nb.njit(cache=True, inline="always")
def ring_substep(params, state, road, pose, arx, ary, arz, h, patch_decay):
    """One internal step of length h at ``pose`` (centre at this step's start).

    ``ar`` the rim's acceleration [m/s^2] (its spin is held: :func:`rim_spin_change`),
    ``patch_decay = 1 - exp(-h / tau_p)`` the relaxation of the
    contact patch's Maxwell element over the step. Returns the loads on the
    rim ``(Fx, Fy, Fz, Mx, My, Mz)`` (world, moment about the centre) at the
    start of the step.

    :func:`ring_kick` evaluates the forces and gives the kick (with the
    chords' implicit solve); then the out-of-plane implicit solve (which
    factorises, allocating, when the step length changes) and the drift.
    """
    rim = ring_kick(params, state, road, pose, arx, ary, arz, h, patch_decay)
    lateral_implicit(params, state, h)
    p1s, p2s, v1s, v2s = state.p1, state.p2, state.v1, state.v2
    ys, vys, bs, vbs = state.y, state.vy, state.beta, state.vbeta
    for i in range(params.n_segments):
        p1s[i] += h * v1s[i]
        p2s[i] += h * v2s[i]
        ys[i] += h * vys[i]
        bs[i] += h * vbs[i]
    kin = state.kinematics
    kin[KIN_PSI] = kin[KIN_PSI] + pose.omega * h
    return rim


# Compiled without reference counting (numba's ``_nrt=False`` flag, which the
# functions it calls inherit when they are compiled for it): it allocates
# nothing (numba refuses to compile an allocation under this flag) and only
# borrows the arrays of its records, which its caller holds. With reference
# counting, each record handed to an inlined helper in the contact loops
# (segment_can_touch, segment_contact, local_zmax, ...) took and dropped a
# reference to every array in it (atomic operations that numba's pruning
# left in place): a fifth of a trailer step on the Belgian paving
# (docs/ring.md, "Performance").
@nb.njit(cache=True, _nrt=False)
def ring_kick(params, state, road, pose, arx, ary, arz, h, patch_decay):
    """The forces of one internal step (:func:`ring_substep`) and the kick they give.

    Evaluates the foundation, belt, inertial and tread-contact forces and the
    contact patch's Maxwell element, updates the velocities (symplectic
    Euler, Coriolis as an exact rotation) and solves the chords' extension
    implicitly. Returns the loads on the rim at the start of the step.
    """
    n = params.n_segments
    m = params.segment_mass
    jt = params.segment_twist_inertia
    cx, cy, cz = pose.cx, pose.cy, pose.cz
    ax, ay, az = pose.ax, pose.ay, pose.az
    omega = pose.omega
    p1s, p2s, v1s, v2s = state.p1, state.p2, state.v1, state.v2
    vys, vbs = state.vy, state.vbeta
    f1, f2, fy, fb = state.f1, state.f2, state.fy, state.fb
    acc = state.patch
    kin = state.kinematics
    cos_t = params.cos_theta
    sin_t = params.sin_theta
    # rotating axes: E1 = cos(psi) f - sin(psi) up, E2 = sin(psi) f + cos(psi) up,
    # f = a x e_z (forward), up = f x a; a x E1 = -E2, a x E2 = E1
    fl = math.sqrt(ay * ay + ax * ax)
    fwx = ay / fl
    fwy = -ax / fl
    fwz = 0.0
    upx = fwy * az - fwz * ay
    upy = fwz * ax - fwx * az
    upz = fwx * ay - fwy * ax
    psi = kin[KIN_PSI]
    cps = math.cos(psi)
    sps = math.sin(psi)
    e1x = cps * fwx - sps * upx
    e1y = cps * fwy - sps * upy
    e1z = cps * fwz - sps * upz
    e2x = sps * fwx + cps * upx
    e2y = sps * fwy + cps * upy
    e2z = sps * fwz + cps * upz
    # foundation: its reaction is the load on the rim
    foundation_forces(params, state)
    r1 = 0.0
    r2 = 0.0
    ry = 0.0
    ma = 0.0
    m1 = 0.0
    m2 = 0.0
    for i in range(n):
        p1 = p1s[i]
        p2 = p2s[i]
        g1 = -f1[i]
        g2 = -f2[i]
        gy = -fy[i]
        r1 += g1
        r2 += g2
        ry += gy
        # moment about the centre of the rim force acting at the segment
        # (E1 x E2 = -a, E1 x a = E2, E2 x a = -E1) and the torsion spring
        ma -= p1 * g2 - p2 * g1
        m1 -= gy * p2
        m2 += gy * p1
        m1 += fb[i] * sin_t[i]
        m2 -= fb[i] * cos_t[i]
    rim_fx = r1 * e1x + r2 * e2x + ry * ax
    rim_fy = r1 * e1y + r2 * e2y + ry * ay
    rim_fz = r1 * e1z + r2 * e2z + ry * az
    rim_mx = m1 * e1x + m2 * e2x + ma * ax
    rim_my = m1 * e1y + m2 * e2y + ma * ay
    rim_mz = m1 * e1z + m2 * e2z + ma * az
    membrane_forces(params, state)
    bending_forces(params, state)
    out_of_plane_forces(params, state)
    # inertial (rotating-frame) forces: centrifugal and the rim's acceleration
    a1 = arx * e1x + ary * e1y + arz * e1z
    a2 = arx * e2x + ary * e2y + arz * e2z
    aa = arx * ax + ary * ay + arz * az
    w2 = omega * omega
    for i in range(n):
        p1 = p1s[i]
        p2 = p2s[i]
        f1[i] += m * (w2 * p1 - a1)
        f2[i] += m * (w2 * p2 - a2)
        fy[i] -= m * aa
    # tread contact
    acc[ACC_DEFL] = -1.0
    w0 = acc[ACC_W]
    px0, py0, pz0 = acc[ACC_PX], acc[ACC_PY], acc[ACC_PZ]
    nx0, ny0, nz0 = acc[ACC_NX], acc[ACC_NY], acc[ACC_NZ]
    tread_contact(params, state, road, pose, e1x, e1y, e1z, e2x, e2y, e2z, fwx, fwy, fwz, h)
    # the contact patch's Maxwell element, between the road and the rim at the
    # patch's centre, along its mean normal (this step's sums)
    fn = acc[ACC_W] - w0
    f_patch = patch_hysteresis(params, state, fn, patch_decay)
    if f_patch != 0.0:
        gx = acc[ACC_NX] - nx0
        gy = acc[ACC_NY] - ny0
        gz = acc[ACC_NZ] - nz0
        gl = math.sqrt(gx * gx + gy * gy + gz * gz)
        gx *= f_patch / gl
        gy *= f_patch / gl
        gz *= f_patch / gl
        lx = (acc[ACC_PX] - px0) / fn - cx
        ly = (acc[ACC_PY] - py0) / fn - cy
        lz = (acc[ACC_PZ] - pz0) / fn - cz
        rim_fx += gx
        rim_fy += gy
        rim_fz += gz
        rim_mx += ly * gz - lz * gy
        rim_my += lz * gx - lx * gz
        rim_mz += lx * gy - ly * gx
        acc[ACC_FX] += gx
        acc[ACC_FY] += gy
        acc[ACC_FZ] += gz
    # symplectic Euler; Coriolis as an exact rotation of the in-plane velocity;
    # the stiff belt terms implicitly after the kick (.implicit)
    relax = 1.0 / (1.0 + h * params.relax_rate)
    cr = math.cos(2.0 * omega * h)
    sr = math.sin(2.0 * omega * h)
    hm = h / m
    hj = h / jt
    for i in range(n):
        # Boris splitting: half kick, rotation, half kick (no energy drift)
        v1 = v1s[i] + 0.5 * hm * f1[i]
        v2 = v2s[i] + 0.5 * hm * f2[i]
        v1s[i] = (cr * v1 - sr * v2 + 0.5 * hm * f1[i]) * relax
        v2s[i] = (sr * v1 + cr * v2 + 0.5 * hm * f2[i]) * relax
        vys[i] = (vys[i] + hm * fy[i]) * relax
        vbs[i] = (vbs[i] + hj * fb[i]) * relax
    chord_implicit(params, state, h)
    return rim_fx, rim_fy, rim_fz, rim_mx, rim_my, rim_mz


@nb.njit(cache=True)
def ring_advance(params, state, road, pose, dt):
    """Advance ``state`` by ``dt`` in internal steps at ``pose`` (the rim's pose at the start).

    Returns ``(n_sub, Fx, Fy, Fz, Mx, My, Mz)``: the number of internal
    steps and the mean rim force and moment over them; ``state.patch``
    receives the summed contact-patch quantities (see :mod:`.tread`),
    its ``ACC_DEFL`` entry those of the last internal step.
    """
    n_sub = int(math.ceil(dt / params.max_step - 1e-9))
    if n_sub < 1:
        n_sub = 1
    h = dt / n_sub
    patch_decay = 1.0 - math.exp(-h / params.patch_hysteresis_time)
    cx, cy, cz = pose.cx, pose.cy, pose.cz
    vx, vy, vz = pose.vx, pose.vy, pose.vz
    omega = pose.omega
    kin = state.kinematics
    # the rim's spin is held over the step; a change since the last one moves the belt's
    # coordinates at once (rim_spin_change), not by an Euler force over the step
    held = 0.0
    arx = 0.0
    ary = 0.0
    arz = 0.0
    if state.initialised[0]:
        if dt > 0.0:
            arx = (vx - kin[KIN_VX]) / dt
            ary = (vy - kin[KIN_VY]) / dt
            arz = (vz - kin[KIN_VZ]) / dt
        held = kin[KIN_HELD]
        if omega != kin[KIN_OMEGA]:
            rim_spin_change(params, state, omega - kin[KIN_OMEGA], held, kin[KIN_SLOPE])
            held = 0.0
    fx = 0.0
    fy = 0.0
    fz = 0.0
    mx = 0.0
    my = 0.0
    mz = 0.0
    acc = state.patch
    for k in range(acc.shape[0]):
        acc[k] = 0.0
    defl = -1.0
    for k in range(n_sub):
        t = k * h
        at = WheelPose(cx + vx * t, cy + vy * t, cz + vz * t, pose.ax, pose.ay, pose.az,
                       vx, vy, vz, omega)
        rfx, rfy, rfz, rmx, rmy, rmz = ring_substep(params, state, road, at, arx, ary, arz, h,
                                                    patch_decay)
        fx += rfx
        fy += rfy
        fz += rfz
        mx += rmx
        my += rmy
        mz += rmz
        defl = acc[ACC_DEFL]
    acc[ACC_DEFL] = defl
    state.initialised[0] = True
    kin[KIN_VX] = vx
    kin[KIN_VY] = vy
    kin[KIN_VZ] = vz
    kin[KIN_OMEGA] = omega
    kin[KIN_TIME] += dt
    kin[KIN_HELD] = held + dt
    return n_sub, fx / n_sub, fy / n_sub, fz / n_sub, mx / n_sub, my / n_sub, mz / n_sub


@nb.njit(cache=True)
def rim_spin_change(params, state, d_omega, held, slope):
    """Bring the belt to the rim whose spin changed by ``d_omega`` [rad/s] after turning for
    ``held`` [s] at the last one, which the rig stepped with the ``slope`` [N m s/rad] the last
    step gave it (:func:`rim_spin_slope`); the belt held where it is.

    The rotating axes turned through the last steps at the spin of their start; the rim turned
    at the mean of the spins at their ends (the trapezoidal rule), further by
    ``t = d_omega held / 2``. So the axes turn on by ``t`` (``psi``) and the belt's coordinates
    in them by ``+t`` (``p' = R(t) p``, as a point at rest is carried in axes spinning with
    ``a``), its velocities with them. Its velocity relative to the rim changes by
    ``-d_omega a x p'`` (``a x E1 = -E2``, ``a x E2 = E1``), its own unchanged, but for the
    moment the rig gave the rim in advance: stepping the spin linearly implicitly, the rim
    took ``held slope d_omega`` more angular momentum than the belt gave it over those steps
    (the foundation's pull of a rim already turning faster), and the belt takes the opposite,
    spread as a common tangential velocity ``beta a x p'``, ``beta = -held slope d_omega /
    sum m |p'|^2``: rim and belt together keep their angular momentum.

    Why: the change was an Euler force ``-m Omega' x p`` spread over the next step, the belt
    moving on with part of the rim's new spin; the rim-belt coupling then grew by
    ``k dt^2 / 2 / (I - dt slope)`` a step, which the XZL's foundation damping all but
    cancelled with its 50 kg m^2, and a rim as light as its own (3.4 kg m^2 on the foundation's
    1.16e6 N m/rad) diverged at 1 ms. Now one step's linear map has
    ``det = 1 - c dt / (I - dt slope)``: the foundation's damping, no more, for any rim."""
    turn = 0.5 * d_omega * held
    state.kinematics[KIN_PSI] += turn
    c = math.cos(turn)
    s = math.sin(turn)
    p1s, p2s, v1s, v2s = state.p1, state.p2, state.v1, state.v2
    n = p1s.shape[0]
    spread = 0.0
    for i in range(n):
        p1 = p1s[i]
        p2 = p2s[i]
        v1 = v1s[i]
        v2 = v2s[i]
        p1s[i] = c * p1 - s * p2
        p2s[i] = s * p1 + c * p2
        v1s[i] = c * v1 - s * v2
        v2s[i] = s * v1 + c * v2
        spread += p1s[i] * p1s[i] + p2s[i] * p2s[i]
    if spread <= 0.0:
        return
    # (beta - d_omega) a x p' = (beta - d_omega) (p2', -p1')
    w = -held * slope * d_omega / (params.segment_mass * spread) - d_omega
    for i in range(n):
        v1s[i] += w * p2s[i]
        v2s[i] -= w * p1s[i]


@nb.njit(cache=True, inline="always")
def _finite(x):
    return x if math.isfinite(x) else 0.0


@nb.njit(cache=True)
def ring_step(wheel, pose, dt):
    """Advance the ring of ``wheel`` by ``dt`` [s] at ``pose``; the loads on the rim.

    ``wheel.contact`` is the :class:`~.records.RingParams`, ``wheel.state``
    the :class:`~.records.RingState` (advanced in place), ``wheel.road``
    the terrain record (:mod:`tyrelab.road.terrain`). Forces and moments are
    the means over the internal steps; the contact point and normal are the
    normal-force-weighted means over the patch, the deflection the largest of
    a contact point (or the gap below the centre when nothing touches); FXW,
    FYW, FZW the patch's resultant in the W-axis. Non-finite values are
    returned as 0.
    """
    params = wheel.contact
    state = wheel.state
    road = wheel.road
    n_sub, fx, fy, fz, mx, my, mz = ring_advance(params, state, road, pose, dt)
    cx, cy, cz = pose.cx, pose.cy, pose.cz
    ax, ay, az = pose.ax, pose.ay, pose.az
    acc = state.patch
    w = acc[ACC_W]
    r0 = params.unloaded_radius
    if w > 0.0:
        px = acc[ACC_PX] / w
        py = acc[ACC_PY] / w
        pz = acc[ACC_PZ] / w
        nl = math.sqrt(acc[ACC_NX] ** 2 + acc[ACC_NY] ** 2 + acc[ACC_NZ] ** 2)
        nx = acc[ACC_NX] / nl
        ny = acc[ACC_NY] / nl
        nz = acc[ACC_NZ] / nl
        rho = acc[ACC_DEFL]
        if rho <= 0.0:
            rho = 1e-9
    else:
        g = terrain_height(road, cx, cy)
        px = cx
        py = cy
        pz = g
        nx = 0.0
        ny = 0.0
        nz = 1.0
        rho = r0 - (cz - g)
        if rho > -1e-9:
            rho = -1e-9
    rho_dot = -(pose.vx * nx + pose.vy * ny + pose.vz * nz)
    # contact-patch resultant in the W-axis: z along the normal, x = a x n
    cfx = acc[ACC_FX] / n_sub
    cfy = acc[ACC_FY] / n_sub
    cfz = acc[ACC_FZ] / n_sub
    wx1 = ay * nz - az * ny
    wx2 = az * nx - ax * nz
    wx3 = ax * ny - ay * nx
    wl = math.sqrt(wx1 * wx1 + wx2 * wx2 + wx3 * wx3)
    if wl > 0.0:
        wx1 /= wl
        wx2 /= wl
        wx3 /= wl
    wy1 = ny * wx3 - nz * wx2
    wy2 = nz * wx1 - nx * wx3
    wy3 = nx * wx2 - ny * wx1
    fxw = cfx * wx1 + cfy * wx2 + cfz * wx3
    fyw = cfx * wy1 + cfy * wy2 + cfz * wy3
    fzw = cfx * nx + cfy * ny + cfz * nz
    fzw = fzw if fzw > 0.0 else 0.0
    kappa = alpha = 0.0
    if w > 0.0:
        # the kinematic slip (ISO 8855 / TYDEX) of the wheel against its free-rolling radius:
        # the tread at R_e below the centre moves at v - omega R_e (a x n), as the handling
        # models' contact point does (handling.slip)
        v_long = pose.vx * wx1 + pose.vy * wx2 + pose.vz * wx3
        kappa, alpha = slip(v_long, v_long - pose.omega * params.rolling_radius,
                            pose.vx * wy1 + pose.vy * wy2 + pose.vz * wy3)
    slope = rim_spin_slope(params, dt)
    state.kinematics[KIN_SLOPE] = slope
    return WheelLoads(_finite(fx), _finite(fy), _finite(fz), _finite(mx), _finite(my),
                      _finite(mz), _finite(px), _finite(py), _finite(pz), _finite(nx),
                      _finite(ny), _finite(nz), _finite(rho), _finite(rho_dot), _finite(fxw),
                      _finite(fyw), _finite(fzw), _finite(kappa), _finite(alpha), slope)


@nb.njit(cache=True, inline="always")
def rim_spin_slope(params, dt):
    """The slope [N m s/rad] of the step's mean moment on the rim about its axle in the rim's
    spin, the belt held: ``-(c_theta + k_theta dt / 2)``, the foundation's tangential dampers
    and springs at the belt radius, ``c_theta = n r_b^2 c_t``, ``k_theta = n r_b^2 k_t`` (a rim
    turned faster by ``d omega`` slides past the belt at ``r_b d omega`` and winds the springs
    by ``r_b d omega t`` within the step). The rigs step the rim's spin with it linearly
    implicitly, ``(I - dt slope) d omega = dt M``, as they step an analytic model's wheel under
    its slip stiffness; with :func:`rim_spin_change` the rim-belt coupling is then stable for
    any rim (the rim alone, the wheel's spin inertia less the tyre's,
    :func:`tyrelab.limits.rim_spin_inertia`: the XZL's 3.4 kg m^2 on 1.16e6 N m/rad)."""
    r2n = params.n_segments * params.belt_radius * params.belt_radius
    return -r2n * (params.tangential_damping + 0.5 * params.tangential_stiffness * dt)
