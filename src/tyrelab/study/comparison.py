"""One run against its reference: the compared channel, the disturbance and response
segments of a condition, and the row of metrics (:func:`compare_to_reference`).

Channel: ``FZ_HUB``. The thesis compares what the trailer's six load cells
measured (5.1: "the measured and simulated load cell measurements will
thus be compared"; the sub-frame's acceleration could not be measured, so
the wheel's inertia could not be removed). ``FZ_HUB`` is that reading (the
tyre's vertical force less the wheel mass times its acceleration, tared
with the wheel hanging free); ``FZ`` is the tyre's own force at the wheel
centre and ``FZW`` the normal force in the contact point, which no load
cell sees. When either signal lacks ``FZ_HUB`` (a measured file mapped to
TYDEX ``FZ``, another rig) ``FZ`` is compared; the ``channel`` column says.

The disturbance (thesis 5.2: "the first section, where the tyre is in
contact with the obstacle") is taken from the *reference's own contact*
and used for every model of the condition:

1. reference with contact-point channels (every simulation) over a raised
   obstacle (cleat, bump): from the first to the last sample whose contact
   point ``Z_CP`` lies more than 1 % of the obstacle's height above the road
   (:func:`~tyrelab.validate.segments.segments_from_contact`; the flexible
   ring's contact point is force-weighted, so: the obstacle carries more
   than 1 % of the load);
2. otherwise, with ``X_WC`` in the road frame: the free circle about the
   reference's own wheel-centre path (``Z_WC``, else the static height)
   reaching the obstacle's profile, its highest point across the tyre's
   width (:func:`~tyrelab.validate.segments.segments_from_contour`; steps and
   potholes: their edges);
3. otherwise (a measured file without positions, a road of unknown
   geometry): the first excursion of the reference's force
   (:func:`~tyrelab.validate.segments.segments_from_signal`).

Why: :func:`~tyrelab.validate.segments.segments_from_geometry` cuts the free
circle at the *static* centre height. The wheel is thrown up by the cleat,
so the tyre leaves it well before that circle does, and the cut runs into
the unloading trough, where the reference's force is small and every
relative error large. Measured on the 50 mm cleat, 12 km/h, LC1 (6 s, FTire
TP = ring-tp as reference, channel FZ_HUB): the ring touches the cleat from
0.327 m before its leading edge to 0.253 m after its trailing edge (t =
1.402-1.591 s; the centre is then 33 mm above its static height); the
static free circle reaches 0.337 m on both sides (1.399-1.616 s): 25 ms
more at the end, 13 % of the window, all of it in the unloading trough
(the reference's FZ_HUB there is 6.7-8.1 kN, static 23.3 kN). The contact
fraction barely matters (0 % to 2 %: 1 ms). m%RE / 80%RE of the
disturbance, old -> this definition:

=========== ============= =============
variant     m%RE [%]      80%RE [%]
=========== ============= =============
OPC lk      36.7 -> 33.9  60.6 -> 56.5
OPC nlk     41.9 -> 39.9  63.6 -> 62.9
3D VC lk    35.9 -> 24.9  81.1 -> 17.0
3D VC nlk   39.3 -> 27.4  90.9 -> 18.6
3D ENV lk   25.8 -> 21.4  58.7 -> 22.6
3D ENV nlk  29.5 -> 25.5  58.7 -> 32.0
=========== ============= =============

The volume model goes from last on 80%RE (and within 1-3 points of the
point model on m%RE) to first on 80%RE and a clear second on m%RE (the
ranking of the three contact models on m%RE stays ENV, VC, OPC; on 80%RE it
turns from ENV, OPC, VC to VC, ENV, OPC); Spearman's ρ between
these six variants' ranking and the thesis's Table 5-2 (which ranks the
volume model first) rises from 0.38 to 0.83 over the five cleat metrics
(m%RE 0.26 -> 0.66, 80%RE -0.43 -> 1.0, RMS 0.71 -> 0.94; response m%RE
0.77 both, response RMS 0.60 -> 0.77, the response now starting where the
contact ends). With ``FZ`` instead of ``FZ_HUB`` and the old cut the volume
model ranks last on m%RE too (59.3 % against the point model's 54.2 %).
The circle about the reference's own centre path (rule 2) gives nearly the
contact window (1.399-1.597 s) and ρ = 0.78. With an analytic model as
reference, rule 1 reads that model's own contact point (for the enveloping
model the cams' effective contact), so the window is its contact.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..errors import InputError
from ..validate.align import align
from ..validate.compare import (METRICS, THESIS_CLEAT, THESIS_TRACK, compare_aligned,
                                response_signals)
from ..validate.distributions import fit_normal
from ..validate.metrics import (FLOOR_FRACTION, RESPONSE_BAND_HZ, match_peaks,
                                relative_error_floor)
from ..validate.segments import (Segments, segments_from_contact, segments_from_contour,
                                 segments_from_signal)

#: the compared channel (the load cells' reading), and the one used when a signal lacks it
CHANNEL, FALLBACK_CHANNEL = "FZ_HUB", "FZ"
#: share of the obstacle's height the contact point must rise for contact (rule 1)
CONTACT_FRACTION = 0.01
OTHER_METRICS = [m for m in METRICS if m not in THESIS_CLEAT and m not in THESIS_TRACK]


@dataclass(frozen=True)
class Obstacle:
    """An obstacle's place on the road: ``kind`` "raised" (cleat, bump: the road returns
    to its base level) or "edge" (step, pothole); its profile (x, height) as seen across
    the tyre's width; ``height`` above the base (negative: a hole) [m]."""

    kind: str
    start: float
    end: float
    height: float
    profile_x: tuple
    profile_z: tuple


def obstacle_of(road: str, half_width: float = 0.0) -> Obstacle | None:
    """The obstacle of a road name, or None (flat road, tracks, random and CRG roads)."""
    from ..road import obstacles as ob
    from ..road.spec import road_from_spec
    try:
        r = road_from_spec(road)
    except InputError:
        return None
    if isinstance(r, ob.Cleat):
        a = np.radians(r.angle)
        reach = half_width * abs(np.tan(a))  # an oblique cleat meets one shoulder first
        lo, hi = r.start - reach, r.start + r.width / np.cos(a) + reach
        h = r.cleat_height
        return Obstacle("raised", lo, hi, h, (lo, lo, hi, hi), (0.0, h, h, 0.0))
    if isinstance(r, ob.TrapezoidalBump):
        xs = tuple(r.start + e for e in r._edges())
        h = r.bump_height
        return Obstacle("raised", xs[0], xs[-1], h, xs, (0.0, h, h, 0.0))
    if isinstance(r, ob.Step):
        return Obstacle("edge", r.start, r.start, r.step_height, (r.start,),
                        (max(r.step_height, 0.0),))
    if isinstance(r, ob.Pothole):
        end = r.start + r.length
        return Obstacle("edge", r.start, end, -r.depth, (r.start, end), (0.0, 0.0))
    return None


def _finite(df: pd.DataFrame, col: str) -> bool:
    return col in df.columns and bool(np.all(np.isfinite(df[col].to_numpy(dtype=float))))


def disturbance_segments(ref: pd.DataFrame, obstacle: Obstacle | None, radius: float,
                         centre_height: float, channel: str = CHANNEL) -> Segments:
    """Disturbance and response of a condition from its reference signal (module notes)."""
    t = ref["RUNTIME"].to_numpy(dtype=float)
    if obstacle is not None:
        if obstacle.kind == "raised" and _finite(ref, "Z_CP") and _finite(ref, "X_CP"):
            try:
                return segments_from_contact(
                    t, ref["Z_CP"].to_numpy(dtype=float), obstacle.height, 0.0,
                    CONTACT_FRACTION, ref["X_CP"].to_numpy(dtype=float),
                    (obstacle.start - radius, obstacle.end + radius))
            except InputError:
                pass  # the contact point never rose (e.g. it stayed on a rim): the contour
        if _finite(ref, "X_WC"):
            z = (ref["Z_WC"].to_numpy(dtype=float) if _finite(ref, "Z_WC")
                 else np.full(t.size, centre_height))
            return segments_from_contour(t, ref["X_WC"].to_numpy(dtype=float), z,
                                         obstacle.profile_x, obstacle.profile_z, radius)
    return segments_from_signal(t, ref[channel].to_numpy(dtype=float))


def near_zero_counts(aligned, seg: Segments | None, floor_fraction: float = FLOOR_FRACTION,
                     peak_kind: str = "both",
                     response_band_hz: float | None = RESPONSE_BAND_HZ) -> tuple[int, int]:
    """(denominators the near-zero floor replaced, denominators) of a comparison.

    The same cuts and floors as :func:`~tyrelab.validate.compare.compare_aligned`:
    with segments, the disturbance samples (floor from the disturbance) and the
    matched peaks of the response's oscillation (floor from it,
    :func:`~tyrelab.validate.compare.response_signals`); without, the measured
    mean and standard deviation of eq. 5.4 (floor from the whole record).
    """
    t, m = aligned.t, aligned.m
    if seg is None:
        floor = relative_error_floor(m, floor_fraction)
        mu, sigma = fit_normal(m)
        return int(abs(mu) < floor) + int(abs(sigma) < floor), 2
    md = m[seg.mask(t, "disturbance")]
    n = int(np.sum(np.abs(md) < relative_error_floor(md, floor_fraction)))
    pr, mr = response_signals(aligned, seg, response_band_hz)
    _, mv, _, _ = match_peaks(pr, mr, peak_kind)
    n += int(np.sum(np.abs(mv) < relative_error_floor(mr, floor_fraction)))
    return n, int(md.size + mv.size)


def compare_to_reference(sim: pd.DataFrame, ref: pd.DataFrame, seg: Segments | None,
                         shift: float | str = 0.0) -> dict:
    """Every metric of ``sim`` against ``ref`` (``seg`` None: a track) as row columns."""
    channel = CHANNEL if CHANNEL in sim.columns and CHANNEL in ref.columns else FALLBACK_CHANNEL
    aligned = align(sim, ref, channel, shift)
    res = compare_aligned(aligned, seg)
    used = [*(THESIS_CLEAT if seg is not None else THESIS_TRACK), *OTHER_METRICS]
    row = {m: float(res[m]) for m in used if m in res}
    near, compared = near_zero_counts(aligned, seg)
    row.update(channel=channel, near_zero_samples=near, compared_samples=compared,
               shift_s=aligned.shift, n_response_peaks=res["details"].get("n_response_peaks"))
    return row
