"""TMeasy's parameters fitted to another handling model's curves: a Magic Formula, PAC89 or
Fiala file converted to TMeasy (as Chrono's TMeasy data sets were gained from PAC2002 files).

At the nominal load and twice it, the source's pure-slip forces are sampled at TMeasy's own
slips (:mod:`tyrelab.tyre.handling.tmeasy`; transport speed ``Re omega + v_N``) -- ``s_x = s``
driving at the ISO slip ratio ``(V + s v_N) / (V (1 - s)) - 1``, ``s_x = -s`` braking at
``(V - s v_N) / (V (1 + s)) - 1``, ``s_y = s`` at ``tan alpha = s (V + v_N) / V`` -- averaged
over the two signs
(TMeasy's curves are odd; a file's offsets are not carried) and fitted by least squares:
each direction's characteristic (dF0, FM, sM, FS, sS) and the normalised pneumatic trail
(its value at zero slip, where it changes sign, where it vanishes) to the aligning moment
``Mz = -L n Fy``, L the contact length (a Magic Formula's residual moment has no place in
TMeasy: the trail takes what it can). The fit keeps every parameter inside what TMeasy's property file
accepts (dF0 >= 2 FM / sM, FS <= FM, sM < sS).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..tyre.handling.tmeasy import (DEFAULT_MAX_LOAD_RATIO, V_NUM, SlipCurve, Trail, characteristic,
                                    law_deflection, normalized_trail, tmeasy_entries,
                                    vertical_coefficients)

#: samples per curve, and the largest TMeasy slips sampled where the source states no range
SAMPLES = 80
MAX_SLIP_X = 0.9
MAX_SLIP_Y = 1.5
#: the aligning moment is fitted up to this many times the lateral force's peak slip
TRAIL_SLIPS = 3.0
#: forward speed of the sampling [m/s]
SPEED = 10.0


@dataclass
class TMeasyFit:
    """The fitted parameters (each a pair: at FZ_NOM and 2 FZ_NOM), the loads [N], and the
    RMS error of each fitted curve over its samples, in % of the sampled curve's peak
    (``rms_pct``: keys ``Fx``, ``Fy``, ``Mz`` and the level 1 or 2)."""

    nominal_load: float
    max_load: float
    longitudinal: tuple
    lateral: tuple
    trail: tuple
    rms_pct: dict = field(default_factory=dict)
    slip_range: tuple = (0.0, 0.0)

    def entries(self):
        """``[(section, key, value)]`` for the property file (:func:`tmeasy_entries`)."""
        return tmeasy_entries(self.nominal_load, self.max_load, self.longitudinal, self.lateral,
                              self.trail)


def fit_characteristic(s, f) -> tuple[SlipCurve, float]:
    """The TMeasy characteristic closest (least squares) to forces ``f`` [N] at slips
    ``s`` > 0, and its RMS error in % of ``max(f)``."""
    from scipy.optimize import least_squares

    s, f = np.asarray(s, float), np.asarray(f, float)
    peak = float(f.max())
    if not peak > 0:
        raise InputError("the source gives no force in this direction to fit TMeasy to",
                         field="handling")
    i = int(f.argmax())

    def curve(p):
        peak, peak_slip, excess, ratio, gap = p
        return SlipCurve(2.0 * peak / peak_slip + excess, peak, peak_slip, ratio * peak,
                         peak_slip + gap)

    def residual(p):
        c = curve(p)
        return np.array([characteristic(x, *c) for x in s]) - f

    slope = f[0] / s[0]
    start = [peak, s[i], max(slope - 2.0 * peak / s[i], 0.0) + 1e-6 * slope,
             min(max(f[-1] / peak, 0.0), 1.0), max(s[-1] - s[i], 1e-3)]
    lower = [1e-9 * peak, 1e-4, 0.0, 0.0, 1e-4]
    upper = [10.0 * peak, s[-1], np.inf, 1.0, 10.0]
    start = np.clip(start, lower, upper)
    best = least_squares(residual, start, bounds=(lower, upper), x_scale="jac", max_nfev=4000)
    c = curve(best.x)
    return c, 100.0 * math.sqrt(np.mean(residual(best.x) ** 2)) / peak


def fit_trail(s, fy, mz, length) -> tuple[Trail, float]:
    """The normalised pneumatic trail whose moment ``-length n(s) fy`` is closest (least
    squares) to ``mz`` [N m] at lateral slips ``s`` > 0, with the lateral forces ``fy`` [N]
    there and the contact length ``length`` [m]; and its RMS error in % of ``max |mz|``. The
    moment, not the trail, is fitted: the trail matters where the force is large."""
    from scipy.optimize import least_squares

    s, fy, mz = (np.asarray(v, float) for v in (s, fy, mz))
    scale = max(float(np.abs(mz).max()), 1e-12)

    def trail(p):
        return Trail(p[0], p[1], p[1] + p[2])

    def residual(p):
        t = trail(p)
        return -length * fy * np.array([normalized_trail(x, *t) for x in s]) - mz

    n = -mz / np.where(np.abs(fy) > 0, length * fy, np.inf)
    crossing = np.flatnonzero(n <= 0.0)
    s0 = float(s[crossing[0]]) if crossing.size else 0.5 * float(s[-1])
    start = [max(float(n[0]), 0.0), s0, max(float(s[-1]) - s0, 1e-3)]
    lower, upper = [0.0, 1e-4, 0.0], [10.0, 10.0, 10.0]
    best = least_squares(residual, np.clip(start, lower, upper), bounds=(lower, upper),
                         x_scale="jac", max_nfev=4000)
    return trail(best.x), 100.0 * math.sqrt(np.mean(residual(best.x) ** 2)) / scale


def _slip_limits(tyre) -> tuple[float, float]:
    """TMeasy's largest slips inside the source's stated range (a Magic Formula's KPUMAX,
    ALPMAX; v_N left out: 0.1 % at 10 m/s), else :data:`MAX_SLIP_X`, :data:`MAX_SLIP_Y`."""
    tir = tyre.tir
    sx, sy = MAX_SLIP_X, MAX_SLIP_Y
    kappa = tir.number("LONG_SLIP_RANGE", "KPUMAX", None)
    if kappa is not None and kappa > 0:
        sx = min(sx, kappa / (1.0 + kappa))
    alpha = tir.number("SLIP_ANGLE_RANGE", "ALPMAX", None)
    if alpha is not None and alpha > 0:
        sy = min(sy, math.tan(min(alpha, 1.5)))
    return sx, sy


def tmeasy_from_handling(tyre, handling: str, nominal_load: float, speed: float = SPEED) -> TMeasyFit:
    """TMeasy's parameters fitted to ``tyre``'s curves under handling model ``handling`` at
    ``nominal_load`` [N] and twice it (module docstring); FZ_MAX 3.5 times the nominal load."""
    from ..tyre.registry import handling_model

    if not (math.isfinite(nominal_load) and nominal_load > 0):
        raise InputError(f"expected a positive nominal load in N, got {nominal_load!r}",
                         field="--nominal-load")
    model = handling_model(handling)
    params = model.build(tyre)
    d1, d2 = vertical_coefficients(tyre.vertical_law)
    s_x_max, s_y_max = _slip_limits(tyre)
    s_x = np.linspace(0.0, s_x_max, SAMPLES + 1)[1:]
    s_y = np.linspace(0.0, s_y_max, SAMPLES + 1)[1:]

    def forces(fz, kappa, tan_alpha):
        return model.forces(params, fz, speed, -kappa * speed, tan_alpha * speed, 0.0)

    def driving(s):
        return (speed + s * V_NUM) / (speed * (1.0 - s)) - 1.0

    def braking(s):
        return (speed - s * V_NUM) / (speed * (1.0 + s)) - 1.0

    curves = {"x": [], "y": [], "trail": []}
    rms = {}
    for level in (1, 2):
        fz = level * nominal_load
        fx = np.array([0.5 * (forces(fz, driving(s), 0.0)[0] - forces(fz, braking(s), 0.0)[0]) for s in s_x])
        lean = (speed + V_NUM) / speed
        # TMeasy's s_y > 0 slides right: the slip angle's tangent is -s_y (V + v_N) / V
        lateral = [(forces(fz, 0.0, -s * lean), forces(fz, 0.0, s * lean)) for s in s_y]
        fy = np.array([0.5 * (a[1] - b[1]) for a, b in lateral])
        mz = np.array([0.5 * (a[2] - b[2]) for a, b in lateral])
        cx, rms[f"Fx{level}"] = fit_characteristic(s_x, fx)
        cy, rms[f"Fy{level}"] = fit_characteristic(s_y, fy)
        length = 2.0 * math.sqrt(tyre.unloaded_radius * law_deflection(d1, d2, fz))
        # the moment where the tyre grips: up to TRAIL_SLIPS times the lateral force's peak slip
        grip = s_y <= TRAIL_SLIPS * cy.peak_slip
        trail, rms[f"Mz{level}"] = fit_trail(s_y[grip], fy[grip], mz[grip], length)
        curves["x"].append(cx)
        curves["y"].append(cy)
        curves["trail"].append(trail)
    return TMeasyFit(nominal_load, DEFAULT_MAX_LOAD_RATIO * nominal_load, tuple(curves["x"]),
                     tuple(curves["y"]), tuple(curves["trail"]), rms, (s_x_max, s_y_max))
