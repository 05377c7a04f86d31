"""Progress output: tqdm bars on a terminal, plain lines (no carriage returns) in a log."""

from __future__ import annotations

import fcntl
import os
import pty
import re
import struct
import subprocess
import sys
import termios

import pytest

LINE = re.compile(r"^(\w[\w ]*): (\d+)/(\d+) (\w+)s \((\d+)%\), [\d.na]+ \w+s/s, ETA [\d.na]+ s( \[.*\])?$")

BENCH = """
import sys, time
from sawdrift.bench.core import _progress
bar = _progress(200, "wave", True)
for i in range(200):
    bar.update(1)
bar.close()
with _progress(7, "long runs", True) as bar:
    for i in range(7):
        bar.set_postfix_str(f"case {i}")
        bar.update(1)
"""


def _run(code: str, tty: bool) -> str:
    """stderr of ``code`` run in a fresh process: a pipe, or a pseudo-terminal."""
    if not tty:
        return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                              check=True).stderr
    leader, follower = pty.openpty()
    fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.DEVNULL,
                            stderr=follower)
    assert proc.wait(timeout=120) == 0
    os.close(follower)
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


def test_benchmark_progress_in_a_log_is_plain_lines_one_per_tenth():
    err = _run(BENCH, tty=False)
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
def test_benchmark_progress_on_a_terminal_is_a_tqdm_bar():
    err = _run(BENCH, tty=True)
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


SLOW = """
import time
from sawdrift.study import progress as pg
pg.FIRST, pg.EVERY = 0.2, 0.4   # the clock of 1 s and 2 s, five times faster
bar = pg.progress(3, "sweep", "cell", expected=1.8)
time.sleep(0.66)          # no cell done yet: the clock still draws the bar
bar.update(1)
time.sleep(0.46)
bar.close()
"""


def test_a_bar_moves_from_the_first_second_before_any_cell_is_done():
    err = _run(SLOW, tty=False)
    lines = err.strip().splitlines()
    first = [x for x in lines if x.startswith("sweep: 0/3")]
    # a line after FIRST, then every EVERY: at about 0.2 and 0.6 s before the first cell
    assert len(first) == 2, lines
    assert "(estimate)" in first[0]
    eta = float(first[0].split("ETA ")[1].split(" s")[0])
    assert 1.4 <= eta <= 1.65  # 1.8 s expected, 0.2 s gone
    assert any(x.startswith("sweep: 1/3") for x in lines), lines


@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminal")
def test_a_terminal_bar_is_redrawn_while_no_cell_finishes():
    err = _run(SLOW, tty=True)
    frames = [f for f in err.split("\r") if "sweep:" in f and "0/3" in f]
    assert len(frames) >= 3, frames  # drawn at 0, about 0.2 and 0.6 s: the clock redraws it
    assert any("estimate" in f for f in frames), frames


def test_a_disabled_counter_prints_nothing():
    err = _run(BENCH.replace("True)", "False)"), tty=False)
    assert err == ""
