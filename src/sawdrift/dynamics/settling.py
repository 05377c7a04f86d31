"""How a settling run got to its drift: the record every settle route returns.

Kept apart from :mod:`.steady` (the window approach) and :mod:`.direct` (the drift solved
directly), which both build it.
"""

from __future__ import annotations

from dataclasses import dataclass

from .batch_means import BatchMeans

#: the slope F' of the force-velocity curve at its zero assumed before one is measured: the mean
#: speed relaxes at lambda = F' mu / m* per period; measured relaxation times to 90 % of 2.7 to
#: 7.7 m*/mu (``benchmarks/bench_steady.py``) put F' between 0.3 and 0.85
SLOPE = 0.5


@dataclass(frozen=True)
class Settling:
    """How a settled run got there.

    ``history`` holds the drift ratios on the way (window means, or the solved drift first);
    ``drift``, where set, is the drift (x* per period) the run reports instead of its last
    window's box mean: a drift solved directly, whose evidence window is a sample of the slow
    vertical modulation rather than its mean, or the tapered mean the full-inertia windows
    settled on.
    """

    settled: bool
    method: str
    horizontal_inertia: float
    window_periods: int
    periods: float
    t90_periods: float
    history: tuple[float, ...]
    #: the long-time mean drift with its error, where the settling gives one instead of a
    #: settled drift (an irregular heavy bouncer, :mod:`.imposed`)
    long_mean: BatchMeans | None = None
    #: the drift (x* per period) reported instead of the last window's box mean, or None
    drift: float | None = None
    #: the beat (periods) of the free vertical oscillation after which a contact that had held
    #: slid again (:mod:`.slip_return`), 0 where none did: why such a run may not settle
    slip_beat: float = 0.0
    #: the motion still moved away from repeating when the search for its periodic orbit ended
    #: (a period doubling unfolding): no steady motion yet, why such a run is not settled
    leaving: bool = False
    #: the distance (drift ratio) the full-inertia windows still estimated to go when they
    #: stopped (:attr:`~.approach._Approach.to_go`): an approach cut off by the windows' cap,
    #: whose long-time mean is that of a stretch still moving
    to_go: float = 0.0
    #: a drift solved directly under a load whose slow-cycle average may be off by this (drift
    #: ratio) beyond the tolerance (:func:`~.direct.averaging_error`): not settled
    uncertain: float = 0.0
    #: the vertical decay time (periods) of the damped orbit a run was sent back from, where its
    #: windows settled sooner (:class:`~.direct.SentBack`): not settled
    slow_vertical: float = 0.0
    #: the growth rate (per period) of the unstable vertical orbit a run's windows kept contact
    #: on (:mod:`.half_resonance`): no steady state, not settled
    unstable: float = 0.0
