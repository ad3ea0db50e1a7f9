"""One compiled entry point for every tyre model: the force on a wheel.

Rigs call :func:`wheel_force` inside their compiled time loops with the
wheel's pose and velocity; it returns the force of the road on the tyre. The
contact model is chosen by a literal integer (``CONTACT_MODELS``), so numba
compiles one specialised, cached loop per model and no dispatch happens at
run time. Python assembles the arrays once with :meth:`TyreModel.kernel_args`.

Output layout of ``out`` (all SI, road frame unless noted):

==========  ====================================================
0:3         force of the road on the tyre [N]
3:6         point it acts at (contact point) [m]
6:9         unit normal of the (effective) road plane
9           deflection rho [m] (<= 0: no contact)
10          deflection rate [m/s]
11:14       FXW, FYW, FZW: force in the W-axis system [N]
==========  ====================================================
"""

from __future__ import annotations

from dataclasses import dataclass

import numba as nb
import numpy as np

from ..core.vec3 import cross, dot, unit
from ..errors import InputError
from .contact.point import GEO_NX, GEO_NY, GEO_NZ, GEO_PX, GEO_PY, GEO_PZ, GEO_RHO, GEO_SIZE, point_contact
from .params import Tyre
from .vertical import normal_force

#: contact model name -> literal id used by the kernels
CONTACT_MODELS = {"point": 0}
OUT_SIZE = 14


@dataclass
class TyreModel:
    """A tyre with the contact model that drives it.

    Parameters
    ----------
    tyre : Tyre
        Parameters (from a ``.tir`` or :func:`tyrelab.tyre.library.load_tyre`).
    contact : str
        ``"point"`` (more models join :data:`CONTACT_MODELS`).
    """

    tyre: Tyre
    contact: str = "point"

    def __post_init__(self):
        if self.contact not in CONTACT_MODELS:
            raise InputError(f"unknown model '{self.contact}', expected one of "
                             f"{', '.join(CONTACT_MODELS)}", field="model")

    @property
    def model_id(self) -> int:
        return CONTACT_MODELS[self.contact]

    def contact_params(self, grid) -> np.ndarray:
        """Model parameters packed for the kernel, for a road grid."""
        step = min(grid.dx, grid.dy if grid.z.shape[1] > 2 else grid.dx)
        return np.array([self.tyre.unloaded_radius, max(step, 1e-4)])

    def kernel_args(self, grid) -> tuple:
        """``(vp, knots, coefs, cp, gp, z, zinfo)`` for :func:`wheel_force`."""
        law = self.tyre.vertical_law
        zinfo = road_info(grid)
        return (law.params, law.knots, law.coefs, self.contact_params(grid), grid.params, grid.z, zinfo)


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
    maxima = np.array([col[i * per:min((i + 1) * per + 1, z.shape[0])].max() for i in range(nblocks)])
    return np.r_[z.min(), z.max(), grid.x0, per * grid.dx, nblocks, maxima]


@nb.njit(cache=True)
def contact_geometry(model, cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
    """Deflection, contact point and normal for contact model ``model``."""
    if model == 0:
        point_contact(cp[0], cp[1], gp, z, zinfo, cx, cy, cz, ax, ay, az, geo)
    else:
        geo[GEO_RHO] = -1.0


@nb.njit(cache=True)
def wheel_force(model, vp, knots, coefs, cp, gp, z, zinfo,
                cx, cy, cz, ax, ay, az, vx, vy, vz, omega, geo, out):
    """Force of the road on the tyre of a wheel at centre c with spin axis a.

    ``v`` is the wheel-centre velocity, ``omega`` its spin rate. The normal
    force follows thesis eq. 2.2 with the deflection rate ``-v . n`` (the
    road does not move; the contact point slides along the road without
    changing the distance to first order).
    """
    contact_geometry(model, cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo)
    rho = geo[GEO_RHO]
    nx = geo[GEO_NX]
    ny = geo[GEO_NY]
    nz = geo[GEO_NZ]
    for k in range(OUT_SIZE):
        out[k] = 0.0
    out[3] = geo[GEO_PX]
    out[4] = geo[GEO_PY]
    out[5] = geo[GEO_PZ]
    out[6] = nx
    out[7] = ny
    out[8] = nz
    out[9] = rho
    if rho <= 0.0:
        return
    rho_dot = -dot(vx, vy, vz, nx, ny, nz)
    fz = normal_force(vp, knots, coefs, rho, rho_dot)
    out[0] = fz * nx
    out[1] = fz * ny
    out[2] = fz * nz
    out[10] = rho_dot
    out[13] = fz
