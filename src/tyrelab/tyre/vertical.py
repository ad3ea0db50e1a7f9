"""The vertical law shared by the point, volume and enveloping contact models.

Thesis eq. 2.2 / 4.1::

    Fz = k(rho) + c_z * rho_dot

with ``k(rho)`` linear (``VERTICAL_STIFFNESS``), a cubic spline through the
``[DEFLECTION_LOAD_CURVE]`` table (up to 100 points), or MF-Tyre 6.x's
quadratic law in ``Q_FZ2`` (:func:`mf_load_deflection`). As in ADAMS/Tire, a
table, when present, replaces the linear stiffness. Beyond the last table
point the spline is continued as a straight line with its end slope (a cubic
continued past its data soon turns over; a tyre does not get softer when it
is pressed harder). The damping coefficient is ramped from zero at zero
deflection to its full value at ``DAMPING_RAMP`` (smoothstep), so the force
has no jump at touch-down; the total is clipped at zero, so there is no
tension and no negative normal force.

Bottoming: a file may say how the tyre bottoms out (the rim, or a run-flat
insert, pressed through the compressed tyre onto the road). Its load is added
to ``k(rho)`` (ADAMS/Tire PAC2002 and Project Chrono's ``ChPac02Tire``): a
``[BOTTOMING_CURVE]`` table of (deflection, added load), linear between its
rows and continued with its last slope; or MF-Tyre 6.1/6.2's
``BOTTOM_STIFF (rho - (R0 - RIM_RADIUS - BOTTOM_OFFST))`` once that is
positive (the loaded radius below the rim radius plus ``BOTTOM_OFFST``).
:func:`bottoming_table` turns either into the table the kernels take.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np
from scipy.interpolate import CubicSpline

from ..errors import InputError

#: default deflection over which damping ramps in [m]
DEFAULT_DAMPING_RAMP = 0.002
#: the bottoming table of a tyre that does not bottom out: no rows
NO_BOTTOMING = np.zeros((0, 2))


class VerticalLaw(NamedTuple):
    """The vertical law of eq. 2.2 as the compiled kernels take it.

    Attributes
    ----------
    stiffness : float
        Linear stiffness [N/m] (used when ``use_table`` is false).
    damping : float
        Damping coefficient c [N s/m].
    damping_ramp : float
        Deflection [m] over which damping ramps in from zero (smoothstep).
    use_table : bool
        True: k(rho) is the cubic spline through the load-deflection table.
    knots : ndarray (n,)
        Spline knots: deflections [m].
    coefs : ndarray (n-1, 4)
        Cubic coefficients per interval, highest power first, in the local
        coordinate ``rho - knots[i]``.
    bottoming : ndarray (m, 2)
        Bottoming load added to k(rho): rows of deflection [m] and load [N],
        from deflection 0, linear between rows and continued with the last
        row's slope (:func:`bottoming_table`); no rows: the tyre does not
        bottom out.
    speed_stiffening : float
        MF-Tyre's stiffening with spin, ``Q_V2 R0 / LONGVL`` [s]: k(rho) (bottoming not
        included) is multiplied by ``1 + speed_stiffening |omega|`` (Pacejka 2012, eq. A3.3);
        0: no speed effect.
    force_softening_x, force_softening_y : float
        MF-Tyre's softening with the horizontal forces, ``(Q_FCX / FNOMIN)^2`` and
        ``(Q_FCY / FNOMIN)^2`` [1/N^2]: the same factor becomes
        ``1 + speed_stiffening |omega| - force_softening_x Fx^2 - force_softening_y Fy^2``
        (Pacejka 2012, eq. A3.3); 0: the forces do not soften the tyre.
    """

    stiffness: float
    damping: float
    damping_ramp: float
    use_table: bool
    knots: np.ndarray
    coefs: np.ndarray
    bottoming: np.ndarray = NO_BOTTOMING
    speed_stiffening: float = 0.0
    force_softening_x: float = 0.0
    force_softening_y: float = 0.0

    @classmethod
    def linear(cls, stiffness, damping, damping_ramp=DEFAULT_DAMPING_RAMP, bottoming=NO_BOTTOMING,
               speed_stiffening=0.0, force_softening=(0.0, 0.0)):
        return cls(float(stiffness), float(damping), float(damping_ramp), False, np.zeros(2),
                   np.zeros((1, 4)), _bottoming_rows(bottoming), float(speed_stiffening),
                   *map(float, force_softening))

    @classmethod
    def table(cls, deflection, load, damping, damping_ramp=DEFAULT_DAMPING_RAMP,
              stiffness=0.0, source="load-deflection table", bottoming=NO_BOTTOMING,
              speed_stiffening=0.0, force_softening=(0.0, 0.0)):
        d = np.asarray(deflection, float)
        f = np.asarray(load, float)
        if d.ndim != 1 or d.shape != f.shape or d.size < 2:
            raise InputError("a load-deflection table needs at least two (deflection, load) rows",
                             source=source)
        if d.size > 100:
            raise InputError(f"a load-deflection table holds at most 100 points, got {d.size}",
                             source=source)
        if not (np.all(np.isfinite(d)) and np.all(np.isfinite(f))):
            raise InputError("a load-deflection table must hold finite numbers only", source=source)
        if np.any(np.diff(d) <= 0):
            raise InputError("deflections must increase strictly down the table", source=source)
        if d[0] < 0 or np.any(f < 0):
            raise InputError("deflections and loads of a load-deflection table must not be negative",
                             source=source)
        if np.any(np.diff(f) < 0):
            raise InputError("the load must not fall as the deflection grows down the table",
                             source=source)
        if d[0] > 0:  # the curve starts at the unloaded tyre
            d = np.r_[0.0, d]
            f = np.r_[0.0, f]
        bc = "not-a-knot" if d.size >= 4 else "natural"
        spline = CubicSpline(d, f, bc_type=bc)
        coefs = np.ascontiguousarray(spline.c.T)  # (n-1, 4), highest power first
        return cls(float(stiffness), float(damping), float(damping_ramp), True,
                   np.ascontiguousarray(d, np.float64), coefs, _bottoming_rows(bottoming),
                   float(speed_stiffening), *map(float, force_softening))

    @classmethod
    def quadratic(cls, linear, quadratic, damping, damping_ramp=DEFAULT_DAMPING_RAMP, stiffness=0.0,
                  up_to=1.0, bottoming=NO_BOTTOMING, speed_stiffening=0.0, force_softening=(0.0, 0.0)):
        """k(rho) = ``linear`` rho + ``quadratic`` rho^2 [N] (``linear`` in N/m, ``quadratic`` in
        N/m^2; :func:`mf_load_deflection`), exact up to the deflection ``up_to`` [m] (one
        spline interval holding the polynomial) and continued with its slope there."""
        if not (linear > 0.0 and up_to > 0.0 and linear + 2.0 * quadratic * up_to > 0.0):
            raise ValueError("a quadratic load-deflection law must rise up to its end")
        coefs = np.array([[0.0, float(quadratic), float(linear), 0.0]])
        return cls(float(stiffness), float(damping), float(damping_ramp), True,
                   np.array([0.0, float(up_to)]), coefs, _bottoming_rows(bottoming),
                   float(speed_stiffening), *map(float, force_softening))

    def static_load(self, rho, omega=0.0):
        """Load k(rho) [N] at deflections ``rho`` [m] (vectorised), the wheel standing or spinning
        at ``omega`` [rad/s] (:func:`rolling_load`)."""
        rho = np.asarray(rho, float)
        out = np.empty(rho.size)
        for i, r in enumerate(rho.ravel()):
            out[i] = rolling_load(self, r, float(omega))
        return out.reshape(rho.shape)

    def deflection_at(self, load, omega=0.0):
        """Deflection [m] that carries ``load`` [N] (inverse of k), at spin ``omega`` [rad/s]."""
        return rolling_deflection(self, float(load), float(omega))


def mf_q_fz1(vertical_stiffness, unloaded_radius, nominal_load, q_fz2):
    """MF-Tyre's ``Q_FZ1 = sqrt((Cz R0 / FNOMIN)^2 - 4 Q_FZ2)``, which no property file states:
    the linear coefficient that makes the law's slope at FNOMIN (and nominal pressure) Cz =
    ``VERTICAL_STIFFNESS`` (Besselink et al. 2010, eq. 4; MFeval 4.3.1 ``calculateRhoRl61``).
    None when ``4 Q_FZ2`` exceeds ``(Cz R0 / FNOMIN)^2``: no such law has the slope Cz there."""
    disc = (vertical_stiffness * unloaded_radius / nominal_load) ** 2 - 4.0 * q_fz2
    return math.sqrt(disc) if disc >= 0.0 else None


def mf_load_deflection(vertical_stiffness, unloaded_radius, nominal_load, q_fz2, pressure_factor=1.0):
    """Coefficients (k1 [N/m], k2 [N/m^2]) of MF-Tyre's static load-deflection law, k1 rho + k2 rho^2.

    Pacejka, *Tyre and Vehicle Dynamics* (2012) eq. A3.3 without its speed and force terms::

        Fz = (Q_FZ1 rho/R0 + Q_FZ2 (rho/R0)^2) (1 + PFZ1 dpi) FNOMIN

    with ``Q_FZ1`` from :func:`mf_q_fz1`; ``pressure_factor`` is ``1 + PFZ1 dpi``. None when
    there is no ``Q_FZ1``.
    """
    q_fz1 = mf_q_fz1(vertical_stiffness, unloaded_radius, nominal_load, q_fz2)
    if q_fz1 is None:
        return None
    scale = pressure_factor * nominal_load
    return scale * q_fz1 / unloaded_radius, scale * q_fz2 / unloaded_radius ** 2


def bottoming_table(deflection=None, load=None, *, stiffness=None, start=None) -> np.ndarray:
    """The bottoming table :class:`VerticalLaw` takes: rows of deflection [m] and added load [N].

    Either a ``[BOTTOMING_CURVE]`` (``deflection``, ``load``: increasing deflections, loads
    that never fall; the file's checks, :func:`tyrelab.tyre.tir_physics.check_physics`) or
    MF-Tyre 6.1/6.2's linear bottoming, ``stiffness`` [N/m] (``BOTTOM_STIFF``) from the
    deflection ``start`` [m] (``R0 - RIM_RADIUS - BOTTOM_OFFST``) on. A curve that starts past
    zero deflection gets a row (0, 0) first, as the load-deflection curve does.
    """
    if stiffness is not None:
        start = max(float(start), 0.0)
        rows = [(start, 0.0), (start + 1.0, float(stiffness))]   # slope BOTTOM_STIFF, continued
    else:
        rows = list(zip(np.asarray(deflection, float), np.asarray(load, float)))
    if rows[0][0] > 0.0:
        rows.insert(0, (0.0, 0.0))
    return np.ascontiguousarray(rows, np.float64)


def _bottoming_rows(bottoming) -> np.ndarray:
    table = np.ascontiguousarray(bottoming, np.float64)
    return table.reshape(-1, 2) if table.size else NO_BOTTOMING


@nb.njit(cache=True)
def bottoming_load(table, rho):
    """Bottoming load [N] at deflection ``rho`` from a :func:`bottoming_table`: linear between
    its rows, continued past the last with the last row's slope."""
    n = table.shape[0]
    k = 1
    while k < n - 1 and table[k, 0] < rho:
        k += 1
    d0 = table[k - 1, 0]
    f0 = table[k - 1, 1]
    slope = (table[k, 1] - f0) / (table[k, 0] - d0)
    return max(f0 + slope * (rho - d0), 0.0)


@nb.njit(cache=True)
def static_load(law, rho):
    """Elastic part k(rho) [N] of :class:`VerticalLaw` ``law`` of a wheel that does not spin,
    bottoming included; zero for rho <= 0 (no tension)."""
    return rolling_load(law, rho, 0.0)


@nb.njit(cache=True)
def rolling_load(law, rho, omega, fx=0.0, fy=0.0):
    """Elastic part [N] of ``law`` at deflection ``rho`` [m] spinning at ``omega`` [rad/s] under
    the horizontal forces ``fx``, ``fy`` [N] (W-axis): ``k(rho) (1 + speed_stiffening |omega| -
    force_softening_x fx^2 - force_softening_y fy^2)`` (that factor at least 0) plus the
    bottoming load (Pacejka 2012, eq. A3.3: these terms scale the tyre's law, not the rim's);
    zero for rho <= 0."""
    if rho <= 0.0:
        return 0.0
    factor = (1.0 + law.speed_stiffening * abs(omega) - law.force_softening_x * fx * fx
              - law.force_softening_y * fy * fy)
    value = _carcass_load(law, rho) * max(factor, 0.0)
    if law.bottoming.shape[0] > 0:
        value += bottoming_load(law.bottoming, rho)
    return value


@nb.njit(cache=True)
def _carcass_load(law, rho):
    """k(rho) [N] without bottoming, for rho > 0: linear or the table's spline (non-negative)."""
    if not law.use_table:
        return law.stiffness * rho
    knots = law.knots
    coefs = law.coefs
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
def normal_force(law, rho, rho_dot, omega, fx=0.0, fy=0.0):
    """Normal force [N] of eq. 2.2 of a wheel spinning at ``omega`` [rad/s] under the
    horizontal forces ``fx``, ``fy`` [N] (:func:`rolling_load`), with damping ramped in near
    zero deflection.

    Never negative, zero after lift-off (rho <= 0).
    """
    if rho <= 0.0:
        return 0.0
    ramp = law.damping_ramp
    c = law.damping
    if rho < ramp:
        t = rho / ramp
        c = c * t * t * (3.0 - 2.0 * t)
    f = rolling_load(law, rho, omega, fx, fy) + c * rho_dot
    return f if f > 0.0 else 0.0


@nb.njit(cache=True)
def static_deflection(law, load):
    """Deflection carrying ``load`` statically, by bisection on k(rho)."""
    return rolling_deflection(law, load, 0.0)


@nb.njit(cache=True)
def rolling_deflection(law, load, omega):
    """Deflection carrying ``load`` at spin ``omega`` [rad/s], by bisection on
    :func:`rolling_load`."""
    if load <= 0.0:
        return 0.0
    lo = 0.0
    hi = 0.01
    while rolling_load(law, hi, omega) < load and hi < 100.0:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if rolling_load(law, mid, omega) < load:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-12:
            break
    return 0.5 * (lo + hi)
