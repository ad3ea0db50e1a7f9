"""The ``tyrelab`` command: a thin layer over the package.

Each subcommand lives in its own module of this package with a
``register(subparsers)`` function that adds its parser and sets
``func(args) -> int``. What a user sees on stderr is always one line per
message, never a traceback:

* bad input (:class:`tyrelab.errors.InputError`, argparse's own errors):
  ``tyrelab: error: ...``, exit status 2;
* a simulation that diverged: ``tyrelab: error: ...`` naming the step and the
  likely parameter, exit status 2;
* a warning (a :class:`tyrelab.guards.PhysicsWarning`, a repeated section
  in a property file ...): ``tyrelab: warning: ...``, the command goes on;
* Ctrl-C: ``tyrelab: interrupted``, exit status 130; ``SIGTERM``:
  ``tyrelab: terminated``, exit status 143 -- both unwind normally, so every
  output being written is removed and a previous file of that name stays;
* the operating system refusing (disk full, permission denied):
  ``tyrelab: error: ...``, exit status 1;
* anything else is a bug: ``tyrelab: internal error (a bug) in 'tyrelab
  CMD': Type: message; run again with --debug for the full trace``, exit
  status 1. ``--debug`` (anywhere on the command line) shows the traceback.
"""

from __future__ import annotations

import argparse
import importlib
import signal
import sys
import threading
import warnings

from .. import stop
from ..errors import InputError

#: subcommand modules, in the order ``tyrelab --help`` lists them
SUBCOMMANDS = ["simulate", "plot", "static", "road", "fit", "modal", "validate", "mf", "curves", "study",
               "soil", "export", "models"]
#: longest message printed for an unexpected error [characters]
MAX_MESSAGE = 400


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread so the command unwinds as on Ctrl-C."""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="tyrelab",
        description="A virtual tyre test lab for rough and off-road terrain.")
    parser.add_argument("--debug", action="store_true",
                        help="show the full Python traceback of an unexpected error")
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


def _one_line(text: str, limit: int = MAX_MESSAGE) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= limit else text[:limit - 3] + "..."


class _LineTracker:
    """sys.stderr while a command runs, remembering whether the cursor was left mid-line:
    a progress bar draws without a newline, and an interrupt can land between its drawing
    and its own record of it (its close then clears nothing)."""

    def __init__(self, stream):
        self._stream = stream
        self.mid_line = False

    def write(self, text):
        # recorded before the write: an interrupt right after the bytes are out (when a
        # watcher sees them) must find the cursor's state already set
        if text:
            self.mid_line = not text.endswith("\n")
        return self._stream.write(text)

    def __getattr__(self, name):
        return getattr(self._stream, name)


def _say(text: str) -> None:
    """One line on stderr starting at the line's start (``\r`` and erase to the end of the
    line first when a progress bar left the cursor mid-line; nothing extra otherwise)."""
    stream = sys.stderr
    if getattr(stream, "mid_line", False):
        stream.write("\r\x1b[K")
    print(text, file=stream)


def _show_warning(message, category, filename, lineno, file=None, line=None):
    _say(f"tyrelab: warning: {_one_line(message)}")


def _set_error(parser, error) -> None:
    """Route argparse's errors of ``parser`` and every nested subcommand parser to ``error``."""
    parser.error = error
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sp in action.choices.values():
                _set_error(sp, error)


#: the signal that asked this command to stop (SIGINT or SIGTERM), once one has
_signalled: list[int] = []


def _on_signal(signum, frame):
    """SIGINT / SIGTERM: remember it and unwind. A signal can arrive while a C library calls
    back into Python (numba compiling through llvmlite), which swallows the exception and
    fails later in some other way; the remembered signal still decides how the command ends,
    and long waits that poll :func:`tyrelab.stop.check` (a study's) stop on it."""
    _signalled.append(signum)
    stop.request(signum)
    if signum == signal.SIGTERM:
        raise Terminated()
    raise KeyboardInterrupt()


def _unraisable(hook_args) -> None:
    """An exception Python could not raise (in a C callback, a destructor): one line, or none
    when it is the interrupt itself."""
    if _signalled or isinstance(hook_args.exc_value, KeyboardInterrupt):
        return
    where = getattr(hook_args.object, "__qualname__", None) or type(hook_args.object).__name__
    _say(f"tyrelab: warning: an error was ignored in {where}: {hook_args.exc_type.__name__}: "
         f"{_one_line(hook_args.exc_value)}")


def _interrupted() -> int | None:
    """Exit status and message if a signal stopped the command, else None."""
    if not _signalled:
        return None
    if _signalled[0] == signal.SIGTERM:
        _say("tyrelab: terminated")
        return 143
    _say("tyrelab: interrupted")
    return 130


def _command(argv) -> str:
    """The verb of the command line (and its action for the verbs that have one)."""
    words = [a for a in argv if not a.startswith("-")]
    if not words:
        return "tyrelab"
    verb = words[:2] if words[0] in ("road", "fit", "mf") else words[:1]
    return "tyrelab " + " ".join(verb)


def main(argv=None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in argv
    argv = [a for a in argv if a != "--debug"]
    main_thread = threading.current_thread() is threading.main_thread()
    _signalled.clear()
    stop.clear()
    previous = {}
    if main_thread:
        for signum in (signal.SIGTERM, signal.SIGINT):
            previous[signum] = signal.signal(signum, _on_signal)
    hook = sys.unraisablehook
    sys.unraisablehook = _unraisable
    stderr = sys.stderr
    sys.stderr = _LineTracker(stderr)   # progress bars write through it (see _say)
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning
            return _main(argv, debug)
    finally:
        stop.clear()  # a later call in this process (a test) starts without it
        sys.stderr = stderr
        sys.unraisablehook = hook
        for signum, handler in previous.items():
            signal.signal(signum, handler)


def _main(argv, debug: bool) -> int:
    try:
        parser = build_parser()

        def error(message):  # argparse's own errors: one line, exit 2
            raise _ArgumentError(message)

        _set_error(parser, error)
        args = parser.parse_args(argv)
        if not getattr(args, "func", None):
            parser.print_help()
            return 1
        return int(args.func(args) or 0)
    except BaseException as exc:
        if isinstance(exc, SystemExit):
            raise
        code = _interrupted()
        if code is not None:
            return code
        if debug and not isinstance(exc, (_ArgumentError, InputError, KeyboardInterrupt)):
            raise
        return _report(exc, argv)


def _report(exc: BaseException, argv) -> int:
    """One line on stderr for the exception that ended the command; returns its exit status."""
    from ..rig.simulation import SimulationError

    if isinstance(exc, _ArgumentError):
        _say(f"tyrelab: error: {_one_line(exc)}")
        return 2
    if isinstance(exc, (InputError, SimulationError)):
        _say(f"tyrelab: error: {_one_line(exc, 2000)}")
        return 2
    if isinstance(exc, Terminated):
        _say("tyrelab: terminated")
        return 143
    if isinstance(exc, KeyboardInterrupt):
        _say("tyrelab: interrupted")
        return 130
    if isinstance(exc, MemoryError):
        _say(f"tyrelab: error: out of memory ({_one_line(exc) or 'MemoryError'}); ask for less "
             "(a coarser step, a shorter run)")
        return 1
    if isinstance(exc, OSError):  # the system refused: disk full, permission denied ...
        what = exc.strerror or _one_line(exc)
        where = f": {exc.filename}" if getattr(exc, "filename", None) else ""
        _say(f"tyrelab: error: {what}{where}")
        return 1
    _say(f"tyrelab: internal error (a bug) in '{_command(argv)}': {type(exc).__name__}: "
         f"{_one_line(exc)}; run again with --debug for the full trace")
    return 1


if __name__ == "__main__":
    sys.exit(main())
