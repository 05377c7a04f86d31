"""Progress on long work: a tqdm bar on a terminal, plain log lines elsewhere.

tqdm redraws its bar with carriage returns and cursor codes, which end up as garbage in a log
file or a CI transcript. When stderr is not a terminal, the counters here print one plain line
whenever another tenth of the work is done, or :data:`EVERY` seconds have passed since the last
line, and at the end, with the rate and an estimate of the time left:
``sweep: 441/882 cells (50%), 612.3 cells/s, ETA 0.7 s`` (before the first unit is done, and
without a size estimate, only the time so far: ``threshold: 0/15 values (0%), 1.0 s so far``).

Cells of seconds each must not leave the user staring at a still line: the bars of
:func:`progress` are redrawn by a clock (:class:`_Ticking`), not only when a cell finishes, the
first time after :data:`FIRST` s and then every :data:`EVERY` s at most, with the elapsed time
and the time left; before the first cell is done the time left comes from the study's size
estimate (``expected`` seconds, :mod:`sawdrift.study.estimate`), marked ``(estimate)``.

:func:`progress` (the sweeps') returns None when disabled; :func:`counter` (the benchmarks')
returns a counter that prints nothing instead, so callers need no test.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

#: seconds between two progress lines (or redraws of a bar) at most, while work is being done
EVERY = 2.0

#: seconds before the first line (or redraw) of a bar whose first unit is not done yet
FIRST = 1.0

#: seconds a step may take silently before :func:`notice` says what it is doing
NOTICE_AFTER = 1.0


class _Lines:
    """A tqdm-like counter that logs plain lines (``update``, ``set_postfix_str``, ``close``)."""

    def __init__(self, total: int, initial: int, unit: str, desc: str, every: float | None = None,
                 expected: float | None = None) -> None:
        self.total, self.n, self.unit, self.desc = total, initial, unit, desc
        self.start_n = initial
        self.every = EVERY if every is None else every
        self.expected = expected
        self.t0 = self.last = time.perf_counter()
        self.next_tenth = (10 * initial) // max(total, 1) + 1
        self.postfix = ""
        self.closed = False
        self.lines = 0

    def tick(self) -> None:
        """A line if none came for :attr:`every` s (:data:`FIRST` s for the first one)."""
        now = time.perf_counter()
        if not self.closed and now - self.last >= (self.every if self.lines else FIRST):
            self._line(now)

    def update(self, k: int = 1) -> None:
        """Count ``k`` more units done; print a line at each tenth or after :attr:`every` s."""
        self.n += k
        now = time.perf_counter()
        if self.total and 10 * self.n >= self.next_tenth * self.total:
            self.next_tenth = (10 * self.n) // self.total + 1
            self._line(now)
        elif now - self.last >= self.every:
            self._line(now)

    def set_postfix_str(self, text: str, refresh: bool = False) -> None:  # noqa: ARG002 - tqdm's
        """A note shown at the end of the next line (the item being worked on)."""
        self.postfix = text

    def _line(self, now: float) -> None:
        self.last = now
        self.lines += 1
        dt = now - self.t0
        done = self.n - self.start_n
        pct = 100.0 * self.n / self.total if self.total else 100.0
        note = f" [{self.postfix}]" if self.postfix else ""
        head = f"{self.desc}: {self.n}/{self.total} {self.unit}s ({pct:.0f}%), "
        if done > 0 and dt > 0:
            rate = done / dt
            tail = f"{rate:.1f} {self.unit}s/s, ETA {(self.total - self.n) / rate:.1f} s"
        elif self.expected is not None:
            tail = f"0.0 {self.unit}s/s, ETA {max(self.expected - dt, 0.0):.1f} s (estimate)"
        else:  # nothing done yet and no estimate: no rate, no time left to print
            tail = f"{dt:.1f} s so far"
        sys.stderr.write(f"{head}{tail}{note}\n")
        sys.stderr.flush()

    def close(self) -> None:
        """Print the last count if the last line did not show it."""
        if not self.closed and self.start_n < self.n < self.total:
            self._line(time.perf_counter())
        self.closed = True

    def __enter__(self) -> _Lines:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class _Off:
    """A counter that prints nothing."""

    def update(self, k: int = 1) -> None:
        """Nothing."""

    def set_postfix_str(self, text: str, refresh: bool = False) -> None:
        """Nothing."""

    def close(self) -> None:
        """Nothing."""

    def __enter__(self) -> _Off:
        return self

    def __exit__(self, *exc: object) -> None:
        pass


class _Ticking:
    """A bar redrawn by a clock thread (:data:`FIRST`, then every :data:`EVERY` s at most).

    Wraps a tqdm bar (redrawn with its elapsed time and, before the first unit is done, the
    estimated time left) or :class:`_Lines` (a line when none came for that long); ``update``,
    ``set_postfix_str`` and ``close`` go to the bar.
    """

    def __init__(self, bar: Any, expected: float | None = None) -> None:
        import threading

        self.bar, self.expected = bar, expected
        self.t0 = time.perf_counter()
        self._stop = threading.Event()
        self._lock = threading.Lock()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        wait = FIRST
        while not self._stop.wait(wait):
            with self._lock:
                self._tick()
            wait = min(EVERY, 0.5)

    def _tick(self) -> None:
        bar = self.bar
        if isinstance(bar, _Lines):
            bar.tick()
            return
        if bar.n == bar.initial and self.expected is not None:
            left = max(self.expected - (time.perf_counter() - self.t0), 0.0)
            bar.set_postfix_str(f"ETA ~{left:.0f} s (estimate)", refresh=False)
        elif self.expected is not None:
            bar.set_postfix_str(getattr(self, "_note", ""), refresh=False)
            self.expected = None
        bar.refresh()

    def update(self, k: int = 1) -> None:
        """Count ``k`` more units done."""
        with self._lock:
            self.bar.update(k)

    def set_postfix_str(self, text: str, refresh: bool = True) -> None:
        """A note shown with the bar (the item being worked on)."""
        with self._lock:
            self._note = text
            self.bar.set_postfix_str(text, refresh=refresh)

    def close(self) -> None:
        """Stop the clock and close the bar."""
        self._stop.set()
        with self._lock:
            self.bar.close()

    def __enter__(self) -> _Ticking:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def progress(total: int, desc: str, unit: str, initial: int = 0, enabled: bool = True,
             leave: bool = True, expected: float | None = None) -> Any:
    """A progress counter with ``update(k)`` and ``close()``, or None when disabled.

    A tqdm bar when stderr is a terminal, plain lines (:class:`_Lines`) otherwise, both redrawn
    by a clock (:class:`_Ticking`) at least every :data:`EVERY` s from the first :data:`FIRST`
    s; ``expected`` (seconds, a size estimate) gives the time left before the first unit is done.
    """
    if not enabled or total <= 0:
        return None
    if _terminal():
        from tqdm import tqdm

        bar: Any = tqdm(total=total, initial=initial, unit=unit, desc=desc, dynamic_ncols=True,
                        leave=leave, mininterval=0.5, maxinterval=EVERY)
    else:
        bar = _Lines(total, initial, unit, desc, expected=expected)
    return _Ticking(bar, expected)


def _terminal() -> bool:
    """Whether stderr is a terminal a bar can be drawn on: one that reports no width (a
    pseudo-terminal of some CI and IDE consoles) drew nothing at all with tqdm's dynamic width,
    and gets the plain lines."""
    import os

    if not sys.stderr.isatty():
        return False
    try:
        return os.get_terminal_size(sys.stderr.fileno()).columns > 0
    except (OSError, ValueError):
        return False


def counter(total: int, desc: str, unit: str, enabled: bool = True, leave: bool = True) -> Any:
    """Like :func:`progress`, but a silent counter instead of None when disabled."""
    bar = progress(total, desc, unit, enabled=enabled, leave=leave)
    return _Off() if bar is None else bar


@contextmanager
def notice(line: str, after: float | None = None, enabled: bool = True) -> Iterator[None]:
    """Print ``line`` to stderr if the block takes longer than ``after`` seconds.

    For a step of unknown length that is usually quick but sometimes takes seconds in silence
    (compiling a contact model's loop on its first use): nothing is printed when it is quick.
    ``after`` defaults to :data:`NOTICE_AFTER`.
    """
    import threading

    if not enabled:
        yield
        return

    def say() -> None:
        sys.stderr.write(f"{line}\n")
        sys.stderr.flush()

    timer = threading.Timer(NOTICE_AFTER if after is None else after, say)
    timer.daemon = True
    timer.start()
    try:
        yield
    finally:
        timer.cancel()


@contextmanager
def run_progress(desc: str, after: float = 2.0) -> Iterator[None]:
    """Show the steps a run takes once it has taken ``after`` seconds: a tqdm counter on a
    terminal, a line every :data:`EVERY` s otherwise (a run of 1e6 periods went minutes with one
    line). The integration reports its steps through
    :data:`sawdrift.dynamics.stepper.PROGRESS`, twins and long-time means included."""
    from ..dynamics import stepper as stepper_module

    t0 = time.perf_counter()
    state: dict[str, Any] = {"steps": 0, "bar": None, "said": t0}

    def report(steps: int) -> None:
        state["steps"] += steps
        now = time.perf_counter()
        if now - t0 < after:
            return
        if _terminal():
            if state["bar"] is None:
                from tqdm import tqdm

                # the steps before the bar appeared as its start, not in its rate
                state["bar"] = tqdm(desc=desc, unit=" steps", unit_scale=True, leave=False,
                                    mininterval=0.5, initial=state["steps"] - steps)
            state["bar"].update(steps)
        elif now - state["said"] >= EVERY:
            state["said"] = now
            sys.stderr.write(f"{desc}: {state['steps']:.3g} steps, "
                             f"{state['steps'] / (now - t0):.3g} steps/s\n")
            sys.stderr.flush()

    stepper_module.PROGRESS[0] = report
    try:
        yield
    finally:
        stepper_module.PROGRESS[0] = None
        if state["bar"] is not None:
            state["bar"].close()

