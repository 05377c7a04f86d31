"""Progress output: tqdm bars on a terminal, plain lines (no carriage returns) in a log.

The counters decide by ``sys.stderr.isatty()``, so each case runs in this process with stderr
replaced: by a string buffer (a log), or by a real pseudo-terminal 100 columns wide (what a user's
terminal gives a process). No new process: the decision and the drawing are the same, without a
process's start-up and its import of the benchmarks (about 1.5 s each).
"""

from __future__ import annotations

import fcntl
import io
import os
import pty
import re
import struct
import sys
import termios
import time
from collections.abc import Callable

import pytest

LINE = re.compile(r"^(\w[\w ]*): (\d+)/(\d+) (\w+)s \((\d+)%\), [\d.na]+ \w+s/s, ETA [\d.na]+ s( \[.*\])?$")


def bench(enabled: bool = True) -> None:
    """The benchmarks' counters: 200 wave runs, then 7 long runs each named by a note."""
    from sawdrift.bench.core import _progress

    bar = _progress(200, "wave", enabled)
    for _ in range(200):
        bar.update(1)
    bar.close()
    with _progress(7, "long runs", enabled) as bar:
        for i in range(7):
            bar.set_postfix_str(f"case {i}")
            bar.update(1)


def slow(monkeypatch: pytest.MonkeyPatch) -> Callable[[], None]:
    """A sweep of 3 cells expected to take 1.8 s, on a clock of 1 s and 2 s five times faster."""
    from sawdrift.study import progress as pg

    monkeypatch.setattr(pg, "FIRST", 0.2)
    monkeypatch.setattr(pg, "EVERY", 0.4)

    def work() -> None:
        bar = pg.progress(3, "sweep", "cell", expected=1.8)
        time.sleep(0.66)  # no cell done yet: the clock still draws the bar
        bar.update(1)
        time.sleep(0.46)
        bar.close()

    return work


def _run(work: Callable[[], None], tty: bool, monkeypatch: pytest.MonkeyPatch) -> str:
    """What ``work`` writes to stderr when stderr is a pipe or log (not a terminal), or a
    pseudo-terminal."""
    if not tty:
        log = io.StringIO()
        assert not log.isatty()
        with monkeypatch.context() as m:
            m.setattr(sys, "stderr", log)
            work()
        return log.getvalue()
    leader, follower = pty.openpty()
    fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))
    terminal = os.fdopen(follower, "w", buffering=1)
    assert terminal.isatty()
    try:
        with monkeypatch.context() as m:
            m.setattr(sys, "stderr", terminal)
            work()
        terminal.flush()
    finally:
        terminal.close()
    os.set_blocking(leader, False)
    chunks = []
    while True:
        try:
            data = os.read(leader, 65536)
        except OSError:  # nothing more (EAGAIN) or the terminal is closed (EIO)
            break
        if not data:
            break
        chunks.append(data)
    os.close(leader)
    return b"".join(chunks).decode(errors="replace")


def test_benchmark_progress_in_a_log_is_plain_lines_one_per_tenth(monkeypatch):
    err = _run(bench, tty=False, monkeypatch=monkeypatch)
    assert "\r" not in err and "\x1b" not in err
    lines = err.strip().splitlines()
    wave = [m for m in map(LINE.match, lines) if m and m.group(1) == "wave"]
    assert [int(m.group(2)) for m in wave] == list(range(20, 201, 20))  # each tenth, once
    assert all(int(m.group(3)) == 200 and m.group(4) == "run" for m in wave)
    long = [m for m in map(LINE.match, lines) if m and m.group(1) == "long runs"]
    assert [int(m.group(2)) for m in long] == [1, 2, 3, 4, 5, 6, 7]  # 7 runs: each one is > 10 %
    assert long[-1].group(6) == " [case 6]"
    assert len(lines) == len(wave) + len(long)


@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminal")
def test_benchmark_progress_on_a_terminal_is_a_tqdm_bar(monkeypatch):
    err = _run(bench, tty=True, monkeypatch=monkeypatch)
    assert "\r" in err and "wave:" in err and "/200 [" in err and "%|" in err
    assert not any(LINE.match(line.strip()) for line in err.replace("\r", "\n").splitlines())


def test_a_slow_counter_prints_a_line_every_so_many_seconds(monkeypatch, capsys):
    """Fewer than a tenth done, but more than ``every`` (2) seconds since the last line: a line."""
    from sawdrift.study import progress as pg

    assert pg.EVERY <= 2.0  # issue 37: at least every 2 s, not per tenth of the cells
    clock = iter([0.0, 0.5, 2.5, 3.0, 4.6, 7.0])
    monkeypatch.setattr(pg.time, "perf_counter", lambda: next(clock))
    bar = pg._Lines(1000, 0, "cell", "sweep")  # t0 = 0
    for _ in range(5):  # at 0.5 s, 2.5 s, 3.0 s, 4.6 s, 7.0 s
        bar.update(1)
    lines = capsys.readouterr().err.strip().splitlines()
    assert [LINE.match(x).group(2) for x in lines] == ["2", "4", "5"]  # at 2.5, 4.6 and 7.0 s
    assert "ETA" in lines[0] and lines[0].startswith("sweep: 2/1000 cells (0%)")


def test_a_bar_moves_from_the_first_second_before_any_cell_is_done(monkeypatch):
    err = _run(slow(monkeypatch), tty=False, monkeypatch=monkeypatch)
    lines = err.strip().splitlines()
    first = [x for x in lines if x.startswith("sweep: 0/3")]
    # a line after FIRST, then every EVERY: at about 0.2 and 0.6 s before the first cell
    assert len(first) == 2, lines
    assert "(estimate)" in first[0]
    eta = float(first[0].split("ETA ")[1].split(" s")[0])
    assert 1.4 <= eta <= 1.65  # 1.8 s expected, 0.2 s gone
    assert any(x.startswith("sweep: 1/3") for x in lines), lines


@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminal")
def test_a_terminal_bar_is_redrawn_while_no_cell_finishes(monkeypatch):
    err = _run(slow(monkeypatch), tty=True, monkeypatch=monkeypatch)
    frames = [f for f in err.split("\r") if "sweep:" in f and "0/3" in f]
    assert len(frames) >= 3, frames  # drawn at 0, about 0.2 and 0.6 s: the clock redraws it
    assert any("estimate" in f for f in frames), frames


def test_a_disabled_counter_prints_nothing(monkeypatch):
    err = _run(lambda: bench(enabled=False), tty=False, monkeypatch=monkeypatch)
    assert err == ""


def test_a_terminal_that_reports_no_width_gets_the_plain_lines(monkeypatch):
    """tqdm's dynamic width drew nothing at all on a pseudo-terminal of 0 columns (some CI and
    IDE consoles): such a terminal gets the plain lines, a terminal with a width the bar."""
    import fcntl
    import os
    import pty
    import struct
    import termios

    from sawdrift.study import progress

    master, slave = pty.openpty()
    try:
        for columns, bar in ((0, False), (80, True)):
            fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, columns, 0, 0))
            with os.fdopen(os.dup(slave), "w") as stream:
                monkeypatch.setattr(progress.sys, "stderr", stream)
                assert progress._terminal() is bar
                drawn = progress.progress(10, "x", "cells")
                assert isinstance(drawn.bar, progress._Lines) is not bar
                drawn.close()
    finally:
        os.close(master)
        os.close(slave)


def test_a_slow_calibration_says_why_before_the_estimate(monkeypatch, capsys):
    """With a cold cache the calibration run compiles the loops: a first sweep printed nothing
    for 28 s, then an estimate of 'under 1 s'. A calibration longer than a second says why."""
    import time

    import sawdrift as sd
    from sawdrift.study import estimate as est

    real = est._rates

    def slow(*args, **kwargs):
        time.sleep(1.4)
        return real(*args, **kwargs)

    monkeypatch.setattr(est, "_rates", slow)
    est.estimate("sweep", [sd.Scene(numerics={"periods": 5})], 1)
    err = capsys.readouterr().err
    assert "sweep: calibrating the size estimate (the first use after installing compiles" in err


def test_a_long_run_shows_its_steps_as_it_goes(monkeypatch, capsys):
    """A run of 1e6 periods went minutes with one 'working' line: the integration reports its
    steps, and past a few seconds (here 0) a line every few seconds (here 0) counts them, the
    run itself unchanged; nothing is reported once the run is over."""
    import sawdrift as sd
    from sawdrift.dynamics import stepper as stepper_module
    from sawdrift.study import progress

    monkeypatch.setattr(progress, "EVERY", 0.0)
    monkeypatch.setattr(stepper_module, "REPORT_STEPS", 1000)
    scene = sd.Scene(numerics={"settle": False, "periods": 40})
    plain = sd.run(scene)
    with progress.run_progress("run: mmd", after=0.0):
        shown = sd.run(scene)
    lines = [line for line in capsys.readouterr().err.splitlines() if line.startswith("run: mmd")]
    counts = [float(line.split(": ")[2].split(" steps")[0]) for line in lines]
    assert len(counts) >= 3 and counts == sorted(counts)
    assert counts[-1] >= shown.steps  # every step counted (a twin's too)
    assert shown.drift_velocity == plain.drift_velocity
    assert stepper_module.PROGRESS[0] is None
