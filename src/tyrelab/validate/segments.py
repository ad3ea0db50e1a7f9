"""Split an obstacle run into the disturbance and the response (thesis 5.2).

The thesis divides a cleat run into the *disturbance* (the tyre in contact
with the obstacle; m%RE, 80%RE and RMS error are computed there) and the
*response* (the free oscillation after it; only its peaks are compared).

From geometry
-------------
A tyre of free radius ``R`` whose centre runs at height ``h_c`` above the
road (the loaded radius) first touches an obstacle edge of height ``h`` when
the horizontal distance from the wheel centre to the edge is
``d = sqrt(R^2 - (h_c - h)^2)`` (the free circle through the edge; zero if
the circle does not reach it), and leaves the trailing edge at the same
distance behind it. The disturbance is the time the wheel centre spends in
``[x_start - d, x_end + d]``; the response runs from its end to the end of
the record (or for ``response_seconds``). Positions come from the
``X_WC`` or ``DISTANCE`` channel, or from a constant speed.

From the signal alone
---------------------
When the geometry is unknown: the pre-impact baseline and noise are the
median and scaled median absolute deviation (1.4826 MAD) of the first
``lead_fraction`` of the record; the event threshold is the larger of
``k_noise`` noise levels and ``event_fraction`` of the largest deviation.
The disturbance is the first excursion: it starts at the last sample before
the first threshold crossing that lies within two noise levels of the
baseline, and ends where the signal, after its first threshold crossing, first
returns through the baseline. This follows the main contact pulse of a
cleat (rise while the tyre climbs on it, return when it rolls off); the
oscillation after that is the response.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError


@dataclass(frozen=True)
class Segments:
    """Disturbance and response as time intervals [start, end] in seconds."""

    disturbance: tuple[float, float]
    response: tuple[float, float]
    method: str = "geometry"

    def mask(self, t, which: str) -> np.ndarray:
        """Boolean mask of the samples of ``t`` inside ``which`` segment."""
        lo, hi = getattr(self, which)
        t = np.asarray(t, dtype=float)
        return (t >= lo) & (t <= hi)


def contact_reach(free_radius: float, centre_height: float, obstacle_height: float) -> float:
    """Horizontal reach ``d = sqrt(R^2 - (h_c - h)^2)`` of the free tyre circle."""
    if not (free_radius > 0 and centre_height > 0 and obstacle_height >= 0):
        raise InputError("radius and centre height must be positive, obstacle height >= 0",
                         field="free_radius")
    gap = centre_height - obstacle_height
    return float(np.sqrt(max(free_radius ** 2 - gap ** 2, 0.0))) if gap > 0 else float(free_radius)


def segments_from_geometry(t, x, obstacle_start: float, obstacle_end: float,
                           obstacle_height: float, free_radius: float,
                           centre_height: float, response_seconds: float | None = None
                           ) -> Segments:
    """Disturbance from the wheel-centre positions and the obstacle geometry.

    Parameters
    ----------
    t, x : array_like
        Time [s] and wheel-centre position along the road [m] (increasing).
    obstacle_start, obstacle_end : float
        Road positions of the obstacle's leading and trailing edge [m].
    obstacle_height : float
        Obstacle height [m].
    free_radius, centre_height : float
        Unloaded tyre radius and wheel-centre height on flat road [m].
    response_seconds : float, optional
        Length of the response; default to the end of the record.
    """
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    if t.shape != x.shape or t.size < 2 or np.any(np.diff(x) <= 0):
        raise InputError("wheel-centre position must increase with time", field="X_WC")
    if obstacle_end < obstacle_start:
        raise InputError("obstacle end lies before its start", field="obstacle_end")
    d = contact_reach(free_radius, centre_height, obstacle_height)
    x0, x1 = obstacle_start - d, obstacle_end + d
    if x1 < x[0] or x0 > x[-1]:
        raise InputError("the run never reaches the obstacle", field="obstacle_start")
    t0 = float(np.interp(x0, x, t))
    t1 = float(np.interp(x1, x, t))
    end = t[-1] if response_seconds is None else min(t[-1], t1 + response_seconds)
    return Segments((t0, t1), (t1, float(end)), "geometry")


def segments_from_speed(t, speed: float, x0: float, obstacle_start: float,
                        obstacle_end: float, obstacle_height: float, free_radius: float,
                        centre_height: float, response_seconds: float | None = None
                        ) -> Segments:
    """As :func:`segments_from_geometry` with ``x = x0 + speed * (t - t[0])``."""
    if not speed > 0:
        raise InputError("speed must be positive", field="speed")
    t = np.asarray(t, dtype=float)
    x = x0 + speed * (t - t[0])
    return segments_from_geometry(t, x, obstacle_start, obstacle_end, obstacle_height,
                                  free_radius, centre_height, response_seconds)


def _baseline(y, lead_fraction):
    n = max(3, int(round(lead_fraction * y.size)))
    lead = y[:n]
    base = float(np.median(lead))
    noise = 1.4826 * float(np.median(np.abs(lead - base)))
    return base, noise


def segments_from_signal(t, y, lead_fraction: float = 0.1, k_noise: float = 5.0,
                         event_fraction: float = 0.05,
                         response_seconds: float | None = None) -> Segments:
    """Disturbance and response from the force signal alone (see module notes)."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.shape != y.shape or t.size < 10 or not np.all(np.isfinite(y)):
        raise InputError("segmentation needs ten or more finite samples", field="signal")
    base, noise = _baseline(y, lead_fraction)
    dev = y - base
    threshold = max(k_noise * noise, event_fraction * float(np.max(np.abs(dev))))
    if not threshold > 0:
        raise InputError("the signal is constant: no disturbance to find", field="signal")
    hits = np.flatnonzero(np.abs(dev) > threshold)
    if hits.size == 0:
        raise InputError("no disturbance above the noise", field="signal")
    first = int(hits[0])
    quiet = np.flatnonzero(np.abs(dev[:first]) <= 2.0 * noise)  # within 2 noise levels
    start = int(quiet[-1]) if quiet.size else 0
    sign = np.sign(dev[first])
    back = np.flatnonzero(sign * dev[first:] <= 0.0)
    if back.size == 0:
        raise InputError("the signal never returns to its baseline after the disturbance",
                         field="signal")
    end = first + int(back[0])
    t_end = _crossing_time(t, dev, end)
    r_end = t[-1] if response_seconds is None else min(t[-1], t_end + response_seconds)
    return Segments((float(t[start]), t_end), (t_end, float(r_end)), "signal")


def _crossing_time(t, dev, i) -> float:
    """Time where ``dev`` crosses zero between samples i-1 and i (linear)."""
    a, b = dev[i - 1], dev[i]
    if a == b:
        return float(t[i])
    return float(t[i - 1] + (t[i] - t[i - 1]) * a / (a - b))
