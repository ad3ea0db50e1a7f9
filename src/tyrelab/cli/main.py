"""The ``tyrelab`` command: a thin layer over the package.

Each subcommand lives in its own module of this package with a
``register(subparsers)`` function that adds its parser and sets
``func(args) -> int``. Bad input raises :class:`tyrelab.errors.InputError`;
it is printed here as one line on stderr with exit status 2, never as a
traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from ..errors import InputError

#: subcommand modules, in the order ``tyrelab --help`` lists them
SUBCOMMANDS = ["simulate", "plot", "static", "road", "fit", "modal", "validate", "mf", "study"]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="tyrelab",
        description="A virtual tyre test lab for rough and off-road terrain.")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in SUBCOMMANDS:
        try:
            module = importlib.import_module(f"tyrelab.cli.{name}")
        except ModuleNotFoundError as exc:
            if exc.name == f"tyrelab.cli.{name}":
                continue  # subcommand not built yet
            raise
        module.register(sub)
    return parser


class _ArgumentError(Exception):
    pass


def main(argv=None) -> int:
    parser = build_parser()

    def error(message):  # argparse's own errors: one line, exit 2
        raise _ArgumentError(message)

    parser.error = error
    for action in parser._subparsers._group_actions if parser._subparsers else []:
        for sp in action.choices.values():
            sp.error = error
    try:
        args = parser.parse_args(argv)
        if not getattr(args, "func", None):
            parser.print_help()
            return 1
        return int(args.func(args) or 0)
    except _ArgumentError as exc:
        print(f"tyrelab: error: {exc}", file=sys.stderr)
        return 2
    except InputError as exc:
        print(f"tyrelab: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("tyrelab: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
