"""``tyrelab export fmu``: a tyre model on its road as an FMI 2.0 co-simulation FMU."""

from __future__ import annotations

from ..limits import MAX_DT
from ._common import (add_options, add_relaxation, bounded_float, input_files, load_value,
                      model_options, output_path, pressure_kpa, relaxation_value, renamed)

#: Python argument names of :func:`tyrelab.cosim.fmu.export_fmu` -> the options that set them
OPTIONS = {"tyre": "--tyre", "model": "--model", "road": "--road", "pressure": "--pressure",
           "stiffness": "--stiffness", "handling": "--handling", "options": "--option",
           "load": "--load", "frame": "--frame", "internal_step": "--internal-step",
           "terrain": "--terrain", "output": "-o", "relaxation": "--relaxation"}


def register(sub):
    from ..road.formats import road_suffixes

    p = sub.add_parser("export", help="export a tyre model for another program (an FMI 2.0 FMU)")
    ss = p.add_subparsers(dest="export_command", metavar="FORMAT")
    ss.required = True
    fmu = ss.add_parser(
        "fmu", help="an FMI 2.0 co-simulation FMU of a tyre model on a road",
        description="Write an FMI 2.0 co-simulation FMU (built with pythonfmu) of a tyre model on "
                    "a road: inputs the wheel centre's pose, velocity and spin (X_WC ... ROTSPEED, "
                    "INCLANGL, YAW_WC), outputs the loads at the wheel centre (FX ... MZ), FZW, "
                    "DEFLECT and more, SI and TYDEX names (docs/cosimulation.md). The tyre's data "
                    "and the road file go inside the FMU; the host needs a Python 3 with tyrelab "
                    "installed.")
    fmu.add_argument("--tyre", default="xzl-16.00R20",
                     help="built-in tyre name, .tir or Chrono .json file (default: xzl-16.00R20)")
    fmu.add_argument("--model", default="point", help="contact model (default: point)")
    fmu.add_argument("--road", default="flat",
                     help="road: flat, cleat:WxH[@ANGLE], bump:H, step:H, pothole:DxL[xW], a track name "
                          f"or FILE{'|'.join(road_suffixes())}[@V] (sizes in mm; default flat)")
    fmu.add_argument("--terrain", default=None, metavar="SOIL",
                     help="a soil over the road (a built-in soil or FILE.toml, copied into the FMU), "
                          "laid round the wheel's position at initialisation, a 12 m window of it "
                          "following the wheel anywhere")
    fmu.add_argument("--pressure", type=pressure_kpa(), default=None, metavar="KPA",
                     help="inflation pressure in kPa (built-in tyres; default 300): the PRESSURE "
                          "parameter's default")
    add_options(fmu)
    fmu.add_argument("--stiffness", choices=("table", "linear"), default=None,
                     help="vertical stiffness: load-deflection spline (table) or linear")
    fmu.add_argument("--handling", default=None,
                     help="tangential force model: none, pac89, mf, tmeasy, tmsimple, fiala (default: "
                          "what the property file describes)")
    add_relaxation(fmu)
    fmu.add_argument("--load", type=load_value, default=0.0,
                     help="INITIAL_LOAD's default: the static load in N (or LC1-LC3) at which the "
                          "model starts in equilibrium (default: none, the model starts unloaded)")
    fmu.add_argument("--frame", choices=("C-axis", "road"), default="C-axis",
                     help="OUTPUT_FRAME's default: the frame of FX ... MZ (default C-axis)")
    fmu.add_argument("--internal-step", type=bounded_float("internal step", 0.0, MAX_DT, "s"),
                     default=0.0, metavar="S",
                     help="INTERNAL_STEP's default: the longest internal step in s (default 0: the "
                          "model's stable step)")
    fmu.add_argument("-o", "--output", default="tyre.fmu", help="the FMU file (default tyre.fmu)")
    fmu.set_defaults(func=run_fmu)


def run_fmu(args) -> int:
    from ..cosim.fmu import export_fmu
    from ..errors import InputError

    out = output_path(args.output, (".fmu",), inputs=input_files(args.tyre, args.road, args.terrain))
    try:
        path = export_fmu(out, tyre=args.tyre, model=args.model, road=args.road,
                          pressure=args.pressure, stiffness=args.stiffness, handling=args.handling,
                          options=model_options(args.option), load=args.load, frame=args.frame,
                          internal_step=args.internal_step, terrain=args.terrain,
                          relaxation=relaxation_value(args))
    except InputError as exc:
        raise renamed(exc, OPTIONS, model_options(args.option)) from None
    ground = args.road if args.terrain is None else f"{args.terrain} over {args.road}"
    print(f"{path}: FMI 2.0 co-simulation FMU, model {args.model} on {ground} "
          "(needs a Python with tyrelab installed in the host)")
    return 0
