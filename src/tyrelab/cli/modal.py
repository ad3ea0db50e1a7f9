"""``tyrelab modal``: natural frequencies and damping of the flexible ring (thesis Table 3-3)."""

from __future__ import annotations

import sys

from ..limits import MAX_SEGMENTS, MIN_LOAD, MIN_SEGMENTS
from ._common import bounded_float, count, input_files, output_path, pressure_kpa


def register(sub):
    p = sub.add_parser("modal", help="modal analysis of the flexible ring tyre model",
                       description="Linearise the flexible ring about the free (or loaded) "
                                   "tyre and print the natural frequencies and damping ratios "
                                   "of the modes of thesis Table 3-3, with the measured values "
                                   "where the tyre has them.")
    p.add_argument("--tyre", default="xzl-16.00R20",
                   help="built-in tyre name or .tir file with [FLEXIBLE_RING] (default: xzl-16.00R20)")
    p.add_argument("--pressure", type=pressure_kpa(), default=None, metavar="KPA",
                   help="inflation pressure in kPa (built-in tyres; default 300)")
    p.add_argument("--load", type=bounded_float("load", MIN_LOAD, None, "N"), default=None, metavar="N",
                   help="linearise about the tyre pressed on a plate under this load in N "
                        "(default: free tyre)")
    p.add_argument("--segments", type=count("--segments", MIN_SEGMENTS, MAX_SEGMENTS), default=100,
                   help=f"belt segments, {MIN_SEGMENTS} to {MAX_SEGMENTS} (default 100)")
    p.add_argument("-o", "--output", default=None, help="also write the table to a .csv file")
    p.set_defaults(func=run)


def run(args) -> int:
    import numpy as np

    from ..io_atomic import atomic_write
    from ..limits import check_wheel_load
    from ..tyre.library import BUILT_IN, load_tyre, modal_table
    from ..tyre.ring.modal import ring_modal

    out = output_path(args.output, (".csv",), inputs=input_files(args.tyre)) if args.output else None
    tyre = load_tyre(args.tyre, args.pressure)
    if args.load:
        check_wheel_load(args.load, tyre, field="--load")
    table = ring_modal(tyre, load=args.load or 0.0, n_segments=args.segments)
    key = f"{tyre.pressure / 1e3:.0f}kPa"
    if str(args.tyre).lower() in {k.lower() for k in BUILT_IN}:
        meas = modal_table(tyre.name).set_index("mode")
        for col, name in ((f"freq_Hz_{key}", "measured_Hz"), (f"damping_pct_{key}", "measured_pct")):
            table[name] = table["mode"].map(meas[col]) if col in meas else np.nan
    state = f"loaded {args.load:.0f} N" if args.load else "free"
    where = f"at {tyre.pressure_text}" if np.isfinite(tyre.pressure) else f"({tyre.pressure_text})"
    print(f"{tyre.name} {where}, {state}:", file=sys.stdout)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.2f}"), file=sys.stdout)
    if out is not None:
        atomic_write(out, lambda tmp: table.to_csv(tmp, index=False))
    return 0
