"""TMsimple handling forces: Fx and Fy of W. Hirschberg's simplified TMeasy (TU Graz, 2009;
as Project Chrono's ``ChTMsimpleTire``, 2023, reconstructs it from E. Heimlich's master's
thesis, TU Graz).

TMeasy's slips, load dependence, combination along the slip's direction and rolling radius
(:mod:`.tmeasy`), with a simpler characteristic of three parameters per direction and load --
the initial slope dF0, the maximum FM and the sliding force FS::

    F(s) = FM sin(B (1 - exp(-s / A))),   B = pi - asin(FS / FM),   A = FM B / dF0

(slope dF0 at s = 0, FS as s grows without bound). No aligning moment (Chrono's template
gives none either). Parameters: TMeasy's property-file keys without the slips and the trail,
``[TYRE_LOAD] FZ_NOM`` (``FZ_MAX``), ``DFX0``, ``FXMAX``, ``FXSLD``, ``DFY0``, ``FYMAX``,
``FYSLD`` (``_1`` at FZ_NOM, ``_2`` at 2 FZ_NOM), which :mod:`tyrelab.tyre.chrono_json` writes
from a Chrono ``TMsimpleTire`` JSON under ``PROPERTY_FILE_FORMAT = 'TMSIMPLE'``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba as nb

from ...errors import InputError
from ..registry import HandlingModel, register_handling
from .slip import DKAPPA, VXLOW, slip
from .tmeasy import (CURVE_SECTIONS, DEFAULT_MAX_LOAD_RATIO, LOAD_SECTION, load_quadratic,
                     rolling_resistance_shift, tmeasy_rolling_moment, tmeasy_rolling_radius,
                     tmeasy_slip, vertical_coefficients)


class SimpleCurve(NamedTuple):
    """One direction's TMsimple parameters at one load: ``slope`` dF0 [N], ``peak`` FM [N],
    ``slide`` FS [N]."""

    slope: float
    peak: float
    slide: float


class TMsimpleParams(NamedTuple):
    """TMsimple's parameters: loads [N], the unloaded radius [m] and TMeasy's vertical law
    ``d1 z + d2 z^2`` (the rolling radius), each direction's curve at FZ_NOM and 2 FZ_NOM."""

    nominal_load: float
    max_load: float
    unloaded_radius: float
    d1: float
    d2: float
    longitudinal: tuple
    lateral: tuple
    #: the rolling resistance's load-centre shift [m] (:func:`.tmeasy.rolling_resistance_shift`)
    rolling_resistance: float = 0.0


def _curve(tir, direction: str, level: int) -> SimpleCurve:
    section = CURVE_SECTIONS[direction]
    d = direction.upper()
    keys = (f"DF{d}0_{level}", f"F{d}MAX_{level}", f"F{d}SLD_{level}")
    curve = SimpleCurve(*(tir.number(section, k, required=True) for k in keys))
    if not (curve.slope > 0 and curve.peak > 0):
        raise InputError(f"expected a positive initial slope and maximum force ({keys[0]}, {keys[1]})",
                         source=tir.source, line=tir.line_of(section, keys[0]), field=keys[0])
    if not 0 <= curve.slide <= curve.peak:
        raise InputError(f"expected {keys[2]} between 0 and {keys[1]}: the sliding force is at most "
                         "the maximum", source=tir.source, line=tir.line_of(section, keys[2]),
                         field=keys[2])
    return curve


def tmsimple_params(tyre) -> TMsimpleParams:
    """The TMsimple record from the tyre's property file (module docstring); an
    :class:`InputError` names the file, line and key of a missing or impossible value."""
    tir = tyre.tir
    if not tir.has(LOAD_SECTION, "FZ_NOM"):
        raise InputError(f"no TMsimple parameters: missing key FZ_NOM in section [{LOAD_SECTION}]",
                         source=tir.source, field="FZ_NOM")
    nominal = tir.number(LOAD_SECTION, "FZ_NOM")
    if not nominal > 0:
        raise InputError("expected a positive nominal load FZ_NOM [N]", source=tir.source,
                         line=tir.line_of(LOAD_SECTION, "FZ_NOM"), field="FZ_NOM")
    maximum = tir.number(LOAD_SECTION, "FZ_MAX", DEFAULT_MAX_LOAD_RATIO * nominal)
    if not maximum >= nominal:
        raise InputError(f"expected FZ_MAX >= FZ_NOM = {nominal:g} N", source=tir.source,
                         line=tir.line_of(LOAD_SECTION, "FZ_MAX"), field="FZ_MAX")
    d1, d2 = vertical_coefficients(tyre.vertical_law)
    return TMsimpleParams(nominal, maximum, float(tyre.unloaded_radius), d1, d2,
                          (_curve(tir, "x", 1), _curve(tir, "x", 2)),
                          (_curve(tir, "y", 1), _curve(tir, "y", 2)), rolling_resistance_shift(tyre))


@nb.njit(cache=True)
def simple_characteristic(s, slope, peak, slide):
    """TMsimple's characteristic ``FM sin(B (1 - exp(-s/A)))`` [N] at slip ``s`` >= 0 (module
    docstring); zero without a positive peak and slope."""
    if not (s > 0.0 and peak > 0.0 and slope > 0.0):
        return 0.0
    b = math.pi - math.asin(min(max(slide / peak, -1.0), 1.0))
    a = peak * b / slope
    return peak * math.sin(b * (1.0 - math.exp(-s / a)))


@nb.njit(cache=True)
def simple_curve_at(levels, q):
    """The :class:`SimpleCurve` at load ratio ``q`` from the curves at FZ_NOM and 2 FZ_NOM
    (each parameter quadratic in the load, as TMeasy's forces)."""
    a, b = levels
    return SimpleCurve(load_quadratic(a.slope, b.slope, q), load_quadratic(a.peak, b.peak, q),
                       load_quadratic(a.slide, b.slide, q))


@nb.njit(cache=True)
def tmsimple_tangential(x, y, v_long, v_slip_x, v_slip_y):
    """``(FXW, FYW)`` [N] of TMsimple's curves ``x``, ``y`` at one load (TMeasy's slips and
    combination, :func:`.tmeasy.tmeasy_slip`)."""
    s, c, n, _ = tmeasy_slip(v_long, v_slip_x, v_slip_y)
    if not s > 0.0:
        return 0.0, 0.0
    f = simple_characteristic(s, math.hypot(x.slope * c, y.slope * n), math.hypot(x.peak * c, y.peak * n),
                              math.hypot(x.slide * c, y.slide * n))
    return f * c, f * n


@nb.njit(cache=True)
def tmsimple_wheel_forces(tp, fz, v_long, v_slip_x, v_slip_y, gamma):
    """TMsimple from the contact point's slip velocities: ``(FXW, FYW, 0, kappa, alpha,
    dFXW/dkappa)``, the slips and the stiffness as :func:`.tmeasy.tmeasy_wheel_forces` gives
    them (the curves at the load found once); no forces without a finite positive load."""
    kappa, alpha = slip(v_long, v_slip_x, v_slip_y)
    if not (fz > 0.0) or not math.isfinite(fz):
        return 0.0, 0.0, 0.0, kappa, alpha, 0.0
    q = min(fz, tp.max_load) / tp.nominal_load
    x = simple_curve_at(tp.longitudinal, q)
    y = simple_curve_at(tp.lateral, q)
    fx, fy = tmsimple_tangential(x, y, v_long, v_slip_x, v_slip_y)
    vref = max(abs(v_long), VXLOW)
    fx2, _ = tmsimple_tangential(x, y, v_long, v_slip_x - DKAPPA * vref, v_slip_y)
    dfx = (fx2 - fx) / DKAPPA
    if not (math.isfinite(fx) and math.isfinite(fy) and math.isfinite(dfx)):
        return 0.0, 0.0, 0.0, kappa, alpha, 0.0
    return fx, fy, 0.0, kappa, alpha, dfx


register_handling(HandlingModel("tmsimple", TMsimpleParams, tmsimple_params, tmsimple_wheel_forces,
                                "TMsimple (Hirschberg; Chrono's 2023 template), no aligning moment",
                                rolling_radius=tmeasy_rolling_radius,
                                rolling_resistance=tmeasy_rolling_moment))
