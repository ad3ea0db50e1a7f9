"""``tyrelab fit``: parameter identification from test data."""

from __future__ import annotations

from ..limits import MAX_FIT_EVALUATIONS
from ._common import count


def register(sub):
    p = sub.add_parser("fit", help="identify model parameters from test data")
    fsub = p.add_subparsers(dest="fit_kind", metavar="MODEL")
    r = fsub.add_parser("ring", help="identify the flexible ring of a built-in tyre from its lab data",
                        description="Fit the ring model to the tyre's flat-plate load-deflection and "
                                    "modal frequencies at 300 and 550 kPa and the eq. 2.3 contact "
                                    "length; reports fitted and held-out errors (several minutes).")
    r.add_argument("--tyre", default="xzl-16.00R20", help="built-in tyre with lab data")
    r.add_argument("--max-evaluations", type=count("--max-evaluations", 1, MAX_FIT_EVALUATIONS), default=25,
                   help=f"optimizer budget, 1 to {MAX_FIT_EVALUATIONS} (default 25)")
    r.add_argument("-o", "--output", default="ring.tir",
                   help="ring property file to write (.tir; checked before the fit starts)")
    r.set_defaults(func=run_ring)
    p.set_defaults(func=lambda args: (p.print_help(), 1)[1])


def run_ring(args) -> int:
    from ..errors import InputError
    from ..fit.ring import fit_ring, markdown_table, write_ring_file
    from ..io_atomic import check_output_path
    from ..tyre.library import BUILT_IN

    out = check_output_path(args.output, (".tir",), "-o")
    if args.tyre not in BUILT_IN:
        raise InputError(f"ring identification needs the lab data of a built-in tyre "
                         f"({', '.join(BUILT_IN)}), got '{args.tyre}'", field="--tyre")
    if args.max_evaluations < 1:
        raise InputError("--max-evaluations must be at least 1", field="--max-evaluations")
    from tqdm import tqdm

    from ..fit.ring import FREE

    # least_squares evaluates the residuals once per step and once per free
    # parameter for each finite-difference Jacobian: an upper bound
    with tqdm(total=args.max_evaluations * (len(FREE) + 1), unit="model", desc="identifying ring",
              leave=False) as bar:
        def step(cost):
            bar.update(1)
            bar.set_postfix(cost=f"{cost:.4g}")

        params, fitted, held = fit_ring(args.tyre, max_nfev=args.max_evaluations, progress=step)
    write_ring_file(params, out)
    print("fitted data:\n" + markdown_table(fitted))
    print("\nheld-out predictions:\n" + markdown_table(held))
    print(f"\n{args.output}: ring parameters")
    return 0

