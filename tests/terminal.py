"""What a terminal shows for a process's raw output, and a reader that watches it live.

The signal tests read a command's stderr as bytes (``text=True`` would turn every ``\\r``
into ``\\n`` and hide what a progress bar does to the line) and render them the way a
VT100-class terminal does with the tty's usual ``onlcr``: ``\\n`` moves to the start of the
next line, ``\\r`` to the start of this one, ``ESC [ n A|B|C|D|G|K`` move or erase, and
printable text overwrites at the cursor. Nothing is wrapped (a line may grow past 80
columns), so text printed after a bar that left the cursor mid-line stays visibly
indented instead of looking right by accident.
"""

from __future__ import annotations

import re
import threading
import time

_TOKEN = re.compile(r"\x1b\[([0-9;?]*)([A-Za-z])|(\r)|(\n)|([^\x1b\r\n]+)|(\x1b)")


def render(data: bytes | str) -> list[str]:
    """The screen's lines (trailing blanks stripped) after ``data`` was written to it."""
    text = data.decode("utf-8", "replace") if isinstance(data, bytes) else data
    screen: list[list[str]] = [[]]
    row = col = 0
    for m in _TOKEN.finditer(text):
        args, final, cr, lf, chars, _lone_escape = m.groups()
        if final:
            n = int(args.split(";")[0]) if args and args.split(";")[0].isdigit() else None
            if final == "A":
                row = max(0, row - (n or 1))
            elif final == "B":
                row += n or 1
            elif final == "C":
                col += n or 1
            elif final == "D":
                col = max(0, col - (n or 1))
            elif final == "G":
                col = max(0, (n or 1) - 1)
            elif final == "K":
                while len(screen) <= row:
                    screen.append([])
                line = screen[row]
                if (n or 0) == 0:
                    del line[col:]
                elif n == 1:
                    line[:col] = [" "] * min(col, len(line))
                else:
                    line.clear()
            continue  # colours and other modes: nothing to show
        if cr:
            col = 0
        elif lf:
            row += 1
            col = 0
        elif chars:
            while len(screen) <= row:
                screen.append([])
            line = screen[row]
            if len(line) < col:
                line.extend(" " * (col - len(line)))
            line[col:col + len(chars)] = list(chars)
            col += len(chars)
        while len(screen) <= row:
            screen.append([])
    lines = ["".join(line).rstrip() for line in screen]
    while lines and not lines[-1]:
        lines.pop()
    return lines


class StreamWatcher:
    """Collects a pipe's bytes on a thread, so a test can wait for a phase's message."""

    def __init__(self, pipe):
        self._pipe = pipe
        self._data = bytearray()
        self._lock = threading.Lock()
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._thread.start()

    def _read(self):
        fd = self._pipe.fileno()
        import os
        while True:
            chunk = os.read(fd, 4096)
            if not chunk:
                return
            with self._lock:
                self._data.extend(chunk)

    @property
    def data(self) -> bytes:
        with self._lock:
            return bytes(self._data)

    def wait_for(self, marker: bytes, process, timeout: float) -> bool:
        """True once ``marker`` was written; False if the process ended or ``timeout`` s passed
        first (a bound on a hung test, never a pass/fail condition on speed)."""
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if marker in self.data:
                return True
            if process.poll() is not None:
                self._thread.join(5)
                return marker in self.data
            time.sleep(0.02)
        return False

    def finish(self, timeout: float = 120) -> bytes:
        """All the bytes, once the writer closed the pipe."""
        self._thread.join(timeout)
        return self.data
