"""What the full-inertia windows' means say beyond their values: their noise, and a beat.

:func:`~.full_inertia.settle_full` compares window means. Two changes of one sign are an
approach it may jump along (Aitken's extrapolation), unless they are within the noise of the
windows (:func:`change_noise`, :func:`chases_noise`); windows that agree have settled, unless a
beat as long as a window makes them all agree on the same biased mean (:func:`beats`). Window
means that keep turning back wander (:func:`wanders`): a long-time mean, not a steady drift.
"""

from __future__ import annotations

import math

import numpy as np

from .batch_means import blocked_error
from .window import Window

#: standard errors of a change between window means (:func:`change_noise`) both changes before
#: a jump must exceed where the jump's own scatter exceeds the accuracy (:func:`chases_noise`)
JUMP_Z = 3.0

#: the window noise (:func:`change_noise`) is at most this many times that of an uncorrelated
#: series as rough as the window's displacements
ROUGH = 5.0

#: accuracies a jump's own scatter may reach before its changes must clear :data:`JUMP_Z`
NOISE_JUMP = 2.0


def change_noise(rows: np.ndarray, speed: float) -> float:
    """The standard error of the change between two window means like this window's (``rows``:
    its :func:`~.batch_means.period_rows`), in drift ratio: sqrt(2) times the batch-means error
    of its per-period displacements, at most :data:`ROUGH` times what their period-to-period
    differences alone give (the error of an uncorrelated series of that roughness).

    The batch-means error counts a smooth modulation of the displacements as noise too (a
    regular hop's slow vertical beat, which repeats and which the tapered window means leave
    out): on mmd m* = 90, A* = 1.71 with a backward wave of half the amplitude it was 2.8e-4,
    forty times what the differences give (7e-6), and refused the jumps of a plain approach
    (changes of 5e-4, ratio 0.86), which then settled 1.7e-3 from brute force. An irregular
    bouncer's displacements are rough: its batch-means error is 3 times the differences' (a
    rigid point at m* = 38.6, A* = 0.025: 4.0e-2 against 1.3e-2) and stands."""
    if speed <= 0.0 or rows.shape[0] < 3:
        return 0.0
    steps = rows[:, 0]
    rough = float(np.std(np.diff(steps))) / math.sqrt(steps.size)
    return min(math.sqrt(2.0) * blocked_error(steps)[1], ROUGH * rough) / speed


def chases_noise(change: float, last: float, q: float, noise: float, eps: float) -> bool:
    """Whether a jump extrapolated from the window changes ``last`` and ``change`` would chase
    their noise: its own scatter, q / (1 - q) times ``noise`` (:func:`change_noise`), exceeds
    the accuracy ``eps``, and either change is within :data:`JUMP_Z` of the noise.

    An irregular bouncer's window means scatter; two changes of one sign among them are as
    likely as not, and with a heavy particle's ratio near one the extrapolation multiplies them
    by tens: a rigid point at m* = 38.6, A* = 0.025 jumped 16 times, by +0.85 and -0.30 in
    turn (changes of 1 to 2.5 noise), and its long-time mean began 81 periods after the last
    jump: 0.032 +- 0.014 against -0.044 from rest (1000 to 4000 periods of brute force). The
    jumps of a regular approach ride changes of 8 to 20 times that noise (mmd m* = 1.8 to 4.2,
    A* = 4.2 to 10), and where its last small jumps are within the noise their scatter is
    within the accuracy.
    """
    amplified = q / (1.0 - q) * noise if q < 1.0 else math.inf
    return amplified > NOISE_JUMP * eps and min(abs(change), abs(last)) <= JUMP_Z * noise


def beats(log: list[np.ndarray], win: Window, d: float, speed: float, eps: float) -> bool:
    """Whether windows that agree hide a beat: the tapered mean over the last two windows
    (contiguous rows of ``log``) differs from the last window's, ``d``, by more than the
    accuracy ``eps``.

    The Hann weights of :func:`~.full_inertia.tapered_drift_ratio` pass half of an oscillation whose period is
    the window's own (a beat of the horizontal motion against the wave, near the contact
    resonance: mmd m* = 0.0024, A* = 5.01 beats every 27.7 periods, its windows are 27 long),
    and every window then shows the same half: consecutive windows agree on a drift 1.2 % off.
    Over two windows that oscillation falls on the weights' second zero, and one of period
    W / 2 to W (a tapered mean's leak up to a fifth of its amplitude) on the third or beyond;
    a settled approach gives the two means the same value. A periodic orbit of several periods
    (box means over whole orbits) has no beat to hide.
    """
    if win.orbit_period > 1 or len(log) < 2 or speed <= 0.0:
        return False
    two = hann_mean(np.concatenate((log[-2][:, 0], log[-1][:, 0]))) / speed
    return abs(two - d) > eps


def hann_mean(steps: np.ndarray) -> float:
    """The mean of per-period displacements with the Hann weights sin^2(pi (k + 1/2) / n)
    (:func:`~.full_inertia.tapered_drift_ratio`, :func:`beats`)."""
    weights = np.sin(np.pi * (np.arange(steps.size) + 0.5) / steps.size) ** 2
    return float(np.dot(weights, steps) / weights.sum())


def wanders(values) -> bool:
    """Whether the window means wander: the changes of the last :data:`WANDER_WINDOWS` turn at
    least :data:`WANDER_TURNS` times, or those of all past the first :data:`WANDER_SKIP` do (a
    beat longer than the last windows: mmd m* = 0.0042, A* = 0.89 swings between 0.014 and
    0.062 in drift ratio over about 10 windows of 27 periods, whose last 7 turn once; its
    last window at the 1059-period cap said 0.028, the mean over the windows 0.035 +- 0.008,
    brute force 0.034)."""
    values = np.asarray(values, dtype=float)
    return (_turns(values[-WANDER_WINDOWS:]) >= WANDER_TURNS
            or _turns(values[WANDER_SKIP:]) >= WANDER_TURNS)


#: the share of their path by which the last window means must have moved one way
#: (:func:`approaches`)
ONE_WAY = 0.8


def approaches(values, accuracy: float) -> bool:
    """Whether the last :data:`WANDER_WINDOWS` window means moved one way, by more than
    ``accuracy`` in all and by at least :data:`ONE_WAY` of the path their changes took: a
    monotone approach still under way (a heavy hopping particle on a damped contact, mmd m* 30,
    A* 2, mu 0.2, e = 0.6: its window means rose from 0.63 to 0.77 over the last 14 windows of
    its cap, brute force goes on to 0.878 after 1e5 periods), not one already within the accuracy
    of its end. A beat may turn a change back by a little (mmd m* 75, A* 1.3, mu 0.2 under a
    load of -0.18 moved by -5e-4 over six changes, one of them +2e-6, and its mean, -0.20278 +-
    0.0001, went unwarned where brute force reaches -0.203186)."""
    values = np.asarray(values, dtype=float)
    last = values[-WANDER_WINDOWS:]
    if last.size < WANDER_WINDOWS:
        return False
    net = abs(last[-1] - last[0])
    return net > accuracy and net >= ONE_WAY * float(np.abs(np.diff(last)).sum())


def _turns(values: np.ndarray) -> int:
    """How many times the changes of a sequence turn (change sign)."""
    changes = np.diff(values)
    return int(np.sum(changes[1:] * changes[:-1] < 0.0)) if changes.size >= 2 else 0


#: sign changes among the last six window changes (of the last WANDER_WINDOWS window means),
#: or among all changes past the first WANDER_SKIP windows, that make a contact-kept run wander
WANDER_TURNS = 2
WANDER_WINDOWS = 7
WANDER_SKIP = 3
