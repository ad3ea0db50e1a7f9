"""The one exception type that reaches a user.

Every reader and parser raises :class:`InputError` for bad input, naming the
file, line or field and what was expected. The command line catches it and
prints the message as one line on stderr with a non-zero exit; Python users get
an ordinary exception with the same message.
"""

from __future__ import annotations

from contextlib import contextmanager


class InputError(ValueError):
    """Bad input from a user: a file, a field, a command-line value.

    Parameters
    ----------
    message : str
        What was wrong and what was expected.
    source : str, optional
        The file (or "command line", "study spec") the bad input came from.
    line : int, optional
        1-based line number in ``source``.
    field : str, optional
        The key, column or option that was wrong.
    """

    def __init__(self, message: str, source: str | None = None,
                 line: int | None = None, field: str | None = None):
        self.source = source
        self.line = line
        self.field = field
        self.reason = message
        where = ""
        if source is not None:
            where = str(source)
            if line is not None:
                where += f", line {line}"
            where += ": "
        if field is not None:
            where += f"{field}: "
        super().__init__(where + message)


def named(known: dict, name: str, what: str, field: str):
    """``known[name]``; an unknown name is an :class:`InputError` listing the known ones
    ("unknown rig 'x', expected one of trailer, quarter-vehicle, ...") on ``field``: the
    lookup of every registry (models, rigs, terrains)."""
    if name not in known:
        raise InputError(f"unknown {what} '{name}', expected one of {', '.join(known)}", field=field)
    return known[name]


@contextmanager
def naming(source):
    """Within it, an :class:`InputError` that names no file is raised again naming ``source``
    (the file, or files, the data it refused came from), its field and reason kept."""
    try:
        yield
    except InputError as exc:
        if exc.source is not None:
            raise
        raise InputError(exc.reason, source=source, field=exc.field) from None
