"""``tyrelab mf``: Magic Formula 5.2/6.1/6.2 property files.

``tyrelab mf curves FILE.tir -o curves.png`` plots Fx(kappa), Fy(alpha) and
Mz(alpha) at several loads.
"""

from __future__ import annotations

from ..errors import InputError


def _load_factors(text: str) -> list[float]:
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        values = []
    if not values or any(not v > 0.0 for v in values):
        raise InputError(f"expected positive numbers separated by commas, found '{text}'",
                         source="command line", field="--loads")
    return values


def _curves(args) -> int:
    from ..report.mf_curves import plot_curves
    from ..tyre.handling.mf import MagicFormula, check_use_mode

    model = MagicFormula.from_tir(args.tir)
    try:
        mode = check_use_mode(args.use_mode)
    except InputError as exc:
        raise InputError(exc.reason, source="command line", field="--use-mode") from None
    out = plot_curves(model, args.output, _load_factors(args.loads), use_mode=mode)
    print(f"wrote {out} (Magic Formula {model.version})")
    return 0


def register(subparsers) -> None:
    parser = subparsers.add_parser("mf", help="Magic Formula 5.2/6.1/6.2 tyre property files",
                                   description="Magic Formula 5.2/6.1/6.2 (PAC2002 family) tools.")
    sub = parser.add_subparsers(dest="mf_command", metavar="MF_COMMAND")
    curves = sub.add_parser("curves", help="plot Fx(kappa), Fy(alpha), Mz(alpha) at several loads",
                            description="Plot pure-slip Fx(kappa), Fy(alpha) and Mz(alpha) at "
                                        "several loads (fractions of FNOMIN), zero camber, LONGVL.")
    curves.add_argument("tir", help="tyre property file (.tir)")
    curves.add_argument("-o", "--output", required=True, help="image file to write (e.g. curves.png)")
    curves.add_argument("--loads", default="0.5,1,1.5",
                        help="loads as fractions of FNOMIN, comma separated (default 0.5,1,1.5)")
    curves.add_argument("--use-mode", type=int, default=111,
                        help="MFeval useMode: 111 (default), 121, 211 or 221")
    curves.set_defaults(func=_curves)
    # argparse errors of the nested parser go through the mf parser, whose
    # error handler the main command replaces (one line, exit 2)
    curves.error = lambda message: parser.error(message)

    def _no_sub(args) -> int:
        parser.print_help()
        return 1

    parser.set_defaults(func=_no_sub)
