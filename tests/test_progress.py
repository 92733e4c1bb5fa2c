"""Progress a person can plan by (issue 70, item 2; axlebox/_progress.py): on a terminal one line
that redraws itself with the simulated time, the rate and the time left; in a log a plain line
every LOG_EVERY_S; counted work with the time an item takes.  Times from a clock the test
drives, so every figure is known."""
import io
import os

import pytest

from axlebox._progress import LOG_EVERY_S, Progress, duration


class Clock:
    def __init__(self):
        self.t = 100.0

    def __call__(self):
        return self.t


@pytest.mark.parametrize("s, text", [(45.0, "45 s"), (89.4, "89 s"), (720.0, "12 min"),
                                     (3900.0, "65 min"), (5400.0, "1 h 30 min"), (7500.0, "2 h 05 min")])
def test_durations_read_as_a_person_reads_them(s, text):
    assert duration(s) == text


def test_a_terminal_gets_one_line_with_the_rate_and_the_time_left():
    """Through a real pseudo-terminal: the first report (after the kernels' compile) starts the
    clock; 0.5 s simulated in 10 s wall is 0.05 simulated s per wall s, and 1.1 s more of the
    1.6 then takes 22 s."""
    master, slave = os.openpty()
    try:
        with open(slave, "w", closefd=False) as f:
            clock = Clock()
            p = Progress("simulating", 1.6, file=f, clock=clock)
            assert p.tty
            clock.t += 40.0                       # the compile before the first chunk
            p(0.25, 1.6)
            clock.t += 5.0
            p(0.5, 1.6)
            p.close()
        out = os.read(master, 4096).decode()
    finally:
        os.close(master)
        os.close(slave)
    assert out.startswith("\rsimulating: 0.250 / 1.6 s") and out.count("\r") >= 2
    last = out.replace("\r\n", "\n").split("\r")[-1]
    assert "0.500 / 1.6 s, 0.05 simulated s per wall s, about 22 s left" in last
    assert out.endswith("\n") and out.count("\n") == 1      # one line, ended once


def test_a_log_gets_a_plain_line_every_few_seconds():
    """Not a terminal (a file): no carriage return, and of 100 reports 1 s apart a line at the
    first, one every LOG_EVERY_S, and the last."""
    f = io.StringIO()
    clock = Clock()
    p = Progress("simulating", 100.0, file=f, clock=clock)
    assert not p.tty
    for k in range(1, 101):
        p(float(k))
        clock.t += 1.0
    p.close()
    lines = f.getvalue().splitlines()
    assert "\r" not in f.getvalue()
    assert len(lines) == 1 + int(99 // LOG_EVERY_S) + (0 if 99 % LOG_EVERY_S == 0 else 1)
    assert lines[0] == "simulating: 1.000 / 100 s"
    assert lines[-1] == "simulating: 100.000 / 100 s, 1 simulated s per wall s, about 0 s left"


def test_counted_work_says_the_time_an_item_takes_and_what_is_left():
    clock = Clock()
    f = io.StringIO()
    p = Progress("sweep", 16, "case", file=f, clock=clock)
    assert p.left(0) == ""
    clock.t += 360.0                              # three cases in 6 min
    assert p.left(3) == "about 26 min left"
    assert p.aside(3) == ", about 26 min left" and p.aside(16) == "" and p.aside(0) == ""
    p(3)
    assert f.getvalue() == "sweep: 3 / 16 cases, 2 min a case, about 26 min left\n"
    assert Progress("bodies", 4, "body", units="bodies", file=f).line(0).startswith(
        "bodies: 0 / 4 bodies")
