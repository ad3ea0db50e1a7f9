"""``tyrelab road``: look at a road, its spectrum, or export it (OpenCRG, Adams .rdf, .obj).

ROAD is anything :func:`tyrelab.road.spec.road_from_spec` accepts: an
obstacle (``cleat:50x50``), a built-in track (``belgian-paving``) or a
``.crg``, ``.rdf`` or ``.obj`` file (``road.crg@0.5``).
"""

from __future__ import annotations

from pathlib import Path

from ..errors import InputError
from ..limits import MAX_GRID_SPACING, MAX_ROAD_WIDTH, MAX_SPECTRUM_LINES, MIN_GRID_SPACING
from ._common import add_force, bounded_float, count, input_files


def _image_path(text: str, inputs=()) -> Path:
    from ..io_atomic import IMAGE_SUFFIXES, check_output_path
    return check_output_path(text, IMAGE_SUFFIXES, "-o", inputs)


def register(sub):
    from ..road.formats import road_formats, writable_suffixes

    road_help = f"road name, track or FILE{'|'.join(road_formats())}[@V]"
    p = sub.add_parser("road", help="show a road, its spectrum (A, n), or export it as OpenCRG")
    rs = p.add_subparsers(dest="road_command", metavar="ACTION")
    rs.required = True

    show = rs.add_parser("show", help="heightmap and a longitudinal cut")
    show.add_argument("road", metavar="ROAD", help=road_help)
    show.add_argument("-o", "--output", default="road.png", help="image file (default road.png)")
    show.add_argument("--y", type=bounded_float("y", -MAX_ROAD_WIDTH, MAX_ROAD_WIDTH, "m"), default=0.0,
                      help="lateral position of the cut [m]")
    add_force(show)
    show.set_defaults(func=run_show)

    spec = rs.add_parser("spectrum", help="displacement spectral density and power-law fit (eq. 3.8)")
    spec.add_argument("road", metavar="ROAD", help=road_help)
    spec.add_argument("-o", "--output", default=None, help="image file for the DSD plot")
    spec.add_argument("--y", type=bounded_float("y", -MAX_ROAD_WIDTH, MAX_ROAD_WIDTH, "m"), default=0.0,
                      help="lateral position of the profile [m]")
    spec.add_argument("--lines", type=count("--lines", 1, MAX_SPECTRUM_LINES), default=1,
                      help=f"average this many profiles across the road (1 to {MAX_SPECTRUM_LINES})")
    spec.add_argument("--band", nargs=2, type=bounded_float("band", 0.0, 1000.0, "cycles/m", low_open=True),
                      default=None, metavar=("LO", "HI"),
                      help="fit band [cycles/m] (default 0.05 10, ISO 8608)")
    add_force(spec)
    spec.set_defaults(func=run_spectrum)

    exp = rs.add_parser("export", help="write the road as an OpenCRG, Adams .rdf or .obj file (or a "
                                       "plugin's format)")
    exp.add_argument("road", metavar="ROAD", help=road_help)
    exp.add_argument("-o", "--output", required=True,
                     help="the file to write: " + ", ".join(
                         f"{s} ({road_formats()[s].name})" for s in writable_suffixes()))
    exp.add_argument("--spacing", nargs=2, default=None,
                     type=bounded_float("spacing", MIN_GRID_SPACING, MAX_GRID_SPACING, "m"),
                     metavar=("DX", "DY"),
                     help=f"grid spacing [m], {MIN_GRID_SPACING:g} to {MAX_GRID_SPACING:g} "
                          "(default: the road's own)")
    exp.add_argument("--format", default="KDBI", choices=("KDBI", "KRBI", "LDFI", "LRFI"),
                     help="OpenCRG data format (default KDBI, binary double)")
    exp.add_argument("--method", choices=("2D", "3D"), default=None,
                     help=".rdf: a 2D poly_line road or a 3D shell (default: 2D when the road "
                          "does not vary across)")
    exp.add_argument("--mu", type=bounded_float("mu", 0.0, 5.0, low_open=True), default=1.0,
                     help=".rdf: the friction coefficient written (default 1.0)")
    add_force(exp)
    exp.set_defaults(func=run_export)

    lst = rs.add_parser("list", help="the road names ROAD accepts")
    lst.set_defaults(func=run_list)


def _road(text, force: bool = False):
    """The road of a command, with its grid's memory checked before it is built."""
    from ..resources import check_resources, grid_cells
    from ..road.spec import road_from_spec

    road = road_from_spec(text, force=force)
    cells = grid_cells(road)
    check_resources(f"the grid of {road.name} ({cells:.3g} nodes)", memory=8.0 * 3 * cells, force=force,
                    field="ROAD")
    return road


def run_show(args) -> int:
    from ..report.road_plots import plot_road, save_figure

    out = _image_path(args.output, input_files(args.road))
    road = _road(args.road, args.force)
    save_figure(plot_road(road, y=args.y), out)
    xmin, xmax, ymin, ymax = road.extent()
    print(f"{out}: {road.name}; x {xmin:g}..{xmax:g} m, y {ymin:g}..{ymax:g} m")
    return 0


def run_spectrum(args) -> int:
    from ..road.iso8608 import BAND, iso_class
    from ..road.spectrum import displacement_spectral_density, fit_power_law

    out = _image_path(args.output, input_files(args.road)) if args.output else None
    band = tuple(args.band) if args.band else BAND
    if band[0] >= band[1]:
        raise InputError(f"band {band[0]:g} {band[1]:g}: the low end must be below the high end",
                         field="--band")
    road = _road(args.road, args.force)
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
    from pathlib import Path

    from ..io_atomic import check_output_path

    from ..road.formats import format_named, writable_suffixes

    out = check_output_path(args.output, writable_suffixes(), "-o", input_files(args.road))
    road = _road(args.road, args.force)
    spacing = tuple(args.spacing) if args.spacing else None
    fmt = format_named(Path(out).suffix)
    options = {name: getattr(args, name) for name in fmt.write_options}
    path, what = fmt.write(road, out, spacing=spacing, force=args.force, **options)
    print(f"{path}: {road.name} as {what}")
    return 0


def run_list(args) -> int:
    from ..road.spec import road_names

    print("\n".join(road_names()))
    return 0
