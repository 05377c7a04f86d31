"""How fast a run put on a damped orbit of hops forgets a vertical disturbance: its Floquet
multipliers.

A contact whose normal force depends on the compression and its rate alone (a damped Hertz
law: no normal memory) has a vertical motion that does not depend on the horizontal one. After
a period of the wave, a small displacement (dy*, dy*') of the vertical state on a periodic
orbit becomes J (dy*, dy*'), J the 2 x 2 monodromy matrix of the vertical motion; its
eigenvalues, the Floquet multipliers, say how the orbit draws nearby motions in. With
|multiplier| = exp(-1 / tau) a disturbance decays over tau periods.

Where tau is long (a weakly damped heavy particle: mmd m* = 300, A* = 1, mu = 0.2, normal
damping 0.1, load -0.1: multipliers 0.99989 in modulus, tau = 9000 periods), the orbit solved
directly is an attractor, but the run from rest need not reach it in any time that matters:
that run keeps a modulation of its hops (its stroboscopic state 1.6e-4 from repeating after
1e5, 2e5 and 4e5 periods) and drifts at 0.025875, 1.4 % from the orbit's 0.025522.

J is measured by finite differences: two twins of the run, displaced by ``D0`` along y* and
y*' (scaled), and the run itself, advanced one period each (three periods of integration).

Whether the run from its own state reaches the orbit is then a measurement of its own:
:func:`reaches_orbit` follows a twin of the run, tau periods at a time, and watches the envelope
of the distance of its vertical state from the orbit's. Near the orbit (closer than
:data:`LINEAR`, where the motion about it is linear) the envelope must keep falling at the
orbit's own rate, exp(-1) per tau. On hertz_tsuji cells of tau = 1300 to 5300 periods, which
reach their orbits (their drifts agree with brute force to 1e-6), it fell by 0.37 per tau all
the way down to 3e-4; at m* = 300 above it fell so to 2.8e-3 and then stayed there (a ratio of
0.99): the run approaches its modulated hop, not the orbit.
"""

from __future__ import annotations

import math

import numpy as np

from .orbit_use import place_on_orbit
from .separated import SeparatedOrbit
from .stepper import Stepper

#: the twins' displacement, in units of the state's scale (:meth:`~.drives.Drive.state_scale`)
D0 = 1e-7


def vertical_jacobian(stepper: Stepper, scale: np.ndarray, periods: int = 1
                      ) -> tuple[np.ndarray, np.ndarray]:
    """(J, z): the 2 x 2 Jacobian of the vertical state (y*, y*') after ``periods`` periods with
    respect to the present one, by finite differences (module docstring), and the vertical state
    the motion itself reaches then. ``stepper`` itself is not advanced."""
    k = stepper.k_per * periods
    base = stepper.twin()
    twins = []
    steps = []
    for axis in (2, 3):  # y*, y*'
        dy = np.zeros(4)
        dy[axis] = D0 * float(scale[axis - 1])
        twins.append(stepper.twin(dy))
        steps.append(dy[axis])
    base.advance(k)
    for twin in twins:
        twin.advance(k)
    jac = np.array([[(t.y[i] - base.y[i]) / d for t, d in zip(twins, steps, strict=True)]
                    for i in (2, 3)])
    return jac, base.y[2:4].copy()


def vertical_decay_periods(stepper: Stepper, scale: np.ndarray) -> float:
    """tau = -1 / ln |multiplier|, periods, of the slowest vertical Floquet multiplier of the
    motion through the stepper's present state, over one period (module docstring); inf where
    a disturbance does not decay (|multiplier| >= 1) or the measurement is not finite.
    ``stepper`` itself is not advanced."""
    jac, _end = vertical_jacobian(stepper, scale)
    if not np.all(np.isfinite(jac)):
        return math.inf
    largest = float(np.max(np.abs(np.linalg.eigvals(jac))))
    if not largest < 1.0:
        return math.inf
    return -1.0 / math.log(largest) if largest > 0.0 else 0.0


#: a vertical distance from the orbit (scaled) below which the motion about it is linear
LINEAR = 1e-2

#: in the linear regime, a tau over which the envelope falls by less than this factor is a
#: plateau: the run is not approaching the orbit (the orbit's own rate gives exp(-1) = 0.37)
PLATEAU = 0.8

#: periods the check runs at most; one that cannot tell by then leaves the orbit placed (as
#: before it), for the evidence window to judge
MOST_PERIODS = 60_000

#: orbits whose disturbances decay within this many periods are placed without the check: the
#: evidence window after them judges the run (:func:`~.direct._left`)
SHORT_DECAY = 30.0


def reaches_orbit(stepper: Stepper, orbit: SeparatedOrbit, scale: np.ndarray
                  ) -> tuple[int, float]:
    """(0, tau) where a run from the stepper's present state reaches the damped ``orbit``, or
    where that cannot be told within :data:`MOST_PERIODS` (the orbit is placed, as before);
    else (the periods after which a twin of the run showed it does not, tau) (module
    docstring); tau is the orbit's vertical decay time (:func:`vertical_decay_periods`). The envelope
    is the largest scaled vertical distance from the orbit's state over the last fifth of each
    tau (the disturbance turns about the orbit); once it is below :data:`LINEAR`, two taus
    that each shrink it by :data:`PLATEAU` or more say the run reaches the orbit, one that does
    not says it does not. ``stepper`` (at a whole period) itself is not advanced."""
    placed = stepper.twin()
    place_on_orbit(placed, orbit)
    tau = vertical_decay_periods(placed, scale)
    if tau <= SHORT_DECAY or not math.isfinite(tau):
        return 0, tau
    y0 = orbit.mean_compression + float(orbit.eta[0])
    v0 = float(orbit.eta_rate[0])
    run = stepper.twin()
    chunk = int(math.ceil(tau))
    spent, falls = 0, 0
    last = math.inf
    while spent + chunk <= MOST_PERIODS:
        ends = run.advance_periods(chunk)
        spent += chunk
        tail = ends[-max(1, chunk // 5):]
        env = float(np.max(np.hypot((tail[:, 2] - y0) / scale[1], (tail[:, 3] - v0) / scale[2])))
        if last < LINEAR:
            if env >= PLATEAU * last:
                return spent, tau
            falls += 1
            if falls == 2:
                return 0, tau
        last = env
    return 0, tau
