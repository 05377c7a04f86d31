"""A contact that looks steady on an unstable orbit: the parametric resonance at half the wave's
frequency.

The normal force of a compliant contact is a nonlinear function of the compression, so the wave,
which modulates the compression once a period, also modulates the contact's stiffness once a
period. A free vertical oscillation whose frequency is near half the wave's (for a Hertz contact
N*'(1) = 1.5, so m* near 1.5 / pi^2 = 0.152; with adhesion the stiffer adhesive contact puts it
at other masses), undamped or damped less than it is pumped, is pumped parametrically, as a
swing is by standing up and crouching twice a swing: the period-one orbit of the vertical motion
is unstable, and any disturbance of it grows exponentially. The run from rest leaves only a
small one, so for tens to hundreds of periods the contact holds or slides exactly as on the
orbit, and windows measured then agree and settle; later the oscillation has grown into a slow
beat of large bounces that moves the drift by 10 to 20 % or changes its regime
(hertz_mindlin_dem, m* = 0.152, A* = 0.1: 0.0304 settled after 60 periods, 0.038 from brute
force over 8000; mmd and jaeger there settled as sticking, where brute force drifts with and
against the wave).

The test, where a run would settle on a window that kept contact:

1. the vertical Jacobian J over one period at the present state (:func:`~.floquet.vertical_jacobian`,
   three periods of integration). Its trace and determinant say how the vertical motion turns
   once a period: an orbit loses its stability to a flip (a disturbance that changes sign every
   period and grows) where tr J crosses -(1 + det J), -2 for an undamped contact (det J = 1), a
   little above it for a damped one. Only a trace within :data:`NEAR_HALF` of that boundary, or
   beyond it, goes on;
2. one Newton step to the orbit from the present state, z - (J - I)^-1 (P(z) - z), and the
   Jacobian J_n over :data:`GROWTH_PERIODS` periods there: the modulus of its largest eigenvalue
   is exp(n r), r the growth rate of a disturbance per period (0 on a stable undamped orbit,
   below 0 on a damped one). A rate above :data:`MIN_RATE` is an unstable orbit. One period is
   not enough near the tongue's edge: the micro-silica example's J has the trace -1.99981 (a
   rotation), while its disturbances grow by 1.2 % a period (J_60 says so).

An unstable orbit is no steady state. The run goes on until its disturbance has grown to
:data:`GROWN` (scaled), as the run from rest would without help, and its drift is the long-time
mean from there (a periodic orbit where the growth ends on one).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .floquet import vertical_jacobian
from .stepper import Stepper

#: a one-period trace within this of -(1 + det J) (the flip boundary: -2 for an undamped
#: contact, det J = 1; a damped one's det J < 1 moves it) is tested over :data:`GROWTH_PERIODS`;
#: of the 1076 cells of the default 41 x 41 mmd sweep that settle in contact, 4 are (one a
#: stable orbit near the edge, m* = 0.1, A* = 0.53)
NEAR_HALF = 0.02

#: periods the growth test follows the orbit's neighbours (its cost: three times this)
GROWTH_PERIODS = 60

#: the least growth rate (per period) that counts as unstable: a disturbance grows e-fold within
#: 1000 periods; a stable orbit's J over 60 periods gives the scheme's own 1e-4 or less
#: (hertz_mindlin_dem, m* = 0.152, A* = 0.01 grows by 5.24e-3 a period: a bound of 5.3e-3 missed
#: it, and it settled 25 to 40 % low; the silica example at 0.007 nm grows by 3.7e-3)
MIN_RATE = 1e-3

#: the scaled distance from the orbit a disturbance grows to before the long-time mean starts
GROWN = 1.0

#: periods a run waits at most for its disturbance to grow
MOST_WAIT = 20_000

#: the long-time mean after the growth spans this many e-folding times 1 / rate (at most
#: ``MOST_FLIGHT_BUDGETS`` mean budgets, :mod:`.integrate`): the beat the
#: disturbance grows into lasts 12 to 17 of them (hertz_mindlin_dem m* = 0.152, A* = 0.1: 320
#: periods at 5.4 % a period; the micro-silica example: 1100 periods at 1.2 %), so about four
#: beats
MEAN_GROWTHS = 64.0


@dataclass(frozen=True)
class Growth:
    """An unstable vertical orbit: its growth rate (per period), the scaled distance of the run
    from it, and the periods the run takes to grow to :data:`GROWN` from there."""

    rate: float
    distance: float

    @property
    def wait(self) -> int:
        """Periods until a disturbance of :attr:`distance` has grown to :data:`GROWN`, at most
        :data:`MOST_WAIT`."""
        if self.distance >= GROWN:
            return 0
        ahead = math.log(GROWN / max(self.distance, 1e-300)) / self.rate
        return int(min(MOST_WAIT, math.ceil(ahead)))

    def mean_periods(self, budget: int, most: int) -> int:
        """The long-time mean's periods: :data:`MEAN_GROWTHS` e-folding times, at least
        ``budget`` (``numerics.mean_periods``) and at most ``most``."""
        return int(min(most, max(budget, math.ceil(MEAN_GROWTHS / self.rate))))


#: a strobe map fitted to the window whose trace is more than this above the flip boundary
#: -(1 + det) is far from it (:func:`far_from_flip`): on 153 mmd runs that kept contact (m* 1e-3
#: to 100, A* 1e-2 to 10) the fitted trace was within 0.11 of the one-period J's
FIT_MARGIN = 0.3

#: the fit is used where its residual is below this share of the strobes' spread
FIT_RESIDUAL = 0.1


def far_from_flip(samples: np.ndarray, scale: np.ndarray) -> bool:
    """Whether the window's own stroboscopic vertical states (y*, y*' at each period's end, rows
    of ``samples``) show an orbit far from the flip boundary: the affine map z -> A z + b fitted
    to consecutive states by least squares (the free oscillation about the orbit turns them
    about it), its trace more than :data:`FIT_MARGIN` above -(1 + det A). No integration: the
    twins of :func:`half_resonance_growth` cost about 0.35 ms a run, a tenth of a 200-period
    run. False where the fit cannot tell (too few states, states that do not move, a residual
    above :data:`FIT_RESIDUAL` of their spread)."""
    if samples.shape[0] < 6:
        return False
    z = samples[:, 2:4] / scale[1:3]
    before, after = z[:-1], z[1:]
    centre = before.mean(axis=0)
    design = np.column_stack((before - centre, np.ones(len(before))))
    fitted, _res, rank, _sv = np.linalg.lstsq(design, after, rcond=None)
    spread = float(np.sqrt(((before - centre) ** 2).sum(axis=1).mean()))
    if rank < 3 or not spread > 0.0:
        return False
    residual = float(np.sqrt(((after - design @ fitted) ** 2).sum(axis=1).mean()))
    if not residual < FIT_RESIDUAL * spread:
        return False
    a = fitted[:2].T
    return bool(np.trace(a) > -(1.0 + np.linalg.det(a)) + FIT_MARGIN)


def half_resonance_growth(stepper: Stepper, scale: np.ndarray,
                          samples: np.ndarray | None = None) -> Growth | None:
    """The growth of the vertical orbit the run is on where that orbit is unstable at half the
    wave's frequency (module docstring), else None; with the window's ``samples``, None at once
    where they show an orbit far from the flip (:func:`far_from_flip`). ``stepper`` is not
    advanced."""
    if samples is not None and far_from_flip(samples, scale):
        return None
    jac, end = vertical_jacobian(stepper, scale)
    if not np.all(np.isfinite(jac)) or np.trace(jac) > -(1.0 + np.linalg.det(jac)) + NEAR_HALF:
        return None
    here = stepper.y[2:4].copy()
    try:
        orbit = here - np.linalg.solve(jac - np.eye(2), end - here)
    except np.linalg.LinAlgError:
        return None
    shift = np.zeros(4)
    shift[2:4] = orbit - here
    on_orbit = stepper.twin(shift)
    long_jac, _end = vertical_jacobian(on_orbit, scale, GROWTH_PERIODS)
    if not np.all(np.isfinite(long_jac)):
        return None
    largest = float(np.max(np.abs(np.linalg.eigvals(long_jac))))
    rate = math.log(largest) / GROWTH_PERIODS if largest > 0.0 else -math.inf
    if not rate > MIN_RATE:
        return None
    distance = float(np.hypot(shift[2] / scale[1], shift[3] / scale[2]))
    return Growth(rate, distance)
