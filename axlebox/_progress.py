"""Progress a person can plan by: how much of how much is done, the rate and the time left.

On a terminal one line redraws itself (at most every ``TTY_EVERY_S``); where the output is not a
terminal (a log file, a pipe, a batch system's capture) a plain line every ``LOG_EVERY_S``
instead, so that a log holds a few readable lines, not thousands of carriage returns.  The rate
is measured from the first report on, so that what came before it (numba loading or compiling
the kernels, the statics) does not make the time left wrong for the rest of the run; counted
work (cases, bodies, records) is timed from the start instead, each item being whole.
"""
from __future__ import annotations

import sys
import time

TTY_EVERY_S = 0.2
LOG_EVERY_S = 10.0


def duration(s: float) -> str:
    """``s`` seconds as a person reads them: 45 s, 12 min, 1 h 05 min."""
    if s < 90.0:
        return f"{s:.0f} s"
    if s < 5400.0:
        return f"{s / 60.0:.0f} min"
    return f"{int(s // 3600)} h {int(s % 3600 // 60):02d} min"


class Progress:
    """A run's progress on ``file`` (stderr by default): call it with the amount done, then
    :meth:`close`.  ``unit``: what ``total`` counts (``"s"`` of simulated time, or a noun such as
    ``"case"``, ``units`` its plural: then counted from the start, with the time an item
    takes)."""

    def __init__(self, what: str, total: float, unit: str = "s", *, units: str | None = None,
                 file=None, every_s=None, clock=time.monotonic):
        self.what, self.total, self.unit = what, float(total), unit
        self.units = units or f"{unit}s"
        self.file = file if file is not None else sys.stderr
        self.tty = bool(getattr(self.file, "isatty", lambda: False)())
        self.every = every_s if every_s is not None else (TTY_EVERY_S if self.tty else LOG_EVERY_S)
        self.clock = clock
        self.counted = unit != "s"
        self._t0, self._d0 = (clock(), 0.0) if self.counted else (None, 0.0)
        self._last = -float("inf")
        self._width = 0

    def left(self, done: float) -> str:
        """``"about 12 min left"``, or ``""`` before a rate is known."""
        if self._t0 is None:
            return ""
        el, gained = self.clock() - self._t0, done - self._d0
        if el <= 0.0 or gained <= 0.0:
            return ""
        return f"about {duration(max(self.total - done, 0.0) * el / gained)} left"

    def aside(self, done: float) -> str:
        """``", about 12 min left"`` to end a log line with, ``""`` once all is done or before a
        rate is known."""
        left = self.left(done) if done < self.total else ""
        return f", {left}" if left else ""

    def line(self, done: float) -> str:
        el = self.clock() - self._t0
        gained = done - self._d0
        if self.counted:
            head = f"{self.what}: {done:g} / {self.total:g} {self.units}"
            rate = f"{duration(el / gained)} a {self.unit}" if gained > 0 and el > 0 else ""
        else:
            head = f"{self.what}: {done:.3f} / {self.total:g} s"
            rate = f"{gained / el:.3g} simulated s per wall s" if gained > 0 and el > 0 else ""
        return ", ".join(p for p in (head, rate, self.left(done)) if p)

    def __call__(self, done: float, total: float | None = None) -> None:
        if total is not None:
            self.total = float(total)
        now = self.clock()
        if self._t0 is None:                  # the first report: the rate is timed from here
            self._t0, self._d0 = now, done
        if now - self._last < self.every and done < self.total:
            return
        self._last = now
        text = self.line(done)
        if self.tty:
            self.file.write("\r" + text.ljust(self._width))
            self._width = len(text)
        else:
            self.file.write(text + "\n")
        self.file.flush()

    def close(self) -> None:
        """Ends the terminal's line (a log's lines are whole already)."""
        if self.tty and self._width:
            self.file.write("\n")
            self.file.flush()
