"""``tyrelab static``: the lab tests of thesis 3.3 on a model (load-deflection, footprint)."""

from __future__ import annotations

import numpy as np

from ._common import positive_float


def register(sub):
    p = sub.add_parser("static", help="static press: load-deflection on a plate or cleat, footprint",
                       description="Press the non-rolling tyre onto the flat plate or a cleat and "
                                   "report the load at each deflection (thesis 3.3).")
    p.add_argument("--tyre", default="xzl-16.00R20", help="built-in tyre or .tir file")
    p.add_argument("--pressure", type=positive_float("pressure", 1e3), default=None, metavar="KPA",
                   help="inflation pressure in kPa (default 300)")
    p.add_argument("--model", default="point", help="contact model (default point)")
    p.add_argument("--stiffness", choices=("table", "linear"), default=None)
    p.add_argument("--test", default="plate",
                   help="plate, cleat:WxH (mm) or footprint (default plate)")
    p.add_argument("--direction", choices=("lateral", "longitudinal"), default="lateral",
                   help="cleat axis across (lateral) or along (longitudinal) the wheel plane")
    p.add_argument("--max-deflection", type=positive_float("deflection", 1e-3), default=0.08,
                   metavar="MM", help="largest press deflection in mm (default 80)")
    p.add_argument("--steps", type=int, default=17, help="number of deflections (default 17)")
    p.add_argument("--load", type=positive_float("load"), default=None, metavar="N",
                   help="footprint load in N (footprint test)")
    p.add_argument("-o", "--output", default=None, help="write the table (.csv) or a plot (.png)")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..api import make_tyre_model
    from ..errors import InputError
    from ..rig.static_press import footprint, static_press

    model = make_tyre_model(args.tyre, args.model, args.pressure, args.stiffness, handling="none")
    if args.test == "footprint":
        from ..report.footprint import plot_footprint
        load = args.load or float(model.tyre.tir.number("VERTICAL", "FNOMIN", default=40e3))
        result = footprint(model, load)
        path = args.output or "footprint.png"
        plot_footprint(result, path)
        print(f"{path}: footprint at {load / 1e3:.1f} kN")
        return 0
    if args.steps < 2:
        raise InputError("need at least 2 steps", field="--steps")
    d = np.linspace(0.0, args.max_deflection, args.steps)
    table = static_press(model, d, args.test, args.direction)
    print(f"# {model.tyre.name} {model.tyre.pressure / 1e3:g} kPa, {model.contact}, {args.test}"
          + (f" ({args.direction})" if args.test != "plate" else ""))
    print(" deflection_mm   load_N")
    for dd, f in zip(table["deflection"], table["load"]):
        print(f"{dd * 1e3:14.1f} {f:9.0f}")
    if args.output:
        if args.output.lower().endswith(".png"):
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
            fig, ax = plt.subplots(figsize=(6, 4.5), constrained_layout=True)
            ax.plot(table["deflection"] * 1e3, table["load"] / 1e3, "o-")
            ax.set_xlabel("deflection [mm]")
            ax.set_ylabel("load [kN]")
            ax.set_title(f"static press, {args.test}")
            ax.grid(alpha=0.3)
            fig.savefig(args.output, dpi=120)
        else:
            table.to_csv(args.output, index=False)
    return 0
