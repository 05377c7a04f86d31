"""Progress on long work: a tqdm bar on a terminal, plain log lines elsewhere.

tqdm redraws its bar with carriage returns and cursor codes, which end up as garbage in a log
file or a CI transcript. When stderr is not a terminal, :func:`progress` prints one plain line
whenever another tenth of the work is done (and at the end), with the rate and an estimate of the
time left: ``sweep: 441/882 cells (50%), 612.3 cells/s, ETA 0.7 s``.
"""

from __future__ import annotations

import sys
import time
from typing import Any


class _Lines:
    """A tqdm-like counter that logs plain lines (update, close)."""

    def __init__(self, total: int, initial: int, unit: str, desc: str) -> None:
        self.total, self.n, self.unit, self.desc = total, initial, unit, desc
        self.start_n = initial
        self.t0 = time.perf_counter()
        self.next_tenth = (10 * initial) // max(total, 1) + 1

    def update(self, k: int = 1) -> None:
        self.n += k
        if self.total and 10 * self.n >= self.next_tenth * self.total:
            self.next_tenth = (10 * self.n) // self.total + 1
            self._line()

    def _line(self) -> None:
        dt = time.perf_counter() - self.t0
        done = self.n - self.start_n
        rate = done / dt if dt > 0 else float("nan")
        eta = (self.total - self.n) / rate if rate and rate == rate and rate > 0 else float("nan")
        pct = 100.0 * self.n / self.total if self.total else 100.0
        sys.stderr.write(f"{self.desc}: {self.n}/{self.total} {self.unit}s ({pct:.0f}%), "
                         f"{rate:.1f} {self.unit}s/s, ETA {eta:.1f} s\n")
        sys.stderr.flush()

    def close(self) -> None:
        if self.n < self.total and self.n > self.start_n:
            self._line()


def progress(total: int, desc: str, unit: str, initial: int = 0, enabled: bool = True) -> Any:
    """A progress counter with ``update(k)`` and ``close()``, or None when disabled."""
    if not enabled or total <= 0:
        return None
    if sys.stderr.isatty():
        from tqdm import tqdm

        return tqdm(total=total, initial=initial, unit=unit, desc=desc, dynamic_ncols=True)
    return _Lines(total, initial, unit, desc)
