"""``tyrelab plot``: a channel of one or more runs against time or distance."""

from __future__ import annotations


def register(sub):
    p = sub.add_parser("plot", help="plot runs (normal force against time, as thesis Figure 5-4)")
    p.add_argument("runs", nargs="+", help="signal tables (.parquet or .csv)")
    p.add_argument("-o", "--output", default="run.png", help="image file (default run.png)")
    p.add_argument("--channel", default="FZW", help="channel to plot (default FZW, the normal force)")
    p.add_argument("--x", choices=("time", "distance"), default="time", help="horizontal axis")
    p.add_argument("--label", action="append", default=None,
                   help="legend label for each run, in order (repeat)")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..errors import InputError
    from ..report.plots import plot_runs
    from ..signal import read_signal

    runs = [read_signal(path) for path in args.runs]
    for path, r in zip(args.runs, runs):
        if args.channel not in r.columns:
            raise InputError(f"no channel '{args.channel}'; it has {', '.join(r.columns)}", source=path)
    if args.label and len(args.label) != len(runs):
        raise InputError(f"{len(args.label)} labels for {len(runs)} runs", field="--label")
    fig = plot_runs(runs, labels=args.label, channel=args.channel, x=args.x)
    fig.savefig(args.output, dpi=120)
    print(f"{args.output}: {args.channel} of {len(runs)} run(s)")
    return 0
