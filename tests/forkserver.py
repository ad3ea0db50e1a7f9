"""A fork server: many short Python programs, their imports paid once.

``tests/test_docs.py`` runs about 90 commands of the documentation, each as a
fresh process would run it; most of a fresh process's time is Python start-up
and importing tyrelab (numpy, pandas, scipy, numba: 1.2-1.3 s), the command
itself often well under a second. So a server process (this file run as a
script) runs the given set-up code once (its imports) and then, for every
request, ``os.fork()``-s a child that

* closes the server's request and reply pipes, ``chdir``-s to the request's
  folder and replaces ``os.environ`` with the request's environment;
* points file descriptors 0, 1 and 2 at ``/dev/null`` and the request's stdout
  and stderr files (so the output of any process it starts goes there too);
* sets a fresh ``sys.argv``, puts the program's folder first on ``sys.path``
  (as ``python FILE`` and a console script do) and runs the program's file in a
  new ``__main__`` module, as ``python FILE`` does (``__file__`` absolute,
  ``sys.argv[0]`` as given): for ``tyrelab ARGS`` the installed console script
  itself, for ``python FILE ARGS`` that file;
* ends the way that interpreter would: its ``SystemExit`` code, ``1`` and the
  traceback on stderr for an exception, after Python's normal shutdown (threads
  joined, ``atexit`` handlers run, streams flushed, modules torn down). The
  server calls :func:`gc.freeze` once its imports are done, so that a child's
  collections and teardown do not copy every page of them (0.27 s a child
  without, 0.08 s with).

The server waits for the child and replies with its exit code (negative: the
signal that killed it, as :attr:`subprocess.Popen.returncode`). Every child is
a fork of the pristine server, which never runs a command itself, so no child
sees anything an earlier one did. Let the set-up import only what the programs
would import first anyway (test_docs: ``tyrelab``, which the console script's
``from tyrelab.cli.main import main`` and any ``from tyrelab... import`` start
with), so that a module a program uses without importing it is missing in the
child too, and run nothing a program could tell from a fresh process: no numba
kernel (numba's thread pool would not survive a fork; the server checks that no
Python thread but its own runs), no signal handler, no ``sys.stderr`` wrapper of
the CLI. The native threads an import starts (OpenBLAS workers, jemalloc's)
have at-fork handlers.

:class:`ForkServer` is the client: it starts the server (in a new session, so
that a command that hangs is killed with everything it started) and sends one
request at a time.
"""

import json
import os
import select
import signal
import subprocess
import sys
import time

#: a server that has not imported its modules in this time is broken [s]
START_TIMEOUT = 300


class ForkServerError(RuntimeError):
    """The server died or could not start (the message holds its log)."""


class ForkServer:
    """A server process that has run ``setup`` (Python source); :meth:`run` forks a program off it.

    ``cwd``, ``env``: the server's own folder and environment (the environment a module
    reads at import, such as ``MPLBACKEND``, is this one); ``log``: a file for the
    server's own stderr.
    """

    def __init__(self, setup, *, cwd, env, log):
        self.log = str(log)
        with open(self.log, "wb") as err:
            self.proc = subprocess.Popen([sys.executable, os.path.abspath(__file__), setup],
                                         cwd=cwd, env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                         stderr=err, start_new_session=True)
        self._buffer = b""
        self._ready = False

    # -- the client side ---------------------------------------------------------------
    def _readline(self, deadline):
        """One reply line; None when the deadline passed first, b"" when the server died."""
        fd = self.proc.stdout.fileno()
        while b"\n" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            if not select.select([fd], [], [], left)[0]:
                continue
            chunk = os.read(fd, 65536)
            if not chunk:
                return b""
            self._buffer += chunk
        line, self._buffer = self._buffer.split(b"\n", 1)
        return line + b"\n"

    def _died(self, what):
        self.kill()
        with open(self.log, encoding="utf-8", errors="replace") as f:
            log = f.read()[-5000:]
        return ForkServerError(f"fork server {what} (exit {self.proc.returncode}); its stderr:\n{log}")

    def wait_ready(self):
        if self._ready:
            return
        line = self._readline(time.monotonic() + START_TIMEOUT)
        if not line or not line.startswith(b"ready"):
            raise self._died("did not start" if line is None else "failed to start")
        self._ready = True

    def run(self, script, argv, *, path0, cwd, env, stdout, stderr, timeout):
        """Run ``script`` as ``__main__`` in a fork of the server: its exit code, or None if it
        had not ended after ``timeout`` seconds (the server and all it started are then killed)."""
        self.wait_ready()
        request = {"script": str(script), "argv": [str(a) for a in argv], "path0": str(path0),
                   "cwd": str(cwd), "env": dict(env), "stdout": str(stdout), "stderr": str(stderr)}
        try:
            self.proc.stdin.write(json.dumps(request).encode() + b"\n")
            self.proc.stdin.flush()
        except OSError:
            raise self._died("is gone") from None
        line = self._readline(time.monotonic() + timeout)
        if line is None:
            self.kill()
            return None
        if not line:
            raise self._died("died")
        return json.loads(line)["code"]

    @property
    def alive(self):
        return self.proc.poll() is None

    def kill(self):
        """Kill the server and everything still running that it started (its session)."""
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        self.proc.wait()

    def close(self):
        """End the server: it exits when its requests end; killed if it does not."""
        try:
            self.proc.stdin.close()
        except OSError:
            pass
        try:
            self.proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            pass
        self.kill()
        self.proc.stdout.close()


# -- the server side (this file run as a script) ---------------------------------------------
def _read_line(fd, buffer):
    while b"\n" not in buffer:
        chunk = os.read(fd, 65536)
        if not chunk:
            return b"", b""
        buffer += chunk
    line, rest = buffer.split(b"\n", 1)
    return line, rest


def _child(request):
    """The forked child: set up the process as ``python FILE`` would have it, run FILE."""
    import importlib.machinery
    import types

    os.chdir(request["cwd"])
    os.environ.clear()
    os.environ.update(request["env"])
    for fd, path, flags in ((0, os.devnull, os.O_RDONLY),
                            (1, request["stdout"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC),
                            (2, request["stderr"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC)):
        opened = os.open(path, flags, 0o666)
        os.dup2(opened, fd)
        os.close(opened)
    sys.argv = request["argv"]
    sys.path.insert(0, request["path0"])
    path = request["script"]
    main = types.ModuleType("__main__")   # what ``python FILE`` runs FILE in
    main.__file__ = path
    main.__cached__ = None
    main.__loader__ = importlib.machinery.SourceFileLoader("__main__", path)
    server = sys.modules["__main__"]      # noqa: F841 (kept: this code's module)
    sys.modules["__main__"] = main
    with open(path, "rb") as f:
        code = compile(f.read(), path, "exec", dont_inherit=True)
    exec(code, main.__dict__)
    sys.exit(0)


def _serve(setup):
    import gc
    import threading
    import warnings

    requests, replies = os.dup(0), os.dup(1)   # the pipes to the client, kept off fds 0 and 1
    null = os.open(os.devnull, os.O_RDONLY)
    os.dup2(null, 0)
    os.close(null)
    os.dup2(2, 1)                               # a stray print goes to the server's log
    if sys.path and sys.path[0] == os.path.dirname(os.path.abspath(__file__)):
        del sys.path[0]                         # each child puts its program's folder there
    start = time.perf_counter()
    exec(compile(setup, "<fork server set-up>", "exec"), {"__name__": "__setup__"})
    if threading.active_count() != 1:
        sys.exit(f"fork server: its set-up started Python threads {[t.name for t in threading.enumerate()]}"
                 "; a fork would lose them")
    # the imported objects out of the collector's sight: a child's collections and its exit
    # would otherwise touch (and so copy) every page of them (0.27 s of each child's exit)
    gc.freeze()
    os.write(replies, f"ready {time.perf_counter() - start:.2f} s\n".encode())
    buffer = b""
    while True:
        line, buffer = _read_line(requests, buffer)
        if not line:
            return
        request = json.loads(line)
        sys.stdout.flush()
        sys.stderr.flush()
        with warnings.catch_warnings():  # left in the child too: its filters are the pristine ones
            # Python >= 3.12 warns of a fork while any thread runs, OpenBLAS's included (see above)
            warnings.filterwarnings("ignore", "This process .* is multi-threaded", DeprecationWarning)
            pid = os.fork()
        if pid == 0:
            os.close(requests)
            os.close(replies)
            _child(request)  # never returns: the program's SystemExit or exception ends the child
        _, status = os.waitpid(pid, 0)
        os.write(replies, json.dumps({"code": os.waitstatus_to_exitcode(status)}).encode() + b"\n")


if __name__ == "__main__":
    _serve(sys.argv[1])
