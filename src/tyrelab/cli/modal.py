"""``tyrelab modal``: natural frequencies and damping of the flexible ring (thesis Table 3-3)."""

from __future__ import annotations

import sys

from ._common import positive_float


def register(sub):
    p = sub.add_parser("modal", help="modal analysis of the flexible ring tyre model",
                       description="Linearise the flexible ring about the free (or loaded) "
                                   "tyre and print the natural frequencies and damping ratios "
                                   "of the modes of thesis Table 3-3, with the measured values "
                                   "where the tyre has them.")
    p.add_argument("--tyre", default="xzl-16.00R20",
                   help="built-in tyre name or .tir file with [FLEXIBLE_RING] (default: xzl-16.00R20)")
    p.add_argument("--pressure", type=positive_float("pressure", 1e3), default=None, metavar="KPA",
                   help="inflation pressure in kPa (built-in tyres; default 300)")
    p.add_argument("--load", type=positive_float("load"), default=None, metavar="N",
                   help="linearise about the tyre pressed on a plate under this load in N "
                        "(default: free tyre)")
    p.add_argument("--segments", type=int, default=100, help="belt segments (default 100)")
    p.add_argument("-o", "--output", default=None, help="also write the table to a .csv file")
    p.set_defaults(func=run)


def run(args) -> int:
    import numpy as np

    from ..errors import InputError
    from ..tyre.library import BUILT_IN, load_tyre, modal_table
    from ..tyre.ring.modal import ring_modal

    if args.segments < 12:
        raise InputError("at least 12 segments", field="--segments")
    tyre = load_tyre(args.tyre, args.pressure)
    table = ring_modal(tyre, load=args.load or 0.0, n_segments=args.segments)
    key = f"{tyre.pressure / 1e3:.0f}kPa"
    if str(args.tyre).lower() in {k.lower() for k in BUILT_IN}:
        meas = modal_table(tyre.name).set_index("mode")
        for col, name in ((f"freq_Hz_{key}", "measured_Hz"), (f"damping_pct_{key}", "measured_pct")):
            table[name] = table["mode"].map(meas[col]) if col in meas else np.nan
    state = f"loaded {args.load:.0f} N" if args.load else "free"
    print(f"{tyre.name} at {tyre.pressure / 1e3:g} kPa, {state}:", file=sys.stdout)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.2f}"), file=sys.stdout)
    if args.output:
        if not args.output.lower().endswith(".csv"):
            raise InputError(f"output file '{args.output}' must end in .csv", field="-o")
        table.to_csv(args.output, index=False)
    return 0
