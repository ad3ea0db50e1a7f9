"""``tyrelab fit tmeasy TYRE -o OUT.tir``: TMeasy's parameters fitted to a tyre's own handling
model's curves, or with ``--measured FILE...`` to measured slip sweeps
(:mod:`tyrelab.fit.tmeasy`), written into a copy of its property file."""

from __future__ import annotations

from ._common import positive_float


def register_tmeasy(fsub) -> None:
    t = fsub.add_parser(
        "tmeasy", help="TMeasy's parameters fitted to another handling model's curves (MF, PAC89, ...)",
        description="Sample the tyre's pure-slip curves under its handling model (the one its "
                    "file describes, or --handling) at the nominal load and twice it -- or read "
                    "measured slip sweeps (--measured) -- fit TMeasy's characteristic and "
                    "pneumatic trail to them by least squares and write the tyre's property file "
                    "with TMeasy's sections added (--handling tmeasy then runs them). Prints each "
                    "curve's RMS error.")
    t.add_argument("tyre", metavar="TYRE", help="built-in tyre name, .tir or Chrono .json file")
    t.add_argument("-o", "--output", required=True, help="property file to write (.tir)")
    t.add_argument("--handling", default=None,
                   help="the handling model whose curves are fitted (default: the file's own)")
    t.add_argument("--measured", nargs="+", default=None, metavar="FILE",
                   help="measured pure-slip sweeps to fit instead (TYDEX .tdx, or .csv/.parquet with "
                        "the channels FZW, LONGSLIP, SLIPANGL, FXW, FYW, MZW in SI, W-axis)")
    t.add_argument("--column-map", default=None, metavar="FILE",
                   help="column map for measured .csv sweeps (lines source,channel,unit, as "
                        "tyrelab validate takes)")
    t.add_argument("--nominal-load", type=positive_float("--nominal-load"), default=None, metavar="N",
                   help="TMeasy's nominal load FZ_NOM in N (default: the file's FNOMIN or FZ_NOM; "
                        "with --measured, half the largest measured load)")
    t.set_defaults(func=run_tmeasy)


def run_tmeasy(args) -> int:
    import copy

    from ..fit.property_file import FIT_SECTION, tidy
    from ..fit.tmeasy import tmeasy_from_handling
    from ..io_atomic import check_output_path
    from ..tyre.library import load_tyre
    from ..tyre.tir import write_tir
    from ._common import handling_for, input_files, nominal_load_for

    out = check_output_path(args.output, (".tir",), "-o",
                            input_files(args.tyre, args.column_map, *(args.measured or [])))
    tyre = load_tyre(args.tyre)
    if args.measured:
        from ..fit.tmeasy import tmeasy_from_runs
        from ..measure.io import read_run

        runs = [read_run(path, column_map=args.column_map) for path in args.measured]
        fit = tmeasy_from_runs(tyre, runs, args.nominal_load)
        source = f"{len(runs)} measured sweep file(s)"
    else:
        handling = handling_for(tyre, args.handling, args.tyre, "to fit TMeasy to",
                                "--handling or --measured")
        nominal = nominal_load_for(tyre, args.nominal_load, args.tyre, "--nominal-load")
        fit = tmeasy_from_handling(tyre, handling, nominal)
        source = f"its {handling} curves"
    tir = copy.deepcopy(tyre.tir)
    tir.header = list(tir.header) + [f"$ TMeasy sections fitted to {source} by tyrelab fit tmeasy"]
    for section, key, value in fit.entries():
        tir.set(section, key, value)
    tir.set(FIT_SECTION, "TMEASY_SOURCE", source)
    for name, value in fit.rms_pct.items():
        tir.set(FIT_SECTION, f"TMEASY_RMS_{name.upper()}_PCT", float(value))
    tidy(tir, new=False)
    write_tir(tir, out)
    (x_low, x_high), (y_low, y_high) = fit.slip_range
    nominal = fit.nominal_load
    print(f"TMeasy fitted to {source}, FZ_NOM {nominal:g} N (TMeasy slips {x_low:.3g} to {x_high:.3g} "
          f"and {y_low:.3g} to {y_high:.3g}); RMS error in % of each curve's largest magnitude:")
    for name, value in fit.rms_pct.items():
        print(f"  {name:7s} {value:7.3f} %")
    print(f"wrote {out}")
    return 0
