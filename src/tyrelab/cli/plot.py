"""``tyrelab plot``: a channel of one or more runs against time or distance."""

from __future__ import annotations


def register(sub):
    p = sub.add_parser("plot", help="plot runs (normal force against time, as thesis Figure 5-4)")
    p.add_argument("runs", nargs="+", help="signal tables (.parquet or .csv)")
    p.add_argument("-o", "--output", default="run.png",
                   help="image file, .png, .pdf, .svg or .jpg (default run.png)")
    p.add_argument("--channel", default="FZW", help="channel to plot (default FZW, the normal force)")
    p.add_argument("--x", choices=("time", "distance"), default="time", help="horizontal axis")
    p.add_argument("--label", action="append", default=None,
                   help="legend label for each run, in order (repeat)")
    p.set_defaults(func=run)


def run(args) -> int:
    from pandas.api.types import is_bool_dtype, is_numeric_dtype

    from ..errors import InputError
    from ..io_atomic import IMAGE_SUFFIXES, save_figure
    from ..report.plots import X_AXES, plot_runs
    from ..signal import read_signal
    from ._common import output_path

    out = output_path(args.output, IMAGE_SUFFIXES, inputs=args.runs)
    if args.label and len(args.label) != len(args.runs):
        raise InputError(f"{len(args.label)} labels for {len(args.runs)} runs", field="--label")
    runs = [read_signal(path) for path in args.runs]
    xcol = X_AXES[args.x][0]
    for path, r in zip(args.runs, runs):
        if len(r) == 0:
            raise InputError("the run has no samples", source=path)
        for col, option in ((args.channel, "--channel"), (xcol, "--x")):
            if col not in r.columns:
                raise InputError(f"no channel '{col}' ({option}); it has {', '.join(r.columns)}",
                                 source=path)
            if not is_numeric_dtype(r[col]) or is_bool_dtype(r[col]):
                raise InputError(f"channel '{col}' ({option}) holds {r[col].dtype} values, not numbers; "
                                 "choose a numeric channel", source=path)
    fig = plot_runs(runs, labels=args.label, channel=args.channel, x=args.x)
    save_figure(fig, out, dpi=120)
    print(f"{args.output}: {args.channel} of {len(runs)} run(s)")
    return 0
