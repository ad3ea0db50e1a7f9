"""Displacement spectral density of a road and its power-law fit (thesis eq. 3.8).

Convention as :mod:`tyrelab.road.iso8608`: spatial frequency ``phi`` in
cycles/m, one-sided density ``S`` in m^2/(cycles/m) (the variance is the
integral of ``S`` over ``phi > 0``), power law ``S = A phi^-n`` (eq. 3.8)
with ``A`` the value at 1 cycle/m. The estimate is Welch's averaged
periodogram (Hann window, 50 % overlap, linear detrend per segment); the fit
is a weighted Whittle likelihood fit over the spectral lines in the band
(0.05-10 cycles/m by default, ISO 8608), each line weighted so that every
logarithmic frequency bin, hence every decade, weighs the same.
"""

from __future__ import annotations

import numpy as np
from scipy import optimize, signal

from ..errors import InputError
from .base import Road
from .iso8608 import BAND

#: Welch segment length [m] by default: the band's lowest frequency, 0.05 cycles/m, is then the
#: 4th spectral line, clear of the window's main lobe around zero and of the linear detrend
SEGMENT = 80.0
#: logarithmic bins per decade in the fit
BINS_PER_DECADE = 20


def road_profile(road: Road, y: float = 0.0, spacing: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Longitudinal profile ``(x, z)`` of a road at lateral position ``y``, over its extent.

    Sampled at ``spacing``, by default the road's own grid spacing (so grid
    roads are read at their nodes) or 0.01 m if that is coarser than 0.05 m.
    """
    xmin, xmax, _, _ = road.extent()
    own, _ = road.default_spacing   # (along x, across)
    dx = float(spacing or (own if own <= 0.05 else 0.01))
    x = xmin + dx * np.arange(int(np.floor((xmax - xmin) / dx + 1e-9)) + 1)
    return x, road.height(x, np.full_like(x, y))


def _profiles(data, spacing, y, lines) -> tuple[list[np.ndarray], float]:
    """The profile(s) to analyse and their spacing, from a road, ``(x, z)`` or ``z``."""
    if isinstance(data, Road):
        if lines and lines > 1 and data.varies_in_y():
            _, _, ymin, ymax = data.extent()
            ys = np.linspace(ymin, ymax, lines + 2)[1:-1]
        else:
            ys = [y]
        xs, zs = zip(*(road_profile(data, yy, spacing) for yy in ys))
        return list(zs), float(xs[0][1] - xs[0][0])
    if isinstance(data, tuple) and len(data) == 2:
        x, z = (np.asarray(d, float) for d in data)
        steps = np.diff(x)
        if x.ndim != 1 or x.shape != z.shape or x.size < 8 or not np.allclose(steps, steps[0], rtol=1e-6):
            raise InputError("a profile (x, z) needs at least 8 equally spaced points", field="profile")
        return [z], float(steps[0])
    z = np.asarray(data, float)
    if z.ndim != 1 or not spacing:
        raise InputError("a bare height array needs 1 dimension and a spacing", field="profile")
    return [z], float(spacing)


def displacement_spectral_density(data, spacing: float | None = None, y: float = 0.0,
                                  segment: float = SEGMENT, lines: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """One-sided displacement spectral density ``(phi, S)`` by Welch's method.

    ``data`` is a :class:`Road` (profile at lateral position ``y``, or the mean
    over ``lines`` evenly spaced profiles of a 3D road), a profile ``(x, z)``,
    or heights ``z`` at ``spacing``. ``segment`` is the Welch segment length [m];
    a profile shorter than two segments is analysed as one segment. phi in cycles/m, S in m^2/(cycles/m).
    """
    profiles, dx = _profiles(data, spacing, y, lines)
    if np.any([not np.all(np.isfinite(p)) for p in profiles]):
        raise InputError("the profile has empty (NaN) heights", field="profile")
    npts = len(profiles[0])
    nper = int(round(segment / dx))
    if npts < 2 * nper:  # too short for two segments: one Hann-windowed periodogram of it all
        nper = npts
    psds = []
    for z in profiles:
        phi, s = signal.welch(z, fs=1.0 / dx, window="hann", nperseg=nper, noverlap=nper // 2,
                              detrend="linear", scaling="density")
        psds.append(s)
    return phi[1:], np.mean(psds, axis=0)[1:]


def log_binned(phi: np.ndarray, s: np.ndarray, band=BAND,
               per_decade: int = BINS_PER_DECADE) -> tuple[np.ndarray, np.ndarray]:
    """Mean spectrum in logarithmic frequency bins inside ``band``: ``(phi_centre, S_mean)``.

    Each bin's frequency is the geometric mean of the frequencies it holds.
    """
    lo, hi = band
    keep = (phi >= lo * (1 - 1e-9)) & (phi <= hi * (1 + 1e-9)) & (s > 0)
    phi, s = phi[keep], s[keep]
    if phi.size < 3:
        raise InputError(f"fewer than 3 spectral lines in the band {lo:g}-{hi:g} cycles/m; "
                         "the profile is too short or too coarse", field="band")
    edges = np.log10(lo) + np.arange(0, np.log10(hi / lo) * per_decade + 2) / per_decade
    idx = np.digitize(np.log10(phi), edges)
    centres, means = [], []
    for b in np.unique(idx):
        m = idx == b
        centres.append(np.exp(np.mean(np.log(phi[m]))))
        means.append(np.mean(s[m]))
    return np.array(centres), np.array(means)


def _line_weights(phi: np.ndarray, band, per_decade: int = BINS_PER_DECADE) -> np.ndarray:
    """Weight of each spectral line: 1 / (lines in its logarithmic bin), so each bin weighs the same."""
    lo, hi = band
    edges = np.log10(lo) + np.arange(0, np.log10(hi / lo) * per_decade + 2) / per_decade
    idx = np.digitize(np.log10(phi), edges)
    _, inverse, counts = np.unique(idx, return_inverse=True, return_counts=True)
    return 1.0 / counts[inverse]


def _whittle_fit(phi: np.ndarray, s: np.ndarray, w: np.ndarray) -> tuple[float, float]:
    """Weighted Whittle (gamma) likelihood fit of ``S = A phi^-n``.

    Minimises ``sum w (ln m + S / m)`` with ``m = A phi^-n``; for a given n the
    best A is ``sum w S phi^n / sum w``. Unlike a least-squares line through
    log S, it is unbiased for the skewed scatter of few-line spectral estimates.
    """
    lphi = np.log(phi)

    def objective(n):
        a = np.sum(w * s * np.exp(n * lphi)) / np.sum(w)
        return np.sum(w) * np.log(a) - n * np.sum(w * lphi)

    best = optimize.minimize_scalar(objective, bounds=(-5.0, 10.0), method="bounded",
                                    options={"xatol": 1e-8})
    n = float(best.x)
    return float(np.sum(w * s * np.exp(n * lphi)) / np.sum(w)), n


def fit_power_law(data, s: np.ndarray | None = None, band=BAND, **dsd_options) -> tuple[float, float]:
    """Fit ``S = A phi^-n`` (eq. 3.8) in ``band``; returns ``(A, n)``.

    Pass either the spectrum ``(phi, S)`` as two arguments, or anything
    :func:`displacement_spectral_density` accepts (then it is computed first).
    Every spectral line in the band counts, weighted so that each
    logarithmic bin (:data:`BINS_PER_DECADE` per decade) weighs the same.
    """
    if s is None:
        phi, s = displacement_spectral_density(data, **dsd_options)
    else:
        phi = np.asarray(data, float)
        s = np.asarray(s, float)
    lo, hi = band
    keep = (phi >= lo * (1 - 1e-9)) & (phi <= hi * (1 + 1e-9)) & (s > 0)
    if keep.sum() < 3:
        raise InputError(f"fewer than 3 spectral lines in the band {lo:g}-{hi:g} cycles/m; "
                         "the profile is too short or too coarse", field="band")
    return _whittle_fit(phi[keep], s[keep], _line_weights(phi[keep], band))
