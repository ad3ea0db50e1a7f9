"""``tyrelab static``: the lab tests of thesis 3.3 on a model (load-deflection, footprint)."""

from __future__ import annotations

import numpy as np

from ..limits import MAX_STATIC_STEPS, MIN_LOAD, MIN_STATIC_STEPS
from ._common import (add_options, bounded_float, count, input_files, model_options, output_path,
                      pressure_kpa, renamed)

#: what ``-o`` may be: a table, or a plot of it
TABLE_SUFFIXES = (".csv",)


def register(sub):
    p = sub.add_parser("static", help="static press: load-deflection on a plate or cleat, footprint",
                       description="Press the non-rolling tyre onto the flat plate or a cleat and "
                                   "report the load at each deflection (thesis 3.3).")
    p.add_argument("--tyre", default="xzl-16.00R20", help="built-in tyre, .tir or Chrono .json file")
    p.add_argument("--pressure", type=pressure_kpa(), default=None, metavar="KPA",
                   help="inflation pressure in kPa (default 300)")
    p.add_argument("--model", default="point", help="contact model (default point)")
    p.add_argument("--stiffness", choices=("table", "linear"), default=None)
    add_options(p)
    p.add_argument("--test", default="plate",
                   help="plate, cleat:WxH (mm) or footprint (default plate)")
    p.add_argument("--direction", choices=("lateral", "longitudinal"), default="lateral",
                   help="cleat axis across (lateral) or along (longitudinal) the wheel plane")
    p.add_argument("--max-deflection", type=bounded_float("deflection", 0.0, 1000.0, "mm", scale=1e-3,
                                                          low_open=True), default=0.08,
                   metavar="MM", help="largest press deflection in mm, below rim contact (default 80)")
    p.add_argument("--steps", type=count("--steps", MIN_STATIC_STEPS, MAX_STATIC_STEPS), default=17,
                   help=f"number of deflections, {MIN_STATIC_STEPS} to {MAX_STATIC_STEPS} (default 17)")
    p.add_argument("--load", type=bounded_float("load", MIN_LOAD, None, "N"), default=None, metavar="N",
                   help="footprint load in N, below the load that reaches the rim (footprint test)")
    p.add_argument("-o", "--output", default=None,
                   help="write the table (.csv) or a plot (.png, .pdf, .svg, .jpg); the footprint "
                        "test writes an image (default footprint.png)")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..errors import InputError
    try:
        return _run(args)
    except InputError as exc:  # the model's records are built by the press: name the options
        raise renamed(exc, {"options": "--option", "model": "--model"},
                      model_options(args.option)) from None


def _run(args) -> int:
    from ..api import make_tyre_model
    from ..errors import InputError
    from ..io_atomic import IMAGE_SUFFIXES, atomic_write, save_figure
    from ..limits import check_wheel_load, rim_deflection
    from ..rig.static_press import footprint, press_road, static_press

    inputs = input_files(args.tyre)
    if args.test == "footprint":
        out = output_path(args.output or "footprint.png", IMAGE_SUFFIXES, inputs=inputs)
    else:
        out = output_path(args.output, TABLE_SUFFIXES + IMAGE_SUFFIXES, inputs=inputs) \
            if args.output else None
        press_road(args.test, args.direction)  # a bad test name or cleat size: refused now
    model = make_tyre_model(args.tyre, args.model, args.pressure, args.stiffness, handling="none",
                            options=model_options(args.option))
    tyre = model.tyre
    if args.test == "footprint":
        from ..report.footprint import plot_footprint
        if args.load is not None:
            load = check_wheel_load(args.load, tyre, field="--load")
        else:
            load = float(tyre.tir.number("VERTICAL", "FNOMIN", default=40e3))
            check_wheel_load(load, tyre, field="FNOMIN (the default --load)")
        result = footprint(model, load)
        plot_footprint(result, out)
        print(f"{out}: footprint at {result['load'] / 1e3:.1f} kN, {1e3 * result['deflection']:.1f} mm "
              f"deflection, {1e3 * result['length']:.0f} x {1e3 * result['width']:.0f} mm")
        return 0
    room, how = rim_deflection(tyre)
    if args.max_deflection >= room:
        raise InputError(f"{args.max_deflection * 1e3:g} mm would press {tyre.name} onto its rim "
                         f"({room * 1e3:.0f} mm = {how}); allowed: below {room * 1e3:.0f} mm",
                         field="--max-deflection")
    d = np.linspace(0.0, args.max_deflection, args.steps)
    table = static_press(model, d, args.test, args.direction)
    print(f"# {tyre.name} {tyre.pressure_text}, {model.contact}, {args.test}"
          + (f" ({args.direction})" if args.test != "plate" else ""))
    print(" deflection_mm   load_N")
    for dd, f in zip(table["deflection"], table["load"]):
        print(f"{dd * 1e3:14.1f} {f:9.0f}")
    if out is not None:
        if out.suffix.lower() in IMAGE_SUFFIXES:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
            fig, ax = plt.subplots(figsize=(6, 4.5), constrained_layout=True)
            ax.plot(table["deflection"] * 1e3, table["load"] / 1e3, "o-")
            ax.set_xlabel("deflection [mm]")
            ax.set_ylabel("load [kN]")
            ax.set_title(f"static press, {args.test}")
            ax.grid(alpha=0.3)
            save_figure(fig, out, dpi=120)
        else:
            atomic_write(out, lambda tmp: table.to_csv(tmp, index=False))
    return 0
