"""Render a local HTML page in headless Chromium and read back its final DOM (test helper).

:func:`render_dom` runs::

    chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage
             --no-first-run --no-default-browser-check --disable-extensions
             --user-data-dir=<fresh temporary folder> --virtual-time-budget=<ms>
             --dump-dom file:///.../page.html

``--virtual-time-budget`` lets the page's scripts and timers run (in
virtual time) until the budget is spent or nothing is pending; ``--dump-dom``
then prints the serialised DOM, i.e. the page *after* its scripts ran
(plotly's drawn SVG, attributes set by scripts). :func:`parse` turns that
text into a small element tree (:class:`Node`) with the standard library's
HTML parser, so the tests need no third-party HTML library.
"""

from __future__ import annotations

import shutil
import subprocess
import tempfile
from html.parser import HTMLParser
from pathlib import Path

#: names the Chromium binary goes by (Debian: ``chromium``; Ubuntu: ``chromium-browser``)
CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")

INSTALL_HINT = ("install it from the system packages (Debian/Ubuntu: "
                "`apt-get update && apt-get install -y chromium`); .ci/run does this")


def find_chromium() -> str | None:
    """Path of the first Chromium binary on PATH, or None."""
    for name in CANDIDATES:
        path = shutil.which(name)
        if path:
            return path
    return None


def render_dom(page, budget_ms: int = 30_000, timeout: float = 240.0) -> str:
    """The DOM of ``page`` (a local HTML file) after its scripts ran, as HTML text.

    Raises RuntimeError when Chromium is missing, fails or prints nothing.
    """
    binary = find_chromium()
    if binary is None:
        raise RuntimeError("Chromium is not installed (none of " + ", ".join(CANDIDATES)
                           + " is on PATH): " + INSTALL_HINT)
    url = Path(page).resolve().as_uri()
    with tempfile.TemporaryDirectory(prefix="tyrelab-chromium-") as profile:
        cmd = [binary, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
               "--no-first-run", "--no-default-browser-check", "--disable-extensions",
               f"--user-data-dir={profile}", f"--virtual-time-budget={int(budget_ms)}",
               "--dump-dom", url]
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if r.returncode != 0 or "<html" not in r.stdout:
        raise RuntimeError(f"{' '.join(cmd)} exited {r.returncode} without a DOM; stderr:\n"
                           + r.stderr[-3000:])
    return r.stdout


VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "param",
        "source", "track", "wbr"}


class Node:
    """An element: ``tag``, ``attrs`` (dict), ``children`` (Nodes and strings)."""

    def __init__(self, tag: str, attrs: dict, parent: Node | None = None):
        self.tag, self.attrs, self.parent, self.children = tag, attrs, parent, []

    @property
    def classes(self) -> set[str]:
        return set((self.attrs.get("class") or "").split())

    def iter(self):
        """This node and every element below it, in document order."""
        yield self
        for c in self.children:
            if isinstance(c, Node):
                yield from c.iter()

    def find_all(self, tag: str | None = None, cls: str | None = None, **attrs) -> list[Node]:
        """Elements below (and including) this one with that tag, class and attributes."""
        return [n for n in self.iter()
                if (tag is None or n.tag == tag) and (cls is None or cls in n.classes)
                and all(n.attrs.get(k.replace("_", "-")) == v for k, v in attrs.items())]

    def find(self, *args, **kw) -> Node | None:
        found = self.find_all(*args, **kw)
        return found[0] if found else None

    def text(self) -> str:
        """All text below this element, concatenated."""
        return "".join(c if isinstance(c, str) else c.text() for c in self.children)


class _Builder(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.root = self.node = Node("#document", {})

    def handle_starttag(self, tag, attrs):
        node = Node(tag, {k: (v if v is not None else "") for k, v in attrs}, self.node)
        self.node.children.append(node)
        if tag not in VOID:
            self.node = node

    def handle_startendtag(self, tag, attrs):
        self.node.children.append(Node(tag, {k: (v or "") for k, v in attrs}, self.node))

    def handle_endtag(self, tag):
        node = self.node
        while node is not None and node.tag != tag:
            node = node.parent
        if node is not None and node.parent is not None:
            self.node = node.parent

    def handle_data(self, data):
        self.node.children.append(data)


def parse(text: str) -> Node:
    """An element tree of an HTML text (the document node)."""
    b = _Builder()
    b.feed(text)
    b.close()
    return b.root
