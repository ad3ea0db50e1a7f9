"""The ``tyrelab`` command and example scripts run as a user runs them, their imports paid once.

A fresh ``python -m tyrelab.cli.main ...`` spends 1.2-1.3 s on Python's start-up and
imports (tyrelab, numpy, pandas, scipy, numba) before a command does its fraction of a
second of work; the CLI tests start about forty of them. :func:`run_tyrelab` and
:func:`python_file` run each as a fresh ``os.fork()`` of a pristine fork server
(``tests/forkserver.py``, the one ``tests/test_docs.py`` uses: its docstring says how a
child is set up as the fresh process would be) that has imported ``tyrelab`` and nothing
more, one server per test process and environment, started at first use and killed at
exit. The child is a real process with its own file descriptors: what it writes to its
stdout and stderr (the CLI's one-line errors, progress bars) reaches files exactly as it
would reach a pipe. Where ``os.fork`` does not exist each runs as a new process.

Both return a :class:`subprocess.CompletedProcess` with text output, newlines translated
as ``subprocess.run(..., text=True)`` translates them (``\\r\\n`` and ``\\r`` become
``\\n``), and raise :class:`subprocess.TimeoutExpired` after ``timeout`` seconds.
"""

from __future__ import annotations

import atexit
import os
import subprocess
import sys
import sysconfig
import tempfile
from pathlib import Path

from forkserver import ForkServer

#: what a fork server runs before forking the programs off it: the import every ``tyrelab``
#: command and example starts with (nothing more: a module that a program uses without
#: importing it must be missing, as for a user), and numba's typing and target contexts,
#: which a process builds at its first kernel call whether the kernel comes from the cache
#: or not (0.15 s a program). No kernel runs.
SERVER_SETUP = """\
import tyrelab
from numba.core.registry import cpu_target
cpu_target.typing_context.refresh()
cpu_target.target_context.refresh()
"""
#: the ``tyrelab`` command (the console script pip installed with this Python)
CONSOLE_SCRIPT = Path(sysconfig.get_path("scripts")) / "tyrelab"

#: the servers of this process, by the environment they were started in
_servers: dict[frozenset, ForkServer] = {}


def _server(env: dict) -> ForkServer:
    """This process's fork server for ``env`` (a module may read its environment at import,
    so a server serves only the environment it was started in)."""
    # pytest names the running test in PYTEST_CURRENT_TEST: not a server's business
    key = frozenset((k, v) for k, v in env.items() if k != "PYTEST_CURRENT_TEST")
    server = _servers.get(key)
    if server is None or not server.alive:
        log = tempfile.NamedTemporaryFile(prefix="tyrelab-forkserver-", suffix=".log", delete=False)
        log.close()
        server = _servers[key] = ForkServer(SERVER_SETUP, cwd=os.getcwd(), env=dict(key), log=log.name)
        atexit.register(_close, server, log.name)
    return server


def _close(server: ForkServer, log: str) -> None:
    server.kill()
    Path(log).unlink(missing_ok=True)


def _text(data: bytes) -> str:
    """Output bytes as ``subprocess.run(..., text=True)`` gives them."""
    return data.decode(errors="replace").replace("\r\n", "\n").replace("\r", "\n")


def _run(script: Path, argv: list[str], fresh: list[str], cwd, env, timeout) -> subprocess.CompletedProcess:
    cwd = str(cwd if cwd is not None else os.getcwd())
    env = dict(os.environ if env is None else env)
    if not hasattr(os, "fork") or not script.is_file():
        return subprocess.run(fresh, capture_output=True, text=True, cwd=cwd, env=env,
                              timeout=timeout, stdin=subprocess.DEVNULL)
    server = _server(env)
    with tempfile.TemporaryDirectory(prefix="tyrelab-cli-") as tmp:
        out, err = Path(tmp) / "stdout", Path(tmp) / "stderr"
        code = server.run(script, argv, path0=script.parent, cwd=cwd, env=env, stdout=out,
                          stderr=err, timeout=timeout)
        if code is None:  # the server and all it started were killed
            raise subprocess.TimeoutExpired(fresh, timeout)
        return subprocess.CompletedProcess(fresh, code, _text(out.read_bytes()), _text(err.read_bytes()))


def run_tyrelab(*args, cwd=None, env=None, timeout: float = 300) -> subprocess.CompletedProcess:
    """``tyrelab ARGS`` in folder ``cwd`` (default this process's) with environment ``env``
    (default this process's)."""
    args = [str(a) for a in args]
    return _run(CONSOLE_SCRIPT, [str(CONSOLE_SCRIPT), *args],
                [sys.executable, "-m", "tyrelab.cli.main", *args], cwd, env, timeout)


def python_file(path, *args, cwd=None, env=None, timeout: float = 300) -> subprocess.CompletedProcess:
    """``python PATH ARGS`` (``PATH`` relative to ``cwd`` or absolute)."""
    args = [str(a) for a in args]
    script = Path(cwd if cwd is not None else os.getcwd()) / path
    return _run(script, [str(path), *args], [sys.executable, str(path), *args], cwd, env, timeout)
