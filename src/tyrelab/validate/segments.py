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

From the reference's own contact with the obstacle
--------------------------------------------------
Thesis 5.2 defines the disturbance as the time "the tyre is in contact with
the obstacle". A run that records its contact point (``X_CP``, ``Z_CP``: the
normal-force-weighted mean of the touching points for the flexible ring)
says directly when the obstacle carries part of the load: its contact point
is raised above the road's base level. :func:`segments_from_contact` takes
the first to the last sample whose contact point lies more than
``fraction`` of the obstacle's height above the base (with a force-weighted
contact point: the obstacle carries more than that fraction of the load).
Without contact channels, :func:`segments_from_contour` uses the run's own
wheel-centre path ``(x(t), z(t))`` -- the wheel rises over the obstacle and
bounces off it, which the static centre height of
:func:`segments_from_geometry` ignores -- and the tyre's contour about it: the
tyre touches the obstacle while the distance from the centre to the
obstacle's profile is below the contour radius.
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


def _span(t, on, method: str, response_seconds: float | None, what: str) -> Segments:
    """Disturbance from the first to the last sample flagged ``on``; response to the end."""
    idx = np.flatnonzero(on)
    if idx.size < 2:
        raise InputError(f"the run is in contact with the obstacle in fewer than two samples "
                         f"({what})", field="obstacle")
    t0, t1 = float(t[idx[0]]), float(t[idx[-1]])
    end = t[-1] if response_seconds is None else min(t[-1], t1 + response_seconds)
    return Segments((t0, t1), (t1, float(end)), method)


def segments_from_contact(t, z_cp, obstacle_height: float, base: float = 0.0,
                          fraction: float = 0.01, x_cp=None, x_range=None,
                          response_seconds: float | None = None) -> Segments:
    """Disturbance: the samples whose contact point lies on the obstacle (module notes).

    Parameters
    ----------
    t, z_cp : array_like
        Time [s] and contact-point height (``Z_CP``) [m] of the run.
    obstacle_height : float
        Height of the obstacle above ``base`` [m] (negative: a hole).
    base : float
        Height of the road away from the obstacle [m].
    fraction : float
        A sample is in contact when ``(z_cp - base) / obstacle_height > fraction``.
    x_cp, x_range : array_like and (float, float), optional
        Contact-point x (``X_CP``) and the road interval the obstacle's
        contact can lie in; samples outside it are ignored.
    response_seconds : float, optional
        Length of the response; default to the end of the record.
    """
    t = np.asarray(t, dtype=float)
    z = np.asarray(z_cp, dtype=float)
    if t.shape != z.shape or t.size < 2 or not np.all(np.isfinite(z)):
        raise InputError("contact-point heights must be finite, one per sample", field="Z_CP")
    if not (np.isfinite(obstacle_height) and obstacle_height != 0.0 and 0.0 < fraction < 1.0):
        raise InputError("obstacle height must be non-zero and 0 < fraction < 1",
                         field="obstacle_height")
    on = (z - base) / obstacle_height > fraction
    if x_cp is not None and x_range is not None:
        x = np.asarray(x_cp, dtype=float)
        x_lo, x_hi = x_range
        on &= (x >= x_lo) & (x <= x_hi)
    return _span(t, on, "contact", response_seconds, "contact point")


def segments_from_contour(t, x, z, profile_x, profile_z, radius: float,
                          response_seconds: float | None = None) -> Segments:
    """Disturbance: the samples where the tyre contour about the run's own wheel centre
    reaches the obstacle (module notes).

    Parameters
    ----------
    t, x, z : array_like
        Time [s] and wheel-centre position along the road and height [m].
    profile_x, profile_z : array_like
        The obstacle's profile: points (x, height) [m] (e.g. the highest
        road point across the tyre's width at each x); a polyline.
    radius : float
        Contour radius [m] (the free radius: the undeformed part of the tyre).
    """
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    z = np.asarray(z, dtype=float)
    px = np.asarray(profile_x, dtype=float)
    pz = np.asarray(profile_z, dtype=float)
    if not (t.shape == x.shape == z.shape) or t.size < 2:
        raise InputError("time, x and z of the wheel centre need one value per sample",
                         field="X_WC")
    if px.shape != pz.shape or px.size < 1 or not radius > 0:
        raise InputError("the obstacle profile needs points and the radius must be positive",
                         field="profile")
    if px.size == 1:
        d2 = (x - px[0]) ** 2 + (z - pz[0]) ** 2
    else:  # distance to each segment of the polyline
        ax, az, bx, bz = px[:-1], pz[:-1], px[1:], pz[1:]
        ex, ez = bx - ax, bz - az
        ll = np.maximum(ex * ex + ez * ez, 1e-30)
        d2 = np.full(t.size, np.inf)
        for i in range(0, t.size, 4096):  # chunks keep the (samples x segments) arrays small
            cx, cz = x[i:i + 4096, None], z[i:i + 4096, None]
            s = np.clip(((cx - ax) * ex + (cz - az) * ez) / ll, 0.0, 1.0)
            d2[i:i + 4096] = np.min((ax + s * ex - cx) ** 2 + (az + s * ez - cz) ** 2, axis=1)
    return _span(t, d2 < radius * radius, "contour", response_seconds, "tyre contour")
