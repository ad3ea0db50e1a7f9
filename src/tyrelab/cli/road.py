"""``tyrelab road``: look at a road, its spectrum, or export it as OpenCRG.

ROAD is anything :func:`tyrelab.road.spec.road_from_spec` accepts: an
obstacle (``cleat:50x50``), a built-in track (``belgian-paving``) or a
``.crg`` file (``road.crg@0.5``).
"""

from __future__ import annotations

import argparse
import math

from ..errors import InputError


def _float(name):
    def parse(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got '{text}'") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"{name} must be finite, got '{text}'")
        return value
    parse.__name__ = name
    return parse


def _positive(name):
    base = _float(name)

    def parse(text):
        value = base(text)
        if value <= 0:
            raise argparse.ArgumentTypeError(f"{name} must be positive, got '{text}'")
        return value
    parse.__name__ = name
    return parse


def _image_path(text: str) -> str:
    if not text.lower().endswith((".png", ".pdf", ".svg", ".jpg")):
        raise InputError(f"image file '{text}' must end in .png, .pdf, .svg or .jpg", field="-o")
    return text


def register(sub):
    p = sub.add_parser("road", help="show a road, its spectrum (A, n), or export it as OpenCRG")
    rs = p.add_subparsers(dest="road_command", metavar="ACTION")
    rs.required = True

    show = rs.add_parser("show", help="heightmap and a longitudinal cut")
    show.add_argument("road", metavar="ROAD", help="road name, track or FILE.crg[@V]")
    show.add_argument("-o", "--output", default="road.png", help="image file (default road.png)")
    show.add_argument("--y", type=_float("y"), default=0.0, help="lateral position of the cut [m]")
    show.set_defaults(func=run_show)

    spec = rs.add_parser("spectrum", help="displacement spectral density and power-law fit (eq. 3.8)")
    spec.add_argument("road", metavar="ROAD", help="road name, track or FILE.crg[@V]")
    spec.add_argument("-o", "--output", default=None, help="image file for the DSD plot")
    spec.add_argument("--y", type=_float("y"), default=0.0, help="lateral position of the profile [m]")
    spec.add_argument("--lines", type=int, default=1, help="average this many profiles across the road")
    spec.add_argument("--band", nargs=2, type=_positive("band"), default=None, metavar=("LO", "HI"),
                      help="fit band [cycles/m] (default 0.05 10, ISO 8608)")
    spec.set_defaults(func=run_spectrum)

    exp = rs.add_parser("export", help="write the road as an OpenCRG file")
    exp.add_argument("road", metavar="ROAD", help="road name, track or FILE.crg[@V]")
    exp.add_argument("-o", "--output", required=True, help="the .crg file to write")
    exp.add_argument("--spacing", nargs=2, type=_positive("spacing"), default=None, metavar=("DX", "DY"),
                     help="grid spacing [m] (default: the road's own)")
    exp.add_argument("--format", default="KDBI", choices=("KDBI", "KRBI", "LDFI", "LRFI"),
                     help="OpenCRG data format (default KDBI, binary double)")
    exp.set_defaults(func=run_export)

    lst = rs.add_parser("list", help="the road names ROAD accepts")
    lst.set_defaults(func=run_list)


def _road(text):
    from ..road.spec import road_from_spec

    return road_from_spec(text)


def run_show(args) -> int:
    from ..report.road_plots import plot_road, save_figure

    out = _image_path(args.output)
    road = _road(args.road)
    save_figure(plot_road(road, y=args.y), out)
    xmin, xmax, ymin, ymax = road.extent()
    print(f"{out}: {road.name}; x {xmin:g}..{xmax:g} m, y {ymin:g}..{ymax:g} m")
    return 0


def run_spectrum(args) -> int:
    from ..road.iso8608 import BAND, iso_class
    from ..road.spectrum import displacement_spectral_density, fit_power_law

    out = _image_path(args.output) if args.output else None
    band = tuple(args.band) if args.band else BAND
    if band[0] >= band[1]:
        raise InputError(f"band {band[0]:g} {band[1]:g}: the low end must be below the high end",
                         field="--band")
    if args.lines < 1:
        raise InputError(f"--lines must be at least 1, got {args.lines}", field="--lines")
    road = _road(args.road)
    phi, s = displacement_spectral_density(road, y=args.y, lines=args.lines)
    a, n = fit_power_law(phi, s, band=band)
    print(f"{road.name}: A = {a:.3g} m^2/(cycles/m), n = {n:.2f} "
          f"(S = A phi^-n, {band[0]:g}-{band[1]:g} cycles/m; ISO 8608 class {iso_class(a, n)})")
    if n <= 0:
        print("note: the spectrum does not fall with frequency; a power law does not describe this road "
              "(periodic or a single obstacle?)")
    if out:
        from ..report.road_plots import plot_spectrum, save_figure

        save_figure(plot_spectrum(phi, s, fit=(a, n), band=band, title=road.name), out)
        print(f"{out}: displacement spectral density")
    return 0


def run_export(args) -> int:
    from ..road.crg import write_crg

    if not args.output.lower().endswith(".crg"):
        raise InputError(f"output file '{args.output}' must end in .crg", field="-o")
    road = _road(args.road)
    path = write_crg(road, args.output, spacing=tuple(args.spacing) if args.spacing else None,
                     fmt=args.format)
    print(f"{path}: {road.name} as OpenCRG {args.format}")
    return 0


def run_list(args) -> int:
    from ..road.spec import road_names

    print("\n".join(road_names()))
    return 0
