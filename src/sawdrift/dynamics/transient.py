"""An irregular transient that ends on a periodic orbit: the run reports the orbit.

A motion that looks chaotic or irregular over hundreds of periods can be a transient (transient
chaos): the trajectory wanders until it falls onto a stable periodic orbit, and then stays on it
for ever. A long-time mean over the wandering is not the motion's long-time behaviour, and its
error bar says nothing of the orbit to come. A rigid point at m* = 0.9, A* = 1.7105, mu = 0.1
wanders for about a thousand periods (a mean of 0.0635 +- 0.0061 in drift ratio over them),
then bounces on an orbit of 26 periods at 0.046173, which brute force over 2000 and 4000 periods
gives to 1e-10. The long-time mean (:func:`~.batch_means.long_time_mean`) looks at the
stroboscopic states of its last chunk of periods; where they repeat
(:func:`~.window.orbit_period`), the run goes on from there on the copy the mean ran on,
measures a window of whole orbits, and that window, settled, is its answer: the drift over whole
orbits, the hop read from the orbit.

The orbit is found only where the transient ends within the mean's budget
(``numerics.mean_periods``); one that ends later is reported as the mean it is, with its error.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from .batch_means import BatchMeans
from .settling import Settling
from .stepper import Stepper
from .window import Window, measure_window

#: the periods at a window's end that :func:`~.window.orbit_period` compares with an orbit before
CHECKED = 8

#: the method a run that ended its transient on an orbit reports (``settle_method``)
METHOD = "mean_then_orbit"


def orbit_window(run: Stepper, twin: Stepper | None, mean: BatchMeans | None, periods: int,
                 speed: float, scale: np.ndarray) -> Window | None:
    """The window of whole orbits that ``twin``, at the end of the long-time ``mean`` that found
    its orbit (:attr:`~.batch_means.BatchMeans.orbit`), runs next: at least two orbits, at least
    ``periods`` (the run's measuring window) and long enough for the orbit to be found in it
    again; None without such a mean, or where the orbit is not found again (it was left: not
    the end of the transient). A ``run`` recording its trajectory gets the window's rows after
    its own (the mean's periods between them are not recorded)."""
    if twin is None or mean is None or not mean.orbit:
        return None
    p = mean.orbit
    length = p * max(2, math.ceil((p + CHECKED) / p), math.ceil(periods / p))
    twin.record, twin.rec_every, twin.rec_chunks, twin.rec_rows = (run.record, run.rec_every,
                                                                   [], 0)
    win = measure_window(twin, length, speed, scale)
    if win.orbit_period == 0:
        return None
    run.rec_chunks.extend(twin.rec_chunks)
    run.rec_rows += twin.rec_rows
    return win


def orbit_settling(settling: Settling, twin: Stepper, win: Window) -> Settling:
    """The settling of a run whose transient ended on the orbit of ``win`` (measured on
    ``twin``): settled, :data:`METHOD`, over all the periods run, its drift the window's (over
    whole orbits)."""
    return replace(settling, settled=True, method=METHOD, window_periods=win.periods,
                   periods=twin.step / twin.k_per, long_mean=None, drift=None)
