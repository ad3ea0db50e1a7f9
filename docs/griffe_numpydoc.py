"""A griffe extension for the API reference (mkdocs.yml, ``mkdocstrings`` ``extensions``).

tyrelab's docstrings are numpydoc as Sphinx reads it; two habits of theirs
render badly through mkdocstrings' numpy parser, and this extension mends
them in the text before it is parsed (the source files are not touched):

* a plain paragraph after the items of a ``Parameters`` (``Returns`` ...)
  section -- numpydoc's sections run to the next header, so griffe reads
  each line of such a paragraph as a parameter ("Every", "that" ...). A
  ``Notes`` header is put before the first non-indented line that is not
  an item (``name``, ``a, b : type``, ``*args``);
* reStructuredText simple tables (rows between ``=====  ====`` rules),
  which Markdown would read as headings, become preformatted text;
* Sphinx roles (``:class:`~tyrelab.tyre.params.Tyre```, ``:func:``,
  ``:mod:``, ``:data:``, ``:attr:``, ``:meth:``, ``:exc:``) become code
  spans with the object's path (``~``: its last component only).
"""

from __future__ import annotations

import re

import griffe

#: numpydoc sections whose body is a list of items
_ITEM_SECTIONS = {"parameters", "other parameters", "returns", "yields", "receives", "raises",
                  "warns", "attributes", "methods"}
#: an item line: names (``a``, ``a, b``, ``*args``) optionally followed by `` : type``
_ITEM = re.compile(r"\*{0,2}[A-Za-z_]\w*(\s*,\s*\*{0,2}[A-Za-z_]\w*)*(\s*:.*)?")
_DASHES = re.compile(r"-{3,}")
_RST_RULE = re.compile(r"[ \t]*=+( +=+)+[ \t]*")
_ROLE = re.compile(r":(?:py:)?(?:class|func|mod|data|attr|meth|exc|obj|const):`(~?)([^`<]+?)`")


def _role(match: re.Match) -> str:
    path = match.group(2).strip()
    return f"`{path.rsplit('.', 1)[-1] if match.group(1) else path}`"


def _tables(lines: list[str]) -> list[str]:
    """reStructuredText simple tables (three ``===  ===`` rules) as fenced text blocks."""
    out, i = [], 0
    while i < len(lines):
        if _RST_RULE.fullmatch(lines[i]):
            rules = [j for j in range(i, len(lines)) if _RST_RULE.fullmatch(lines[j])][:3]
            if len(rules) == 3:
                indent = lines[i][:len(lines[i]) - len(lines[i].lstrip())]
                out += [indent + "```text", *lines[i:rules[2] + 1], indent + "```"]
                i = rules[2] + 1
                continue
        out.append(lines[i])
        i += 1
    return out


def mend(text: str) -> str:
    """The docstring ``text`` mended as the module docstring says."""
    lines, fenced = [], False
    for line in _tables(text.split("\n")):  # roles mended outside the tables (columns stay aligned)
        fenced = fenced != (line.strip() in ("```text", "```"))
        lines.append(line if fenced or line.strip() == "```" else _ROLE.sub(_role, line))
    out: list[str] = []
    in_items = False
    previous_blank = False
    for i, line in enumerate(lines):
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        if _DASHES.fullmatch(nxt.strip() or "x") and line.strip():
            in_items = line.strip().lower() in _ITEM_SECTIONS
        elif (in_items and previous_blank and line and not line[0].isspace()
              and not _DASHES.fullmatch(line.strip()) and not _ITEM.fullmatch(line.rstrip())):
            in_items = False
            out += ["Notes", "-----"]
        out.append(line)
        previous_blank = not line.strip()
    return "\n".join(out)


class NumpydocMend(griffe.Extension):
    """Apply :func:`mend` to every docstring as it is loaded."""

    def on_object(self, *, obj, **kwargs) -> None:
        if obj.docstring is not None:
            obj.docstring.value = mend(obj.docstring.value)
