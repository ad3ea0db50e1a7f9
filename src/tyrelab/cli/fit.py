"""``tyrelab fit``: parameter identification from test data.

``fit vertical|damping|patch|shape FILES -o tyre.tir`` fits one step of
thesis chapter 4 (:mod:`tyrelab.fit.workflow`) from test files (CSV or TYDEX
named as :mod:`tyrelab.fit.lab_files` says, or a campaign folder whose tests
of that kind are used); ``fit all CAMPAIGN -o tyre.tir`` runs every step on a
campaign (:mod:`tyrelab.fit.campaign`). An existing output file is updated
(its other sections and its units kept); ``--into BASE.tir`` starts from
another file. A fit report (HTML) is written beside the output unless
``--no-report``. ``fit ring CAMPAIGN`` identifies the flexible ring from a
campaign (:mod:`tyrelab.fit.ring_step`; ``fit all`` runs it too unless
``--skip ring``); ``fit ring`` without a campaign identifies a built-in
tyre's ring from the thesis's tables. ``fit cams``
runs the enveloping model's cam-count study (:mod:`tyrelab.fit.cams`, thesis
6.2): a CSV table, an error-against-cost PNG beside it, the recommended
N_LENGTH x N_WIDTH printed (and, with ``--into BASE``, written into a copy of
BASE named after the output, ``NAME.tir``). ``fit tmeasy TYRE`` fits TMeasy's
parameters to the tyre's own handling model's curves (:mod:`tyrelab.cli.fit_tmeasy`).
"""

from __future__ import annotations

import sys

from ..limits import MAX_FIT_EVALUATIONS
from ._common import count, positive_float

#: step -> (test kind its loose files are, help)
STEPS = {"vertical": ("load_deflection", "linear stiffness and load-deflection table from plate presses "
                                         "(thesis 3.3.1, 4.2)"),
         "damping": ("drop_test", "tyre damping from a trailer drop test: the rig fitted to the trace, "
                                  "beside eqs. 3.1-3.7"),
         "patch": ("contact_patch", "PA1/PA2 (eq. 2.3), PB1-PB3 (eq. 2.4) and the half-width table from "
                                    "contact-patch sizes (4.4)"),
         "shape": ("carcass_profile", "the [SHAPE] table from the carcass profile (4.3)")}


def register(sub):
    p = sub.add_parser("fit", help="identify model parameters from test data")
    fsub = p.add_subparsers(dest="fit_kind", metavar="MODEL")
    r = fsub.add_parser("ring", help="identify the flexible ring from a campaign (or a built-in tyre)",
                        description="Fit the ring model to a campaign's flat-plate presses (one or "
                                    "more pressures), modal results (Table 3-3 form), the file's drop-"
                                    "test damping and eq. 2.3 contact length, and its dynamic cleat "
                                    "runs marked use = \"fit\"; reports fitted and held-out errors "
                                    "(minutes). Without CAMPAIGN: a built-in tyre's thesis data.")
    r.add_argument("campaign", nargs="?", metavar="CAMPAIGN", default=None,
                   help="campaign folder or its campaign.toml (default: the built-in --tyre)")
    r.add_argument("--tyre", default="xzl-16.00R20", help="built-in tyre with lab data (without CAMPAIGN)")
    _evaluations(r)
    _outputs(r, default=None)
    r.set_defaults(func=run_ring)
    for step, (kind, text) in STEPS.items():
        s = fsub.add_parser(step, help=text, description=text + ". FILES: test files (CSV or TYDEX, "
                            "columns named by quantity and unit, e.g. deflection_mm, load_N), or a "
                            "campaign folder / campaign.toml whose tests of this kind are used.")
        s.add_argument("files", nargs="+", metavar="FILE", help=f"{kind} files or a campaign")
        if step == "vertical":
            s.add_argument("--table-step", type=positive_float("--table-step", 1e-3), default=None,
                           help="deflection step of the table a raw loop is averaged onto, mm "
                                "(default 5)")
        if step == "damping":
            from ._common import load_value
            s.add_argument("--load", type=load_value, default=None,
                           help="trailer load case of the drop (LC1-LC3) or wheel load in N (default LC1)")
        _outputs(s)
        s.set_defaults(func=run_step, step=step)
    a = fsub.add_parser("all", help="every step of thesis chapter 4 from a test campaign",
                        description="Fit vertical, damping, patch, shape and the flexible ring from "
                                    "a campaign folder (campaign.toml and its files); steps without "
                                    "tests are skipped with a note.")
    a.add_argument("campaign", metavar="CAMPAIGN", help="campaign folder or its campaign.toml")
    a.add_argument("--skip", action="append", default=[], metavar="STEP",
                   choices=("vertical", "damping", "patch", "shape", "ring"),
                   help="a step not to run (repeatable), e.g. --skip ring for a fit in seconds")
    _evaluations(a)
    _outputs(a)
    a.set_defaults(func=run_all)
    _register_cams(fsub)
    from .fit_tmeasy import register_tmeasy
    register_tmeasy(fsub)
    p.set_defaults(func=lambda args: (p.print_help(), 1)[1])


def _register_cams(fsub):
    from ..fit.cams import ABS_TOL, COST_TOL, MAX_CAMS, MIN_CAMS, REL_TOL
    from ..limits import MAX_SPEED, MIN_SPEED
    from ._common import bounded_float, load_value, pressure_kpa
    c = fsub.add_parser("cams", help="cam-count study of the enveloping model: error against cost "
                                     "(thesis 6.2)",
                        description="Run the enveloping model at every N_LENGTH x N_WIDTH on the "
                                    "trailer over each road and speed, compare its FZW with a reference "
                                    "over the disturbance (RMS error, %% of the reference's peak), time it "
                                    "and recommend the cheapest pair within the tolerance of the best. "
                                    "Writes the table (CSV) and a plot (PNG, same name).")
    c.add_argument("--tyre", default="xzl-16.00R20", help="built-in tyre name or .tir file "
                                                          "(default: xzl-16.00R20)")
    c.add_argument("--pressure", type=pressure_kpa(), default=None, metavar="KPA",
                   help="inflation pressure in kPa (built-in tyres; default 300)")
    cams = count("cam count", MIN_CAMS, MAX_CAMS)
    c.add_argument("--lengths", type=cams, nargs="+", default=[1, 3, 5, 7], metavar="N",
                   help=f"cams along the patch, {MIN_CAMS} to {MAX_CAMS} (default 1 3 5 7)")
    c.add_argument("--widths", type=cams, nargs="+", default=[1, 3, 6], metavar="N",
                   help=f"cams across the patch, {MIN_CAMS} to {MAX_CAMS} (default 1 3 6)")
    c.add_argument("--road", nargs="+", action="extend", default=None, metavar="R",
                   help="roads (default cleat:50x50)")
    c.add_argument("--speed", nargs="+", action="extend", default=None, metavar="KMH",
                   type=bounded_float("speed", MIN_SPEED * 3.6, MAX_SPEED * 3.6, "km/h", scale=1 / 3.6),
                   help="towing speeds in km/h (default 12)")
    c.add_argument("--load", type=load_value, default="LC1",
                   help="load case LC1-LC3 or a wheel load in N (default LC1)")
    c.add_argument("--reference", default="ring",
                   help="a contact model (ring, ring-tp, volume ...), enveloping:NLxNW, or a measured "
                        "run (.tdx, .csv, .parquet; one road and speed) (default ring)")
    c.add_argument("--duration", type=positive_float("--duration"), default=None,
                   help="simulated seconds per run (default: to the road's end)")
    c.add_argument("--repeat", type=count("--repeat", 1, 100), default=5,
                   help="timed runs per configuration, the fastest counts (default 5)")
    c.add_argument("--rel-tol", type=bounded_float("--rel-tol", 0.0, 10.0), default=REL_TOL,
                   help=f"tolerance relative to the best error (default {REL_TOL:g})")
    c.add_argument("--abs-tol", type=bounded_float("--abs-tol", 0.0, 100.0), default=ABS_TOL,
                   help=f"tolerance in percentage points (default {ABS_TOL:g}); the larger counts")
    c.add_argument("--cost-tol", type=bounded_float("--cost-tol", 0.0, 10.0), default=COST_TOL,
                   help=f"costs within this fraction of the cheapest count as equal (default {COST_TOL:g})")
    c.add_argument("--into", metavar="BASE", default=None,
                   help="also write a copy of this property file (or built-in tyre) with the "
                        "recommended N_LENGTH / N_WIDTH, named after the output (NAME.tir)")
    c.add_argument("-o", "--output", default="cams.csv", help="table to write (.csv)")
    c.set_defaults(func=run_cams)


def _evaluations(p):
    p.add_argument("--max-evaluations", type=count("--max-evaluations", 1, MAX_FIT_EVALUATIONS), default=25,
                   help=f"the ring's optimizer budget, 1 to {MAX_FIT_EVALUATIONS} (default 25)")


def _outputs(p, default="tyre.tir"):
    p.add_argument("-o", "--output", default=default,
                   help="property file to write (.tir); an existing file is updated, its other "
                        "sections and units kept (default tyre.tir; ring.tir for a built-in ring)")
    p.add_argument("--into", metavar="BASE", default=None,
                   help="start from this property file (or built-in tyre) instead")
    p.add_argument("--radius", type=positive_float("--radius", 1e-3), default=None,
                   help="unloaded radius, mm (a new file without a campaign [tyre] table)")
    p.add_argument("--width", type=positive_float("--width", 1e-3), default=None,
                   help="section width, mm (likewise)")
    p.add_argument("--report", default=None,
                   help="fit report to write (.html; default: beside the output, NAME_fit.html)")
    p.add_argument("--no-report", action="store_true", help="write no report")


def run_ring(args) -> int:
    if args.campaign is not None:
        from ..fit.campaign import read_campaign
        args.output = args.output or "tyre.tir"
        _paths(args, [args.campaign, args.into])
        campaign = read_campaign(args.campaign)
        return _fit(args, campaign, _ring_steps(args, campaign), [campaign.source, args.into])
    from ..errors import InputError
    from ..fit.ring import fit_ring, markdown_table, write_ring_file
    from ..io_atomic import check_output_path
    from ..tyre.library import BUILT_IN

    args.output = args.output or "ring.tir"
    out = check_output_path(args.output, (".tir",), "-o")
    if args.tyre not in BUILT_IN:
        raise InputError(f"ring identification without a campaign needs the lab data of a built-in "
                         f"tyre ({', '.join(BUILT_IN)}), got '{args.tyre}'", field="--tyre")
    with _ring_bar(args) as step:
        params, fitted, held = fit_ring(args.tyre, max_nfev=args.max_evaluations, progress=step)
    write_ring_file(params, out)
    print("fitted data:\n" + markdown_table(fitted))
    print("\nheld-out predictions:\n" + markdown_table(held))
    print(f"\n{args.output}: ring parameters")
    return 0


def _ring_bar(args):
    """A context giving the ring's progress callback (a bar of model evaluations)."""
    from contextlib import contextmanager

    from tqdm import tqdm

    from ..fit.ring import FREE

    @contextmanager
    def bar():
        # least_squares evaluates the residuals once per step and once per free
        # parameter for each finite-difference Jacobian: an upper bound. No fixed position:
        # tqdm puts it under `fit all`'s bar, and alone it is line 0, whose closing returns
        # the cursor to the line's start (a bar at position 1 closes with the cursor past
        # its cleared text, and the next message would be printed there)
        with tqdm(total=args.max_evaluations * (len(FREE) + 1), unit="model", desc="identifying ring",
                  leave=False, delay=1.0) as b:
            def step(cost):
                b.update(1)
                b.set_postfix(cost=f"{cost:.4g}")
            yield step
    return bar()


def _paths(args, inputs):
    """Checked output and report paths, before any work."""
    from pathlib import Path

    from ..io_atomic import check_output_path
    out = check_output_path(args.output, (".tir",), "-o", inputs)
    report = None
    if not args.no_report:
        report = args.report or str(Path(args.output).with_name(Path(args.output).stem + "_fit.html"))
        report = check_output_path(report, (".html",), "--report", [*inputs, args.output])
    return out, report


def _ring_steps(args, campaign) -> tuple[str, ...]:
    """The ring's fit starts from the tyre's vertical law and its drop-test damping: from the
    base file when it has them, else fitted first from the campaign's own load-deflection and
    drop tests (so ``fit ring CAMPAIGN`` works on its own, without ``fit all`` or ``--into``)."""
    from ..fit import lab_files as lf
    from ..fit.workflow import start_tir
    start = start_tir(campaign, _base(args, campaign))   # as the fit starts: --into, -o or the manifest's
    has = {"vertical": start.has("VERTICAL", "VERTICAL_STIFFNESS")
           or start.table("DEFLECTION_LOAD_CURVE") is not None,
           "damping": start.number("VERTICAL", "VERTICAL_DAMPING", 0.0) > 0}
    tests = {"vertical": lf.LoadDeflection, "damping": lf.DropTrace}
    first = tuple(step for step in ("vertical", "damping") if not has[step]
                  and [t for t in campaign.of(tests[step]) if t.use == "fit"])
    if first:
        them = "them" if len(first) > 1 else "it"
        print(f"tyrelab: the start has no {' or '.join(first)} fit: fitting {them} first from the "
              "campaign's own tests", file=sys.stderr)
    return first + ("ring",)  # what is still missing, the ring fit names


def _base(args, campaign):
    """The file the fit starts from: --into, else an existing output, else none (a new file)."""
    from pathlib import Path

    from ..errors import InputError
    from ..tyre.tir import read_tir
    if args.into:
        if Path(args.into).is_file():
            return read_tir(args.into)
        from ..tyre.library import BUILT_IN, SINGLE_FILE, load_tyre
        if args.into in BUILT_IN or args.into in SINGLE_FILE:
            return load_tyre(args.into).tir
        raise InputError(f"no such property file or built-in tyre '{args.into}'", field="--into")
    if Path(args.output).is_file():
        return read_tir(args.output)
    if campaign.base is None:
        for key in ("radius", "width"):
            if getattr(args, key) is not None:
                campaign.tyre[{"radius": "unloaded_radius"}.get(key, key)] = getattr(args, key)
        if "unloaded_radius" not in campaign.tyre or "width" not in campaign.tyre:
            raise InputError("a new property file needs the tyre's unloaded radius and width: give "
                             "--radius and --width (mm), --into BASE.tir, or a campaign whose "
                             "campaign.toml has them in [tyre]", field="-o")
    return None


def _fit(args, campaign, steps, inputs, **skip) -> int:
    """Fit ``steps`` of ``campaign``, write the file and the report, print the summary."""
    from tqdm import tqdm

    from ..fit.workflow import fit_campaign
    from ..tyre.tir import write_tir
    out, report = _paths(args, inputs + [t.source for t in campaign.tests])
    base = _base(args, campaign)
    if base is not None:
        for key in ("radius", "width"):
            if getattr(args, key) is not None:
                campaign.tyre[{"radius": "unloaded_radius"}.get(key, key)] = getattr(args, key)
    ring = "ring" in steps and getattr(args, "max_evaluations", None)
    # delay: a mistake found at once is one line, with no bar drawn before it
    with tqdm(total=len(steps) + 1, desc="fitting", unit="step", leave=False, delay=1.0) as bar:
        if ring:
            with _ring_bar(args) as step:
                result = fit_campaign(campaign, steps, base, progress=lambda name: bar.update(1),
                                      ring_evaluations=args.max_evaluations, ring_progress=step,
                                      **skip)
        else:
            result = fit_campaign(campaign, steps, base, progress=lambda name: bar.update(1), **skip)
    write_tir(result.tir, out, units=result.tir.units or None)
    if report is not None:
        from ..report.fit_report import figure_count, write_report
        with tqdm(total=figure_count(result), desc="report", unit="figure", leave=False) as bar:
            write_report(result, report, progress=lambda: bar.update(1))
    print(summary(result))
    print(f"\n{out}: property file" + (f"\n{report}: fit report" if report else ""))
    return 0


def summary(result) -> str:
    """The fitted parameters and notes as Markdown text."""
    from ..fit.workflow import shown
    lines = ["| parameter | value | RMS, fitted | error, held out | equation |", "|---|---|---|---|---|"]
    for step in result.steps.values():
        for r in step.rows:
            held = "; ".join(f"{k}: {shown(v, r['error_unit'])}" for k, v in (r["held_out"] or {}).items())
            lines.append(f"| {r['parameter']} | {shown(r['value'], r['unit'])} | "
                         f"{shown(r['rms'], r['error_unit'])} | {held} | {r['equation']} |")
    return "\n".join(lines + [""] + [f"- {n}" for n in result.notes])


def run_step(args) -> int:
    from ..fit.campaign import loose_files
    kind = STEPS[args.step][0]
    options = {}
    if args.step == "vertical" and args.table_step is not None:
        options["step"] = args.table_step
    if args.step == "damping" and args.load is not None:
        options["load_case"] = args.load
    _paths(args, [*args.files, args.into])
    campaign = loose_files(args.files, kind, **options)
    return _fit(args, campaign, (args.step,), [*args.files, args.into])


def run_all(args) -> int:
    from ..fit.campaign import read_campaign
    from ..fit.workflow import STEPS as ALL
    _paths(args, [args.campaign, args.into])
    campaign = read_campaign(args.campaign)
    steps = tuple(s for s in ALL if s not in args.skip)
    return _fit(args, campaign, steps, [campaign.source, args.into], skip_missing=True,
                skipped=tuple(dict.fromkeys(args.skip)))


def run_cams(args) -> int:
    from pathlib import Path

    from tqdm import tqdm

    from ..errors import InputError
    from ..fit.cams import cam_count_study, check_reference, study_runs, tir_lines
    from ..io_atomic import atomic_write, check_output_path
    from ..report.cam_study import plot_cam_study
    from ._common import input_files

    roads = args.road or ["cleat:50x50"]
    speeds = args.speed or [12 / 3.6]
    inputs = input_files(args.tyre, args.reference, args.into, *roads)
    out = check_output_path(args.output, (".csv",), "-o", inputs)
    png = check_output_path(out.with_suffix(".png"), (".png",), "-o", inputs)
    tir_out = base = None
    if args.into:
        from ..tyre.tir import read_tir
        tir_out = check_output_path(out.with_suffix(".tir"), (".tir",), "--into", inputs)
        if Path(args.into).is_file():
            base = read_tir(args.into)
        else:
            from ..tyre.library import BUILT_IN, SINGLE_FILE, load_tyre
            if args.into not in BUILT_IN and args.into not in SINGLE_FILE:
                raise InputError(f"no such property file or built-in tyre '{args.into}'", field="--into")
            base = load_tyre(args.into).tir
    check_reference(args.reference)  # before the progress bar
    from ..road.spec import road_from_spec
    for road in roads:  # an unknown road or a bad size: before the progress bar too
        road_from_spec(road)
    total = study_runs(args.lengths, args.widths, roads, speeds, args.reference)
    with tqdm(total=total, desc="cam study", unit="config", leave=False) as bar:
        def step(label):
            bar.set_postfix_str(label)
            bar.update(1)
        study = cam_count_study(args.tyre, args.lengths, args.widths, roads, speeds, load=args.load,
                                reference=args.reference, pressure=args.pressure,
                                duration=args.duration, repeat=args.repeat, rel_tol=args.rel_tol,
                                abs_tol=args.abs_tol, cost_tol=args.cost_tol, progress=step)
    table = study.table.copy()
    table.insert(table.columns.get_loc("speed") + 1, "speed_kmh", table["speed"] * 3.6)
    atomic_write(out, lambda tmp: table.to_csv(tmp, index=False, float_format="%.6g"))
    plot_cam_study(study, png)
    nl, nw = study.recommended
    shown = study.summary.assign(**{"wall_ms_per_s": study.summary["wall_s_per_sim_s"] * 1e3})
    print(shown[["n_length", "n_width", "error_pct", "wall_ms_per_s", "qualifies"]]
          .to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    print(f"\nmetric: {study.metric}; reference: {study.reference}")
    print(f"rule: {study.rule}")
    print(f"recommended: N_LENGTH = {nl}, N_WIDTH = {nw}")
    if tir_out is not None:
        from ..tyre.tir import write_tir
        base.set("CONTACT_PATCH", "N_LENGTH", int(nl))
        base.set("CONTACT_PATCH", "N_WIDTH", int(nw))
        write_tir(base, tir_out, units=base.units or None)
        print(f"{tir_out}: {args.into} with the recommended counts")
    else:
        print("add to the property file:\n" + tir_lines(study.recommended))
    print(f"\n{out}: table\n{png}: plot")
    return 0
