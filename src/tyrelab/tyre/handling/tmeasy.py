"""TMeasy handling forces: Fx, Fy and Mz of G. Rill's "Tire Model made Easy".

Sources: G. Rill, *Road Vehicle Dynamics: Fundamentals and Modeling* (CRC Press 2012),
chapter 3 (the tyre: slips, the generalised force characteristic, the pneumatic trail);
G. Rill, "An engineer's guess on tyre parameter made possible with TMeasy" (2015); and
Project Chrono's ``ChTMeasyTire`` (R. Gericke, 2023), whose property keys, parameter guess
(:mod:`tyrelab.tyre.chrono_templates`) and steady-state force law this module follows, so
that a Chrono TMeasy file gives here the forces it gives there.

The model (W-axis, SI; ``v_x`` the wheel centre's speed along the heading, ``v_sx``,
``v_sy`` the slip velocity of the tread at the contact point, ``Re`` the rolling radius)::

    v_t  = Re |omega| + v_N                       transport speed, v_N = 0.01 m/s
    s_x  = -v_sx / v_t,   s_y = -v_sy / v_t        TMeasy's slips (> 0: driving; sliding right)
    q    = min(Fz, FZ_MAX) / FZ_NOM
    X(q) = q (2 X1 - X2/2 - (X1 - X2/2) q)         forces and slopes: through 0, X1 at q = 1,
    x(q) = x1 + (x2 - x1) (q - 1)                   X2 at q = 2; slips and the trail linear

Each direction has its characteristic ``F(s)`` (:func:`characteristic`) from the initial
slope ``dF0``, the maximum ``FM`` at ``sM`` and the sliding force ``FS`` from ``sS`` on. The
two combine along the slip's direction ``(cos phi, sin phi) = (s_x, s_y) / s``,
``s = hypot(s_x, s_y)``: each curve parameter ``P = hypot(Px cos phi, Py sin phi)``, and
``(Fx, Fy) = F(s) (cos phi, sin phi)``. (Rill's book divides the slips by normalising factors
before combining; Chrono's 2023 template, validated on the FED-Alpha and KRC tests, combines
them as written here. Pure slip is the same either way.)

The aligning moment is the lateral force times the pneumatic trail, a fraction ``n(|s_y|)``
(:func:`normalized_trail`) of the contact length ``L = 2 sqrt(R0 z)``: ``Mz = -L n Fy``;
rolling backwards it turns over, as PAC89's and the Magic Formula's do. The rolling radius
is Chrono's ``Re = (2 R0 + (R0 - z)) / 3``, z the deflection carrying ``Fz`` under TMeasy's
own vertical law ``Fz = d1 z + d2 z^2`` (:class:`TMeasyParams`).

Not carried: the camber's lateral force and bore torque (Chrono's 2023 template has none
either; camber acts through the contact geometry only), the rolling resistance moment
(no handling model here gives one), Chrono's Dahl bristle model, which replaces these forces
below 1 m/s and blends into them up to 3 m/s (a state per wheel; here the curve holds at
every speed, the slips staying finite through ``v_N``), and the friction scale on the slips
``sM``, ``sS`` (the ground's friction scale multiplies the whole force here, as for every
handling model).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb
import numpy as np

from ...errors import InputError
from ..registry import HandlingModel, register_handling
from .rolling_resistance import ROLLING_SECTION, rolling_resistance_moment
from .slip import DKAPPA, VXLOW, slip

#: Chrono's ``m_vnum``: the speed added to the transport speed so that slip stays finite [m/s]
V_NUM = 0.01
#: FZ_MAX when a file gives none: Chrono's ``3.5 FZ_NOM``
DEFAULT_MAX_LOAD_RATIO = 3.5
#: how far below ``2 FM / sM`` a file's initial slope may be written (its rounding) [-]
SLOPE_ROUNDING = 1e-9

#: property-file sections and keys (Chrono's TMeasy parameter file, ``ExportParameterFile``);
#: ``_1`` at FZ_NOM, ``_2`` at 2 FZ_NOM
LOAD_SECTION = "TYRE_LOAD"
CURVE_SECTIONS = {"x": "LONGITUDINAL_PARAMETERS", "y": "LATERAL_PARAMETERS"}
CURVE_KEYS = ("DF{d}0", "F{D}MAX", "S{D}MAX", "F{D}SLD", "S{D}SLD")
TRAIL_SECTION = "ALIGNING_PARAMETERS"
TRAIL_KEYS = ("PT_NORM", "SY_CHSI", "SY_ZERO")
#: each key's section, by its stem (the key without ``_1`` / ``_2``)
KEY_SECTIONS = {**{key.format(d=d, D=d.upper()).upper(): CURVE_SECTIONS[d]
                   for d in "xy" for key in CURVE_KEYS},
                **{key: TRAIL_SECTION for key in TRAIL_KEYS}}


class SlipCurve(NamedTuple):
    """One direction's force characteristic at one load (Rill 2012, ch. 3).

    ``slope`` dF0 [N] (per unit slip), ``peak`` FM [N] at ``peak_slip`` sM, ``slide`` FS [N]
    from ``slide_slip`` sS on.
    """

    slope: float
    peak: float
    peak_slip: float
    slide: float
    slide_slip: float


class Trail(NamedTuple):
    """The pneumatic trail over the contact length: ``at_zero`` at s_y = 0, crossing zero
    at ``sign_change`` and vanishing from ``vanish`` on."""

    at_zero: float
    sign_change: float
    vanish: float


class TMeasyParams(NamedTuple):
    """TMeasy's parameters: loads [N], the unloaded radius [m], its vertical law
    ``Fz = d1 z + d2 z^2`` (``d1`` [N/m], ``d2`` [N/m^2]; the deflection for the rolling
    radius and the contact length) and each curve at FZ_NOM and 2 FZ_NOM."""

    nominal_load: float
    max_load: float
    unloaded_radius: float
    d1: float
    d2: float
    longitudinal: tuple  # (SlipCurve at FZ_NOM, SlipCurve at 2 FZ_NOM)
    lateral: tuple
    trail: tuple  # (Trail at FZ_NOM, Trail at 2 FZ_NOM)
    #: the rolling resistance's load-centre shift [m]: ``[ROLLING_COEFFICIENTS] QSY1`` R0
    rolling_resistance: float = 0.0


# --- the property file ---------------------------------------------------------------------

def _curve_keys(direction: str, level: int) -> tuple[str, ...]:
    return tuple(k.format(d=direction.lower(), D=direction.upper()).upper() + f"_{level}"
                 for k in CURVE_KEYS)


def _numbers(tir, section, keys):
    return [tir.number(section, k, required=True) for k in keys]


def _refuse(tir, section, key, message):
    return InputError(message, source=tir.source, line=tir.line_of(section, key), field=key)


def _slip_curve(tir, direction: str, level: int) -> SlipCurve:
    section = CURVE_SECTIONS[direction]
    keys = _curve_keys(direction, level)
    curve = SlipCurve(*_numbers(tir, section, keys))
    slope, peak, peak_slip, slide, slide_slip = keys
    if not (curve.slope > 0 and curve.peak > 0 and curve.peak_slip > 0):
        raise _refuse(tir, section, slope, "expected a positive initial slope, maximum force and "
                      f"slip at the maximum ({slope}, {peak}, {peak_slip})")
    if not curve.peak_slip < curve.slide_slip:
        raise _refuse(tir, section, slide_slip, f"expected {slide_slip} above {peak_slip}: sliding "
                      "begins after the maximum")
    if not 0 <= curve.slide <= curve.peak:
        raise _refuse(tir, section, slide, f"expected {slide} between 0 and {peak}: the sliding "
                      "force is at most the maximum")
    # below 2 FM / sM the curve's slope would rise past dF0 on the way to its peak (Chrono
    # raises dF0 to that bound silently; a file that needs it is refused here). A slope at the
    # bound, as a fit may leave it, is allowed its last written digit (1e-9 of it)
    if curve.slope < 2.0 * curve.peak / curve.peak_slip * (1.0 - SLOPE_ROUNDING):
        raise _refuse(tir, section, slope, f"expected {slope} >= 2 {peak} / {peak_slip} = "
                      f"{2 * curve.peak / curve.peak_slip:.6g} N: a lower initial slope would "
                      "not be the curve's steepest")
    return curve


def _trail(tir, level: int) -> Trail:
    keys = tuple(f"{k}_{level}" for k in TRAIL_KEYS)
    trail = Trail(*_numbers(tir, TRAIL_SECTION, keys))
    if not trail.at_zero >= 0:
        raise _refuse(tir, TRAIL_SECTION, keys[0], f"expected {keys[0]} >= 0")
    if not 0 < trail.sign_change <= trail.vanish:
        raise _refuse(tir, TRAIL_SECTION, keys[1], f"expected 0 < {keys[1]} <= {keys[2]}")
    return trail


def vertical_coefficients(law) -> tuple[float, float]:
    """``(d1, d2)`` of TMeasy's vertical law ``Fz = d1 z + d2 z^2`` from a tyre's
    :class:`~tyrelab.tyre.vertical.VerticalLaw` (bottoming left out): the linear law's
    stiffness; a quadratic law's own coefficients; through a table's rows, the least-squares
    fit, as Chrono's ``SetVerticalStiffness`` fits its spring curve."""
    if not law.use_table:
        return float(law.stiffness), 0.0
    z = np.asarray(law.knots, float)
    if z.size == 2 and law.coefs[0, 0] == 0.0 and z[0] == 0.0:  # VerticalLaw.quadratic
        return float(law.coefs[0, 2]), float(law.coefs[0, 1])
    # the spline's value at each knot: each interval's constant term, and the last interval
    # at its end (the table's rows; bottoming, a separate table, is not in the spline)
    f = np.r_[law.coefs[:, 3], np.polyval(law.coefs[-1], z[-1] - z[-2])]
    (d1, d2), *_ = np.linalg.lstsq(np.column_stack([z, z * z]), f, rcond=None)
    return float(d1), float(d2)


def tmeasy_params(tyre) -> TMeasyParams:
    """The TMeasy record from the tyre's property file.

    Parameters
    ----------
    tyre : Tyre
        Its ``tir`` must hold ``[TYRE_LOAD] FZ_NOM`` (``FZ_MAX`` optional: 3.5 FZ_NOM),
        ``[LONGITUDINAL_PARAMETERS]`` ``DFX0``, ``FXMAX``, ``SXMAX``, ``FXSLD``, ``SXSLD``,
        ``[LATERAL_PARAMETERS]`` the same with Y, and ``[ALIGNING_PARAMETERS]``
        ``PT_NORM``, ``SY_CHSI``, ``SY_ZERO``, each with ``_1`` (at FZ_NOM) and ``_2`` (at
        2 FZ_NOM): Chrono's TMeasy parameter file, which :mod:`tyrelab.tyre.chrono_json`
        writes from a Chrono TMeasy JSON.

    Raises
    ------
    InputError
        Naming the file, line and key: a missing key, a load that is not positive, a curve
        whose sliding starts before its maximum, whose sliding force exceeds the maximum or
        whose initial slope is below ``2 FM / sM``, a trail that changes sign after it vanishes.
    """
    tir = tyre.tir
    if not tir.has(LOAD_SECTION, "FZ_NOM"):
        raise InputError(f"no TMeasy parameters: missing key FZ_NOM in section [{LOAD_SECTION}]; the "
                         "tmeasy handling model needs Chrono's TMeasy parameter file",
                         source=tir.source, field="FZ_NOM")
    nominal = tir.number(LOAD_SECTION, "FZ_NOM")
    if not nominal > 0:
        raise _refuse(tir, LOAD_SECTION, "FZ_NOM", "expected a positive nominal load FZ_NOM [N]")
    maximum = tir.number(LOAD_SECTION, "FZ_MAX", DEFAULT_MAX_LOAD_RATIO * nominal)
    if not maximum >= nominal:
        raise _refuse(tir, LOAD_SECTION, "FZ_MAX", f"expected FZ_MAX >= FZ_NOM = {nominal:g} N")
    d1, d2 = vertical_coefficients(tyre.vertical_law)
    return TMeasyParams(nominal, maximum, float(tyre.unloaded_radius), d1, d2,
                        (_slip_curve(tir, "x", 1), _slip_curve(tir, "x", 2)),
                        (_slip_curve(tir, "y", 1), _slip_curve(tir, "y", 2)),
                        (_trail(tir, 1), _trail(tir, 2)), rolling_resistance_shift(tyre))


def rolling_resistance_shift(tyre) -> float:
    """The rolling resistance's load-centre shift [m] of a TMeasy or TMsimple file: its
    coefficient ``[ROLLING_COEFFICIENTS] QSY1`` (Chrono's "Rolling Resistance Coefficient")
    times the unloaded radius (:mod:`.rolling_resistance`); 0 without one."""
    tir = tyre.tir
    coefficient = tir.number(ROLLING_SECTION, "QSY1", 0.0)
    if not coefficient >= 0.0:
        raise _refuse(tir, ROLLING_SECTION, "QSY1", "expected a rolling resistance coefficient >= 0")
    return coefficient * float(tyre.unloaded_radius)


@nb.njit(cache=True)
def tmeasy_rolling_moment(params, fz, fx, v_long, omega, kappa, gamma, radius):
    """The rolling resistance moment [N m] of TMeasy and TMsimple (Chrono's
    ``-c Fz R0 tanh(omega)``, :func:`.rolling_resistance.rolling_resistance_moment`)."""
    return rolling_resistance_moment(params.rolling_resistance, fz, omega)


def tmeasy_entries(nominal_load, max_load, longitudinal, lateral, trail):
    """``[(section, key, value)]`` of a property file holding these TMeasy parameters (each
    curve and trail a pair: at FZ_NOM and 2 FZ_NOM): what :func:`tmeasy_params` reads back."""
    out = [(LOAD_SECTION, "FZ_NOM", float(nominal_load)), (LOAD_SECTION, "FZ_MAX", float(max_load))]
    for direction, levels in (("x", longitudinal), ("y", lateral)):
        for level, curve in enumerate(levels, start=1):
            out += [(CURVE_SECTIONS[direction], key, float(value))
                    for key, value in zip(_curve_keys(direction, level), curve)]
    for level, t in enumerate(trail, start=1):
        out += [(TRAIL_SECTION, f"{key}_{level}", float(value)) for key, value in zip(TRAIL_KEYS, t)]
    return out


# --- the compiled law ------------------------------------------------------------------------

@nb.njit(cache=True)
def load_quadratic(x1, x2, q):
    """A force or slope at load ratio ``q``: the parabola through 0, ``x1`` at q = 1 and
    ``x2`` at q = 2 (Rill 2012; Chrono's ``InterpQ``)."""
    return q * (2.0 * x1 - 0.5 * x2 - (x1 - 0.5 * x2) * q)


@nb.njit(cache=True)
def load_linear(x1, x2, q):
    """A slip or trail parameter at load ratio ``q``: the line through ``x1`` at q = 1 and
    ``x2`` at q = 2 (Chrono's ``InterpL``)."""
    return x1 + (x2 - x1) * (q - 1.0)


@nb.njit(cache=True)
def curve_at(levels, q):
    """The :class:`SlipCurve` at load ratio ``q`` from the curves at FZ_NOM and 2 FZ_NOM."""
    a, b = levels
    return SlipCurve(load_quadratic(a.slope, b.slope, q), load_quadratic(a.peak, b.peak, q),
                     load_linear(a.peak_slip, b.peak_slip, q), load_quadratic(a.slide, b.slide, q),
                     load_linear(a.slide_slip, b.slide_slip, q))


@nb.njit(cache=True)
def characteristic(s, slope, peak, peak_slip, slide, slide_slip):
    """TMeasy's force characteristic F(s) [N] at slip ``s`` >= 0 (Rill 2012, ch. 3).

    Up to ``sM`` the rational function ``dF0 s / (1 + (s/sM) (s/sM + dF0 sM/FM - 2))``
    (slope dF0 at 0, the maximum FM at sM); from sM a parabola falling with the curvature
    the rational function has there, ``a = (FM/sM)^2 / (dF0 sM)``, joined with continuous
    slope at ``s* = sM + (FM - FS) / (a (sS - sM))`` to a second parabola that reaches FS
    flat at sS (a smooth cubic step from FM to FS where s* would lie beyond sS); FS from sS
    on. A slope below ``2 FM / sM`` is raised to it, as Chrono does. Zero for s <= 0 or a
    curve without a positive peak.
    """
    if not (s > 0.0 and peak > 0.0 and peak_slip > 0.0):
        return 0.0
    df0 = max(slope, 2.0 * peak / peak_slip)
    if slide_slip < peak_slip:
        slide_slip = peak_slip
    if s < peak_slip:
        sn = s / peak_slip
        return df0 * s / (1.0 + (sn + df0 * peak_slip / peak - 2.0) * sn)
    if s >= slide_slip:
        return slide
    a = (peak / peak_slip) ** 2 / (df0 * peak_slip)
    s_star = peak_slip + (peak - slide) / (a * (slide_slip - peak_slip))
    if s_star <= slide_slip:
        if s <= s_star:
            return peak - a * (s - peak_slip) ** 2
        b = a * (s_star - peak_slip) / (slide_slip - s_star)
        return slide + b * (slide_slip - s) ** 2
    sn = (s - peak_slip) / (slide_slip - peak_slip)
    return peak - (peak - slide) * sn * sn * (3.0 - 2.0 * sn)


@nb.njit(cache=True)
def normalized_trail(sy, at_zero, sign_change, vanish):
    """The pneumatic trail over the contact length at lateral slip ``|sy|`` (Rill 2012, ch. 3;
    Chrono's ``AlignmentTorque``): from ``at_zero`` falling through zero at ``sign_change``
    (a blend, weighted ``sign_change / vanish``, of a line and a smooth step), negative
    beyond and back to zero at ``vanish``."""
    s = abs(sy)
    vanish = max(vanish, sign_change)
    if s >= vanish or sign_change <= 0.0:
        return 0.0
    w = sign_change / vanish
    if s <= sign_change:
        sn = s / sign_change
        return (1.0 - w) * at_zero * (1.0 - sn) + w * at_zero * (1.0 - (3.0 - 2.0 * sn) * sn * sn)
    sn = (vanish - s) / (vanish - sign_change)
    return -at_zero * (1.0 - w) * (s - sign_change) / sign_change * sn * sn


@nb.njit(cache=True)
def trail_at(trail, q, sy):
    """The normalised trail at lateral slip ``sy`` and load ratio ``q`` from ``trail`` (at
    FZ_NOM and 2 FZ_NOM; each parameter linear in the load, Chrono's ``InterpL``)."""
    a, b = trail
    return normalized_trail(sy, load_linear(a.at_zero, b.at_zero, q),
                            load_linear(a.sign_change, b.sign_change, q),
                            load_linear(a.vanish, b.vanish, q))


@nb.njit(cache=True)
def characteristic_at_loads(slip, q, levels, out):
    """Each signed slip's force into ``out`` [N]: the characteristic (odd in the slip) of the
    curve at load ratio ``q`` from ``levels`` (the curves at FZ_NOM and 2 FZ_NOM) -- what a
    fit compares with samples at many loads."""
    for i in range(slip.shape[0]):
        c = curve_at(levels, q[i])
        f = characteristic(abs(slip[i]), c.slope, c.peak, c.peak_slip, c.slide, c.slide_slip)
        out[i] = f if slip[i] >= 0.0 else -f


@nb.njit(cache=True)
def trail_moments(slip, q, length, fy, trail, out):
    """Each sample's aligning moment ``-L n(|s_y|) Fy`` into ``out`` [N m]: contact length
    ``length`` [m] and lateral force ``fy`` [N] given, the trail at load ratio ``q`` from
    ``trail`` (at FZ_NOM and 2 FZ_NOM)."""
    for i in range(slip.shape[0]):
        out[i] = -length[i] * trail_at(trail, q[i], slip[i]) * fy[i]


@nb.njit(cache=True)
def law_deflection(d1, d2, fz):
    """The deflection [m] carrying ``fz`` [N] under TMeasy's law ``d1 z + d2 z^2``."""
    if not fz > 0.0:
        return 0.0
    if d2 == 0.0:
        return fz / d1
    disc = d1 * d1 + 4.0 * d2 * fz
    if disc <= 0.0:  # a softening law past its top: at its top
        return -d1 / (2.0 * d2)
    # the root near fz / d1, written without cancellation
    return 2.0 * fz / (d1 + math.sqrt(disc))


@nb.njit(cache=True)
def tmeasy_deflection(tp, fz):
    """The deflection [m] carrying ``fz`` [N] under the record's law (:func:`law_deflection`)."""
    return law_deflection(tp.d1, tp.d2, fz)


@nb.njit(cache=True)
def tmeasy_rolling_radius(tp, fz, omega):
    """Chrono's TMeasy rolling radius ``(2 R0 + (R0 - z)) / 3`` [m] at load ``fz`` [N]."""
    z = min(tmeasy_deflection(tp, fz), tp.unloaded_radius)
    return tp.unloaded_radius - z / 3.0


@nb.njit(cache=True)
def tmeasy_slip(v_long, v_slip_x, v_slip_y):
    """TMeasy's combined slip ``s`` and its direction ``(cos phi, sin phi)``, and ``s_y``, from
    the wheel centre's speed along the heading and the contact point's slip velocity [m/s]:
    ``s_x = -v_sx / v_t``, ``s_y = -v_sy / v_t``, ``v_t = Re |omega| + v_N`` with ``Re omega =
    v_long - v_sx`` (module docstring); the direction (1, 1)/sqrt 2 without slip."""
    v_t = abs(v_long - v_slip_x) + V_NUM
    sx = -v_slip_x / v_t
    sy = -v_slip_y / v_t
    s = math.hypot(sx, sy)
    if s > 0.0:
        return s, sx / s, sy / s, sy
    return s, math.sqrt(0.5), math.sqrt(0.5), sy


@nb.njit(cache=True)
def tmeasy_tangential(x, y, v_long, v_slip_x, v_slip_y):
    """``(FXW, FYW, s_y)`` [N, N, -] of TMeasy's curves ``x``, ``y`` at one load
    (:func:`curve_at`) from the wheel centre's speed along the heading and the contact point's
    slip velocity [m/s] (W-axis; module docstring): the combined characteristic along the
    slip's direction (:func:`tmeasy_slip`)."""
    s, c, n, sy = tmeasy_slip(v_long, v_slip_x, v_slip_y)
    if not s > 0.0:
        return 0.0, 0.0, sy
    f = characteristic(s, math.hypot(x.slope * c, y.slope * n), math.hypot(x.peak * c, y.peak * n),
                       math.hypot(x.peak_slip * c, y.peak_slip * n),
                       math.hypot(x.slide * c, y.slide * n),
                       math.hypot(x.slide_slip * c, y.slide_slip * n))
    return f * c, f * n, sy


@nb.njit(cache=True)
def tmeasy_wheel_forces(tp, fz, v_long, v_slip_x, v_slip_y, gamma):
    """TMeasy from the contact point's slip velocities, with the slip stiffness.

    Returns ``(FXW, FYW, MZW, kappa, alpha, dFXW/dkappa)`` [N, N, N m, -, rad, N] at load
    ``fz`` [N]. The rolling speed ``Re omega`` is ``v_long - v_slip_x`` (the slip velocity is
    the tread's at the rolling radius: :func:`tmeasy_rolling_radius`). kappa and alpha are
    the ISO slips every handling model reports (:func:`~.slip.slip`), not TMeasy's own, and
    the stiffness is FXW's change per unit of that kappa with the wheel's spin (a forward
    difference moving ``v_slip_x`` by ``-DKAPPA max(|v_long|, VXLOW)``; TMeasy's transport
    speed moves with it), which is what the rigs' implicit spin step needs; both FXW are at
    the same load, whose curves are found once. The aligning moment is the trail times FYW,
    turned over rolling backwards (the trail then lies ahead of the centre along x). Camber
    is not used (module docstring). No forces without a finite positive load.
    """
    kappa, alpha = slip(v_long, v_slip_x, v_slip_y)
    if not (fz > 0.0) or not math.isfinite(fz):
        return 0.0, 0.0, 0.0, kappa, alpha, 0.0
    q = min(fz, tp.max_load) / tp.nominal_load
    x = curve_at(tp.longitudinal, q)
    y = curve_at(tp.lateral, q)
    fx, fy, sy = tmeasy_tangential(x, y, v_long, v_slip_x, v_slip_y)
    z = min(tmeasy_deflection(tp, fz), tp.unloaded_radius)
    mz = -2.0 * math.sqrt(tp.unloaded_radius * z) * trail_at(tp.trail, q, sy) * fy
    if v_long < 0.0:
        mz = -mz
    vref = max(abs(v_long), VXLOW)
    fx2, _, _ = tmeasy_tangential(x, y, v_long, v_slip_x - DKAPPA * vref, v_slip_y)
    dfx = (fx2 - fx) / DKAPPA
    if not (math.isfinite(fx) and math.isfinite(fy) and math.isfinite(mz) and math.isfinite(dfx)):
        return 0.0, 0.0, 0.0, kappa, alpha, 0.0
    return fx, fy, mz, kappa, alpha, dfx


register_handling(HandlingModel("tmeasy", TMeasyParams, tmeasy_params, tmeasy_wheel_forces,
                                "TMeasy (Rill; Chrono's 2023 template), combined slip",
                                rolling_radius=tmeasy_rolling_radius,
                                rolling_resistance=tmeasy_rolling_moment))
