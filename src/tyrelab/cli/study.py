"""``tyrelab study``: a validation campaign (spec -> runs on Dask -> results store)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ._common import soil_row_text


def _workers(text: str) -> int:
    """argparse type: a number of worker processes, 1 to 1024."""
    try:
        n = int(text)
    except ValueError:
        n = 0
    if not 1 <= n <= 1024:
        raise argparse.ArgumentTypeError(f"--workers expects a whole number from 1 to 1024, got '{text}'")
    return n


def register(sub):
    p = sub.add_parser("study", help="run a validation campaign (default: the thesis campaign)",
                       description="Expand a study spec (TOML) into runs, compute them as Dask tasks "
                                   "(worker processes on this machine, or a cluster) and keep each "
                                   "run's signal table in a resumable results folder. With no SPEC: "
                                   "the built-in thesis campaign on the XZL 16.00R20, referenced to "
                                   "the ring-tp model (not a measurement).")
    p.add_argument("spec", nargs="?", default=None, help="study spec file (TOML); default: built-in")
    p.add_argument("--example", action="store_true", help="print a commented example spec and exit")
    p.add_argument("--workers", type=_workers, default=None, metavar="N",
                   help="worker processes of the local cluster (default: one per core; at most one "
                        "per 0.5 GiB of the machine's memory)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="a running Dask scheduler, e.g. tcp://host:8786 (default: a local cluster)")
    p.add_argument("-o", "--output", default=None, metavar="FOLDER",
                   help="results folder (default: the spec's [study] output)")
    p.set_defaults(func=run)


def run(args) -> int:
    from .. import study

    if args.example:
        sys.stdout.write(study.example_spec())
        return 0
    from ..io_atomic import check_output_folder

    if args.output is not None:
        check_output_folder(args.output, "-o")
    spec = study.builtin_spec() if args.spec is None else study.load_spec(args.spec)
    output = args.output if args.output is not None else spec.output
    check_output_folder(output, "-o" if args.output is not None else "[study] output")
    result = study.run(spec, workers=args.workers, scheduler=args.scheduler, output=output)
    index = result.index
    done = int((index["status"] == "done").sum()) if len(index) else 0
    failed = index[index["status"] == "failed"] if len(index) else index
    print(f"{output}: {done} runs finished, {len(failed)} failed; {result.reference_note}")
    print(f"report: {Path(output) / study.REPORT}")
    summary = result.summary
    if len(summary):
        print("verdict (thesis Table 5-15 rules):")
        print(summary.to_string())
    soil = result.soil_curves
    if len(soil):
        print("on soil (steady drawbar pull, driving torque, sinkage per model and slip):")
        for test, part in soil.groupby("test", sort=False):
            print(f"  {test}:")
            for row in part.itertuples():
                print("    " + soil_row_text(row, 16))
    for _, row in failed.iterrows():
        print(f"  failed: {row['model']} on {row['test']} at {row['speed_kmh']:g} km/h "
              f"{row['load']}: {row['error']}", file=sys.stderr)
    return 1 if len(failed) else 0
