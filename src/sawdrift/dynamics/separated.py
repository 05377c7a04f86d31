"""The periodic orbit of a heavy particle, solved directly: imposed mean height and mean speed.

For m* >> 1 the particle's motion splits into slow and fast parts (separation of motions,
Blechman 2000): a mean compression Y and a mean horizontal speed V, which change only over
hundreds of wave periods, and small fast parts eta(t*), xi(t*) of one wave period forced by the
contact forces, of amplitude O(1/m*):

    a*(t*) = Y + eta(t*) - u_y(t*)              b*(t*) = (V t* + xi(t*) - u_x(t*)) / (theta mu)
    m* eta'' = (1 - N*) - <1 - N*>              m* xi'' = -mu (T* - <T*>)

(eq. 5 of the paper with the period means taken out; <.> is the mean over one period). The
steady drift is the periodic orbit on which the means balance too:

    <N*>(Y) = 1   (the weight)                 mu <T*>(V) = L   (the mean friction balances
                                                                    the tangential load L, 0
                                                                    without one)

Both conditions are solved here at a fixed, small cost: for a given (Y, V) the fast parts are
the periodic solutions of their equations (integrated twice in Fourier space), iterated with the
forces they give (a contraction: the contact's stiffness 1.5 against m* (2 pi)^2); the contact
law runs over a few periods of the imposed motion until its memory repeats, and the last
period's means are the residuals. The normal law holds no memory of the tangential motion, so Y
is solved first; V is then the first zero of the force-velocity curve <T*>(V) met going from
rest in the direction the mean force pushes (bracketed on a grid of drift ratios, then Brent's
method). Nothing here depends on m* except the fast parts' size: the cost is a few hundred wave
periods of the contact law alone, against the O(m*/mu) periods a particle takes to reach its
drift and the windows of O(sqrt(m*)) periods that the free vertical oscillation (undamped, so it
never dies out) imposes on any measurement of a run.

Where it does not apply, :func:`separated_orbit` returns None and the run settles by windows
(:mod:`.full_inertia`):

* a contact whose memory does not repeat at the zero (a creeping contact, no gross slip: its
  tangential spring loads a little further every period; the creep is set by the particle's slow
  ringing on its tangential contact stiffness, which this construction removes). Where the
  contact comes near sliding as a whole (:data:`NEAR_SLIP`), the curve is first sampled again
  with evaluations of 6, then :data:`LONGEST_PERIODS` periods: a contact slipping over part of
  its period can take more than three to wash its memory in. A memory that repeats with no
  gross slip anywhere in the period (the exact Mindlin law of jaeger) is a creep of partial
  slip too, whose drift the ringing may set: the orbit is marked (``partial_slip``) and only
  starts windows that must confirm it (jaeger m* = 1400, A* = 0.465, mu = 0.5: the orbit's
  -0.003865 against -0.002999 from brute force; at 0.47 and beyond it is right);
* an orbit that loses contact. A run started from rest keeps the free vertical oscillation its
  start-up left (the normal contact is undamped), and where contact is lost that oscillation
  changes the drift: measured on mmd, the drift of runs from rest differs from the orbit's by
  1e-4 to 5e-3 (relative) for hopping at A* 1 to 3 and by 1 to 8 % for bouncing at A* 6 to 10
  (m* 300 to 1e4), too far to start the windows at;
* forces this module does not carry (rotation, adhesion, air drag; the scene's normal damping
  it does, in the law it drives: :mod:`.orbit_law`)
  and a drive that depends on x*. A constant tangential load L it carries: it adds L / mu to the
  mean force, -<T*>(V) + L / mu, and leaves the fast parts (about the mean) as they are.

Where contact is kept, the orbit is the start of the full-inertia windows (only the speed is set
to it; the run's vertical state stays), which then confirm it instead of relaxing from rest:
the costly first stage at reduced inertia is not needed. The run's own vertical oscillation
keeps its drift within the tolerance of the orbit's there (measured: 4.7e-4 relative at mmd,
m* = 1e3, A* = 0.6, mu = 0.1, against a run from rest of 4e5 periods).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..codegen import Generated, generate, rebind
from . import adams_bashforth as ig
from . import fast_parts as fp
from .approach import SLIDING_FRACTION
from .drives.travelling import TravellingWave
from .drives.two_wave import needs_two_waves
from .orbit_law import solver_history
from .roots import brentq, first_passed
from .stepper import Stepper

#: the separated orbit is solved from this m* up (the fast parts' contraction factor, about
#: 1.5 / (m* (2 pi)^2) times the stiffening of the contact, is then below about 0.05): below
#: :data:`SOLVED_MIN_MASS` only as the start of full-inertia windows that confirm it
SEPARATED_MIN_MASS = 3.0

#: from this m* up the drift averaged over a slow vertical cycle (at least
#: :data:`~.torus.SLOW_PERIODS` long) is the reported drift, and from :data:`ORBIT_ALONE_MASS`
#: up also the orbit's own drift where that cycle cannot be averaged over; below, they start
#: the windows. Measured (benchmarks/bench_solved_low_mass.py): on 216 cells at m* = 4 to 13.3
#: (three models, A* 0.3 to 5, mu 0.1 and 0.5) the 135 solved drifts were within 6.6e-4 of
#: brute force but one (jaeger m* 10, A* 3, mu 0.5: 1.5e-3), where the windows they replaced
#: were up to 1.8e-3 off (33 cells outside the bound before, 12 after) in 3.3 times the periods
SOLVED_MIN_MASS = 5.0

#: below this m* the orbit's own drift is not reported as solved: a cycle faster than
#: :data:`~.torus.SLOW_PERIODS` is not averaged out of it, and it was 1e-3 from brute force at
#: m* = 3 to 10 (mmd, A* = 0.7, mu = 0.1), the cycle's average within 2.2e-4 at m* = 20
ORBIT_ALONE_MASS = 30.0

#: drift ratios at which the force-velocity curve is sampled for the first zero (the bracket)
GRID = (0.0005, 0.002, 0.005, 0.01, 0.02, 0.04, 0.07, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7,
        0.8, 0.9, 1.0, 1.2, 1.5, 2.0, 3.0)

#: periods of imposed motion per evaluation: the contact's memory is washed in over the first,
#: the means are taken over the last
PERIODS = 3

#: longest evaluation: a contact whose memory has not repeated at the zero after PERIODS, and
#: that comes near sliding as a whole (NEAR_SLIP), is evaluated again over twice as many, up to
#: this (mmd m* = 1e3 to 1e4 at the stick boundary, A* = 0.165 to 0.173: 6 periods repeat to
#: 1e-15)
LONGEST_PERIODS = 12

#: |T*| / N* (T* in units of mu) a contact must reach somewhere in its period for the longer
#: evaluations: mmd m* 100 to 300 at A* 0.155 to 0.1625 reach 0.975 to 0.999; sticking cells
#: farther from the boundary 0.23 to 0.64, and their memory does not repeat (they creep)
NEAR_SLIP = 0.9

#: fast-part iterations at most per evaluation, and their convergence (in a*, relative)
FAST_ITERATIONS = 12
FAST_TOL = 1e-12

#: the contact memory repeats when T* of the last two periods agree to this (a sliding or
#: hopping orbit: 1e-14; a creeping contact, whose spring loads further every period: 1e-3)
PERIODIC_TOL = 1e-9


@dataclass(frozen=True)
class Stuck:
    """What :func:`separated_orbit` returns where there is no period-one orbit to solve for: a
    contact that sticks or creeps (held by its tangential stiffness, it needs no approach from
    rest), or one that slips over part of the period and whose memory had not repeated after
    the evaluation's periods. ``start``: the zero of the force-velocity curve found there (x*
    per period), where full-inertia windows can start; None where the curve restores both ways
    at rest."""

    start: float | None = None


#: :class:`Stuck` without a start: the force-velocity curve restores both ways at rest, or the
#: contact at its zero slides over less of the period than the full-inertia windows' threshold
#: of a slowly relaxing mean speed (:data:`~.full_inertia.SLIDING_FRACTION`)
STUCK = Stuck()

#: what :func:`separated_orbit` returns where its ``regular`` probe finds the run's lift-offs
#: not those of a period-one orbit (an irregular bouncer)
IRREGULAR = "irregular"


@dataclass(frozen=True)
class SeparatedOrbit:
    """The periodic orbit found by :func:`separated_orbit` (arrays: one period of K samples)."""

    drift: float  # V, x* per period
    mean_compression: float  # Y
    eta: np.ndarray
    eta_rate: np.ndarray
    xi_rate: np.ndarray
    normal: np.ndarray  # N* on the orbit
    tangential: np.ndarray  # T* on the orbit
    evaluations: int  # force-velocity points computed
    slope: float  # d<T*>/dV at the zero (per unit of x* per period), from the closest points
    loses_contact: bool  # a* <= 0 somewhere on the orbit
    curve: tuple[tuple[float, float], ...]  # (drift ratio, -<T*>) sampled on the way to the zero
    problem: _Problem = field(repr=False, compare=False)  # the imposed motion, for .torus
    #: no gross slip anywhere in the period, contact kept: a creep of partial slip, which the
    #: particle's ringing on its tangential stiffness may set instead (module docstring)
    partial_slip: bool = False


def load_offset(prm: np.ndarray) -> float:
    """A constant tangential load L in the units of the mean friction <T*>: m* x*'' = -mu T* + L
    (the integrator's), so the drift is the zero of -<T*>(V) + L / mu; the fast parts, about
    the mean, do not see it."""
    return float(prm[ig.P_LOAD]) / float(prm[ig.P_MU])


def solvable(scene, rigid: bool) -> bool:
    """Whether a scene's drift may be solved directly (module docstring), read off the scene:
    heavy, compliant, friction on, one travelling wave, and none of the forces the solution
    leaves out (rotation and rolling resistance, air drag, adhesion). A constant tangential
    load is in it (:attr:`_Problem.offset`), and the scene's normal damping
    (``effects.normal_damping``, ``material.restitution``) in the contact law it drives
    (:func:`solver_history`). :func:`applies`
    adds what only the built run knows; the size estimate uses this."""
    eff = scene.effects
    drive = scene.drive
    return (not rigid and scene.particle.m_star >= SEPARATED_MIN_MASS
            and getattr(drive, "kind", None) == "wave" and not needs_two_waves(drive)
            and eff.friction and not eff.rotation
            and eff.rolling_resistance == 0.0 and eff.air_drag == 0.0
            and (eff.adhesion == "none" or scene.material.adhesion == 0.0))


def applies(stepper: Stepper, scene) -> bool:
    """Whether the orbit can be solved directly on the built run of ``scene``: :func:`solvable`,
    and the run has a contact memory to drive and the single travelling wave as its drive."""
    return (stepper.history is not None and isinstance(stepper.drive, TravellingWave)
            and solvable(scene, stepper.rigid))


_LOOPS: dict[object, object] = {}


def history_body(fs, is_, pp, path, db, periods, n_out, t_out):
    """The contact law ``force`` (a global, bound per kernel) along ``periods`` repetitions of one
    period of sampled a*, b* and their rates (the rows of ``path``), b* moved on by ``db`` each
    period: N*, T* of the last period into ``n_out``, ``t_out``; returns the largest change of
    T* from the period before (the memory committed step by step)."""
    k_per = path.shape[1]
    change = 0.0
    for p in range(periods):
        for k in range(k_per):
            n, t = force(fs, is_, pp, path[0, k], path[1, k] + p * db, path[2, k],  # noqa: F821
                         path[3, k])
            if p == periods - 1:
                d = abs(t - t_out[k])
                if d > change:
                    change = d
            n_out[k] = n
            t_out[k] = t
    return change


def history_loop(force, compiled: bool):
    """:func:`history_body` bound to a kernel's ``force``: compiled once per kernel and cached on
    disk across processes (:mod:`sawdrift.codegen`, as the wave loop), or plain Python."""
    if not compiled:
        return rebind((history_body,), {"force": force})["history_body"]
    fn = _LOOPS.get(force)
    if fn is None:
        fn = generate(Generated(
            prefix="sawdrift_loop_", doc="the contact law along a sampled history",
            templates=(history_body,), namespace={"force": force}, imports="",
            bind={"force": force}, decorator="njit(cache=True, _nrt=False)",
            memory_options={"_nrt": False},
        ))["history_body"]
        _LOOPS[force] = fn
    return fn


class _Problem:
    """One period of the imposed motion: the drive's samples, and the contact law bound into the
    compiled loops of :mod:`.fast_parts` that run on it from an empty memory of the run's law."""

    def __init__(self, stepper: Stepper, t0: float):
        self.k = stepper.k_per
        prm = stepper.prm
        self.m = float(prm[ig.P_M])
        self.mu = float(prm[ig.P_MU])
        self.scale_b = 1.0 / (float(prm[ig.P_THETA]) * self.mu)
        #: the tangential load in the mean force's units (:func:`load_offset`)
        self.offset = load_offset(prm)
        surface = stepper.drive.functions()[0]
        t = t0 + np.arange(self.k) / self.k
        u = np.array([surface(float(ti), 0.0, stepper.dp) for ti in t])
        self.ux, self.uxd, self.uy, self.uyd = u.T
        self.t = np.arange(self.k) / self.k
        motion = np.stack((self.ux, self.uxd, self.uy, self.uyd, self.t))
        #: the imposed motion, the spectral tables and scratch rows (:mod:`.fast_parts`)
        self.tables = (motion, fp.spectral_tables(self.k), np.zeros((fp.WORK_ROWS, self.k)))
        #: the contact memory the loops drive (reset at the start of every evaluation)
        self.scratch = solver_history(stepper)
        force, fs, is_, pp = self.scratch.kernel_call()
        normal, npp, alone = fp.normal_alone(self.scratch, stepper.compiled)
        self.contact = (fs, is_, pp, npp)
        self.prm = np.array([self.m, self.mu, self.scale_b, PERIODS, float(alone)])
        self.loops = fp.fast_loops(force, self.scratch.kernel_reset(), normal, stepper.compiled)
        self.evaluations = 0
        #: how far the contact's memory was from repeating in the last :meth:`fast`
        self.residual = 0.0

    @property
    def periods(self) -> int:
        """Periods of imposed motion per evaluation of the contact law (:data:`PERIODS`)."""
        return int(self.prm[fp.PR_PERIODS])

    @periods.setter
    def periods(self, n: int) -> None:
        self.prm[fp.PR_PERIODS] = float(n)

    def orbit(self, eta: np.ndarray, eta_d: np.ndarray | None = None,
              xi: np.ndarray | None = None) -> np.ndarray:
        """A new orbit array (rows of :mod:`.fast_parts`) holding eta, eta' and xi (else 0)."""
        out = np.zeros((fp.ORBIT_ROWS, self.k))
        out[fp.ETA] = eta
        if eta_d is not None:
            out[fp.ETA_D] = eta_d
        if xi is not None:
            out[fp.XI] = xi
        return out

    def fast(self, y_mean: float, v: float, eta: np.ndarray, xi: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Iterate the fast parts at fixed (Y, V) to their periodic solution (one compiled call,
        :func:`~.fast_parts.fast_body`); returns eta, eta', xi, xi', N*, T*."""
        o = self.orbit(eta, xi=xi)
        count, self.residual = self.loops["fast_body"](self.contact, y_mean, v, self.prm,
                                                       self.tables, o, FAST_ITERATIONS, FAST_TOL)
        self.evaluations += int(count)
        return o[fp.ETA], o[fp.ETA_D], o[fp.XI], o[fp.XI_D], o[fp.NORMAL], o[fp.TANGENTIAL]

    def normal_mean(self, y_mean: float, orbit: np.ndarray) -> float:
        """<N*> over one period at the mean compression Y, at rest horizontally, on the vertical
        fast part eta, eta' in ``orbit`` (its xi rows zero)."""
        self.evaluations += 1
        return float(self.loops["normal_mean_body"](self.contact, y_mean, self.prm,
                                                    self.tables[0], orbit))

    def vertical(self, y_mean: float, orbit: np.ndarray, iterations: int) -> float:
        """``iterations`` steps of the vertical fast part at Y in ``orbit`` (in place, at rest
        horizontally, :func:`~.fast_parts.vertical_body`); <N*> of the last contact run."""
        self.evaluations += iterations
        return float(self.loops["vertical_body"](self.contact, y_mean, self.prm, self.tables,
                                                 orbit, iterations))

    def cycle_push(self, heights: np.ndarray, weights: np.ndarray, v: float, nodes: np.ndarray,
                   sweeps: int) -> float:
        """-sum_j w_j <T*>_j at speed V over the nodes of a slow vertical cycle, each node's
        horizontal fast part stepped ``sweeps`` times on from where ``nodes[j]`` holds it (one
        compiled call, :func:`~.fast_parts.node_push_body`)."""
        return float(self.loops["node_push_body"](self.contact, heights, weights, v, self.prm,
                                                  self.tables, nodes, sweeps)) + self.offset


def _mean_compression(p: _Problem) -> tuple[float, np.ndarray]:
    """Y with <N*> = 1 and the vertical fast part eta on it (the normal law ignores b*)."""
    orbit = p.orbit(np.zeros(p.k))
    y_mean = 1.0
    for _ in range(FAST_ITERATIONS):
        seen: dict[float, float] = {}  # brentq evaluates the bracket's ends again

        def excess(y: float, orbit: np.ndarray = orbit, seen: dict = seen) -> float:
            if y not in seen:
                seen[y] = p.normal_mean(y, orbit) - 1.0
            return seen[y]

        lo, hi = y_mean - 0.5, y_mean + 0.5
        while excess(lo) > 0.0:
            lo -= 2.0 * (hi - lo)
        while excess(hi) < 0.0:
            hi += 2.0 * (hi - lo)
        y_new = brentq(excess, lo, hi, xtol=1e-13, rtol=1e-13)
        eta = orbit[fp.ETA].copy()
        p.vertical(y_new, orbit, 1)
        change = float(np.max(np.abs(orbit[fp.ETA] - eta))) + abs(y_new - y_mean)
        y_mean = y_new
        if change <= FAST_TOL * max(1.0, abs(y_mean)):
            break
    return y_mean, orbit[fp.ETA].copy()


def separated_orbit(stepper: Stepper, scene, speed: float, tol: float,
                    keep_contact: bool = True, regular: Callable[[], bool] | None = None
                    ) -> SeparatedOrbit | Stuck | str | None:
    """The period-one orbit of a heavy particle (module docstring); a :class:`Stuck` where the
    contact sticks or creeps (no such orbit); None where the direct solution does not apply.

    Parameters
    ----------
    stepper
        The run, past its ramp at a whole period (the drive is sampled from there).
    speed
        2 pi r A*, the scale of the drift ratio.
    tol
        ``numerics.settle_tolerance``: the zero is found to a hundredth of it.
    keep_contact
        Return None for an orbit that loses contact (else it is returned, ``loses_contact``).
    regular
        Where the orbit loses contact, asked before the force-velocity curve is sampled whether
        the run's own fast motion can be a period-one orbit (a probe of its lift-offs); False
        returns :data:`IRREGULAR` without the curve's twenty-odd evaluations.
    """
    if speed <= 0.0 or not applies(stepper, scene):
        return None
    t0 = stepper.step / stepper.k_per
    if abs(t0 - round(t0)) > 1e-9 or t0 < stepper.drive.ramp_periods(scene):
        return None
    p = _Problem(stepper, round(t0))
    y_mean, eta = _mean_compression(p)
    loses = float(np.min(y_mean + eta - p.uy)) <= 0.0
    if loses and keep_contact:
        # the orbit loses contact: the free vertical oscillation a run's start leaves (undamped)
        # moves a hopping drift by up to 8 % from the orbit's (module docstring)
        return None
    if loses and regular is not None and not regular():
        return IRREGULAR
    while True:
        found = _curve_zero(p, y_mean, eta, speed, tol)
        if not isinstance(found, tuple):
            return found
        d_star, got, pushes = found
        if p.residual <= PERIODIC_TOL:
            break
        # the memory does not repeat at the zero: a contact slipping over part of the period
        # can wash its memory in slowly (mmd m* = 1e4, A* = 0.165: the last two of 3 periods
        # differ by 1.9e-2, of 6 by 1e-15, and the mean force of 3 periods put the zero at
        # 0.0078 against 0.0113), so the curve is sampled again with evaluations twice as long,
        # up to LONGEST_PERIODS; where it still does not repeat, no gross slip loads the
        # tangential spring a little more every period (a creeping contact): no orbit
        n_f, t_f = got[4], got[5]
        near = bool(np.any((n_f > 0.0) & (np.abs(t_f) >= NEAR_SLIP * n_f)))
        if near and 2 * p.periods <= LONGEST_PERIODS:
            # (a contact far from sliding as a whole all through its period only creeps)
            p.periods = 2 * p.periods
            continue
        sliding = _sliding_share(n_f, t_f)
        # held, it returns to its drift from rest by itself; sliding over a share of the
        # period, its mean speed is a slow variable and the zero is where windows should start
        return Stuck(d_star * speed) if sliding >= SLIDING_FRACTION else STUCK
    return SeparatedOrbit(d_star * speed, y_mean, got[0], got[1], got[3], got[4], got[5],
                          p.evaluations, _slope(pushes, d_star, speed), loses,
                          tuple(sorted(pushes.items())), p,
                          partial_slip=not loses and _sliding_share(got[4], got[5]) == 0.0)


def _sliding_share(normal: np.ndarray, tangential: np.ndarray) -> float:
    """The share of the period's samples ``normal``, ``tangential`` in which the contact slides
    as a whole (|T*| at its Coulomb bound N*)."""
    return float(np.mean((normal > 0.0) & (np.abs(tangential) >= (1.0 - ig.SLIP_RTOL) * normal)))


#: shares of the drift at which the force-velocity curve is sampled on the way to it, and the
#: gap (share of the drift) a sample already there closes (:func:`_curve_zero`)
APPROACH_SHARES = (0.5, 0.75, 0.85, 0.92)
APPROACH_GAP = 0.05


def _curve_zero(p: _Problem, y_mean: float, eta: np.ndarray, speed: float, tol: float
                ) -> tuple[float, tuple[np.ndarray, ...], dict[float, float]] | Stuck | None:
    """The first zero of the force-velocity curve met from rest, by evaluations of
    ``p.periods`` periods: (its drift ratio, the fast parts there (:meth:`_Problem.fast`), the
    curve's points (drift ratio, -<T*>)); :data:`STUCK` where the curve restores both ways at
    rest, None without a zero up to three times the surface speed."""
    xi = np.zeros(p.k)
    pushes: dict[float, float] = {}
    last_d, last_got = math.nan, None  # the last evaluation: its drift ratio and fast parts

    def push(d: float) -> float:
        """The mean acceleration sign at drift ratio d: -<T*> (the particle speeds up if > 0)."""
        nonlocal xi, last_d, last_got
        got = p.fast(y_mean, d * speed, eta, xi)
        xi = got[2]
        last_d, last_got = d, got
        pushes[d] = -float(np.mean(got[5])) + p.offset
        return pushes[d]

    eps = 1e-7
    up, down = push(eps), push(-eps)
    if up < 0.0 < down:
        return STUCK  # restoring both ways: the contact sticks (or creeps): settle by windows
    sign = 1.0 if up > 0.0 and (down >= 0.0 or up >= -down) else -1.0
    f_start = up if sign > 0 else down
    root = first_passed(push, [sign * g for g in GRID], sign * eps,
                        lambda f: f == 0.0 or (f < 0.0) != (f_start < 0.0))
    if root is None:
        return None  # no zero up to three times the surface speed: not a steady drift here
    lo, hi = root if pushes[root[1]] != 0.0 else (root[1], root[1])
    try:
        # the bracket's ends as the search left them (not evaluated again)
        d_star = lo if lo == hi else brentq(push, lo, hi, xtol=1e-2 * tol * max(abs(lo), 0.02),
                                            rtol=1e-10, fa=pushes[lo], fb=pushes[hi])
    except ValueError:
        return None  # a NaN force inside the bracket (its ends, the search's, change sign)
    # Brent's last evaluation is usually at its answer: the fast parts there are not computed again
    got = last_got if last_d == d_star else p.fast(y_mean, d_star * speed, eta, xi)
    residual = p.residual  # the memory's repetition at the zero, which the caller judges
    for share in APPROACH_SHARES:
        # the curve on the approach from rest, where the search left gaps: the time to 90 % of
        # the drift (approach_periods) integrates 1 / <T*>(V), which the chord across a gap
        # overstated (the motor example: 19259 periods from rest to 90 %, brute force 18450)
        d = share * d_star
        if min(abs(d - s) for s in pushes) > APPROACH_GAP * abs(d_star):
            push(d)
    p.residual = residual
    return d_star, got, pushes


def _slope(pushes: dict[float, float], d_star: float, speed: float) -> float:
    """d<T*>/dV at the zero: the secant through the sampled points closest to it on either side
    (NaN without one on each side)."""
    below = [d for d in pushes if d < d_star]
    above = [d for d in pushes if d > d_star]
    if not below or not above:
        return math.nan
    d0, d1 = max(below), min(above)
    return -(pushes[d1] - pushes[d0]) / ((d1 - d0) * speed)
