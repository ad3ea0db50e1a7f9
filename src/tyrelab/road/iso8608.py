"""Random roads from a displacement spectral density: ISO 8608 classes and power laws.

Frequency convention
--------------------
Spatial frequency ``n`` in **cycles/m** (not rad/m) and the **one-sided**
displacement spectral density ``Gd(n)`` in m^3 = m^2/(cycles/m), so the
variance of a profile is the integral of ``Gd`` over ``n > 0``. This is the
convention of ISO 8608 (``Gd(n) = Gd(n0) (n / n0)^-w``, ``n0 = 0.1``
cycles/m) and of the thesis's eq. 3.8 (``S_z = A phi^-n``, ``A`` the value at
1 cycle/m). The two are the same power law with ``A = Gd(n0) n0^w``. ISO 8608
also gives the angular form ``Phi(Omega) = Gd(n) / (2 pi)`` at
``Omega0 = 1 rad/m`` (:func:`angular_psd_at_omega0`).

Synthesis
---------
A profile is a sum of cosines at the frequencies ``k / P`` of its period
``P`` inside the band, amplitude ``sqrt(2 Gd(n_k) dn)`` and uniformly random
phase (the harmonic method, e.g. Cebon 1999, ch. 2; Tyan et al. 2009), built
by an inverse FFT. A 3D surface has an isotropic 2D spectrum: each
longitudinal frequency ``n_x`` carries ``M`` lateral waves whose lateral
frequencies are drawn from the isotropic spectrum's conditional density
``~ (n_x^2 + n_y^2)^-(w+1)/2`` (a scaled Student t with ``w`` degrees of
freedom), kept inside the disc ``|n| <= n_max``. So every longitudinal
profile has exactly the target ``Gd`` in the band, and two parallel tracks have
the coherence of an isotropic surface.
"""

from __future__ import annotations

import numpy as np
from scipy import fft, special

from .. import limits, resources
from ..errors import InputError
from .base import GriddedRoad
from .grid import RoadGrid

#: ISO 8608 reference spatial frequency [cycles/m]
N0 = 0.1
#: ISO 8608 waviness of the classes
W_ISO = 2.0
#: geometric mean Gd(n0) [m^3] of ISO 8608 road classes A-H (ISO 8608:1995 table 1)
ISO_CLASSES = {c: 16e-6 * 4.0 ** i for i, c in enumerate("ABCDEFGH")}
#: default band [cycles/m]: 20 m to 0.1 m wavelength (ISO 8608, thesis section 3.4.3)
BAND = (0.05, 10.0)
#: lateral waves per longitudinal frequency in a 3D surface
LATERAL_WAVES = 32


def power_law(spec) -> tuple[float, float]:
    """``(A, n)`` of ``S(phi) = A phi^-n`` (eq. 3.8) from a class letter or an ``(A, n)`` pair."""
    if isinstance(spec, str):
        key = spec.strip().upper()
        if key not in ISO_CLASSES:
            raise InputError(f"unknown ISO 8608 road class '{spec}'; expected one of A-H", field="road class")
        return ISO_CLASSES[key] * N0 ** W_ISO, W_ISO
    try:
        a, n = (float(v) for v in spec)
    except (TypeError, ValueError):
        raise InputError(f"expected an ISO 8608 class A-H or a pair (A, n), got {spec!r}",
                         field="road class") from None
    if not (np.isfinite(a) and np.isfinite(n) and a > 0 and n > 0):
        raise InputError(f"power law needs finite A > 0 and n > 0, got A = {a}, n = {n}", field="road class")
    if a > 1.0 or n > 10.0:
        raise InputError(f"power law A = {a:g}, n = {n:g} is no road: allowed A <= 1 m^2/(cycles/m) "
                         "(ISO 8608 class H is 2.6e-3) and n <= 10", field="road class")
    return a, n


def dsd(phi, a: float, n: float) -> np.ndarray:
    """Displacement spectral density ``A phi^-n`` [m^2/(cycles/m)], phi in cycles/m (eq. 3.8)."""
    return a * np.asarray(phi, float) ** (-n)


def gd_at_n0(a: float, n: float) -> float:
    """ISO 8608 ``Gd(n0)`` [m^3] of the power law ``(A, n)``."""
    return a * N0 ** (-n)


def angular_psd_at_omega0(a: float, n: float) -> float:
    """ISO 8608 ``Phi(Omega0)`` [m^3] at ``Omega0 = 1 rad/m``: ``Gd(1 / 2 pi) / 2 pi``."""
    return dsd(1.0 / (2 * np.pi), a, n) / (2 * np.pi)


def iso_class(a: float, n: float) -> str:
    """The ISO 8608 class whose ``Gd(n0)`` band (a factor 2 around its mean) holds this road."""
    idx = int(np.clip(np.round(np.log(gd_at_n0(a, n) / 16e-6) / np.log(4.0)), 0, 7))
    return "ABCDEFGH"[idx]


def profile_variance(a: float, n: float, band=BAND) -> float:
    """Variance [m^2] of a band-limited power-law profile: the integral of ``A phi^-n``."""
    lo, hi = band
    if abs(n - 1.0) < 1e-12:
        return a * np.log(hi / lo)
    return a * (lo ** (1 - n) - hi ** (1 - n)) / (n - 1)


def _bins(npts: int, dx: float, band) -> tuple[np.ndarray, np.ndarray, float]:
    """FFT bin indices and frequencies inside the band (below Nyquist), and the bin width."""
    dn = 1.0 / (npts * dx)
    k = np.arange(1, (npts - 1) // 2 + 1)
    f = k * dn
    keep = (f >= band[0]) & (f <= band[1])
    if not keep.any():
        raise InputError(f"no frequency of a {npts * dx:g} m road at {dx:g} m spacing lies in the band "
                         f"{band[0]:g}-{band[1]:g} cycles/m", field="band")
    return k[keep], f[keep], dn


def _check_sizes(length: float, spacing: float, what: str = "length",
                 high: float = limits.MAX_ROAD_LENGTH) -> int:
    if not (length > 0 and spacing > 0):
        raise InputError(f"length and spacing must be positive, got {length}, {spacing}", field="road")
    limits.check_number(length, "road", 0.0, high, "m", low_open=True, what=f"random road {what}")
    limits.check_number(spacing, "road", limits.MIN_GRID_SPACING, limits.MAX_GRID_SPACING, "m",
                        what="random road grid spacing")
    return int(np.floor(length / spacing + 1e-9)) + 1


def iso8608_profile(spec, length: float = 100.0, spacing: float = 0.01, seed=0,
                    band=BAND) -> tuple[np.ndarray, np.ndarray]:
    """A random longitudinal profile ``(x, z)`` [m] with the spectrum of ``spec``.

    ``spec`` is an ISO 8608 class letter or ``(A, n)`` of eq. 3.8. Points at
    ``x = 0, spacing, ...`` up to ``length``; deterministic for a given seed.
    """
    a, n = power_law(spec)
    nx = _check_sizes(length, spacing)
    npts = fft.next_fast_len(nx)
    k, f, dn = _bins(npts, spacing, band)
    rng = np.random.default_rng(seed)
    amp = np.sqrt(2.0 * dsd(f, a, n) * dn)
    spectrum = np.zeros(npts // 2 + 1, complex)
    spectrum[k] = 0.5 * npts * amp * np.exp(2j * np.pi * rng.random(k.size))
    z = fft.irfft(spectrum, npts)[:nx]
    return spacing * np.arange(nx), z


def _lateral_frequencies(f, n, band, m, rng) -> np.ndarray:
    """Lateral frequencies ``(len(f), m)`` drawn from the isotropic conditional density."""
    ny_max = np.sqrt(np.maximum(band[1] ** 2 - f ** 2, 0.0))
    t_max = ny_max * np.sqrt(n) / f
    # Student's t distribution with n degrees of freedom: its CDF and inverse CDF (scipy.stats'
    # t.cdf and t.ppf call these; scipy.stats itself costs 0.3 s of import in every process)
    lo = special.stdtr(n, -t_max)
    u = lo[:, None] + (1.0 - 2.0 * lo[:, None]) * rng.random((f.size, m))
    t = special.stdtrit(n, u)
    return f[:, None] * t / np.sqrt(n)


def iso8608_surface(spec, length: float = 100.0, width: float = 4.0,
                    spacing: tuple[float, float] = (0.01, 0.01), seed=0, band=BAND,
                    lateral_waves: int = LATERAL_WAVES, chunk: int = 16) -> np.ndarray:
    """Heights ``z[i, j]`` at ``x = i dx``, ``y = -width/2 + j dy`` of an isotropic random surface.

    Built column block by column block so the memory is the result plus a few MB.
    """
    a, n = power_law(spec)
    dx, dy = spacing
    nx = _check_sizes(length, dx)
    ny = _check_sizes(width, dy, "width", limits.MAX_ROAD_WIDTH)
    npts = fft.next_fast_len(nx)
    k, f, dn = _bins(npts, dx, band)
    rng = np.random.default_rng(seed)
    amp = np.sqrt(2.0 * dsd(f, a, n) * dn / lateral_waves)
    phase = np.exp(2j * np.pi * rng.random((k.size, lateral_waves))) * amp[:, None]
    fy = _lateral_frequencies(f, n, band, lateral_waves, rng)
    y = -0.5 * width + dy * np.arange(ny)
    z = np.empty((nx, ny))
    spectrum = np.zeros((npts // 2 + 1, chunk), complex)
    for j0 in range(0, ny, chunk):
        yj = y[j0:j0 + chunk]
        waves = np.exp(2j * np.pi * fy[:, :, None] * yj[None, None, :])
        spectrum[k, :yj.size] = 0.5 * npts * np.einsum("km,kmj->kj", phase, waves)
        z[:, j0:j0 + yj.size] = fft.irfft(spectrum[:, :yj.size], npts, axis=0)[:nx]
    return z


def _taper(nx: int, dx: float, length: float) -> np.ndarray:
    """Raised-cosine ramp from 0 to 1 over ``length`` at both ends (1 when length is 0)."""
    w = np.ones(nx)
    m = int(round(length / dx))
    if m > 0:
        ramp = 0.5 - 0.5 * np.cos(np.pi * np.arange(m) / m)
        m = min(m, nx // 2)
        w[:m] = ramp[:m]
        w[nx - m:] = ramp[:m][::-1]
    return w


class RandomRoad(GriddedRoad):
    """A random road of an ISO 8608 class or power law ``(A, n)`` (eq. 3.8), as a :class:`Road`.

    Parameters
    ----------
    spec : str or (float, float)
        Class letter A-H, or ``(A, n)``: A [m^2/(cycles/m)] at 1 cycle/m, n the exponent.
    length, width : float
        Size [m]; ``width=None`` gives a 2D profile road (same height across).
    spacing : (dx, dy)
        Synthesis grid [m]; heights between nodes are bilinear.
    seed : int
        Random seed; the road is a deterministic function of all arguments.
    band : (lo, hi)
        Spatial frequency band [cycles/m].
    start : float
        x [m] where the road begins; before it (and after its end) the height
        continues flat at the edge value.
    taper : float
        Length [m] of a raised-cosine ramp at each end that brings the heights to 0.
    """

    def __init__(self, spec="C", length: float = 100.0, width: float | None = 4.0,
                 spacing: tuple[float, float] = (0.01, 0.01), seed=0, band=BAND,
                 start: float = 0.0, taper: float = 0.0, force: bool = False):
        self.a, self.n = power_law(spec)
        self.band = tuple(float(b) for b in band)
        if not (len(self.band) == 2 and all(np.isfinite(self.band)) and 0 < self.band[0] < self.band[1]):
            raise InputError(f"band must be two increasing positive frequencies, got {band}", field="band")
        dx, dy = (float(s) for s in spacing)
        nx = _check_sizes(length, dx)
        ny = _check_sizes(width, dy, "width", limits.MAX_ROAD_WIDTH) if width else 2
        resources.check_resources(f"a random road of {nx} x {ny} nodes", memory=8.0 * 4 * nx * ny,
                               force=force, field="road", hint="use a coarser spacing or a smaller road")
        limits.check_number(start, "road", -limits.MAX_ROAD_LENGTH, limits.MAX_ROAD_LENGTH, "m",
                            what="random road start")
        limits.check_number(taper, "road", 0.0, 0.5 * length, "m", what="random road taper")
        if width:
            z = iso8608_surface((self.a, self.n), length, width, (dx, dy), seed, band)
            y0 = -0.5 * width
        else:
            z = np.repeat(iso8608_profile((self.a, self.n), length, dx, seed, band)[1][:, None], 2, axis=1)
            width, dy = 4.0, 4.0
            y0 = -2.0
        z *= _taper(z.shape[0], dx, taper)[:, None]
        self._varies_in_y = not (z.shape[1] == 2 and dy == width)
        self._grid = RoadGrid(float(start), y0, dx, dy, z)
        self.default_spacing = (dx, dy)
        label = spec.upper() if isinstance(spec, str) else f"A = {self.a:.3g}, n = {self.n:.3g}"
        self.name = f"random road ({label}), {length:g} m x {width:g} m, seed {seed}"

