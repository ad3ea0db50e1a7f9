"""The wheel interface: what every tyre model gives every rig.

As in Project Chrono's ``ChTire``, every tyre model sits behind one step,
:func:`wheel_step` ("advance this wheel by dt on this road"), so every rig
takes every model. Across the compiled boundary everything is a named
record (NamedTuple):

* :class:`Wheel` -- what a rig holds per wheel: the vertical law, the
  contact model's parameter record, the handling model's parameter record,
  the ground (a terrain record, :mod:`tyrelab.road.terrain`: the rigid road's
  :class:`~tyrelab.road.grid.RoadSurface`, ...) and the model's internal
  state;
* :class:`WheelPose` -- where the rim is and how it moves;
* :class:`ContactGeometry` -- what an analytic contact model finds;
* :class:`WheelLoads` -- what the road does to the tyre.

Conventions (written once, see ARCHITECTURE.md): SI units; road frame x
forward along the road, z up; forces and moments are those *of the road on
the tyre*, moments about the wheel centre; FXW, FYW, FZW in the W-axis
system (z along the road normal, x in the wheel plane).

Dispatch happens at compile time, on the type of the parameter records
(:mod:`tyrelab.tyre.registry`) and of the terrain record
(:mod:`tyrelab.road.terrain`): numba compiles, and caches on disk, one
specialisation of each rig loop per combination of models and ground.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np
from numba.extending import overload

from ..core.named_index import named_index
from ..core.vec3 import cross, dot, unit
from ..road.terrain import terrain_contact, terrain_friction, terrain_is_rigid
from .handling.relaxation import SlipLag, lagged, relaxation_lengths
from .handling.slip import VXLOW, slip  # the slips' low-speed floor, one value for both
from .registry import contact_by_record, handling_by_record
from .vertical import VerticalLaw, normal_force

#: the fixed point of a load that softens with its forces (MF-Tyre's Q_FCX, Q_FCY): at most
#: this many passes, done when the load moves by less than this fraction of itself
MAX_SOFTENING_PASSES = 60
SOFTENING_TOLERANCE = 1e-10


class WheelPose(NamedTuple):
    """Position and motion of a rim (road frame, SI).

    ``c`` wheel centre [m], ``a`` unit spin axis (pointing to the wheel's
    left), ``v`` velocity of the centre [m/s], ``omega`` spin rate about
    ``a`` [rad/s] (positive when rolling forward).
    """

    cx: float
    cy: float
    cz: float
    ax: float
    ay: float
    az: float
    vx: float
    vy: float
    vz: float
    omega: float


class ContactGeometry(NamedTuple):
    """What an analytic contact model finds: deflection, contact point, normal.

    ``deflection`` <= 0 means no contact (its magnitude is then the gap, or
    0 when unknown); ``n`` is the unit normal of the (effective) road plane,
    pointing out of the road; ``curvature`` is the effective road curvature
    along the heading [1/m] (enveloping model; 0 otherwise).
    """

    deflection: float
    px: float
    py: float
    pz: float
    nx: float
    ny: float
    nz: float
    curvature: float


class WheelLoads(NamedTuple):
    """Loads of the road on the tyre after a wheel step.

    ``f`` force [N] and ``m`` moment about the wheel centre [N m] (road
    frame); ``p`` contact point, ``n`` road normal there; ``deflection``
    [m] (<= 0: no contact) and its rate [m/s]; ``fxw, fyw, fzw`` the
    contact force in the W-axis system [N] (``fzw`` >= 0 always); ``kappa``
    longitudinal slip, ``alpha`` slip angle [rad]; ``dspin_domega``
    d(spin moment)/d(omega) [N m s], which lets a rig integrate the spin
    implicitly (the slip stiffness makes it a stiff degree of freedom).
    """

    fx: float
    fy: float
    fz: float
    mx: float
    my: float
    mz: float
    px: float
    py: float
    pz: float
    nx: float
    ny: float
    nz: float
    deflection: float
    deflection_rate: float
    fxw: float
    fyw: float
    fzw: float
    kappa: float
    alpha: float
    dspin_domega: float


#: number of fields of a :class:`WheelLoads` (the columns of :func:`loads_table`)
N_LOADS = len(WheelLoads._fields)
#: the columns of a row of poses (:func:`loads_table`): a :class:`WheelPose`'s fields, in
#: order, and their positions (``p[WP.cz]``)
POSE_FIELDS = WheelPose._fields
WP = named_index("WheelPoseIndex", POSE_FIELDS)


class Wheel(NamedTuple):
    """One wheel as a rig holds it: laws, parameters, road and state.

    ``contact`` and ``handling`` are the parameter records of the chosen
    models (:mod:`tyrelab.tyre.registry`); ``road`` is the terrain record of
    the ground (:mod:`tyrelab.road.terrain`; the rigid road's
    :class:`~tyrelab.road.grid.RoadSurface`), which the models query only
    through the terrain interface; ``state`` is the contact model's internal
    state (its own record or array; mutated in place by :func:`wheel_step`);
    ``lag`` the transient slip of the handling model's forces (relaxation
    lengths and carcass deflections, :mod:`tyrelab.tyre.handling.relaxation`;
    its deflections mutated in place too).
    Build one with :meth:`tyrelab.tyre.model.TyreModel.wheel`.
    """

    law: VerticalLaw
    contact: tuple
    handling: tuple
    road: tuple
    state: object
    lag: SlipLag


# --- compile-time dispatch on the record types ---------------------------------

def contact_geometry(params, road, pose):
    """:class:`ContactGeometry` of the analytic contact model whose record is ``params``."""
    raise NotImplementedError("compiled only")


@overload(contact_geometry, inline="always")
def _contact_geometry(params, road, pose):
    geometry = contact_by_record(params).geometry
    if geometry is None:
        return None

    def impl(params, road, pose):
        return geometry(params, road, pose)
    return impl


def handling_forces(params, fz, v_long, v_slip_x, v_slip_y, gamma):
    """``(FXW, FYW, MZW, kappa, alpha, dFXW/dkappa)`` of the handling model of ``params``."""
    raise NotImplementedError("compiled only")


@overload(handling_forces)
def _handling_forces(params, fz, v_long, v_slip_x, v_slip_y, gamma):
    forces = handling_by_record(params).forces

    def impl(params, fz, v_long, v_slip_x, v_slip_y, gamma):
        return forces(params, fz, v_long, v_slip_x, v_slip_y, gamma)
    return impl


def rolling_lever(params, fz, omega, sx, sy, sz):
    """The lever ``a x r`` of a slip velocity's spin part, ``(sx, sy, sz)``, stretched to the
    effective rolling radius the handling model of ``params`` defines its slip with
    (:attr:`~tyrelab.tyre.registry.HandlingModel.rolling_radius`, at load ``fz`` [N] and spin
    ``omega`` [rad/s]): scaled from its length ``|a x r|``, r's distance from the axis; as it
    is for a model without one (decided at compile time: no work per step)."""
    raise NotImplementedError("compiled only")


@overload(rolling_lever)
def _rolling_lever(params, fz, omega, sx, sy, sz):
    radius = handling_by_record(params).rolling_radius
    if radius is None:
        def impl(params, fz, omega, sx, sy, sz):
            return sx, sy, sz
    else:
        def impl(params, fz, omega, sx, sy, sz):
            stretch = radius(params, fz, omega) / math.sqrt(sx * sx + sy * sy + sz * sz)
            return sx * stretch, sy * stretch, sz * stretch
    return impl


def has_handling(params):
    """True unless ``params`` is the record of the "none" handling model (compile time)."""
    raise NotImplementedError("compiled only")


@overload(has_handling)
def _has_handling(params):
    active = handling_by_record(params).name != "none"

    def impl(params):
        return active
    return impl


def rolling_moment(params, fz, fx, v_long, omega, kappa, gamma, radius):
    """The rolling resistance moment My [N m] of the handling model of ``params`` about the
    W-axis y (:attr:`~tyrelab.tyre.registry.HandlingModel.rolling_resistance`) at the loaded
    radius ``radius`` [m]; 0 for a model without one (compile time)."""
    raise NotImplementedError("compiled only")


def overturning_moment(params, fz, fy, v_long, gamma):
    """The overturning moment Mx [N m] of the handling model of ``params`` about the W-axis x
    at the contact point (:attr:`~tyrelab.tyre.registry.HandlingModel.overturning`); 0 for a
    model without one (compile time)."""
    raise NotImplementedError("compiled only")


def _moment_or_zero(stub, hook: str) -> None:
    """Compile ``stub(params, ...)`` as the handling model's optional moment ``hook`` (an
    attribute of :class:`~tyrelab.tyre.registry.HandlingModel`) called with the same
    arguments, or as 0.0 for a model without it (decided at compile time)."""
    @overload(stub)
    def _dispatch(params, *args):
        own = getattr(handling_by_record(params), hook)
        if own is None:
            def impl(params, *args):
                return 0.0
            return impl

        def impl(params, *args):  # noqa: F811 - the other branch's
            return own(params, *args)
        return impl


_moment_or_zero(rolling_moment, "rolling_resistance")
_moment_or_zero(overturning_moment, "overturning")


def wheel_step(wheel, pose, dt):
    """Advance ``wheel`` by ``dt`` [s] at ``pose``; returns its :class:`WheelLoads`.

    Analytic contact models (no state) evaluate their geometry, the vertical
    law and the handling model (:func:`analytic_wheel_step`); models with
    dynamics (the ring) advance their state with their own registered step.
    """
    raise NotImplementedError("compiled only")


def _field_type(record_type, name):
    """numba type of field ``name`` of a NamedTuple type (at compile time)."""
    return record_type.types[record_type.fields.index(name)]


@overload(wheel_step)
def _wheel_step(wheel, pose, dt):
    model = contact_by_record(_field_type(wheel, "contact"))
    if model.step is not None:
        step = model.step

        def impl(wheel, pose, dt):
            return step(wheel, pose, dt)
        return impl

    # the model's geometry is called directly, not through the contact_geometry overload:
    # an inline overload is compiled on its own before it is inlined, a second full typing
    # of the contact model (0.8 s of the enveloping trailer's cold compile)
    geometry = model.geometry

    def impl(wheel, pose, dt):
        return analytic_wheel_step(wheel, pose, geometry(wheel.contact, wheel.road, pose), dt)
    return impl


@nb.njit(cache=True, inline="always")
def analytic_wheel_step(wheel, pose, geo, dt):
    """Loads of an analytic contact model at contact geometry ``geo`` over a step ``dt`` [s]:
    eq. 2.2 along the contact normal, plus handling.

    The normal force is thesis eq. 2.2 with the deflection rate ``-v . n``
    (the road does not move; the contact point slides along the road
    without changing the distance to first order); the handling model adds
    FXW, FYW and an aligning moment from the slip of the contact point
    (rigid-ring kinematics: the lever is the loaded radius, or the handling
    model's effective rolling radius if it defines its slip with one,
    :func:`rolling_lever`), scaled by the
    ground's friction scale there (:func:`~tyrelab.road.terrain.terrain_friction`;
    the whole curve scales, its slip stiffness too: the handling models take no
    friction input). With a transient slip (``wheel.lag``), the forces are those of the
    lagged slips and the carcass deflections advance by ``dt``
    (:mod:`~tyrelab.tyre.handling.relaxation`); ``kappa`` and ``alpha`` stay the
    kinematic slips. A handling model with a rolling resistance adds its moment My about the
    W-axis y (:func:`rolling_moment`; its slope in the spin is left out of ``dspin_domega``,
    a fraction of a per cent of the slip's). A law that softens with the horizontal forces (MF-Tyre's
    ``Q_FCX``, ``Q_FCY``) and the forces at its load are solved together (the
    load that carries its own forces). A ground that is not rigid then answers
    the contact's forces (:func:`~tyrelab.road.terrain.terrain_contact`, a point
    contact: area 0); on the rigid road that branch is compiled out.
    """
    rho = geo.deflection
    nx, ny, nz = geo.nx, geo.ny, geo.nz
    px, py, pz = geo.px, geo.py, geo.pz
    if rho <= 0.0:
        if dt > 0.0:  # off the ground the carcass springs back: no deflection to land with
            wheel.lag.deflection[0] = 0.0
            wheel.lag.deflection[1] = 0.0
        return WheelLoads(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, px, py, pz, nx, ny, nz, rho, 0.0,
                          0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    cx, cy, cz = pose.cx, pose.cy, pose.cz
    ax, ay, az = pose.ax, pose.ay, pose.az
    vx, vy, vz = pose.vx, pose.vy, pose.vz
    omega = pose.omega
    rho_dot = -dot(vx, vy, vz, nx, ny, nz)
    fz = normal_force(wheel.law, rho, rho_dot, omega)
    rx, ry, rz = px - cx, py - cy, pz - cz
    fxw = 0.0
    fyw = 0.0
    mzw = 0.0
    kappa = 0.0
    alpha = 0.0
    dspin = 0.0
    wxx = wxy = wxz = wyx = wyy = wyz = 0.0
    v_slip_x = v_slip_y = 0.0
    rolling = 0.0  # the rolling resistance moment about the W-axis y
    overturning = 0.0  # the overturning moment about the W-axis x
    if has_handling(wheel.handling):
        # W-axis: z along the normal, x in the wheel plane
        tx, ty, tz = cross(ax, ay, az, nx, ny, nz)
        wxx, wxy, wxz = unit(tx, ty, tz)
        wyx, wyy, wyz = cross(nx, ny, nz, wxx, wxy, wxz)
        v_long = dot(vx, vy, vz, wxx, wxy, wxz)
        vref = abs(v_long) if abs(v_long) > VXLOW else VXLOW  # the slips' speed (slip.py)
        gamma = math.asin(max(-1.0, min(1.0, dot(ax, ay, az, nx, ny, nz))))
        # the ground's friction scale (1 on the rigid road, where the products are exact)
        mu = terrain_friction(wheel.road, px, py)
        ax_r, ay_r, az_r = cross(ax, ay, az, rx, ry, rz)
        softens = wheel.law.force_softening_x != 0.0 or wheel.law.force_softening_y != 0.0
        lag = wheel.lag
        lags = lag.from_model or lag.length_x > 0.0 or lag.length_y > 0.0  # SlipLag.active
        u1 = lag.deflection[0]
        v1 = lag.deflection[1]
        gain = 1.0
        sx = sy = sz = dfx = 0.0
        low, high = 0.0, fz  # the softened load lies between none and the unsoftened load
        for _ in range(MAX_SOFTENING_PASSES):
            # velocity of the wheel material at the contact point: v + omega a x r, the lever
            # stretched to the handling model's effective rolling radius when it has one (the
            # Magic Formula's slip is (omega Re - Vx) / Vx: its tread leaves the patch at Re, not
            # at the loaded radius; Besselink et al. 2010 eq. 7, MFeval)
            sx, sy, sz = rolling_lever(wheel.handling, fz, omega, ax_r, ay_r, az_r)
            v_slip_x = dot(vx + omega * sx, vy + omega * sy, vz + omega * sz, wxx, wxy, wxz)
            v_slip_y = dot(vx + omega * sx, vy + omega * sy, vz + omega * sz, wyx, wyy, wyz)
            if lags:
                # the forces of the lagged slips: the carcass deflections after this step, at
                # this load's relaxation lengths (relaxation.py); the slip speed as slip()'s
                length_x, length_y = relaxation_lengths(wheel.handling, lag, fz, v_long, gamma)
                u1, lagged_x, gain = lagged(lag.deflection[0], length_x, v_slip_x, vref, dt)
                v1, lagged_y, _ = lagged(lag.deflection[1], length_y, v_slip_y, vref, dt)
                fxw, fyw, mzw, kappa, alpha, dfx = handling_forces(wheel.handling, fz, v_long,
                                                                   lagged_x, lagged_y, gamma)
            else:
                fxw, fyw, mzw, kappa, alpha, dfx = handling_forces(wheel.handling, fz, v_long,
                                                                   v_slip_x, v_slip_y, gamma)
            fxw *= mu
            fyw *= mu
            mzw *= mu
            dfx *= mu
            if not softens:
                break
            # MF-Tyre's law softens with the forces it carries, which grow with the load
            # (Pacejka 2012, eq. A3.3): the load that carries its own forces, by fixed point
            # (a contraction where the softening is a few per cent of the load), kept inside
            # the bracket of the root and halving it where a step would leave it
            softened = normal_force(wheel.law, rho, rho_dot, omega, fxw, fyw)
            if abs(softened - fz) <= SOFTENING_TOLERANCE * max(softened, 1.0):
                fz = softened
                break
            if softened > fz:
                low = fz
            else:
                high = fz
            fz = softened if low < softened < high else 0.5 * (low + high)
        if dfx != 0.0:
            # spin moment of FXW at the contact point: ((r x w_x) . a) FXW, and
            # d kappa / d omega = -((a x r) . w_x) / max(|V_x|, VXLOW)
            lx, ly, lz = cross(rx, ry, rz, wxx, wxy, wxz)
            lever = dot(lx, ly, lz, ax, ay, az)
            # a lagged slip answers a change of spin over the step by its gain only
            dspin = lever * dfx * gain * (-dot(sx, sy, sz, wxx, wxy, wxz) / vref)
        if lags:
            lag.deflection[0] = u1
            lag.deflection[1] = v1
            kappa, alpha = slip(v_long, v_slip_x, v_slip_y)  # the kinematic slips, as without
        rolling = rolling_moment(wheel.handling, fz, fxw, v_long, omega, kappa, gamma,
                                 math.sqrt(rx * rx + ry * ry + rz * rz))
        overturning = overturning_moment(wheel.handling, fz, fyw, v_long, gamma)
    if not terrain_is_rigid(wheel.road):  # a deformable ground answers (compiled out on rigid)
        fz, fxw, fyw = terrain_contact(wheel.road, px, py, rho, 0.0, v_slip_x, v_slip_y, fz, fxw,
                                       fyw, dt)
    fx = fz * nx + fxw * wxx + fyw * wyx
    fy = fz * ny + fxw * wxy + fyw * wyy
    fzz = fz * nz + fxw * wxz + fyw * wyz
    mx, my, mz = cross(rx, ry, rz, fx, fy, fzz)
    # the aligning moment about the normal, the rolling resistance about the W-axis y, the
    # overturning moment about its x
    # (summed from the left, as before the overturning moment was added: bit for bit without it)
    mx = mx + mzw * nx + rolling * wyx + overturning * wxx
    my = my + mzw * ny + rolling * wyy + overturning * wxy
    mz = mz + mzw * nz + rolling * wyz + overturning * wxz
    return WheelLoads(fx, fy, fzz, mx, my, mz, px, py, pz, nx, ny, nz, rho, rho_dot, fxw, fyw,
                      fz, kappa, alpha, dspin)


def pose(cx=0.0, cy=0.0, cz=0.0, axis=(0.0, 1.0, 0.0), velocity=(0.0, 0.0, 0.0),
         omega=0.0) -> WheelPose:
    """A :class:`WheelPose` from named arguments (Python side)."""
    ax, ay, az = (float(v) for v in axis)
    vx, vy, vz = (float(v) for v in velocity)
    return WheelPose(float(cx), float(cy), float(cz), ax, ay, az, vx, vy, vz, float(omega))


@nb.njit(cache=True)
def step_many(wheel, poses, dt, out):
    """:func:`wheel_step` at each row of ``poses`` (n, 10: columns :data:`POSE_FIELDS`), loads
    into ``out`` (n, N_LOADS)."""
    for k in range(poses.shape[0]):
        p = poses[k]
        loads = wheel_step(wheel, WheelPose(p[WP.cx], p[WP.cy], p[WP.cz], p[WP.ax], p[WP.ay],
                                            p[WP.az], p[WP.vx], p[WP.vy], p[WP.vz], p[WP.omega]),
                           dt)
        for j in range(N_LOADS):
            out[k, j] = loads[j]


def loads_table(wheel: Wheel, poses, dt: float = 0.0) -> "np.ndarray":
    """Run :func:`wheel_step` over an array of poses; one :class:`WheelLoads` row each."""
    poses = np.ascontiguousarray(np.atleast_2d(poses), np.float64)
    out = np.zeros((poses.shape[0], N_LOADS))
    step_many(wheel, poses, dt, out)
    return out
