"""The rows a run records: its trajectory (at most :data:`RECORDS_PER_PERIOD` a period, thinned
past :data:`MAX_TRAJECTORY_ROWS` so that a run's memory does not grow with its length) and its
stroboscopic samples (one row a period)."""

from __future__ import annotations

import numpy as np

from . import adams_bashforth as ig

__all__ = ["MAX_TRAJECTORY_ROWS", "NO_ROWS", "RECORDS_PER_PERIOD", "SEGMENT_ROWS", "strobe_rows",
           "thinned"]

#: Trajectory samples recorded per wave period (at most).
RECORDS_PER_PERIOD = 200

#: Most trajectory rows a run keeps (11 floats a row: 92 MB); a longer record is thinned
#: (:func:`thinned`)
MAX_TRAJECTORY_ROWS = 1 << 20

#: Rows of the buffer one segment of a recorded advance fills (5.8 MB)
SEGMENT_ROWS = 1 << 16


def thinned(chunks: list[np.ndarray], h: float, every: int) -> tuple[list[np.ndarray], int]:
    """Every other row of the recorded ``chunks`` (taken every ``every`` steps of ``h``): the
    rows at multiples of twice the interval, as one chunk, and that interval, to record at from
    there (the caller thins past :data:`MAX_TRAJECTORY_ROWS`)."""
    data = np.concatenate(chunks)
    steps = np.rint(data[:, 0] / h).astype(np.int64)
    return [data[steps % (2 * every) == 0]], 2 * every


#: the loops' row buffer where nothing is recorded (they write rows only with rec_every > 0)
NO_ROWS = np.zeros((0, ig.N_REC))


def strobe_rows(strobe: tuple[np.ndarray, int], rows: np.ndarray) -> None:
    """Put trajectory rows taken at period boundaries into ``samples[j - 1]``, j the periods
    since ``t0`` (``strobe`` = (samples, t0)); the rows' time is column 0, the state columns 1-4."""
    samples, t0 = strobe
    if rows.shape[0] == 0:
        return
    first, last = round(rows[0, 0]) - t0, round(rows[-1, 0]) - t0
    if last - first == rows.shape[0] - 1:
        # one row a period, in order (the loops record them so): a slice, not an index per row
        lo, hi = max(first, 1), min(last, samples.shape[0])
        if lo <= hi:
            samples[lo - 1:hi] = rows[lo - first:hi - first + 1, 1:5]
        return
    j = np.rint(rows[:, 0]).astype(np.int64) - t0
    inside = (j >= 1) & (j <= samples.shape[0])
    samples[j[inside] - 1] = rows[inside, 1:5]
