"""``tyrelab simulate``: one run of a tyre model on a rig over a road."""

from __future__ import annotations

import sys

from ._common import load_value, output_path, positive_float


def register(sub):
    p = sub.add_parser("simulate", help="run a tyre model over a road on the test trailer",
                       description="Run a tyre model on the towed test trailer (or a quarter "
                                   "vehicle) over a road and write the signal table.")
    p.add_argument("--tyre", default="xzl-16.00R20",
                   help="built-in tyre name or .tir file (default: xzl-16.00R20)")
    p.add_argument("--pressure", type=positive_float("pressure", 1e3), default=None, metavar="KPA",
                   help="inflation pressure in kPa (built-in tyres; default 300)")
    p.add_argument("--model", default="point", help="contact model (default: point)")
    p.add_argument("--stiffness", choices=("table", "linear"), default=None,
                   help="vertical stiffness: load-deflection spline (table, default when the file has one) "
                        "or linear")
    p.add_argument("--handling", choices=("none", "pac89", "mf"), default=None,
                   help="tangential force model (default: what the property file describes)")
    p.add_argument("--road", default="cleat:50x50",
                   help="road: flat, cleat:WxH[@ANGLE], bump:H, step:H, pothole:DxL[xW], a track name "
                        "or FILE.crg (sizes in mm; default cleat:50x50)")
    p.add_argument("--speed", type=positive_float("speed", 1 / 3.6), default=12 / 3.6, metavar="KMH",
                   help="towing speed in km/h (default 12)")
    p.add_argument("--load", type=load_value, default="LC1",
                   help="load case LC1, LC2, LC3 (thesis Table 3-4) or a wheel load in N (default LC1)")
    p.add_argument("--rig", choices=("trailer", "quarter-vehicle", "rolling", "drop", "wheel-drop"),
                   default="trailer",
                   help="trailer (default), quarter-vehicle, rolling (axle at fixed height), "
                        "drop (the trailer's drop test, thesis 3.4.1), wheel-drop")
    p.add_argument("--left-wheel", default=None, metavar="MODEL",
                   help="trailer rigs: contact model of the left wheel on flat ground (default: --model), "
                        "e.g. point: the same tyre and vertical law at a fraction of a ring's cost")
    p.add_argument("--duration", type=positive_float("duration"), default=None, metavar="S",
                   help="simulated time in s (default: until the road ends)")
    p.add_argument("--dt", type=positive_float("time step"), default=1e-3, metavar="S",
                   help="integration time step in s (default 0.001)")
    p.add_argument("--rate", type=positive_float("output rate"), default=1000.0, metavar="HZ",
                   help="output sample rate in Hz (default 1000)")
    p.add_argument("-o", "--output", type=str, default="run.parquet",
                   help="output signal table, .parquet or .csv (default run.parquet)")
    p.set_defaults(func=run)


def run(args) -> int:
    from .. import simulate
    from ..signal import write_signal

    output_path(args.output)
    table = simulate(tyre=args.tyre, model=args.model, road=args.road, speed=args.speed,
                     load=args.load, pressure=args.pressure, stiffness=args.stiffness,
                     handling=args.handling, rig=args.rig, left_wheel=args.left_wheel,
                     duration=args.duration, dt=args.dt, output_rate=args.rate)
    write_signal(table, args.output)
    fz = table["FZW"]
    print(f"{args.output}: {len(table)} samples over {table['RUNTIME'].iloc[-1]:.2f} s; "
          f"normal force {fz.min() / 1e3:.1f} to {fz.max() / 1e3:.1f} kN "
          f"(static {table.attrs['metadata'].get('static_wheel_load_N', float('nan')) / 1e3:.1f} kN)",
          file=sys.stdout)
    return 0
