"""A stop asked for by a signal, remembered for code whose own exception may be swallowed.

The command line turns SIGTERM and Ctrl-C into an exception raised in the main thread
(:mod:`tyrelab.cli.main`). Python runs a signal handler between any two bytecodes of the
main thread, also inside a finalizer or a callback whose exceptions are only reported
(``sys.unraisablehook``), never raised: a study waiting on its workers, whose futures and
comms run such callbacks all the time, then simply went on computing. The handler also
records the stop here, and long waits poll :func:`check`.
"""

from __future__ import annotations

_requested: list[int] = []


def request(signum: int) -> None:
    """Remember that signal ``signum`` asked the command to stop."""
    _requested.append(int(signum))


def requested() -> int | None:
    """The first signal that asked for a stop, or None."""
    return _requested[0] if _requested else None


def clear() -> None:
    """Forget earlier requests (a new command starts)."""
    _requested.clear()


def check() -> None:
    """Raise KeyboardInterrupt if a stop was asked for (the caller unwinds as on Ctrl-C)."""
    if _requested:
        raise KeyboardInterrupt(f"stopped by signal {_requested[0]}")
