"""Every module imports on its own, and the light packages have no import cycles.

Two checks:

* **Each module imported first.** A fresh interpreter imports ``tyrelab``
  (which any ``import tyrelab.x`` runs first anyway) and then, for every module
  of the package, forks a child that imports just that module. A child starts
  from exactly the state a fresh ``python -c "import tyrelab.x"`` reaches
  after the package's ``__init__``, so this is that check for every module at
  the cost of one interpreter start (one subprocess per module where there is
  no ``fork``). It fails on a module-level import cycle or a broken import.
* **No cycles, even through function-level imports**, among the modules of
  the packages below: a function-level import that closes a cycle works but
  hides a dependency in the wrong direction (such as ``road.crg`` parsing road
  names through ``road.spec``, which itself opens ``.crg`` files). Read
  statically from the sources, nothing imported.
"""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "tyrelab"

#: The layers of ARCHITECTURE.md's table, in its order: a module may import (at any level,
#: module or function) only modules of its own layer or of the layers above it. ``tyrelab``
#: is the package's own ``__init__`` (the front door re-exporting ``simulate`` ...).
LAYERS = (
    ("tyrelab.core",),
    ("tyrelab._version", "tyrelab.errors", "tyrelab.limits", "tyrelab.resources", "tyrelab.io_atomic",
     "tyrelab.signal",
     "tyrelab.guards", "tyrelab.stop", "tyrelab.plugins"),
    ("tyrelab.road",),
    ("tyrelab.tyre",),
    ("tyrelab.rig",),
    ("tyrelab.api", "tyrelab.registry", "tyrelab"),
    ("tyrelab.cosim",),
    ("tyrelab.measure",),
    ("tyrelab.validate",),
    ("tyrelab.fit",),
    ("tyrelab.report",),
    ("tyrelab.study",),
    ("tyrelab.cli",),
)

_DRIVER = r"""
import importlib, os, subprocess, sys, traceback
import tyrelab
# third-party libraries loaded once here only for speed (children share them); they
# cannot change the order in which tyrelab's own modules import each other
for lib in ("pandas", "matplotlib.pyplot", "scipy.signal", "scipy.optimize"):
    try:
        importlib.import_module(lib)
    except ImportError:
        pass

modules = sys.argv[1:]
failed = []
for name in modules:
    if not hasattr(os, "fork"):
        r = subprocess.run([sys.executable, "-c", f"import {name}"], capture_output=True, text=True)
        if r.returncode:
            failed.append(name)
            print(f"--- import {name} failed:\n{r.stderr}", flush=True)
        continue
    pid = os.fork()
    if pid == 0:
        code = 0
        try:
            importlib.import_module(name)
        except BaseException:
            print(f"--- import {name} failed:\n{traceback.format_exc()}", flush=True)
            code = 1
        sys.stdout.flush()
        os._exit(code)
    _, status = os.waitpid(pid, 0)
    if status:
        failed.append(name)
print(f"{len(modules) - len(failed)} of {len(modules)} modules imported first; failed: {failed}")
sys.exit(1 if failed else 0)
"""


def _modules() -> dict[str, tuple[Path, bool]]:
    """Every module of the package by dotted name: (file, is a package)."""
    mods = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        is_pkg = parts[-1] == "__init__"
        if is_pkg:
            parts = parts[:-1]
        mods[".".join(parts)] = (path, is_pkg)
    return mods


def _runtime_nodes(tree):
    """Every node of ``tree`` except those under ``if TYPE_CHECKING:`` (type hints only:
    never imported when the program runs)."""
    todo = [tree]
    while todo:
        node = todo.pop()
        yield node
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test):
                todo.extend(child.orelse)
                continue
            todo.append(child)


def _imports(name: str, path: Path, is_pkg: bool, mods) -> set[str]:
    """The package's modules that ``name`` imports when it runs, at any level (module or
    function; ``if TYPE_CHECKING:`` imports left out)."""
    here = name.split(".") if is_pkg else name.split(".")[:-1]
    out = set()
    for node in _runtime_nodes(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = here[:len(here) - (node.level - 1)]
                base = ".".join(up + ([base] if base else []))
            # ``from pkg import mod`` imports the module pkg.mod; ``from mod import name`` just mod
            targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in mods else base for a in node.names]
        else:
            continue
        out.update(t for t in targets if t in mods and t != name)
    return out


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan, iterative)."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    found.append(sorted(comp))
    return found


def test_every_module_imports_when_imported_first():
    names = sorted(_modules())
    r = subprocess.run([sys.executable, "-c", _DRIVER, *names], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, f"{r.stdout}\n{r.stderr}"


def _layer(name: str) -> int:
    """Index in :data:`LAYERS` of a module (its longest matching package)."""
    best, depth = None, -1
    for i, layer in enumerate(LAYERS):
        for prefix in layer:
            if (name == prefix or name.startswith(prefix + ".")) and prefix.count(".") > depth:
                best, depth = i, prefix.count(".")
    assert best is not None, f"{name} is in no layer of ARCHITECTURE.md's table"
    return best


def test_imports_follow_the_layers_of_the_architecture():
    """ARCHITECTURE.md's layer table, as :data:`LAYERS`: no import points down it."""
    mods = _modules()
    down = []
    for name, (path, is_pkg) in mods.items():
        for target in _imports(name, path, is_pkg, mods):
            if _layer(target) > _layer(name):
                down.append(f"{name} (layer {_layer(name)}) imports {target} (layer {_layer(target)})")
    assert not down, "imports pointing down the layers:\n" + "\n".join(sorted(down))


def test_the_layer_table_of_architecture_md_is_the_one_enforced():
    """The table's package column, row by row, names the packages of :data:`LAYERS`."""
    text = (PACKAGE.parents[1] / "ARCHITECTURE.md").read_text(encoding="utf-8")
    table = text[text.index("## Layers"):text.index("## Documentation and examples")]
    rows = [ln for ln in table.splitlines() if ln.startswith("| `tyrelab")]
    named = [set(re.findall(r"`(tyrelab[\w.]*)`", ln.split("|")[1])) for ln in rows]
    assert named == [set(layer) for layer in LAYERS]


def test_the_package_has_no_import_cycles():
    """No cycle anywhere, counting function-level imports (type-hint-only ones aside)."""
    mods = _modules()
    graph = {name: _imports(name, path, is_pkg, mods) for name, (path, is_pkg) in mods.items()}
    bad = _cycles(graph)
    detail = "\n".join(" <-> ".join(c) + ": " + "; ".join(f"{m} imports {sorted(graph[m] & set(c))}"
                                                         for m in c) for c in bad)
    assert not bad, f"import cycles (counting function-level imports):\n{detail}"


def test_cycle_finder_finds_a_cycle():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}, "e": set()}
    assert _cycles(graph) == [["a", "b", "c"]]
