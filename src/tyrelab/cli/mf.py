"""``tyrelab mf``: Magic Formula 5.2/6.1/6.2 property files.

``tyrelab mf curves FILE.tir -o curves.png`` plots Fx(kappa), Fy(alpha) and
Mz(alpha) at several loads (``--pressure KPA``: an MF-Tyre 6.x file at another pressure).
"""

from __future__ import annotations

from ..errors import InputError
from ._common import comma_numbers, pressure_kpa


#: largest load asked for, as a fraction of FNOMIN (far beyond any file's FZMAX)
MAX_LOAD_FACTOR = 10.0
#: most loads (curves per panel) in one figure
MAX_LOADS = 20


def _load_factors(text: str) -> list[float]:
    return comma_numbers(text, "--loads", MAX_LOADS, lambda v: 0.0 < v <= MAX_LOAD_FACTOR,
                         f"numbers 0 < f <= {MAX_LOAD_FACTOR:g} (fractions of FNOMIN)")


def _curves(args) -> int:
    from ..io_atomic import IMAGE_SUFFIXES, check_output_path
    from ..report.mf_curves import plot_curves
    from ..tyre.handling.mf import MagicFormula, check_use_mode

    output = check_output_path(args.output, IMAGE_SUFFIXES, "-o", inputs=[args.tir])
    factors = _load_factors(args.loads)
    try:
        mode = check_use_mode(args.use_mode)
    except InputError as exc:
        raise InputError(exc.reason, source="command line", field="--use-mode") from None
    from ..tyre.params import Tyre
    model = MagicFormula.from_tir(args.tir)   # its coefficients checked first
    tyre = Tyre.from_tir(model.tir)
    if args.pressure is not None:   # an MF-Tyre 6.x file at another pressure (tyre.pressure.at_pressure)
        from ..tyre.pressure import at_pressure
        tyre = at_pressure(tyre, args.pressure, args.tir)
        model = MagicFormula.from_tir(tyre.tir)
    out = plot_curves(model, output, factors, use_mode=mode, pressure_text=tyre.pressure_text)
    print(f"wrote {out} (Magic Formula {model.version}, {tyre.pressure_text})")
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
    curves.add_argument("--pressure", type=pressure_kpa(), default=None, metavar="KPA",
                        help="inflation pressure in kPa (default: the file's INFLPRES); an MF-Tyre "
                             "6.1/6.2 file with pressure terms, within its [INFLATION_PRESSURE_RANGE]")
    curves.set_defaults(func=_curves)
    # argparse errors of the nested parser go through the mf parser, whose
    # error handler the main command replaces (one line, exit 2)
    curves.error = lambda message: parser.error(message)

    def _no_sub(args) -> int:
        parser.print_help()
        return 1

    parser.set_defaults(func=_no_sub)
