"""``tyrelab soil``: the soil library, and a wheel's slip curve and rut in a soil bin."""

from __future__ import annotations

import sys

from ..limits import MAX_SPEED, MIN_LOAD, MIN_SPEED
from ._common import bounded_float, input_files, output_path, pressure_kpa, soil_row_text


def register(sub):
    p = sub.add_parser("soil", help="soils: the library, a slip curve (pull, torque, sinkage) and the rut")
    ss = p.add_subparsers(dest="soil_command", metavar="ACTION")
    ss.required = True
    lst = ss.add_parser("list", help="the built-in soils and their parameters (SI)")
    lst.set_defaults(func=run_list)

    cur = ss.add_parser("curve", help="steady drawbar pull, torque and sinkage against slip",
                        description="Drive the wheel through a soil bin (the single-wheel tester) at "
                                    "each slip and plot the steady drawbar pull, driving torque and "
                                    "sinkage against slip; optionally the rut of the last run.")
    cur.add_argument("--terrain", required=True, metavar="SOIL",
                     help="a built-in soil (tyrelab soil list) or a soil file FILE.toml")
    cur.add_argument("--tyre", default="xzl-16.00R20", help="built-in tyre, .tir or Chrono .json file")
    cur.add_argument("--pressure", type=pressure_kpa(), default=None, metavar="KPA",
                     help="inflation pressure in kPa (built-in tyres; default 300)")
    cur.add_argument("--model", default="rigid",
                     help="contact model(s) that run on soil, comma-separated: one curve each on the "
                          "plot, e.g. rigid,point (default rigid)")
    cur.add_argument("--load", type=bounded_float("load", MIN_LOAD, None, "N"), default=23.3e3, metavar="N",
                     help="dead weight on the wheel in N (default 23300)")
    cur.add_argument("--speed", type=bounded_float("speed", MIN_SPEED * 3.6, MAX_SPEED * 3.6, "km/h",
                                                   scale=1 / 3.6), default=1.0, metavar="KMH",
                     help="carriage speed in km/h (default 3.6)")
    cur.add_argument("--slips", type=_slips, default=(0.0, 0.1, 0.2, 0.3, 0.4, 0.6), metavar="S,S,...",
                     help="slips, comma-separated, each in [-1, 0.99]: driving s = 1 - V/(R_e omega), "
                          "braking s = R_e omega/V - 1 (-1 locked), R_e the free-rolling radius; "
                          "a list that starts with a minus is given as --slips=-1,-0.2,0 "
                          "(default 0,0.1,0.2,0.3,0.4,0.6)")
    cur.add_argument("--duration", type=bounded_float("duration", 0.5, 60.0, "s"), default=3.0, metavar="S",
                     help="simulated time of each run in s; the second half is averaged (default 3)")
    cur.add_argument("-o", "--output", default="slip_curve.png",
                     help="the plot (.png, .pdf, .svg) or the table (.csv) (default slip_curve.png)")
    cur.add_argument("--rut", default=None, metavar="IMAGE", help="also draw the last run's rut")
    cur.set_defaults(func=run_curve)


def _slips(text: str) -> tuple[float, ...]:
    import argparse
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected slips separated by commas, got '{text}'") from None
    if not values or not all(-1.0 <= v <= 0.99 for v in values):
        raise argparse.ArgumentTypeError(f"each slip must be in [-1, 0.99] (-1: locked), got '{text}'")
    return values


def run_list(args) -> int:
    import math

    from ..road.soil import load_soil, soil_names
    print(f"{'name':<13}{'n':>6}{'kc':>11}{'kphi':>12}{'c [Pa]':>9}{'phi':>6}{'K [m]':>8}  label")
    for name in soil_names():
        s, label = load_soil(name)
        print(f"{name:<13}{s.n:>6.3g}{s.kc:>11.4g}{s.kphi:>12.5g}{s.cohesion:>9.4g}"
              f"{math.degrees(s.friction_angle):>6.3g}{s.janosi_k:>8.3g}  {label}")
    print("kc in N/m^(n+1), kphi in N/m^(n+2), phi in deg (Wong 2008 Table 2.3; Chrono's demo)")
    return 0


def run_curve(args) -> int:
    from ..api import divergence_error, make_tyre_model
    from ..io_atomic import IMAGE_SUFFIXES, atomic_write, save_figure
    from ..rig.simulation import SimulationError
    from ..rig.single_wheel import STEP, single_wheel, slip_curve
    from ..road.soil import load_soil
    import pandas as pd

    inputs = input_files(args.tyre, args.terrain)
    out = output_path(args.output, (".csv",) + IMAGE_SUFFIXES, inputs=inputs)
    rut = output_path(args.rut, IMAGE_SUFFIXES, field="--rut", inputs=inputs) if args.rut else None
    _, soil_name = load_soil(args.terrain)
    names = [m.strip() for m in args.model.split(",") if m.strip()]
    models = [make_tyre_model(args.tyre, name, args.pressure, handling="none") for name in names]
    bar = None
    if sys.stderr.isatty():
        from tqdm import tqdm
        bar = tqdm(total=len(args.slips) * len(models), unit="run", desc="slip curve", file=sys.stderr)
    curves = []
    try:
        for name, model in zip(names, models):
            try:
                curves.append(slip_curve(model, args.terrain, args.load, args.speed, args.slips,
                                         args.duration,
                                         progress=(lambda done: bar.update(1)) if bar else None)
                              .assign(model=name))
            except SimulationError as exc:  # named as tyrelab.simulate names it
                raise divergence_error(exc, model, STEP, args.load, args.terrain) from None
    finally:
        if bar is not None:
            bar.close()
    curve = pd.concat(curves, ignore_index=True)
    model = models[-1]
    title = (f"{model.tyre.name}, {soil_name}, {args.load / 1e3:.3g} kN, "
             f"{args.speed * 3.6:.3g} km/h")
    if out.suffix.lower() == ".csv":
        atomic_write(out, lambda tmp: curve.to_csv(tmp, index=False, float_format="%.6g"))
    else:
        from ..report.soil_plots import plot_slip_curve
        save_figure(plot_slip_curve(curve, title), out)
    for row in curve.itertuples():
        print(soil_row_text(row, 11))
    print(f"{out}: slip curve")
    if rut:
        from ..report.soil_plots import plot_rut
        _, bed = single_wheel(model, args.terrain, args.load, args.speed, slip=args.slips[-1],
                              duration=args.duration, return_bed=True)
        save_figure(plot_rut(bed, f"rut of {names[-1]} after s = {args.slips[-1]:g}"), rut)
        print(f"{rut}: rut")
    return 0
