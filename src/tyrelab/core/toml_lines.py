"""Where things are in a TOML text: tomllib gives no line numbers; study specs and fit campaigns need them."""

from __future__ import annotations

import bisect
import re
import tomllib

#: a bare TOML key
BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


class TomlLocator:
    """The line of every table, key and array element of a (valid) TOML text.

    Paths are tuples: keys as str, array-of-tables and array indices as int
    (from 0). Inline tables and arrays are followed, so
    ``("test", 2, "reference", "files", 1)`` is found too.
    """

    def __init__(self, text: str):
        self.text = text
        self.n = len(text)
        self.pos = 0
        self._newlines = [i for i, c in enumerate(text) if c == "\n"]
        self.lines: dict[tuple, int] = {}
        self._arrays_of_tables: dict[tuple, int] = {}
        self._scan()

    def line_at(self, pos: int) -> int:
        return bisect.bisect_left(self._newlines, pos) + 1

    def line(self, path) -> int | None:
        """Line of ``path``, else of its nearest enclosing key or table found."""
        path = tuple(path)
        for k in range(len(path), 0, -1):
            if path[:k] in self.lines:
                return self.lines[path[:k]]
        return None

    # -- lexing -----------------------------------------------------------
    def _peek(self, k: int = 0) -> str:
        i = self.pos + k
        return self.text[i] if i < self.n else ""

    def _blank(self, newlines: bool = False):
        """Skip spaces and tabs (and with ``newlines``, line ends and comments)."""
        while self.pos < self.n:
            c = self.text[self.pos]
            if c in " \t" or (newlines and c in "\r\n"):
                self.pos += 1
            elif c == "#" and newlines:
                self._comment()
            else:
                break

    def _comment(self):
        end = self.text.find("\n", self.pos)
        self.pos = self.n if end < 0 else end

    def _string(self):
        """Skip a string at ``pos`` (any of TOML's four kinds)."""
        q = self._peek()
        triple = self.text.startswith(q * 3, self.pos)
        self.pos += 3 if triple else 1
        while self.pos < self.n:
            c = self.text[self.pos]
            if c == "\\" and q == '"':
                self.pos += 2
                continue
            if triple and self.text.startswith(q * 3, self.pos):
                self.pos += 3
                while self._peek() == q:  # up to two quotes may end the content
                    self.pos += 1
                return
            self.pos += 1
            if not triple and c == q:
                return

    def _key(self) -> list[str]:
        """A dotted key at ``pos``: its parts, decoded as TOML does."""
        parts = []
        while True:
            self._blank()
            start = self.pos
            if self._peek() in "\"'":
                self._string()
                raw = self.text[start:self.pos]
                parts.append(next(iter(tomllib.loads(f"{raw} = 0"))))
            else:
                m = BARE_KEY.match(self.text, self.pos)
                if m is None:  # not reached for valid TOML
                    raise ValueError(f"cannot read a key at offset {self.pos}")
                self.pos = m.end()
                parts.append(m.group())
            self._blank()
            if self._peek() != ".":
                return parts
            self.pos += 1

    def _value(self, path: tuple):
        c = self._peek()
        if c == "[":
            self.pos += 1
            i = 0
            while True:
                self._blank(newlines=True)
                if self._peek() in ("]", ""):
                    self.pos += 1
                    return
                self.lines[path + (i,)] = self.line_at(self.pos)
                self._value(path + (i,))
                self._blank(newlines=True)
                if self._peek() == ",":
                    self.pos += 1
                i += 1
        elif c == "{":
            self.pos += 1
            while True:
                self._blank(newlines=True)
                if self._peek() in ("}", ""):
                    self.pos += 1
                    return
                self._assignment(path)
                self._blank(newlines=True)
                if self._peek() == ",":
                    self.pos += 1
        elif c in "\"'":
            self._string()
        else:  # number, boolean, date-time: up to a separator
            while self.pos < self.n and self.text[self.pos] not in ",]}#\r\n":
                self.pos += 1

    def _assignment(self, table: tuple):
        start = self.pos
        path = table + tuple(self._key())
        self.lines.setdefault(path, self.line_at(start))
        self._blank()
        if self._peek() == "=":
            self.pos += 1
        self._blank()
        self._value(path)

    def _resolve(self, names) -> tuple:
        """A header's path: each array of tables on the way stands for its last element."""
        path: tuple = ()
        for name in names:
            path += (name,)
            if path in self._arrays_of_tables:
                path += (self._arrays_of_tables[path] - 1,)
        return path

    def _scan(self):
        table: tuple = ()
        while True:
            self._blank(newlines=True)
            if self.pos >= self.n:
                return
            start = self.pos
            if self._peek() == "[":
                double = self._peek(1) == "["
                self.pos += 2 if double else 1
                names = self._key()
                self.pos += 2 if double else 1
                if double:
                    parent = self._resolve(names[:-1]) + (names[-1],)
                    count = self._arrays_of_tables.get(parent, 0) + 1
                    self._arrays_of_tables[parent] = count
                    table = parent + (count - 1,)
                else:
                    table = self._resolve(names)
                self.lines.setdefault(table, self.line_at(start))
            else:
                self._assignment(table)
            self._blank()
            if self._peek() == "#":
                self._comment()
