"""``tyrelab curves``: a handling model's pure-slip curves, one or more tyres side by side.

``tyrelab curves hmmwv-pac89 HMMWV_TMeasyTire.json HMMWV_FialaTire.json --loads 4900 -o c.png``
draws Fx(kappa), Fy(alpha) and Mz(alpha) of each tyre under its own handling model (the one
its file describes, or ``--handling``, once for all or once per tyre): three
parameterisations of one tyre compared, or one file under two models (``tyrelab curves
mf.tir mf.tir --handling mf --handling tmeasy`` after ``tyrelab fit tmeasy``).
"""

from __future__ import annotations

from ..errors import InputError
from ..limits import MAX_SPEED, MIN_LOAD, MIN_SPEED
from ._common import bounded_float, comma_numbers, handling_for, nominal_load_for

#: most loads per tyre, and most tyres, in one figure
MAX_LOADS = 6
MAX_TYRES = 6


def _loads(text: str) -> list[float]:
    return comma_numbers(text, "--loads", MAX_LOADS, lambda v: v >= MIN_LOAD,
                         f"wheel loads in N (each at least {MIN_LOAD:g})")


def _run(args) -> int:
    from ..io_atomic import IMAGE_SUFFIXES, check_output_path
    from ..report.handling_curves import DEFAULT_LOAD_FACTORS, curve_set, plot_curve_sets
    from ..tyre.library import load_tyre
    from ..tyre.registry import handling_model

    output = check_output_path(args.output, IMAGE_SUFFIXES, "-o", inputs=args.tyres)
    if len(args.tyres) > MAX_TYRES:
        raise InputError(f"at most {MAX_TYRES} tyres in one figure, got {len(args.tyres)}",
                         source="command line", field="TYRE")
    loads = _loads(args.loads) if args.loads is not None else None
    chosen = args.handling or []
    if len(chosen) not in (0, 1, len(args.tyres)):
        raise InputError(f"give --handling once (every tyre) or once per tyre ({len(args.tyres)}), "
                         f"got {len(chosen)}", source="command line", field="--handling")
    for name in chosen:
        handling_model(name)  # an unknown name is refused before any tyre is read
    sets = []
    for k, name in enumerate(args.tyres):
        tyre = load_tyre(name)
        handling = handling_for(tyre, chosen[k if len(chosen) > 1 else 0] if chosen else None, name,
                                "to draw", "--handling (tyrelab models lists them)")
        tyre_loads = loads
        if tyre_loads is None:
            nominal = nominal_load_for(tyre, None, name, "--loads")
            tyre_loads = [f * nominal for f in DEFAULT_LOAD_FACTORS]
        try:
            sets.append(curve_set(tyre, handling, tyre_loads, args.speed, label=tyre.name))
        except InputError as exc:
            raise InputError(f"{handling}: {exc.reason}", source=exc.source or str(name), line=exc.line,
                             field=exc.field) from None
    out = plot_curve_sets(sets, output, args.speed)
    print(f"wrote {out} ({', '.join(f'{s.label}: {s.handling}' for s in sets)})")
    return 0


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "curves", help="plot handling models' pure-slip curves Fx(kappa), Fy(alpha), Mz(alpha)",
        description="Plot pure-slip curves -- FXW against the slip ratio, FYW and MZW against the "
                    "slip angle (W-axis, ISO slips, zero camber) -- of one or more tyres, each "
                    "under the handling model its file describes (or --handling), at several "
                    "loads.")
    p.add_argument("tyres", nargs="+", metavar="TYRE",
                   help="built-in tyre name, .tir or Chrono .json file (up to 6)")
    p.add_argument("-o", "--output", required=True, help="image file to write (e.g. curves.png)")
    p.add_argument("--handling", action="append", default=None, metavar="NAME",
                   help="handling model: once for every tyre, or once per tyre in their order "
                        "(default: each file's own)")
    p.add_argument("--loads", default=None,
                   help="wheel loads in N, comma separated (default: 0.5, 1 and 1.5 times the "
                        "file's nominal load FNOMIN or FZ_NOM)")
    p.add_argument("--speed", type=bounded_float("speed", MIN_SPEED * 3.6, MAX_SPEED * 3.6, "km/h",
                                                 scale=1 / 3.6), default=36.0 / 3.6,
                   help="forward speed in km/h (default 36)")
    p.set_defaults(func=_run)
