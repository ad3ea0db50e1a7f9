"""TMeasy's parameters fitted to pure-slip curves: another handling model's (a Magic Formula,
PAC89 or Fiala file converted to TMeasy, as Chrono's TMeasy data sets were gained from
PAC2002 files) or measured ones (a flat-track or trailer test's slip sweeps).

Samples are put in TMeasy's own terms (:mod:`tyrelab.tyre.handling.tmeasy`; transport speed
``Re omega + v_N``): the slip ``s_x = kappa / (1 + kappa)`` (ISO ``kappa``; a sampled
model is evaluated at the ``kappa`` that gives ``s_x`` exactly, ``v_N`` included) with FXW,
``s_y = -tan alpha`` with FYW and MZW, at their loads. Each direction's characteristic at
FZ_NOM and at 2 FZ_NOM (dF0, FM, sM, FS, sS each; TMeasy's load interpolation between) is
fitted by least squares to every sample at once, the curve odd in the slip (a file's offsets
are not carried), keeping every parameter inside what TMeasy's property file accepts
(dF0 >= 2 FM / sM, FS <= FM, sM < sS); then the normalised pneumatic trail (its value at zero
slip, where it changes sign, where it vanishes) to the aligning moment ``Mz = -L n Fy``, L
the contact length, where the tyre grips (lateral slips up to :data:`TRAIL_SLIPS` times the
fitted peak slip; a Magic Formula's residual moment has no place in TMeasy). A sampled
model is sampled only inside its file's slip range (:func:`_slip_limits`): a tyre measured in
braking only is fitted on its braking side.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from ..tyre.handling.tmeasy import (DEFAULT_MAX_LOAD_RATIO, V_NUM, SlipCurve, Trail,
                                    characteristic_at_loads, curve_at, law_deflection,
                                    tmeasy_entries, trail_moments, vertical_coefficients)

#: samples per curve and load, and the largest TMeasy slips sampled where the source states no range
SAMPLES = 80
MAX_SLIP_X = 0.9
MAX_SLIP_Y = 1.5
#: the aligning moment is fitted up to this many times the lateral force's peak slip
TRAIL_SLIPS = 3.0
#: forward speed of the sampling [m/s]
SPEED = 10.0
#: a measured sample is pure slip when the other slip is at most this (rad for the angle)
PURE = 1e-3
#: the least-squares fits' stopping tolerances (scipy's default 1e-8 leaves 1e-7 on exact data)
TOLERANCES = {"ftol": 1e-12, "xtol": 1e-12, "gtol": 1e-12}
#: channels a measured sweep must have
SWEEP_CHANNELS = ("FZW", "LONGSLIP", "SLIPANGL", "FXW", "FYW", "MZW")


@dataclass
class Samples:
    """One direction's pure-slip samples in TMeasy's terms: the signed slip, the load [N],
    the force along the slip [N] (FXW; FYW); lateral samples also the aligning moment [N m]."""

    slip: np.ndarray
    load: np.ndarray
    force: np.ndarray
    moment: np.ndarray | None = None


@dataclass
class TMeasyFit:
    """The fitted parameters (each a pair: at FZ_NOM and 2 FZ_NOM), the loads [N], the RMS
    error of each fitted curve over its samples in % of their largest magnitude (``rms_pct``:
    ``Fx``, ``Fy``, ``Mz``) and the TMeasy slips sampled, ``((s_x low, high), (s_y low, high))``."""

    nominal_load: float
    max_load: float
    longitudinal: tuple
    lateral: tuple
    trail: tuple
    rms_pct: dict = field(default_factory=dict)
    slip_range: tuple = ((0.0, 0.0), (0.0, 0.0))

    def entries(self):
        """``[(section, key, value)]`` for the property file (:func:`tmeasy_entries`)."""
        return tmeasy_entries(self.nominal_load, self.max_load, self.longitudinal, self.lateral,
                              self.trail)


def _curve(p) -> SlipCurve:
    """A characteristic from (FM, sM, dF0 - 2 FM/sM, FS/FM, sS - sM): inside TMeasy's bounds."""
    peak, peak_slip, excess, ratio, gap = (float(v) for v in p)
    return SlipCurve(2.0 * peak / peak_slip + excess, peak, peak_slip, ratio * peak, peak_slip + gap)


def _binned(s, f, bins: int = 40):
    """Mean slip and force in ``bins`` slip bins of equal count (sorted by slip)."""
    order = np.argsort(s)
    parts = np.array_split(order, min(bins, s.size))
    return (np.array([s[k].mean() for k in parts]), np.array([f[k].mean() for k in parts]))


def _start(s, f) -> list[float]:
    """A first guess (the :func:`_curve` parameters) from a curve's samples at positive slip."""
    s, f = _binned(s, f)
    i = int(f.argmax())
    peak = float(f[i])
    slope = f[0] / s[0] if s[0] > 0 else 2.0 * peak / s[i]
    return [peak, float(s[i]), max(slope - 2.0 * peak / s[i], 0.0) + 1e-6 * abs(slope),
            min(max(f[-1] / peak, 0.0), 1.0), max(float(s[-1] - s[i]), 1e-3)]


def _least_squares(residual, start, lower, upper):
    """The parameters inside ``[lower, upper]`` that minimise ``residual``'s squares (started
    at ``start``, clipped into the bounds), and the residual's RMS in % (the residuals are
    fractions of a scale)."""
    from scipy.optimize import least_squares

    best = least_squares(residual, np.clip(start, lower, upper), bounds=(lower, upper),
                         x_scale="jac", max_nfev=4000, **TOLERANCES)
    return best.x, 100.0 * math.sqrt(np.mean(residual(best.x) ** 2))


def fit_direction(samples: Samples, nominal: float, max_load: float) -> tuple[tuple, float]:
    """The characteristics at FZ_NOM and 2 FZ_NOM closest (least squares) to every sample, the
    curve odd in the slip; and the RMS error in % of the largest force magnitude."""
    s, f = samples.slip, samples.force
    q = np.minimum(samples.load, max_load) / nominal
    scale = float(np.abs(f).max())
    moving = np.abs(s) > 0
    if not (scale > 0 and moving.any()):
        raise InputError("the samples show no force in this direction to fit TMeasy to",
                         field="handling")
    # a first guess from the force per unit load ratio: forces and slope twice at 2 FZ_NOM
    per_load = np.sign(s[moving]) * f[moving] / q[moving]
    peak, peak_slip, excess, ratio, gap = _start(np.abs(s[moving]), per_load)
    start = np.array([peak, peak_slip, excess, ratio, gap, 2.0 * peak, peak_slip, 2.0 * excess, ratio, gap])
    s_top = float(np.abs(s).max())
    lower = np.tile([1e-9 * scale, 1e-4, 0.0, 0.0, 1e-4], 2)
    upper = np.tile([10.0 * scale, max(s_top, 2e-4), np.inf, 1.0, 10.0], 2)
    out = np.empty_like(f)

    def residual(p):
        characteristic_at_loads(s, q, (_curve(p[:5]), _curve(p[5:])), out)
        return (out - f) / scale

    p, rms = _least_squares(residual, start, lower, upper)
    return (_curve(p[:5]), _curve(p[5:])), rms


def fit_trail(samples: Samples, nominal: float, max_load: float, lateral: tuple,
              tyre) -> tuple[tuple, float]:
    """The normalised trails at FZ_NOM and 2 FZ_NOM whose moments ``-L n Fy`` (L the contact
    length ``2 sqrt(R0 z)``, z the deflection of TMeasy's law fitted to ``tyre``'s,
    :func:`~tyrelab.tyre.handling.tmeasy.vertical_coefficients`) are closest to the samples' where
    the tyre grips (|s_y| up to :data:`TRAIL_SLIPS` times the fitted peak slip at its load);
    and the RMS error in % of the largest moment magnitude there. The moment, not the trail,
    is fitted: the trail matters where the force is large."""
    q = np.minimum(samples.load, max_load) / nominal
    grip = np.array([abs(s) <= TRAIL_SLIPS * curve_at(lateral, qi).peak_slip
                     for s, qi in zip(samples.slip, q)])
    s, q, fy, mz = samples.slip[grip], q[grip], samples.force[grip], samples.moment[grip]
    d1, d2 = vertical_coefficients(tyre.vertical_law)
    length = np.array([2.0 * math.sqrt(tyre.unloaded_radius * law_deflection(d1, d2, fz))
                       for fz in samples.load[grip]])
    scale = max(float(np.abs(mz).max()), 1e-12)
    out = np.empty_like(mz)

    def trails(p):
        return Trail(p[0], p[1], p[1] + p[2]), Trail(p[3], p[4], p[4] + p[5])

    def residual(p):
        trail_moments(np.abs(s), q, length, fy, trails(p), out)
        return (out - mz) / scale

    carries = np.abs(fy) > 1e-3 * np.abs(fy).max()
    n = -mz[carries] / (length[carries] * fy[carries])
    a = np.abs(s[carries])
    order = np.argsort(a)
    n0 = max(float(np.median(n[order[:max(3, order.size // 10)]])), 0.0)
    crossing = a[order][n[order] <= 0.0]
    s0 = float(crossing[0]) if crossing.size else 0.5 * float(a.max())
    one = [n0, s0, max(float(a.max()) - s0, 1e-3)]
    lower, upper = np.tile([0.0, 1e-4, 0.0], 2), np.tile([10.0, 10.0, 10.0], 2)
    p, rms = _least_squares(residual, one + one, lower, upper)
    return trails(p), rms


def fit_tmeasy(x: Samples, y: Samples, nominal: float, tyre) -> TMeasyFit:
    """TMeasy from longitudinal samples ``x`` and lateral ``y`` (with moments) at nominal load
    ``nominal`` [N] (FZ_MAX 3.5 times it, Chrono's default); ``tyre``'s vertical law gives the
    contact length."""
    if not (math.isfinite(nominal) and nominal > 0):
        raise InputError(f"expected a positive nominal load in N, got {nominal!r}", field="--nominal-load")
    maximum = DEFAULT_MAX_LOAD_RATIO * nominal
    longitudinal, rms_x = fit_direction(x, nominal, maximum)
    lateral, rms_y = fit_direction(y, nominal, maximum)
    trail, rms_m = fit_trail(y, nominal, maximum, lateral, tyre)
    return TMeasyFit(nominal, maximum, longitudinal, lateral, trail,
                     {"Fx": rms_x, "Fy": rms_y, "Mz": rms_m},
                     tuple((float(d.slip.min()), float(d.slip.max())) for d in (x, y)))


def _slip_limits(tyre) -> tuple[tuple[float, float], tuple[float, float]]:
    """TMeasy's slips ``((s_x low, high), (s_y low, high))`` inside the source's stated range (a
    Magic Formula's KPUMIN, KPUMAX, ALPMIN, ALPMAX; ``s_x = kappa / (1 + kappa)``, ``s_y =
    -tan(alpha)``, v_N left out: 0.1 % at 10 m/s), else :data:`MAX_SLIP_X`, :data:`MAX_SLIP_Y`.
    TMeasy's curve is odd: where the range has both signs, both sides reach the shorter side's
    slip (the same slips on each); a side the range leaves out is ``0``, no samples there (a tyre
    measured in braking only, ``KPUMAX = 0``, is clipped flat at zero force on the driving side,
    which an odd curve cannot follow)."""
    tir = tyre.tir

    def reach(bound, limit, magnitude):  # how far one side goes: 0 where the range excludes it
        return limit if bound is None else min(limit, magnitude(bound))

    def kappa_slip(kappa):  # TMeasy's slip magnitude of a slip ratio: endless at lock
        return abs(kappa) / (1.0 + kappa) if kappa > -1.0 else math.inf

    def sides(low, high):
        if low > 0.0 and high > 0.0:
            low = high = min(low, high)
        return -low, high

    x = sides(reach(tir.number("LONG_SLIP_RANGE", "KPUMIN", None), MAX_SLIP_X,
                    lambda k: kappa_slip(k) if k < 0.0 else 0.0),
              reach(tir.number("LONG_SLIP_RANGE", "KPUMAX", None), MAX_SLIP_X,
                    lambda k: kappa_slip(k) if k > 0.0 else 0.0))
    y = sides(reach(tir.number("SLIP_ANGLE_RANGE", "ALPMAX", None), MAX_SLIP_Y,
                    lambda a: math.tan(min(a, 1.5)) if a > 0.0 else 0.0),
              reach(tir.number("SLIP_ANGLE_RANGE", "ALPMIN", None), MAX_SLIP_Y,
                    lambda a: math.tan(min(-a, 1.5)) if a < 0.0 else 0.0))
    return x, y


def tmeasy_from_handling(tyre, handling: str, nominal_load: float, speed: float = SPEED) -> TMeasyFit:
    """TMeasy fitted to ``tyre``'s curves under handling model ``handling``, sampled at
    ``nominal_load`` [N] and twice it at TMeasy's own slips (module docstring)."""
    from ..tyre.registry import handling_model

    model = handling_model(handling)
    params = model.build(tyre)
    (s_x_low, s_x_high), (s_y_low, s_y_high) = _slip_limits(tyre)
    grid = np.linspace(0.0, 1.0, SAMPLES + 1)[1:]

    def kappa(s):  # the ISO slip ratio at which TMeasy's transport speed gives s_x = s
        return (speed + s * V_NUM) / (speed * (1.0 - s)) - 1.0

    lean = (speed + V_NUM) / speed  # s_y > 0 slides right: tan alpha = -s_y (V + v_N) / V
    xs, ys = [], []
    for fz in (nominal_load, 2.0 * nominal_load):
        for s in _sides(grid, s_x_low, s_x_high):
            xs.append((s, fz, model.at_slips(params, fz, speed, kappa(s), 0.0)[0]))
        for s in _sides(grid, s_y_low, s_y_high):
            ys.append((s, fz, *model.at_slips(params, fz, speed, 0.0, -s * lean)[1:3]))
    x, y = np.array(xs), np.array(ys)
    return fit_tmeasy(Samples(x[:, 0], x[:, 1], x[:, 2]), Samples(y[:, 0], y[:, 1], y[:, 2], y[:, 3]),
                      nominal_load, tyre)


def _sides(grid, low: float, high: float) -> np.ndarray:
    """The slips ``high grid`` and ``low grid`` (``grid`` in (0, 1]), a side without range left out."""
    return np.r_[high * grid if high > 0 else [], low * grid if low < 0 else []]


def samples_from_runs(runs) -> tuple[Samples, Samples]:
    """Pure-slip samples from measured sweeps (tables with :data:`SWEEP_CHANNELS`, SI, W-axis:
    :func:`tyrelab.measure.io.read_run`): rows with load whose other slip is at most
    :data:`PURE` (longitudinal: ``s_x = kappa / (1 + kappa)``; lateral: ``s_y = -tan alpha``)."""
    xs, ys = [], []
    for run in runs:
        missing = [c for c in SWEEP_CHANNELS if c not in run.columns]
        if missing:
            raise InputError(f"a slip sweep needs the channels {', '.join(SWEEP_CHANNELS)}; missing "
                             f"{', '.join(missing)}", source=run.attrs.get("path"), field=missing[0])
        d = run[list(SWEEP_CHANNELS)].to_numpy(dtype=float)
        fz, kappa, alpha, fx, fy, mz = d.T
        ok = np.isfinite(d).all(axis=1) & (fz > 0) & (kappa > -1.0) & (np.abs(alpha) < 1.5)
        pure_x = ok & (np.abs(alpha) <= PURE) & (np.abs(kappa) > 0)
        pure_y = ok & (np.abs(kappa) <= PURE) & (np.abs(alpha) > 0)
        xs.append(np.c_[kappa[pure_x] / (1.0 + kappa[pure_x]), fz[pure_x], fx[pure_x]])
        ys.append(np.c_[-np.tan(alpha[pure_y]), fz[pure_y], fy[pure_y], mz[pure_y]])
    x, y = np.vstack(xs), np.vstack(ys)
    for name, part in (("longitudinal", x), ("lateral", y)):
        if part.shape[0] < 10:
            raise InputError(f"too few pure {name}-slip samples ({part.shape[0]}) to fit TMeasy: "
                             f"the sweeps need rows with the other slip at most {PURE:g}",
                             field="--measured")
    return Samples(x[:, 0], x[:, 1], x[:, 2]), Samples(y[:, 0], y[:, 1], y[:, 2], y[:, 3])


def tmeasy_from_runs(tyre, runs, nominal_load: float | None = None) -> TMeasyFit:
    """TMeasy fitted to measured slip sweeps (:func:`samples_from_runs`); the contact length
    from ``tyre``'s vertical law. ``nominal_load`` [N] default: half the largest measured load
    (so that 2 FZ_NOM is the heaviest sweep)."""
    x, y = samples_from_runs(runs)
    if nominal_load is None:
        nominal_load = 0.5 * float(max(x.load.max(), y.load.max()))
    return fit_tmeasy(x, y, nominal_load, tyre)

