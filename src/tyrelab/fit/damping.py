"""Tyre damping from the trailer drop test (thesis 3.4.1, eqs. 3.1-3.7).

The trailer, lifted until its wheels just leave the ground, is dropped; the
rim's vertical motion decays to static equilibrium. The thesis models the
trailer as a pendulum pivoting about the (fixed) hitch, with the tyres as a
spring and a damper at the axle, lever ``l`` (eq. 3.1)::

    I0 theta'' + c l^2 theta' + k l^2 theta = 0

so ``omega_n = sqrt(k l^2 / I0)`` (eq. 3.4) and ``xi = c l^2 / (2 omega_n I0)``
(eq. 3.5); the damping ratio comes from the logarithmic decrement of
consecutive oscillations, ``delta = ln(x1 / x2)`` (eq. 3.6),
``xi = delta / sqrt(delta^2 + (2 pi)^2)`` (eq. 3.7). With the thesis's trace
this gave 2.66 N s/mm for the XZL 16.00R20 at 300 kPa. (Eq. 3.1 prints the
spring term as ``k l theta``; eq. 3.4 shows ``k l^2`` was meant.)
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from scipy.signal import find_peaks

from ..errors import InputError
from .search import refine_minimum, term_sse


class DropTestDamping(NamedTuple):
    """Result of :func:`drop_test_damping` (SI; per tyre where it says so)."""

    #: damping ratio xi of the trailer's pitch about the hitch (eq. 3.7), mean over the cycles
    ratio: float
    #: undamped natural frequency [Hz] (from the damped period and xi)
    frequency: float
    #: damping coefficient of one tyre [N s/m] (eq. 3.5 divided among the wheels)
    damping: float
    #: vertical stiffness of one tyre [N/m] (eq. 3.4 divided among the wheels)
    stiffness: float
    #: the logarithmic decrement of each cycle used (eq. 3.6)
    decrements: np.ndarray


def drop_test_damping(time, displacement, inertia, lever, wheels=2, cycles=3) -> DropTestDamping:
    """Tyre damping from a drop-test trace by the thesis's pendulum procedure.

    Parameters
    ----------
    time, displacement : array_like
        Time [s] and the rim's (axle's) vertical position [m], from the
        release on; the first extreme after the release (the first
        compression) starts the cycles.
    inertia : float
        Moment of inertia of the trailer about the hitch's pitch axis [kg m^2].
    lever : float
        Hitch-to-axle distance l [m].
    wheels : int
        Tyres on the axle; c and k of eqs. 3.4-3.5 are their sum.
    cycles : int
        Whole oscillations to average the decrement over.

    The decrement of each cycle is taken from the peak-to-peak heights of
    successive half cycles, ``delta = 2 ln(h_k / h_{k+1})``, so the final
    equilibrium need not be known.
    """
    t = np.asarray(time, float)
    z = np.asarray(displacement, float)
    if t.shape != z.shape or t.ndim != 1 or not (np.all(np.isfinite(t)) and np.all(np.isfinite(z))):
        raise InputError("a drop-test trace needs finite time and displacement of equal length",
                         field="drop test")
    if not (inertia > 0 and lever > 0 and wheels >= 1):
        raise InputError("inertia, lever and wheels of the drop test must be positive",
                         field="drop test")
    # maxima and minima in time order (scipy's find_peaks: plateaus count once)
    ext = np.sort(np.r_[find_peaks(z)[0], find_peaks(-z)[0]])
    need = 2 * cycles + 2
    if ext.size < need:
        raise InputError(f"the drop-test trace has {ext.size} extremes; {need} are needed for "
                         f"{cycles} cycles (a longer record, or less damping)", field="drop test")
    ext = ext[:need]
    heights = np.abs(np.diff(z[ext]))
    half = np.log(heights[:-1] / heights[1:])            # per half cycle
    decrements = half[0::2] + half[1::2]                  # per cycle, eq. 3.6
    decrements = decrements[:cycles]
    delta = float(np.mean(decrements))
    xi = delta / math.sqrt(delta * delta + 4.0 * math.pi ** 2)      # eq. 3.7
    period = 2.0 * float(np.mean(np.diff(t[ext])))
    omega_n = 2.0 * math.pi / period / math.sqrt(1.0 - xi * xi)
    c_total = 2.0 * xi * omega_n * inertia / lever ** 2               # eq. 3.5
    k_total = omega_n ** 2 * inertia / lever ** 2                     # eq. 3.4
    return DropTestDamping(xi, omega_n / (2.0 * math.pi), c_total / wheels, k_total / wheels,
                           decrements)


class FreeDecay(NamedTuple):
    """Result of :func:`free_decay`."""

    #: damping ratio [-]
    ratio: float
    #: undamped natural frequency [Hz]
    frequency: float


def free_decay(time, signal, frequency_guess=3.0) -> FreeDecay:
    """Damping ratio and natural frequency of a free decay, by a least-squares
    fit of one damped oscillation about an offset::

        x(t) = A exp(-xi omega t) cos(omega sqrt(1 - xi^2) t + phi) + x0

    Unlike the decrement of two peaks (:func:`drop_test_damping`) it uses
    every sample, so a small oscillation on a rolling rig (after a cleat)
    is measured through the ripple of the road and the tread.

    Parameters
    ----------
    time, signal : array_like
        The record [s] and the decaying quantity (any unit), from the start
        of the free decay on.
    frequency_guess : float
        Starting value of the frequency [Hz].
    """
    from scipy.optimize import curve_fit

    t = np.asarray(time, float)
    x = np.asarray(signal, float)
    if t.shape != x.shape or t.size < 20 or not (np.all(np.isfinite(t)) and np.all(np.isfinite(x))):
        raise InputError("a free decay needs at least 20 finite samples of time and signal",
                         field="free decay")
    t = t - t[0]

    def model(t, a, xi, f, phi, x0):
        w = 2.0 * math.pi * f
        return a * np.exp(-xi * w * t) * np.cos(w * math.sqrt(max(1.0 - xi * xi, 0.0)) * t + phi) + x0

    start = [0.5 * float(np.ptp(x)), 0.03, float(frequency_guess), 0.0, float(x.mean())]
    (a, xi, f, phi, x0), _ = curve_fit(model, t, x, p0=start, maxfev=20000)
    return FreeDecay(float(xi), float(abs(f)))


def trailer_drop_damping(trailer, duration=3.0, cycles=3) -> DropTestDamping:
    """The drop test of thesis 3.4.1 on ``trailer`` (:meth:`~tyrelab.rig.trailer.Trailer.drop`),
    evaluated with :func:`drop_test_damping` (both wheels, lever hitch-to-axle)."""
    signal = trailer.drop(duration=duration, progress=False)
    return drop_test_damping(signal["RUNTIME"].to_numpy(), signal["Z_WC"].to_numpy(),
                             float(trailer.setup.inertia[1, 1]),
                             float(trailer.geometry.hitch_to_axle), 2, cycles)


def ring_drop_test_damping(tyre, rp, load_case="LC1") -> DropTestDamping:
    """The simulated drop test of the trailer on ring parameters ``rp`` (both wheels)."""
    from ..rig.trailer import Trailer
    from ..tyre.model import TyreModel
    model = TyreModel(tyre, "ring", options={"parameters": rp})
    return trailer_drop_damping(Trailer(model, load_case))


def lowpass(time, signal, cutoff):
    """``signal`` through a zero-phase 4th-order Butterworth low-pass at ``cutoff`` [Hz]
    (``scipy.signal.filtfilt``): measurement noise off a drop-test trace before its extremes are
    read; at 10 Hz it changes a 2-3 Hz decay by less than 1e-4. ``cutoff`` 0: unchanged."""
    from scipy.signal import butter, filtfilt

    x = np.asarray(signal, float)
    if not cutoff:
        return x
    t = np.asarray(time, float)
    rate = 1.0 / float(np.median(np.diff(t)))
    if not cutoff < 0.5 * rate:
        raise InputError(f"the low-pass cut-off {cutoff:g} Hz is not below half the sampling rate "
                         f"({0.5 * rate:g} Hz)", field="lowpass")
    b, a = butter(4, cutoff / (0.5 * rate))
    if x.size <= 3 * max(len(a), len(b)):
        raise InputError("the trace is too short to filter", field="lowpass")
    return filtfilt(b, a, x)


#: the release is fitted to the fall's first part: down to this share of the whole drop, before
#: the tyre's force bends the fall much (a quarter gave 2-3 ms early)
RELEASE_SHARE = 0.15
#: and to the samples up to this long [s] before that, held at rest or falling
RELEASE_WINDOW = 0.3


def drop_release(time, displacement) -> float:
    """The instant [s] a drop-test trace's rim is let go: where it leaves its rest level.

    A logger runs before the release, so a trace may begin with the trailer
    held at rest. From rest the rim falls as ``z = z_rest - a (t - t_r)^2 / 2``
    (it starts with no speed; the tyre's force is still small), and before
    ``t_r`` it stays at ``z_rest``. For each candidate ``t_r`` (from 50 ms
    before the window on) this is linear in ``z_rest`` and ``a``, solved by
    least squares; the candidate with the smallest residual, to a quarter of
    a sample (:func:`~tyrelab.fit.search.refine_minimum`), is the release.
    The window is the samples from :data:`RELEASE_WINDOW` before the rim has
    fallen :data:`RELEASE_SHARE` of the whole drop up to that point (read on
    a 21-sample running median, so noise does not set it).

    On the trailer's simulated drop with 0.1 (0.5) mm of noise the estimate
    is within 2.6 (6) ms; :func:`fit_drop_trace` fits the release exactly.
    """
    from scipy.ndimage import median_filter

    t = np.asarray(time, float)
    z = np.asarray(displacement, float)
    if t.shape != z.shape or t.ndim != 1 or t.size < 50:
        raise InputError("a drop-test trace needs at least 50 samples of time and displacement",
                         field="drop test")
    smooth = median_filter(z, size=21, mode="nearest")
    deepest = int(np.argmin(smooth))
    top = float(np.max(smooth[:deepest + 1]))
    drop = top - float(smooth[deepest])
    if not drop > 0:
        raise InputError("the trace never falls below where it starts: no drop to find (is the "
                         "rim height up positive? a trace logged down positive is read with "
                         "positive = \"down\" in its [[test]])", field="drop test")
    q = int(np.flatnonzero(smooth[:deepest + 1] < top - RELEASE_SHARE * drop)[0])
    dt = float(np.median(np.diff(t)))
    lo = int(np.searchsorted(t, t[q] - RELEASE_WINDOW))
    tw, zw = t[lo:q + 1], z[lo:q + 1]

    def sse(candidates):   # z_rest, then the fall a (t - t_r)^2 / 2 from the release on
        h = 0.5 * np.clip(tw[None, :] - candidates[:, None], 0.0, None) ** 2
        return term_sse(np.stack([np.ones_like(h), h], axis=2), zw)

    return refine_minimum(sse, tw[0] - 0.05, tw[-1], 0.25 * dt)


class RigDropFit(NamedTuple):
    """Result of :func:`fit_drop_trace` (SI)."""

    #: damping coefficient of one tyre [N s/m]
    damping: float
    #: factor on the tyre's load-deflection law that fits the trace best (1: the law as given)
    stiffness_scale: float
    #: RMS of measured minus simulated rim displacement [m]
    rms: float
    #: the trace's time from the release [s] (negative while held), measured (its zero moved to
    #: fit best) and simulated rim displacement from the release [m]
    time: np.ndarray
    measured: np.ndarray
    simulated: np.ndarray
    #: simulated drop tests run
    evaluations: int
    #: the release on the trace's own clock [s] (fitted with the damper)
    release: float = 0.0


def _scaled(tyre, damping, scale):
    import dataclasses
    table = tyre.load_deflection
    if table is not None:
        table = table * np.array([1.0, scale])
    return dataclasses.replace(tyre, vertical_damping=float(damping),
                               vertical_stiffness=tyre.vertical_stiffness * scale, load_deflection=table)


def simulated_drop(tyre, time, load_case="LC1", geometry=None, contact="point"):
    """Rim displacement [m] from the release of the trailer's drop test
    (:meth:`~tyrelab.rig.trailer.Trailer.drop`) at the times ``time`` [s] of a trace."""
    from ..rig.trailer import Trailer
    from ..tyre.model import TyreModel
    t = np.asarray(time, float)
    signal = Trailer(TyreModel(tyre, contact), load_case, geometry).drop(
        duration=float(t[-1]) + 2e-3, progress=False)
    z = signal["Z_WC"].to_numpy()
    return np.interp(t, signal["RUNTIME"].to_numpy(), z - z[0])  # held at rest before t = 0


#: the drop-trace fit's unknowns, in the optimiser's vector (those chosen): the damping as a
#: multiple of its start, the release's shift [s] from :func:`drop_release`'s estimate, the
#: factor on the load-deflection law; with their bounds and scales
DROP_FIT_UNKNOWNS = ("damping", "release", "scale")
#: how far [s] the fit may move the release from its estimate; samples this far before it are kept
RELEASE_SHIFT = 0.02
_DROP_FIT_BOUNDS = {"damping": (1e-3, 100.0), "release": (-RELEASE_SHIFT, RELEASE_SHIFT),
                    "scale": (0.2, 5.0)}
_DROP_FIT_SCALES = {"damping": 1.0, "release": 1e-3, "scale": 1.0}


def fit_drop_trace(time, displacement, tyre, load_case="LC1", geometry=None, fit_stiffness=True,
                   start=None, fit_damping=True) -> RigDropFit:
    """Tyre damping by fitting the rig's own simulated drop test to a measured trace (thesis 3.4.1).

    The trailer of :mod:`tyrelab.rig.trailer` (``geometry``, loaded to
    ``load_case``) stands on both wheels, each the point model with ``tyre``'s
    vertical law (eq. 2.2) and damper c; it is dropped as in the test and c
    (with ``fit_stiffness`` also a factor s on the load-deflection law) is
    chosen by least squares on the displacement from the release::

        min over (c, s, t_r, z0) of sum_i (z_sim(t_i - t_r; c, s) - z_meas(t_i) - z0)^2

    (the offset z0 of the trace's zero, solved in closed form: the mean
    residual; ``z_sim`` is zero before the release). The release ``t_r``
    starts from :func:`drop_release` and moves by at most
    :data:`RELEASE_SHIFT`; samples held at rest before that are left out.

    No pendulum, small-angle or linear-spring assumption is made: the hitch
    moves the axle on an arc, the spring is the tyre's own curve, the damper
    ramps in at touch-down -- so comparing c with :func:`drop_test_damping`'s
    tells how good the pendulum assumption of eqs. 3.1-3.7 is.

    Parameters
    ----------
    time, displacement : array_like
        The trace: time [s] and rim (axle) height [m], up positive (only its
        changes are used), from the release on or from any time before it
        while the trailer was held.
    tyre : Tyre
        Radius, vertical law and masses; its damping is the starting value.
    load_case : str or float
        Trailer load case (Table 3-4) or wheel load [N].
    start : float, optional
        Starting damping [N s/m] (default the tyre's, else 1 kN s/m).
    fit_damping : bool
        False keeps the tyre's damper (and, without ``fit_stiffness``, its
        law): only the release is fitted, as for a held-out trace.
    """
    from scipy.optimize import least_squares

    t = np.asarray(time, float)
    z = np.asarray(displacement, float)
    if t.size < 50 or t.shape != z.shape:
        raise InputError("a drop-test trace needs at least 50 samples of time and displacement",
                         field="drop test")
    release0 = drop_release(t, z)
    keep = t >= release0 - RELEASE_SHIFT
    t, z = t[keep] - release0, z[keep] - z[keep][0]
    c0 = float(start or tyre.vertical_damping or 1000.0)
    chosen = [n for n in DROP_FIT_UNKNOWNS
              if {"damping": fit_damping, "release": True, "scale": fit_stiffness}[n]]
    calls = 0

    def unknowns(p):
        v = {"damping": 1.0, "release": 0.0, "scale": 1.0}
        v.update(zip(chosen, p))
        return v

    def residual(p):
        nonlocal calls
        calls += 1
        v = unknowns(p)
        r = simulated_drop(_scaled(tyre, v["damping"] * c0, v["scale"]), t - v["release"], load_case,
                           geometry) - z
        return r - r.mean()

    sol = least_squares(residual, [0.0 if n == "release" else 1.0 for n in chosen],
                        bounds=([_DROP_FIT_BOUNDS[n][0] for n in chosen],
                                [_DROP_FIT_BOUNDS[n][1] for n in chosen]),
                        x_scale=[_DROP_FIT_SCALES[n] for n in chosen], diff_step=1e-4)
    v = unknowns(sol.x)
    scale, damping, shift = float(v["scale"]), float(v["damping"] * c0), float(v["release"])
    t = t - shift
    sim = simulated_drop(_scaled(tyre, damping, scale), t, load_case, geometry)
    z = z + float(np.mean(sim - z))
    return RigDropFit(damping, scale, float(np.sqrt(np.mean((sim - z) ** 2))), t, z, sim, calls + 1,
                      release0 + shift)
