"""``tyrelab validate SIM MEAS``: compare a simulated run with a measurement.

Prints the metrics table (Markdown) and writes an HTML page with the
overlay, the relative error over time and the force distributions.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from ..errors import InputError
from ..limits import MAX_SPEED
from ._common import bounded_float


def _segments(text: str):
    """'auto', 'none', 'geometry' or 'T0:T1[:T2]' (disturbance T0..T1, response T1..T2)."""
    from ..validate.segments import Segments
    if text == "geometry":
        return "geometry"
    if text in ("auto", "none"):
        return None if text == "none" else "auto"
    try:
        times = [float(x) for x in text.split(":")]
    except ValueError:
        raise InputError(f"expected 'auto', 'none' or T0:T1[:T2], got '{text}'",
                         source="command line", field="--segments") from None
    if not all(math.isfinite(t) for t in times):
        raise InputError(f"segment times must be finite seconds, got '{text}'",
                         source="command line", field="--segments")
    if len(times) not in (2, 3) or any(b <= a for a, b in zip(times, times[1:])):
        raise InputError("segment times must be increasing: T0:T1[:T2]",
                         source="command line", field="--segments")
    end = times[2] if len(times) == 3 else float("inf")
    return Segments((times[0], times[1]), (times[1], end), "command line")


def _numbers(text: str, n: int, option: str) -> list[float]:
    try:
        values = [float(x) for x in text.split(":")]
    except (ValueError, AttributeError):
        values = []
    if len(values) != n or not all(math.isfinite(v) for v in values):
        raise InputError(f"expected {n} finite numbers separated by ':', got '{text}'",
                         source="command line", field=option)
    return values


def _geometry_segments(args, meas):
    """Segments from --obstacle, --tyre and the measured positions or --speed."""
    import numpy as np

    from ..validate.segments import segments_from_geometry, segments_from_speed
    if args.obstacle is None or args.tyre is None:
        raise InputError("--segments geometry needs --obstacle and --tyre",
                         source="command line", field="--segments")
    x0, x1, h = _numbers(args.obstacle, 3, "--obstacle")
    radius, centre = _numbers(args.tyre, 2, "--tyre")
    t = meas["RUNTIME"].to_numpy(dtype=float)
    if args.speed is not None:
        return segments_from_speed(t, args.speed, args.x0, x0, x1, h, radius, centre)
    for col in ("X_WC", "DISTANCE"):
        if col in meas.columns and np.all(np.isfinite(meas[col])):
            return segments_from_geometry(t, meas[col].to_numpy(dtype=float), x0, x1, h,
                                          radius, centre)
    raise InputError("the measurement has no X_WC or DISTANCE channel; give --speed",
                     source="command line", field="--speed")


def _shift(text: str):
    if text == "auto":
        return "auto"
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"expected seconds or 'auto', got '{text}'", source="command line",
                         field="--shift") from None
    if not math.isfinite(value):
        raise InputError(f"expected finite seconds or 'auto', got '{text}'", source="command line",
                         field="--shift")
    return value


def _compare(aligned, segments, args, compared: str) -> dict:
    """:func:`~tyrelab.validate.compare.compare_aligned` of the files ``compared`` (their
    names); where the automatic segmentation finds no disturbance in the measurement, the
    error names the file and the options that avoid it."""
    from ..validate.compare import compare_aligned
    try:
        return compare_aligned(aligned, segments, slope=args.slope)
    except InputError as exc:
        if segments == "auto" and exc.field == "signal":
            raise InputError(f"--segments auto: {exc.reason}; give --segments none (no split) or "
                             "T0:T1[:T2] seconds", source=args.meas, field=args.channel) from None
        if exc.source is None:  # a metric of the pair: name both files
            raise InputError(exc.reason, source=compared, field=exc.field or args.channel) from None
        raise


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "validate", help="compare a simulated run with a measurement (thesis chapter 5)",
        description="Compare SIM with MEAS on MEAS's time base (SIM interpolated, "
                    "optionally shifted) and report the thesis metrics and more.")
    p.add_argument("sim", help="simulated run (.parquet, .csv or .tdx)")
    p.add_argument("meas", help="measured run (.tdx, .csv or .parquet)")
    p.add_argument("--channel", default="FZ", help="compared channel (default FZ)")
    p.add_argument("--segments", default="auto",
                   help="'auto' (from the measured signal), 'geometry' (--obstacle, --tyre), "
                        "'none', or T0:T1[:T2] seconds")
    p.add_argument("--obstacle", default=None, metavar="X0:X1:H",
                   help="obstacle leading and trailing edge and height [m] (--segments geometry)")
    p.add_argument("--tyre", default=None, metavar="R:HC",
                   help="free tyre radius and wheel-centre height on flat road [m]")
    p.add_argument("--speed", type=bounded_float("speed", 0.0, MAX_SPEED, "m/s", low_open=True), default=None,
                   help="constant speed [m/s] when MEAS has no X_WC or DISTANCE channel")
    p.add_argument("--x0", type=bounded_float("x0", -1e4, 1e4, "m"), default=0.0,
                   help="wheel-centre position at MEAS's first sample [m] (with --speed)")
    p.add_argument("--shift", default="0",
                   help="seconds the simulation is delayed by, or 'auto' (cross-correlation; a "
                        "logger's own clock and an early start are found)")
    p.add_argument("--max-shift", type=bounded_float("max-shift", 0.0, 1e4, "s"), default=None,
                   help="limit of the auto shift [s] (default: any that leaves a quarter of the "
                        "shorter record overlapping)")
    p.add_argument("--repeat", default=None,
                   help="a second measurement of the same test: report its scatter beside")
    p.add_argument("--column-map", default=None,
                   help="column map file for a measured .csv (source,channel,unit)")
    p.add_argument("--slope", type=bounded_float("slope", 0.0, 100.0, low_open=True), default=5.0,
                   help="S-N slope for pseudo-damage (0 < slope <= 100)")
    p.add_argument("--html", default=None,
                   help="output page (default: MEAS name + '_validation.html' in the cwd)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..measure.io import read_run
    from ..report.validation_page import page_html, write_page
    from ..validate.align import align
    from ..validate.compare import METRICS, metric_row
    from ..validate.tables import metrics_table, table_html, table_markdown_by_metric

    from ..io_atomic import check_output_path

    out = Path(args.html) if args.html else Path(Path(args.meas).stem + "_validation.html")
    check_output_path(out, (".html", ".htm"), "--html",
                      inputs=[args.sim, args.meas, args.repeat, args.column_map])
    segments = _segments(args.segments)
    shift = _shift(args.shift)
    sim = read_run(args.sim)
    meas = read_run(args.meas, column_map=args.column_map)
    for path, df in ((args.sim, sim), (args.meas, meas)):
        for col in ("RUNTIME", args.channel):
            if col not in df.columns:
                raise InputError("channel not in the run", source=str(path), field=col)
    if segments == "geometry":
        segments = _geometry_segments(args, meas)
    aligned = align(sim, meas, args.channel, shift, args.max_shift)
    result = _compare(aligned, segments, args, f"{args.sim} vs {args.meas}")
    rows = {Path(args.sim).stem: metric_row(result)}
    notes = [f"channel {args.channel}; simulation shifted by {aligned.shift:.4g} s; "
             f"{aligned.t.size} compared samples, {aligned.dropped} dropped (NaN)"]
    seg = result["details"]["segments"]
    if seg is not None:
        notes.append(f"disturbance {seg.disturbance[0]:.4g}-{seg.disturbance[1]:.4g} s, "
                     f"response {seg.response[0]:.4g}-{min(seg.response[1], aligned.t[-1]):.4g} s"
                     f" ({seg.method})")
    if args.repeat:
        other = read_run(args.repeat, column_map=args.column_map)
        rep = _compare(align(other, meas, args.channel, shift, args.max_shift), segments, args,
                       f"{args.repeat} vs {args.meas}")
        rows["measured repeatability"] = metric_row(rep)
    if "psd_skipped" in result["details"]:
        notes.append(f"no PSD metrics: {result['details']['psd_skipped']}")
    table = metrics_table(rows)
    print(table_markdown_by_metric(table, {k: u for k, (u, _) in METRICS.items()}))
    for note in notes:
        print(note)
    write_page(out, page_html(f"Validation: {Path(args.sim).name} vs {Path(args.meas).name}",
                              table_html(table, best=0), aligned, result, notes))
    print(f"page written: {out}")
    return 0
