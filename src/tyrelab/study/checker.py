"""Checking a parsed TOML document field by field, each failure one line naming the
file, the line (:mod:`tyrelab.core.toml_lines`) and the key path."""

from __future__ import annotations

import json
import math
from pathlib import Path

from ..errors import InputError
from ..core.toml_lines import BARE_KEY, TomlLocator


def describe_value(value) -> str:
    if isinstance(value, bool):
        return f"the boolean {str(value).lower()}"
    if isinstance(value, (int, float)):
        return f"the number {value!r}"
    if isinstance(value, str):
        return f"the string {json.dumps(value)}"
    if isinstance(value, list):
        return "an array"
    if isinstance(value, dict):
        return "a table"
    return f"a date/time ({value})"


def _format_path(path) -> str:
    out = ""
    for part in path:
        if isinstance(part, int):
            out += f"[{part + 1}]"
        else:
            name = part if BARE_KEY.fullmatch(part) else json.dumps(part)
            out += ("." if out else "") + name
    return out or "(top level)"


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


class Checker:
    def __init__(self, text: str, source, base: Path):
        self.text = text
        self.source = str(source)
        self.base = base
        self._locator: TomlLocator | None = None

    def fail(self, path, message: str):
        line = None
        try:  # the locator reads any valid TOML; should it not, the message still stands
            if self._locator is None:
                self._locator = TomlLocator(self.text)
            line = self._locator.line(path)
        except (ValueError, IndexError):
            pass
        raise InputError(message, source=self.source, line=line, field=_format_path(path))

    # -- generic checks -------------------------------------------------------
    def table(self, value, path, allowed, required=(), what="a table"):
        if not isinstance(value, dict):
            self.fail(path, f"expected {what}, got {describe_value(value)}")
        for key in value:
            if key not in allowed:
                self.fail(path + (key,), f"unknown key {json.dumps(key)}; allowed keys: {', '.join(allowed)}")
        for key in required:
            if key not in value:
                self.fail(path, f"missing key '{key}' (required; keys: {', '.join(allowed)})")
        return value

    def array_of_tables(self, doc, key):
        value = doc.get(key)
        if value is None:
            self.fail((key,), f"missing: the spec needs at least one [[{key}]] table")
        if not isinstance(value, list) or not value:
            self.fail((key,), f"expected one or more [[{key}]] tables, got {describe_value(value)}")
        return value

    def string(self, value, path, what="a string"):
        if not isinstance(value, str):
            self.fail(path, f"expected {what}, got {describe_value(value)}")
        return value

    def label(self, value, path):
        self.string(value, path, "a non-empty label (string)")
        if not value.strip() or any(ord(c) < 32 or ord(c) == 127 for c in value):
            self.fail(path, f"expected a non-empty label without control characters, got {json.dumps(value)}")
        return value

    def number(self, value, path, what, low=None, high=None, low_open=True):
        """A finite number in (low, high] (or [low, high] with ``low_open=False``)."""
        if not _is_number(value):
            self.fail(path, f"expected {what}, got {describe_value(value)}")
        v = float(value)
        bad = (not math.isfinite(v) or (low is not None and (v <= low if low_open else v < low))
               or (high is not None and v > high))
        if bad:
            self.fail(path, f"expected {what}, got {value!r}")
        return v

    def unique_label(self, value, path, seen: dict, what: str) -> str:
        """A label not used before in ``seen`` (label -> index, updated); ``path`` is
        (table, index, key)."""
        name = self.label(value, path)
        if name in seen:
            self.fail(path, f"duplicate {what} label {json.dumps(name)} (also {what}[{seen[name] + 1}])")
        seen[name] = path[1]
        return name

    def choice(self, value, path, known, what):
        self.string(value, path, f"a {what} name")
        if value not in known:
            self.fail(path, f"unknown {what} {json.dumps(value)}; expected one of: {', '.join(known)}")
        return value

    def path(self, value, path, what) -> Path:
        self.string(value, path, f"the path of {what}")
        if not value.strip():
            self.fail(path, f"expected the path of {what}, got an empty string")
        p = Path(value).expanduser()
        p = p if p.is_absolute() else self.base / p
        if not p.is_file():
            self.fail(path, f"no such {what}: {p}")
        return p.resolve()
