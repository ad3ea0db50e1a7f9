"""The documentation builds, and every command it shows runs as written.

* ``mkdocs build --strict`` (mkdocs.yml at the repository root; warnings
  are errors, among them a broken link, a page missing from the navigation
  and a docstring the API reference cannot parse).
* Every shell command in a fenced code block (``bash``, ``sh``, ``shell``,
  ``console`` or unlabelled) of README.md and docs/ that starts with
  ``tyrelab `` or ``python examples/``, and every ``python`` block, runs in
  a fresh temporary folder holding a copy of ``examples/`` (nothing else is
  substituted), the blocks of one page in their order (a page may use a
  file an earlier command of it wrote), and exits 0. Commands that take many
  minutes are skipped only through :data:`SKIP`, each with its reason.

How the commands run (issue 29: this test took 144-205 s on 2 cores). A fresh
process costs 1.2-1.3 s of start-up and imports (tyrelab, numpy, pandas, scipy,
numba) before a command does its fraction of a second of work, 90-odd times.
So each of the two page workers has a fork server (``tests/forkserver.py``): a
process that has imported ``tyrelab`` once (and nothing more, so that a module
a step uses without importing it fails here as it would for a user) and built
numba's typing and target contexts (as every process does at its first kernel
call), and runs nothing itself: no kernel, no command. Each step is a fresh
``os.fork()`` of that pristine server, set up as the fresh process would be:
the page's folder as working directory, :func:`_env` as environment, its own
``sys.argv`` and ``sys.path[0]``, stdin from /dev/null, stdout and stderr to
files, the program run in a new ``__main__`` (``tyrelab ARGS``: the installed
``tyrelab`` console script itself; a ``python`` block or ``python FILE``: that
file, ``python`` being this interpreter) and its exit code that of Python's
own exit. A command that is not plain words (pipes, redirections, ``&&``,
quotes, ``$``, globs: see :func:`plain_argv`) runs through ``bash -c`` in a new
process, as does every step where ``os.fork`` does not exist. The pages with
the most steps start first (README.md alone is a third of the time).
"""

from __future__ import annotations

import importlib.util
import os
import queue
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from cli_process import CONSOLE_SCRIPT, SERVER_SETUP

ROOT = Path(__file__).resolve().parents[1]
#: pages whose commands are run: the README and every documentation page
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
#: fence languages whose lines are shell commands ("" = no language given, as in the README)
SHELL = {"", "bash", "sh", "shell", "console"}
#: a command that has not finished in this time has hung [s]
TIMEOUT = 600

#: commands shown in the documentation that this test does not run: pattern -> why
SKIP = {
    r"^tyrelab study\s*(#.*)?$":
        "the thesis's whole campaign: 200 runs, 2.5-3 minutes on 2 cores (README, Benchmarks); "
        "the study machinery runs in tests/test_study_*.py, the example spec via "
        "'tyrelab study spec.toml --workers 2' and examples/small_campaign.py",
    r"^tyrelab fit ring\b":
        "identifies the flexible ring: several minutes of ring simulations; "
        "tests/test_ring_fit_campaign_fast.py runs 'tyrelab fit ring' end to end on a reduced "
        "campaign (default run), tests/test_fit_ring_campaign.py the whole identification (slow)",
    r"^python examples/(?!run_all\.py)\w+\.py\s*(#.*)?$":
        "an example of the gallery: tests/test_examples.py runs each as written, in a fresh copy "
        "of examples/, and checks what it prints and draws (every script has its test there: "
        "test_every_example_is_tested_and_in_the_gallery)",
    r"--scheduler tcp://HEAD:":
        "needs a Dask scheduler running on a machine named HEAD (the README's multi-machine "
        "set-up); the runner's scheduler path is tested in tests/test_study_runner.py",
}

#: commands run here with a cheaper option added: pattern -> (added text, why)
SHORTEN = {
    r"^tyrelab fit all\b(?!.*--skip)": (
        " --skip ring", "the ring step identifies the flexible ring (minutes of ring simulations); "
        "tests/test_ring_fit_campaign_fast.py runs it end to end on a reduced campaign, "
        "tests/test_fit_campaign.py runs fit all"),
}

#: a word bash passes on as it is: no quote, expansion, glob, redirection, operator or comment
PLAIN_WORD = re.compile(r"[\w\-./:@=,+%]+", re.ASCII)

FENCE = re.compile(r"^(?P<indent>[ \t]*)(?P<fence>```+|~~~+)[ \t]*(?P<lang>[\w+-]*)[^\n]*$")


def blocks(text: str):
    """(language, body lines) of every fenced code block of a Markdown text, in order."""
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        fence, indent, lang = m.group("fence"), len(m.group("indent")), m.group("lang").lower()
        body, i = [], i + 1
        while i < len(lines) and not lines[i].strip().startswith(fence):
            body.append(lines[i][indent:] if lines[i][:indent].strip() == "" else lines[i])
            i += 1
        i += 1
        yield lang, body


def steps(page: Path):
    """The page's runnable steps in order: ("shell", command) and ("python", source)."""
    out = []
    for lang, body in blocks(page.read_text(encoding="utf-8")):
        if lang in SHELL:
            for line in body:
                cmd = line.strip()
                if lang == "console" and cmd.startswith("$ "):
                    cmd = cmd[2:].strip()
                if cmd.startswith(("tyrelab ", "python examples/")) or cmd == "tyrelab":
                    out.append(("shell", cmd))
        elif lang == "python" and not any(line.startswith("--8<--") for line in body):
            out.append(("python", "\n".join(body) + "\n"))
    return out


def skip_reason(cmd: str) -> str | None:
    for pattern, why in SKIP.items():
        if re.search(pattern, cmd):
            return why
    return None


def _env() -> dict:
    env = dict(os.environ)
    env["MPLBACKEND"] = "Agg"
    env["NO_MKDOCS_2_WARNING"] = "1"
    return env


def plain_argv(cmd: str) -> list[str] | None:
    """The argv bash makes of ``cmd`` when that is just its words split at blanks (a trailing
    ``# comment`` dropped); None for anything else: a pipe, redirection, ``&&``, quote, ``$``..."""
    words = re.split(r"[ \t]+", cmd.strip())
    for i, word in enumerate(words):
        if word.startswith("#"):
            words = words[:i]
            break
    return words if words and all(PLAIN_WORD.fullmatch(w) for w in words) else None


def fork_program(cmd: str, folder: Path) -> tuple[Path, list[str]] | None:
    """(file run as ``__main__``, ``sys.argv``) of a shell command a fork server can run in
    ``folder``: ``tyrelab ARGS`` and ``python FILE.py ARGS`` as plain words; else None."""
    words = plain_argv(cmd)
    if not words:
        return None
    if words[0] == "tyrelab" and CONSOLE_SCRIPT.is_file():
        return CONSOLE_SCRIPT, [str(CONSOLE_SCRIPT), *words[1:]]
    if words[0] == "python" and len(words) > 1 and words[1].endswith(".py") and not words[1].startswith("-"):
        return folder / words[1], words[1:]
    return None


def _page_id(page: Path) -> str:
    return str(page.relative_to(ROOT))


# -- the site ------------------------------------------------------------------------------
def test_mkdocs_build_strict(tmp_path):
    missing = [m for m in ("mkdocs", "mkdocstrings", "mkdocstrings_handlers.python", "material")
               if importlib.util.find_spec(m.split(".")[0]) is None]
    if missing:
        pytest.skip(f"documentation tools not installed ({', '.join(missing)}): pip install '.[test]'")
    site = tmp_path / "site"
    proc = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
                          cwd=ROOT, env=_env(), capture_output=True, text=True, timeout=TIMEOUT)
    assert proc.returncode == 0, f"mkdocs build --strict failed:\n{proc.stdout}\n{proc.stderr[-5000:]}"
    assert "WARNING" not in proc.stderr, proc.stderr
    # the pages are there, with the API reference generated and the examples' figures and sources
    api = (site / "api" / "index.html").read_text(encoding="utf-8")
    assert "Run a tyre model on a rig over a road" in api          # tyrelab.simulate's docstring
    assert "drop_test_damping" in api and "Notes" in api
    page = (site / "examples" / "cleat_run" / "index.html").read_text(encoding="utf-8")
    assert "img/cleat_run.png" in page and "plot_runs" in page     # figure and included script
    assert (site / "examples" / "img" / "cleat_run.png").is_file()
    assert (site / "ring" / "index.html").is_file()
    assert "--8&lt;--" not in page and "--8<--" not in page         # every snippet was included


def test_every_page_is_in_the_navigation():
    nav = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    for page in (ROOT / "docs").rglob("*.md"):
        assert str(page.relative_to(ROOT / "docs")) in nav, page


def test_the_channel_table_lists_every_signal_channel():
    from tyrelab.signal import CHANNELS

    text = (ROOT / "docs" / "formats.md").read_text(encoding="utf-8")
    listed = re.findall(r"^\| `([A-Z_]+)` \|", text, re.M)
    assert listed == list(CHANNELS)


# -- the commands --------------------------------------------------------------------------
def test_commands_are_found_and_every_skip_is_used():
    """The extraction sees the commands (README's unlabelled blocks included), and each
    entry of SKIP still matches a command somewhere (a stale entry would hide nothing)."""
    commands = [cmd for page in PAGES for kind, cmd in steps(page) if kind == "shell"]
    assert len(commands) > 40
    assert any(c.startswith("python examples/") for c in commands)
    for pattern in [*SKIP, *SHORTEN]:
        assert any(re.search(pattern, c) for c in commands), f"SKIP entry matches nothing: {pattern}"


def run_page(page: Path, folder: Path, server=None) -> tuple[str | None, list[str]]:
    """Run the page's steps in ``folder`` (a copy of examples/ is put there first), forked off
    ``server`` (a :class:`forkserver.ForkServer`) where they can be, else each in a new process;
    return the first failure (or None) and the commands skipped through :data:`SKIP`."""
    shutil.copytree(ROOT / "examples", folder / "examples", ignore=shutil.ignore_patterns("__pycache__"))
    output = folder.with_name(folder.name + "-output")  # the forked steps' stdout and stderr
    output.mkdir()
    skipped = []
    for n, (kind, text) in enumerate(steps(page)):
        if kind == "shell":
            why = skip_reason(text)
            if why:
                skipped.append(f"{_page_id(page)}: {text}: {why}")
                continue
            for pattern, (extra, why) in SHORTEN.items():
                if re.search(pattern, text):
                    text = text.split("#")[0].rstrip() + extra
                    skipped.append(f"{_page_id(page)}: run as '{text}': {why}")
            program = fork_program(text, folder)
            argv = ["bash", "-c", text]
        else:
            script = folder / f"_block{n}.py"
            script.write_text(text, encoding="utf-8")
            program = script, [script.name]
            argv = [sys.executable, script.name]
        if server is not None and program is not None:
            file, args = program
            out, err = output / f"{n}.stdout", output / f"{n}.stderr"
            try:
                code = server.run(file, args, path0=file.parent, cwd=folder, env=_env(),
                                  stdout=out, stderr=err, timeout=TIMEOUT)
            except RuntimeError as exc:  # the server itself failed (forkserver.ForkServerError)
                return f"{_page_id(page)}: {exc}\nwhile running\n{text}", skipped
            if code is None:
                return f"{_page_id(page)}: no end after {TIMEOUT} s:\n{text}", skipped
            stdout, stderr = (f.read_text(errors="replace") for f in (out, err))
        else:
            try:
                proc = subprocess.run(argv, cwd=folder, env=_env(), capture_output=True, text=True,
                                      timeout=TIMEOUT, stdin=subprocess.DEVNULL)
            except subprocess.TimeoutExpired:
                return f"{_page_id(page)}: no end after {TIMEOUT} s:\n{text}", skipped
            code, stdout, stderr = proc.returncode, proc.stdout, proc.stderr
        if code != 0:
            return (f"{_page_id(page)}: exit {code} from\n{text}\n"
                    f"stdout:\n{stdout[-2000:]}\nstderr:\n{stderr[-3000:]}"), skipped
    return None, skipped


def run_pages(pages: list[Path], folder: Path, workers: int = 2) -> list[tuple[str | None, list[str]]]:
    """:func:`run_page` for every page, each in its own fresh folder under ``folder``, ``workers``
    pages at a time, each worker with a fork server (none where ``os.fork`` does not exist)."""
    from concurrent.futures import ThreadPoolExecutor

    from forkserver import ForkServer

    started = []

    def new_server():
        log = folder / f"forkserver{len(started)}.log"
        started.append(ForkServer(SERVER_SETUP, cwd=folder, env=_env(), log=log))
        return started[-1]

    servers = queue.Queue()
    for _ in range(workers):
        servers.put(new_server() if hasattr(os, "fork") else None)

    def one(n: int, page: Path):
        server, t = servers.get(), time.perf_counter()
        try:
            return run_page(page, folder / f"page{n}", server)
        finally:
            print(f"{_page_id(page)}: {time.perf_counter() - t:.1f} s")
            servers.put(new_server() if server is not None and not server.alive else server)

    # the longest page first (README.md: a third of all the time), so that it does not start last
    order = sorted(range(len(pages)), key=lambda n: -len(steps(pages[n])))
    try:
        with ThreadPoolExecutor(max_workers=workers) as pool:
            results = dict(zip(order, pool.map(one, order, [pages[n] for n in order])))
        return [results[n] for n in range(len(pages))]
    finally:
        for server in started:
            server.close()


def test_commands_run_as_written(tmp_path):
    """Every page in its own fresh folder, two pages at a time (each page's steps in order),
    the steps forked off a server that has imported tyrelab (see the module's docstring)."""
    results = run_pages([p for p in PAGES if steps(p)], tmp_path)
    for _, skipped in results:  # listed with their reasons in the test's output (-rA or -s)
        for line in skipped:
            print(f"skipped (SKIP): {line}")
    failures = [failure for failure, _ in results if failure]
    assert not failures, "\n\n".join(failures)
