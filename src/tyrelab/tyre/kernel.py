"""One compiled entry point for every tyre model: the loads on a wheel.

Rigs call :func:`wheel_force` inside their compiled time loops with the
wheel's pose and velocity; it returns the force and moment of the road on
the tyre. The contact model and the handling model are chosen by literal
integers (:data:`CONTACT_MODELS`, :data:`HANDLING_MODELS`): each rig has one
small entry function per combination (:mod:`tyrelab.rig._entries`), so numba
compiles a specialised, disk-cached loop per combination and no dispatch
happens at run time. Python assembles the arrays once with
:meth:`TyreModel.kernel_args`.

Output layout of ``out`` (SI, road frame unless noted):

==========  ====================================================
0:3         force of the road on the tyre [N]
3:6         contact point (where the resultant acts) [m]
6:9         unit normal of the (effective) road plane
9           deflection rho [m] (<= 0: no contact)
10          deflection rate [m/s]
11:14       FXW, FYW, FZW: force in the W-axis system [N]
14:17       moment of the road on the tyre about the wheel centre [N m]
17          longitudinal slip kappa [-]
18          slip angle alpha [rad]
19          d(spin moment)/d(omega) [N m s]: lets rigs integrate the
            spin implicitly (tyre slip stiffness makes it a stiff DOF)
==========  ====================================================
"""

from __future__ import annotations

from dataclasses import dataclass, field

import math

import numba as nb
import numpy as np
from numba.core import types
from numba.core.errors import TypingError
from numba.extending import overload

from ..core.vec3 import cross, dot, unit
from ..errors import InputError
from .contact.enveloping import enveloping_contact, enveloping_params
from .contact.point import GEO_NX, GEO_NY, GEO_NZ, GEO_PX, GEO_PY, GEO_PZ, GEO_RHO, point_contact
from .contact.volume import volume_contact, volume_params
from .handling.slip import VXLOW, handling_forces, handling_params
from .params import Tyre
from .ring.kernel import ring_wheel_force
from .vertical import normal_force

#: contact model name -> literal id used by the kernels
CONTACT_MODELS = {"point": 0, "volume": 1, "enveloping": 2, "ring": 3, "ring-tp": 4}
#: handling model name -> literal id
HANDLING_MODELS = {"none": 0, "pac89": 1, "mf": 2}
OUT_SIZE = 20
#: width of the road blocks whose maximum height bounds the contact search [m]
BLOCK_LENGTH = 0.04


def road_info(grid) -> np.ndarray:
    """``[zmin, zmax, x0, block_dx, nblocks, block maxima...]`` of a road grid.

    The maxima are taken over all y for blocks of :data:`BLOCK_LENGTH` along
    x; contact models use them to skip the part of the road no tyre can reach.
    """
    z = grid.z
    per = max(1, int(round(BLOCK_LENGTH / grid.dx)))
    nblocks = -(-z.shape[0] // per)
    col = z.max(axis=1)
    # a block's maximum includes its right edge node (bilinear cells span nodes)
    ends = np.minimum(np.arange(1, nblocks + 1) * per + 1, z.shape[0])
    maxima = np.maximum.reduceat(col, np.arange(nblocks) * per)
    maxima = np.maximum(maxima, col[ends - 1])
    return np.r_[z.min(), z.max(), grid.x0, per * grid.dx, nblocks, maxima]


@dataclass
class TyreModel:
    """A tyre with the models that drive it.

    Parameters
    ----------
    tyre : Tyre
        Parameters (from a ``.tir`` or :func:`tyrelab.tyre.library.load_tyre`).
    contact : str
        Contact model: one of :data:`CONTACT_MODELS`.
    handling : str
        Handling (tangential force) model: ``"none"``, ``"pac89"`` or ``"mf"``.
    """

    tyre: Tyre
    contact: str = "point"
    handling: str = "none"
    options: dict = field(default_factory=dict)

    def __post_init__(self):
        if self.contact not in CONTACT_MODELS:
            raise InputError(f"unknown model '{self.contact}', expected one of "
                             f"{', '.join(CONTACT_MODELS)}", field="model")
        if self.handling not in HANDLING_MODELS:
            raise InputError(f"unknown handling model '{self.handling}', expected one of "
                             f"{', '.join(HANDLING_MODELS)}", field="handling")

    @property
    def model_id(self) -> int:
        return CONTACT_MODELS[self.contact]

    @property
    def handling_id(self) -> int:
        return HANDLING_MODELS[self.handling]

    @property
    def is_ring(self) -> bool:
        return self.contact.startswith("ring")

    def contact_params(self, grid) -> np.ndarray:
        """Contact-model parameters packed for the kernel, for a road grid."""
        if self.contact == "point":
            step = min(grid.dx, grid.dy if grid.z.shape[1] > 2 else grid.dx)
            return np.array([self.tyre.unloaded_radius, max(step, 1e-4)])
        if self.contact == "volume":
            return volume_params(self.tyre, grid, **self.options)
        if self.contact == "enveloping":
            return enveloping_params(self.tyre, grid, **self.options)
        from .ring.model import ring_params
        return ring_params(self.tyre, grid, tread_pattern=self.contact == "ring-tp", **self.options)

    def initial_state(self, load: float) -> np.ndarray:
        """Internal state of the tyre at a static ``load`` [N] (empty for analytic models)."""
        if not self.is_ring:
            return np.zeros(1)
        from .ring.model import ring_initial_state
        return ring_initial_state(self.tyre, load, tread_pattern=self.contact == "ring-tp",
                                  **self.options)

    def kernel_args(self, grid) -> tuple:
        """``(vp, knots, coefs, cp, hp, gp, z, zinfo)`` for :func:`wheel_force`."""
        law = self.tyre.vertical_law
        return (law.params, law.knots, law.coefs, self.contact_params(grid),
                handling_params(self.tyre, self.handling), grid.params, grid.z, road_info(grid))


def _literal(value, what):
    if not isinstance(value, types.IntegerLiteral):
        raise TypingError(f"the {what} id must be a compile-time constant (see rig/_entries.py)")
    return value.literal_value


def contact_geometry(model, cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
    """Deflection, contact point and normal of analytic contact model ``model``.

    Compiled by overload: ``model`` must be a compile-time constant, and only
    the chosen model's code is compiled.
    """
    raise NotImplementedError("compiled only")


@overload(contact_geometry, prefer_literal=True)
def _contact_geometry(model, cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
    m = _literal(model, "contact model")
    if m == 0:
        def impl(model, cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
            point_contact(cp[0], cp[1], gp, z, zinfo, cx, cy, cz, ax, ay, az, geo)
    elif m == 1:
        def impl(model, cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
            volume_contact(cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo)
    elif m == 2:
        def impl(model, cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
            enveloping_contact(cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo)
    else:
        raise TypingError(f"contact model {m} is not an analytic contact model")
    return impl


def wheel_force(model, handling, vp, knots, coefs, cp, hp, gp, z, zinfo, ts,
                cx, cy, cz, ax, ay, az, vx, vy, vz, omega, dt, geo, out):
    """Loads of the road on the tyre of a wheel at centre c with spin axis a.

    ``v`` is the wheel-centre velocity, ``omega`` the spin rate (positive
    rolling forward), ``ts`` the tyre's internal state (advanced by ``dt``
    for models that have one). ``model`` and ``handling`` must be
    compile-time constants: the overload compiles only the chosen models.
    """
    raise NotImplementedError("compiled only")


@overload(wheel_force, prefer_literal=True)
def _wheel_force(model, handling, vp, knots, coefs, cp, hp, gp, z, zinfo, ts,
                 cx, cy, cz, ax, ay, az, vx, vy, vz, omega, dt, geo, out):
    m = _literal(model, "contact model")
    _literal(handling, "handling model")
    if m >= 3:
        def impl(model, handling, vp, knots, coefs, cp, hp, gp, z, zinfo, ts,
                 cx, cy, cz, ax, ay, az, vx, vy, vz, omega, dt, geo, out):
            for k in range(OUT_SIZE):
                out[k] = 0.0
            ring_wheel_force(model, cp, ts, gp, z, zinfo, cx, cy, cz, ax, ay, az,
                             vx, vy, vz, omega, dt, out)
        return impl

    def impl(model, handling, vp, knots, coefs, cp, hp, gp, z, zinfo, ts,
             cx, cy, cz, ax, ay, az, vx, vy, vz, omega, dt, geo, out):
        analytic_wheel_force(model, handling, vp, knots, coefs, cp, hp, gp, z, zinfo,
                             cx, cy, cz, ax, ay, az, vx, vy, vz, omega, geo, out)
    return impl


@nb.njit(cache=True)
def analytic_wheel_force(model, handling, vp, knots, coefs, cp, hp, gp, z, zinfo,
                         cx, cy, cz, ax, ay, az, vx, vy, vz, omega, geo, out):
    """:func:`wheel_force` for the analytic contact models.

    The normal force is thesis eq. 2.2 with the deflection rate ``-v . n``
    (the road does not move; the contact point slides along the road
    without changing the distance to first order); the handling model adds
    FXW, FYW and an aligning moment from the slip of the contact point.
    """
    for k in range(OUT_SIZE):
        out[k] = 0.0
    contact_geometry(model, cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo)
    rho = geo[GEO_RHO]
    nx = geo[GEO_NX]
    ny = geo[GEO_NY]
    nz = geo[GEO_NZ]
    px = geo[GEO_PX]
    py = geo[GEO_PY]
    pz = geo[GEO_PZ]
    out[3] = px
    out[4] = py
    out[5] = pz
    out[6] = nx
    out[7] = ny
    out[8] = nz
    out[9] = rho
    if rho <= 0.0:
        return
    rho_dot = -dot(vx, vy, vz, nx, ny, nz)
    fz = normal_force(vp, knots, coefs, rho, rho_dot)
    out[10] = rho_dot
    out[13] = fz
    rx, ry, rz = px - cx, py - cy, pz - cz
    fxw = 0.0
    fyw = 0.0
    mzw = 0.0
    wxx = wxy = wxz = wyx = wyy = wyz = 0.0
    if handling != 0:
        # W-axis: z along the normal, x in the wheel plane
        tx, ty, tz = cross(ax, ay, az, nx, ny, nz)
        wxx, wxy, wxz = unit(tx, ty, tz)
        wyx, wyy, wyz = cross(nx, ny, nz, wxx, wxy, wxz)
        # velocity of the wheel material at the contact point: v + omega a x r
        sx, sy, sz = cross(ax, ay, az, rx, ry, rz)
        v_long = dot(vx, vy, vz, wxx, wxy, wxz)
        v_slip_x = dot(vx + omega * sx, vy + omega * sy, vz + omega * sz, wxx, wxy, wxz)
        v_slip_y = dot(vx + omega * sx, vy + omega * sy, vz + omega * sz, wyx, wyy, wyz)
        gamma = math.asin(max(-1.0, min(1.0, dot(ax, ay, az, nx, ny, nz))))
        fxw, fyw, mzw, kappa, alpha, dfx = handling_forces(handling, hp, fz, v_long, v_slip_x,
                                                           v_slip_y, gamma)
        out[17] = kappa
        out[18] = alpha
        if dfx != 0.0:
            # spin moment of FXW at the contact point: ((r x w_x) . a) FXW, and
            # d kappa / d omega = -((a x r) . w_x) / max(|V_x|, VXLOW)
            lx, ly, lz = cross(rx, ry, rz, wxx, wxy, wxz)
            lever = dot(lx, ly, lz, ax, ay, az)
            vref = abs(v_long) if abs(v_long) > VXLOW else VXLOW
            out[19] = lever * dfx * (-dot(sx, sy, sz, wxx, wxy, wxz) / vref)
    out[11] = fxw
    out[12] = fyw
    fx = fz * nx + fxw * wxx + fyw * wyx
    fy = fz * ny + fxw * wxy + fyw * wyy
    fzz = fz * nz + fxw * wxz + fyw * wyz
    out[0] = fx
    out[1] = fy
    out[2] = fzz
    mx, my, mz = cross(rx, ry, rz, fx, fy, fzz)
    out[14] = mx + mzw * nx
    out[15] = my + mzw * ny
    out[16] = mz + mzw * nz
