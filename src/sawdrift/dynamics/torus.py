"""The drift of a heavy particle on its slow vertical oscillation: a second averaging.

A run from rest does not reach the period-one orbit of :mod:`.separated`. The normal contact is
undamped, so the free vertical oscillation of the particle on its contact (period
2 pi sqrt(m*/1.5) wave periods and longer, far slower than the wave) that the start-up leaves
goes on for ever, and the drift is the mean over it. Where contact is kept it moves the drift
by less than the tolerance; where contact is lost it moves it by up to 8 % (mmd, m* = 1e4,
A* = 10: orbit 0.847, run from rest 0.784).

That oscillation is slow against the wave and fast against the drift's approach (O(m*/mu)
periods), so it is averaged in turn (Bogoliubov and Mitropolsky, second order of the method of
averaging). The mean compression Y obeys m* Y'' = 1 - <N*>(Y), with <N*>(Y) the period mean of
the normal force on the fast motion at Y (:mod:`.separated`). This is a conservative oscillator
of energy

    E = m* Y'^2 / 2 + Phi(Y),          Phi(Y) = integral from Y_orbit to Y of (<N*>(s) - 1) ds,

fixed by the run's state when it starts settling (its Y and Y' are the state minus the orbit's
fast part). Y runs between the turning points Phi(Y1) = Phi(Y2) = E and spends the time
dY / |Y'| = dY / sqrt(2 (E - Phi(Y)) / m*) at each height. The steady drift V is the zero of the
friction force averaged over that cycle:

    F(V) = integral of <T*>(V, Y) dY / |Y'|  /  integral of dY / |Y'|  =  0,

each <T*>(V, Y) on the fast motion at Y and V with the full m*. The integrals are taken by
Gauss-Legendre quadrature in the angle phi of Y = c - r cos(phi) (which removes the turning
points' inverse square roots), and the zero is bracketed from the orbit's drift and found by
Brent's method. The horizontal speed does not change over one slow cycle (it relaxes over
O(m*/mu) periods), and the contact memory follows Y within a few periods, so both enter as
constants at each node. The cost does not depend on m*.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from . import fast_parts as fp
from .roots import brentq
from .separated import SeparatedOrbit
from .stepper import Stepper

#: Gauss-Legendre nodes over the half cycle of the slow oscillation
NODES = 8

#: steps of the potential's walk out from the orbit on one side, at most
WALK = 400

#: the slow cycle must last at least this many wave periods for the averaging to hold (a heavy
#: particle thrown for several periods at a time, bouncing at A* = 6, m* = 3000: its motion is
#: not a fast orbit about a slow height); at 10 periods (m* = 5 on its contact) the cycle's
#: average was within 6.6e-4 of brute force on 134 of 135 cells (separated.SOLVED_MIN_MASS)
SLOW_PERIODS = 10.0

#: fast-part iterations at each node (from the orbit's, which differ by O(1/m*))
NODE_ITERATIONS = 3

#: steps of each node's horizontal fast part per evaluation of the cycle-averaged force
NODE_SWEEPS = 1


class _Potential:
    """Phi(Y) by trapezoids of <N*> - 1 on a uniform grid of ``step`` walked out from the orbit's
    Y on both sides as far as asked, then interpolated linearly."""

    def __init__(self, orbit: SeparatedOrbit, step: float):
        self.orbit, self.step = orbit, step
        #: the orbit's vertical fast part, on which <N*>(Y) is taken (at rest horizontally)
        self.fast = orbit.problem.orbit(orbit.eta, orbit.eta_rate)
        y0 = orbit.mean_compression
        f0 = self._normal_excess(y0)
        self.sides = {1.0: ([y0], [0.0], [f0]), -1.0: ([y0], [0.0], [f0])}

    def _normal_excess(self, y: float) -> float:
        """<N*> - 1 over one period at the mean compression ``y`` on the orbit's vertical fast
        part."""
        return self.orbit.problem.normal_mean(y, self.fast) - 1.0

    def _extend(self, direction: float) -> None:
        ys, phis, fs = self.sides[direction]
        y = ys[-1] + direction * self.step
        f = self._normal_excess(y)
        phis.append(phis[-1] + 0.5 * (fs[-1] + f) * (y - ys[-1]))
        ys.append(y)
        fs.append(f)

    def __call__(self, y: float) -> float:
        direction = 1.0 if y >= self.orbit.mean_compression else -1.0
        ys, phis, _ = self.sides[direction]
        while (y - ys[-1]) * direction > 0.0:
            if len(ys) > WALK:
                return math.nan
            self._extend(direction)
        return float(np.interp(y, ys[::int(direction)], phis[::int(direction)]))

    def turning_point(self, energy: float, direction: float) -> float:
        """Y on one side where Phi reaches ``energy`` (NaN beyond :data:`WALK` steps)."""
        ys, phis, _ = self.sides[direction]
        while phis[-1] < energy:
            if len(ys) > WALK:
                return math.nan
            self._extend(direction)
        k = int(np.searchsorted(phis, energy))
        if k == 0:
            return ys[0]
        share = (energy - phis[k - 1]) / (phis[k] - phis[k - 1])
        return ys[k - 1] + share * (ys[k] - ys[k - 1])


@lru_cache(maxsize=4)
def _gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on [-1, 1] (computed once: 0.1 ms a call)."""
    return np.polynomial.legendre.leggauss(n)


def slow_cycle(stepper: Stepper, orbit: SeparatedOrbit
               ) -> tuple[np.ndarray, np.ndarray, float] | None:
    """Heights Y_j, time weights w_j (summing to one) and the period (in wave periods) of the
    slow vertical cycle the run is on, or None if its energy has no turning point within reach."""
    m = orbit.problem.m
    y_now = stepper.y[2] - orbit.eta[0]
    rate_now = stepper.y[3] - orbit.eta_rate[0]
    # the grid of Phi is set by the cycle's amplitude, estimated on the linearized potential
    # (stiffness N*'(1) = 1.5 of a Hertz contact): the run may pass the orbit's Y at speed
    offset = math.hypot(y_now - orbit.mean_compression, rate_now * math.sqrt(m / 1.5))
    phi = _Potential(orbit, max(offset / 32.0, 1e-6))
    energy = 0.5 * m * rate_now**2 + phi(y_now)
    if not math.isfinite(energy):
        return None
    if energy <= 1e-14:
        return np.array([orbit.mean_compression]), np.ones(1), math.inf
    y1 = phi.turning_point(energy, -1.0)
    y2 = phi.turning_point(energy, 1.0)
    if not (math.isfinite(y1) and math.isfinite(y2)):
        return None
    c, r = 0.5 * (y1 + y2), 0.5 * (y2 - y1)
    x, w = _gauss_legendre(NODES)
    angle = 0.5 * math.pi * (x + 1.0)
    heights = c - r * np.cos(angle)
    kinetic = np.array([energy - phi(h) for h in heights])
    # dt = dY / |Y'| with |Y'| = sqrt(2 (E - Phi) / m*): the half cycle's time, in wave periods
    times = 0.5 * math.pi * w * r * np.sin(angle) / np.sqrt(2.0 * np.maximum(kinetic, 1e-300) / m)
    return heights, times / times.sum(), 2.0 * float(times.sum())


def torus_drift(stepper: Stepper, orbit: SeparatedOrbit, speed: float, tol: float
                ) -> tuple[float, float, float] | None:
    """The steady drift (x* per period) averaged over the run's slow vertical cycle (module
    docstring), the lift-offs per period it implies (the time share of the cycle whose orbit
    loses contact) and the cycle's period (wave periods), or None where the cycle or a bracket of
    the zero is not found.

    Parameters
    ----------
    stepper
        The run at a whole period after the ramp (its state gives the cycle's energy).
    orbit
        :func:`~.separated.separated_orbit` at that period (its problem and fast parts).
    speed, tol
        The drift ratio's scale and ``numerics.settle_tolerance``.
    """
    cycle = slow_cycle(stepper, orbit)
    if cycle is None:
        return None
    heights, weights, period = cycle
    if period < SLOW_PERIODS:
        return None  # not slow against the wave: the averaging does not hold
    p = orbit.problem
    # each node's orbit array: its vertical fast part, from the orbit's (they differ by
    # O(1/m*)), and the horizontal one, iterated on from call to call of push
    nodes = np.zeros((heights.size, fp.ORBIT_ROWS, p.k))
    lifts = 0.0
    for j, (h, w) in enumerate(zip(heights, weights, strict=True)):
        nodes[j, fp.ETA] = orbit.eta
        nodes[j, fp.ETA_D] = orbit.eta_rate
        p.vertical(float(h), nodes[j], NODE_ITERATIONS)
        lifts += w * float(np.min(h + nodes[j, fp.ETA] - p.uy) <= 0.0)

    def push(d: float) -> float:
        """-F at drift ratio d: positive where the cycle-averaged friction speeds it up. Each
        call steps every node's horizontal fast part once on from where the calls before left
        it: the root's last evaluations, close together, have converged it (two steps a call
        moved the drifts of 120 solved cells by at most 4.5e-6 relative, for a third more
        work)."""
        return p.cycle_push(heights, weights, d * speed, nodes, NODE_SWEEPS)

    d0 = orbit.drift / speed
    f0 = push(d0)
    scale = max(abs(d0), 0.02)
    step = 0.05 * scale * (1.0 if f0 > 0.0 else -1.0)
    # the orbit's slope of the force-velocity curve predicts the cycle-averaged zero (a step of
    # -f0 / slope): the bracket's first step is twice that, at most the 5 % taken without one
    slope = -speed * orbit.slope
    if math.isfinite(slope) and slope < 0.0:
        step = math.copysign(min(max(2.0 * abs(f0 / slope), 1e-4 * scale), abs(step)), step)
    for _ in range(10):
        d1 = d0 + step
        f1 = push(d1)
        if (f1 > 0.0) != (f0 > 0.0):
            (lo, f_lo), (hi, f_hi) = sorted(((d0, f0), (d1, f1)))
            try:
                root = brentq(push, lo, hi, xtol=1e-2 * tol * max(abs(d0), 0.02), rtol=1e-10,
                              fa=f_lo, fb=f_hi)
            except ValueError:
                # a NaN force inside the bracket (its ends, the search's, change sign): no
                # clean zero here, no average
                return None
            return speed * root, lifts, period
        d0, f0, step = d1, f1, 2.0 * step
    return None
