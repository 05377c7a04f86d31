"""Progress on long work: a tqdm bar on a terminal, plain log lines elsewhere.

tqdm redraws its bar with carriage returns and cursor codes, which end up as garbage in a log
file or a CI transcript. When stderr is not a terminal, the counters here print one plain line
whenever another tenth of the work is done, or :data:`EVERY` seconds have passed since the last
line, and at the end, with the rate and an estimate of the time left:
``sweep: 441/882 cells (50%), 612.3 cells/s, ETA 0.7 s``.

:func:`progress` (the sweeps') returns None when disabled; :func:`counter` (the benchmarks')
returns a counter that prints nothing instead, so callers need no test.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

#: seconds between two plain progress lines at most (while work is being done)
EVERY = 30.0

#: seconds a step may take silently before :func:`notice` says what it is doing
NOTICE_AFTER = 1.0


class _Lines:
    """A tqdm-like counter that logs plain lines (``update``, ``set_postfix_str``, ``close``)."""

    def __init__(self, total: int, initial: int, unit: str, desc: str, every: float = EVERY) -> None:
        self.total, self.n, self.unit, self.desc = total, initial, unit, desc
        self.start_n = initial
        self.every = every
        self.t0 = self.last = time.perf_counter()
        self.next_tenth = (10 * initial) // max(total, 1) + 1
        self.postfix = ""
        self.closed = False

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
        dt = now - self.t0
        done = self.n - self.start_n
        rate = done / dt if dt > 0 else float("nan")
        eta = (self.total - self.n) / rate if rate > 0 else float("nan")
        pct = 100.0 * self.n / self.total if self.total else 100.0
        note = f" [{self.postfix}]" if self.postfix else ""
        sys.stderr.write(f"{self.desc}: {self.n}/{self.total} {self.unit}s ({pct:.0f}%), "
                         f"{rate:.1f} {self.unit}s/s, ETA {eta:.1f} s{note}\n")
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


def progress(total: int, desc: str, unit: str, initial: int = 0, enabled: bool = True,
             leave: bool = True) -> Any:
    """A progress counter with ``update(k)`` and ``close()``, or None when disabled.

    A tqdm bar when stderr is a terminal, plain lines (:class:`_Lines`) otherwise.
    """
    if not enabled or total <= 0:
        return None
    if sys.stderr.isatty():
        from tqdm import tqdm

        return tqdm(total=total, initial=initial, unit=unit, desc=desc, dynamic_ncols=True,
                    leave=leave)
    return _Lines(total, initial, unit, desc)


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
