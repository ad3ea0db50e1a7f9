"""The vertical law shared by the point, volume and enveloping contact models.

Thesis eq. 2.2 / 4.1::

    Fz = k(rho) + c_z * rho_dot

with ``k(rho)`` linear (``VERTICAL_STIFFNESS``) or a cubic spline through the
``[DEFLECTION_LOAD_CURVE]`` table (up to 100 points). As in ADAMS/Tire, a
table, when present, replaces the linear stiffness. Beyond the last table
point the spline is continued as a straight line with its end slope (a cubic
continued past its data soon turns over; a tyre does not get softer when it
is pressed harder). The damping coefficient is ramped from zero at zero
deflection to its full value at ``DAMPING_RAMP`` (smoothstep), so the force
has no jump at touch-down; the total is clipped at zero, so there is no
tension and no negative normal force.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba as nb
import numpy as np
from scipy.interpolate import CubicSpline

from ..errors import InputError

#: default deflection over which damping ramps in [m]
DEFAULT_DAMPING_RAMP = 0.002


@dataclass(frozen=True)
class VerticalLaw:
    """Compiled-ready vertical law.

    ``params`` = ``[stiffness, damping, damping_ramp, use_table]``;
    ``knots`` (n,) deflections [m]; ``coefs`` (n-1, 4) cubic coefficients per
    interval, highest power first, in the local coordinate ``rho - knots[i]``.
    """

    params: np.ndarray
    knots: np.ndarray
    coefs: np.ndarray

    @classmethod
    def linear(cls, stiffness, damping, damping_ramp=DEFAULT_DAMPING_RAMP):
        p = np.array([stiffness, damping, damping_ramp, 0.0])
        return cls(p, np.zeros(2), np.zeros((1, 4)))

    @classmethod
    def table(cls, deflection, load, damping, damping_ramp=DEFAULT_DAMPING_RAMP,
              stiffness=0.0, source="load-deflection table"):
        d = np.asarray(deflection, float)
        f = np.asarray(load, float)
        if d.ndim != 1 or d.shape != f.shape or d.size < 2:
            raise InputError("a load-deflection table needs at least two (deflection, load) rows",
                             source=source)
        if d.size > 100:
            raise InputError(f"a load-deflection table holds at most 100 points, got {d.size}",
                             source=source)
        if np.any(np.diff(d) <= 0):
            raise InputError("deflections must increase strictly down the table", source=source)
        if d[0] > 0:  # the curve starts at the unloaded tyre
            d = np.r_[0.0, d]
            f = np.r_[0.0, f]
        bc = "not-a-knot" if d.size >= 4 else "natural"
        spline = CubicSpline(d, f, bc_type=bc)
        coefs = np.ascontiguousarray(spline.c.T)  # (n-1, 4), highest power first
        p = np.array([stiffness, damping, damping_ramp, 1.0])
        return cls(p, d, coefs)

    def static_load(self, rho):
        """Static load k(rho) [N] at deflections ``rho`` [m] (vectorised)."""
        rho = np.asarray(rho, float)
        out = np.empty(rho.size)
        for i, r in enumerate(rho.ravel()):
            out[i] = static_load(self.params, self.knots, self.coefs, r)
        return out.reshape(rho.shape)

    def deflection_at(self, load):
        """Static deflection [m] that carries ``load`` [N] (inverse of k)."""
        return static_deflection(self.params, self.knots, self.coefs, float(load))


@nb.njit(cache=True)
def static_load(vp, knots, coefs, rho):
    """Elastic part k(rho) [N]; zero for rho <= 0 (no tension)."""
    if rho <= 0.0:
        return 0.0
    if vp[3] == 0.0:
        return vp[0] * rho
    n = knots.shape[0]
    if rho >= knots[n - 1]:
        # linear continuation with the spline's end slope
        c = coefs[n - 2]
        h = knots[n - 1] - knots[n - 2]
        f_end = ((c[0] * h + c[1]) * h + c[2]) * h + c[3]
        slope = (3.0 * c[0] * h + 2.0 * c[1]) * h + c[2]
        value = f_end + slope * (rho - knots[n - 1])
    else:
        lo = 0
        hi = n - 1
        while hi - lo > 1:  # bisection over at most 100 knots
            mid = (lo + hi) // 2
            if knots[mid] <= rho:
                lo = mid
            else:
                hi = mid
        c = coefs[lo]
        h = rho - knots[lo]
        value = ((c[0] * h + c[1]) * h + c[2]) * h + c[3]
    return value if value > 0.0 else 0.0


@nb.njit(cache=True)
def normal_force(vp, knots, coefs, rho, rho_dot):
    """Normal force [N] of eq. 2.2 with damping ramped in near zero deflection.

    Never negative, zero after lift-off (rho <= 0).
    """
    if rho <= 0.0:
        return 0.0
    ramp = vp[2]
    c = vp[1]
    if rho < ramp:
        t = rho / ramp
        c = c * t * t * (3.0 - 2.0 * t)
    f = static_load(vp, knots, coefs, rho) + c * rho_dot
    return f if f > 0.0 else 0.0


@nb.njit(cache=True)
def static_deflection(vp, knots, coefs, load):
    """Deflection carrying ``load`` statically, by bisection on k(rho)."""
    if load <= 0.0:
        return 0.0
    lo = 0.0
    hi = 0.01
    while static_load(vp, knots, coefs, hi) < load and hi < 100.0:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if static_load(vp, knots, coefs, mid) < load:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-12:
            break
    return 0.5 * (lo + hi)
