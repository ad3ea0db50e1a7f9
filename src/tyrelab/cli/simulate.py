"""``tyrelab simulate``: one run of a tyre model on a rig over a road."""

from __future__ import annotations

import sys

from ..limits import MAX_DT, MAX_DURATION, MAX_OUTPUT_RATE, MAX_SPEED, MIN_DT, MIN_SPEED
from ._common import (add_force, add_options, add_relaxation, bounded_float, input_files, load_value,
                      model_options, output_path, pressure_kpa, relaxation_value, renamed)

#: Python argument names of :func:`tyrelab.simulate` -> the options that set them
OPTIONS = {"speed": "--speed", "duration": "--duration", "dt": "--dt", "output_rate": "--rate",
           "load": "--load", "pressure": "--pressure", "rig": "--rig", "left_wheel": "--left-wheel",
           "stiffness": "--stiffness", "tyre": "--tyre", "model": "--model", "road": "--road",
           "options": "--option", "handling": "--handling", "terrain": "--terrain",
           "rig_options": "--slip/--torque", "slip": "--slip", "torque": "--torque",
           "relaxation": "--relaxation"}


def _rig_options(args) -> dict | None:
    """The single-wheel tester's ``--slip`` and ``--torque`` as the rig's options (None: none)."""
    options = {k: v for k, v in (("slip", args.slip), ("torque", args.torque)) if v is not None}
    return options or None


def register(sub):
    from ..rig.registry import rigs
    from ..road.formats import road_suffixes

    p = sub.add_parser("simulate", help="run a tyre model over a road on the test trailer",
                       description="Run a tyre model on the towed test trailer (or a quarter "
                                   "vehicle) over a road and write the signal table. Every value "
                                   "is checked before the run (bounds in tyrelab.limits); a run "
                                   "that leaves the models' valid range (rim contact, an "
                                   "overturned trailer) prints a warning line per finding.")
    p.add_argument("--tyre", default="xzl-16.00R20",
                   help="built-in tyre name, .tir or Chrono .json file (default: xzl-16.00R20)")
    p.add_argument("--pressure", type=pressure_kpa(), default=None, metavar="KPA",
                   help="inflation pressure in kPa (built-in tyres; default 300)")
    p.add_argument("--model", default="point", help="contact model (default: point)")
    add_options(p)
    p.add_argument("--stiffness", choices=("table", "linear"), default=None,
                   help="vertical stiffness: load-deflection spline (table, default when the file has one) "
                        "or linear")
    p.add_argument("--handling", default=None,
                   help="tangential force model: none, pac89, mf, tmeasy, tmsimple, fiala or a "
                        "plugin's (tyrelab models lists them; default: what the property file "
                        "describes)")
    add_relaxation(p)
    p.add_argument("--terrain", default=None, metavar="SOIL",
                   help="the ground over the road: a built-in soil (lete-sand, dry-sand, sandy-loam, "
                        "clayey-soil, snow, chrono-demo), a soil file FILE.toml, or a plugin's terrain "
                        "(tyrelab models); the road is its initial surface")
    p.add_argument("--slip", type=bounded_float("slip", -1.0, 0.99), default=None,
                   metavar="S", help="single-wheel tester: driving slip s = 1 - V / (R_e omega), 0 to "
                        "0.99, or braking s = R_e omega / V - 1, -1 (locked) to 0 (R_e: the model's "
                        "free-rolling radius on hard ground)")
    p.add_argument("--torque", type=bounded_float("torque", -1e6, 1e6, "N m"), default=None,
                   metavar="NM", help="single-wheel tester, instead of --slip: the driving torque in "
                        "N m under which the wheel spins freely (negative brakes, 0 tows it); its "
                        "slip is then the soil's answer (LONGSLIP)")
    p.add_argument("--road", default=None,
                   help="road: flat, cleat:WxH[@ANGLE], bump:H, step:H, pothole:DxL[xW], a track name "
                        f"or FILE{'|'.join(road_suffixes())}[@V] (sizes in mm; default cleat:50x50, "
                        "flat for the single-wheel tester)")
    p.add_argument("--speed", type=bounded_float("speed", MIN_SPEED * 3.6, MAX_SPEED * 3.6, "km/h",
                                                 scale=1 / 3.6),
                   default=12 / 3.6, metavar="KMH",
                   help=f"towing speed in km/h, {MIN_SPEED * 3.6:g} to {MAX_SPEED * 3.6:g} (default 12)")
    p.add_argument("--load", type=load_value, default="LC1",
                   help="load case LC1, LC2, LC3 (thesis Table 3-4) or a wheel load in N (default LC1)")
    known = rigs()
    p.add_argument("--rig", choices=tuple(known), default="trailer",
                   help="; ".join(f"{name}: {r.summary}" for name, r in known.items()) + " (default trailer)")
    p.add_argument("--left-wheel", default=None, metavar="MODEL",
                   help="trailer rigs: contact model of the left wheel on flat ground (default: --model), "
                        "e.g. point: the same tyre and vertical law at a fraction of a ring's cost")
    p.add_argument("--duration", type=bounded_float("duration", 0.0, MAX_DURATION, "s", low_open=True),
                   default=None, metavar="S",
                   help=f"simulated time in s, at most {MAX_DURATION:g} (default: until the road ends)")
    p.add_argument("--dt", type=bounded_float("time step", MIN_DT, MAX_DT, "s"), default=1e-3, metavar="S",
                   help=f"integration time step in s, {MIN_DT:g} to {MAX_DT:g} and at most the model's "
                        "stable step (default 0.001)")
    p.add_argument("--rate", type=bounded_float("output rate", 0.0, MAX_OUTPUT_RATE, "Hz", low_open=True),
                   default=None, metavar="HZ",
                   help="output sample rate in Hz, at most 1/dt (default 1000, or every step when "
                        "--dt is above 1 ms)")
    p.add_argument("-o", "--output", type=str, default="run.parquet",
                   help="output signal table, .parquet or .csv (default run.parquet)")
    add_force(p)
    p.set_defaults(func=run)


def run(args) -> int:
    from .. import simulate
    from ..errors import InputError
    from ..signal import write_signal

    out = output_path(args.output, inputs=input_files(args.tyre, args.road, args.terrain))
    try:
        table = simulate(tyre=args.tyre, model=args.model, road=args.road, speed=args.speed,
                         load=args.load, pressure=args.pressure, stiffness=args.stiffness,
                         handling=args.handling, rig=args.rig, left_wheel=args.left_wheel,
                         duration=args.duration, dt=args.dt, output_rate=args.rate, force=args.force,
                         options=model_options(args.option), terrain=args.terrain,
                         rig_options=_rig_options(args), relaxation=relaxation_value(args))
    except InputError as exc:
        raise renamed(exc, OPTIONS, model_options(args.option)) from None
    write_signal(table, out)
    fz = table["FZW"]
    found = table.attrs["metadata"].get("physics_warnings", [])
    note = (f"; OUTSIDE the models' valid range: {len(found)} warning(s) above" if found else "")
    print(f"{args.output}: {len(table)} samples over {table['RUNTIME'].iloc[-1]:.2f} s; "
          f"normal force {fz.min() / 1e3:.1f} to {fz.max() / 1e3:.1f} kN "
          f"(static {table.attrs['metadata'].get('static_wheel_load_N', float('nan')) / 1e3:.1f} kN)"
          + note, file=sys.stdout)
    return 0
