"""The drift of a heavy particle whose fast motion is irregular: friction at an imposed speed.

A heavy particle bouncing irregularly (mmd, m* = 3000, A* = 6: lift-offs 0.4 times a period at
no fixed phase) has no periodic orbit to solve for, and its mean speed relaxes over O(m*/mu)
periods, so a run from rest takes of order 1e6 periods and is still not settled. Its vertical
motion, though, does not depend on the horizontal one at all (the normal force is a function
of the compression alone), and over the time the speed takes to change, the horizontal velocity
is a constant V plus an oscillation of O(mu/m*). So the run's own vertical motion is recorded
once, over many periods and several of its slow cycles, and the contact law is driven along it
with the tangential displacement of an imposed speed,

    a*(t*) as recorded,        b*(t*) = (V t* - u_x(t*)) / (theta mu),

which gives the friction force T*(t*; V) and its long-time mean <T*>(V) over the record. The
steady drift is the first zero of <T*>(V) met from rest in the direction the mean force pushes
(as for :mod:`.separated`), and its error is the batch-means error of the per-period mean force
at the zero (Flyvbjerg and Petersen blocking, :func:`.batch_means.blocked_error`) divided by the
slope of <T*>(V) there; where the record is quasi-periodic, the zero of its weighted Birkhoff
average with the horizontal fast motion at full inertia, far more accurate, and that average's
own error (:mod:`.imposed_weighted`). The record's cost grows with the slow vertical period (its length is at
least two full-inertia windows, :func:`.full_inertia.full_window_length`), not with the
relaxation time m*/mu.
"""

from __future__ import annotations

import numpy as np

from . import adams_bashforth as ig
from .batch_means import BatchMeans, blocked_error
from .birkhoff import weighted_mean
from .fast_parts import _periodic_rate
from .full_inertia import full_window_length, shift_speed
from .imposed_weighted import weighted_zero
from .orbit_law import solver_history
from .roots import brentq, first_passed
from .separated import GRID, history_loop, load_offset
from .stepper import Stepper
from .window import Window, measure_window

#: periods per chunk of the record (its length: ``numerics.mean_periods``, or two full-inertia
#: windows if longer)
CHUNK = 16

#: columns of the trajectory rows the record keeps: x*, y*, y*', a*, b*
_RECORDED = [1, 3, 4, 5, 6]

#: periods of the record the bracket of the zero is searched on (the zero itself: all of it);
#: the bracket is widened on the whole record where the two disagree
BRACKET_PERIODS = 100

#: the zero is found to this in drift ratio (a tenth of the tolerance, against a batch-means
#: error of 5e-3 to 1e-2 over a 500-period record)
ROOT_XTOL = 1e-4

#: the zero on the record's first part, where the secants on the whole record start, is found
#: to this (they move it by more: the first part's own batch error)
START_XTOL = 1e-3

#: periods at the start of the record left out of the means (the contact memory fills in)
WASH_PERIODS = 2


class _Record:
    """The run's recorded vertical motion and the drive, at the steps the contact law sees."""

    def __init__(self, stepper: Stepper, cols: np.ndarray):
        """``cols``: x*, y*, y*', a*, b* of every step of the record (:func:`record_columns`),
        from a whole period after the ramp."""
        k = stepper.k_per
        x, y, vy, a, b = cols
        prm = stepper.prm
        self.mu = float(prm[ig.P_MU])
        self.m = float(prm[ig.P_M])
        self.scale_b = 1.0 / (float(prm[ig.P_THETA]) * self.mu)
        #: the horizontal fast motion (xi*, xi*') at the kept steps added to the imposed one, or
        #: None (:meth:`add_fast_motion`)
        self.fast: tuple[np.ndarray, np.ndarray] | None = None
        self._fast_version = 0  # counts the fast motions set (the last evaluation's key)
        #: the tangential load as a mean friction (:func:`~.separated.load_offset`)
        self.offset = load_offset(prm)
        self.k = k
        self.a, self._vy = a, vy
        # the drive, periodic after the ramp: u_y = y* - a*, u_x = x* - b*/scale (no rotation),
        # one period of it (the record's first)
        self._ux1 = x[:k] - b[:k] / self.scale_b
        self._uxd1 = _periodic_rate(self._ux1)
        self._uyd1 = _periodic_rate(y[:k] - a[:k])
        # the law as the loop has it, the scene's normal damping included (:mod:`.orbit_law`)
        self.scratch = solver_history(stepper)
        force, self.fs, self.is_, self.pp = self.scratch.kernel_call()
        self.loop = history_loop(force, stepper.compiled)
        self.keep = _contact_steps(a, self.scratch.model)

    @property
    def keep(self) -> np.ndarray:
        """Indices of the steps the contact law is driven through (:func:`_contact_steps`)."""
        return self._keep

    @keep.setter
    def keep(self, steps: np.ndarray) -> None:
        # the record at those steps, taken once: t*, u_x, u_x' (periodic), a*, a*'
        self._keep = steps
        phase = steps % self.k
        self._t = steps / self.k
        self._ux = self._ux1[phase]
        self._uxd = self._uxd1[phase]
        #: the contact law's paths (a*, b*, a*', b*') over the kept steps, one per length asked
        #: for (the bracket's first part, the whole record): a*, a*' fixed, b*, b*' per speed
        self.paths: dict[int, np.ndarray] = {}
        self._a = self.a[steps]
        self._adot = self._vy[steps] - self._uyd1[phase]
        #: the last evaluation (speed, length, fast motion, T* over the kept steps)
        self.last: tuple[float, int, int, np.ndarray] | None = None

    def _path(self, m: int) -> np.ndarray:
        path = self.paths.get(m)
        if path is None:
            path = self.paths[m] = np.empty((4, m))
            path[0] = self._a[:m]
            path[2] = self._adot[:m]
        return path

    def _kept_friction(self, v: float, n: int) -> tuple[int, np.ndarray]:
        """(kept steps within the first ``n``, T* at them) at the imposed speed ``v``."""
        m = int(np.searchsorted(self._keep, n))
        if self.last is not None and self.last[:3] == (v, n, self._fast_version):
            return m, self.last[3]
        path = self._path(m)
        np.multiply(v * self._t[:m] - self._ux[:m], self.scale_b, out=path[1])
        np.multiply(v - self._uxd[:m], self.scale_b, out=path[3])
        if self.fast is not None:
            path[1] += self.fast[0][:m] * self.scale_b
            path[3] += self.fast[1][:m] * self.scale_b
        self.scratch.reset()
        t_kept = np.empty(m)
        self.loop(self.fs, self.is_, self.pp, path, 0.0, 1, np.empty(m), t_kept)
        self.last = (v, n, self._fast_version, t_kept)
        return m, t_kept

    def add_fast_motion(self, v: float) -> None:
        """Drive the law from now on along the imposed speed plus the horizontal fast motion
        that the friction at ``v`` gives the particle at full inertia, the next order of the
        separation of motions:

            m* xi*'' = -mu (T*(t*) - <T*>),    xi*' of zero mean over the record,

        integrated along the whole record by the trapezoidal rule (steps of 1/k periods), <T*>
        and the mean of xi*' taken as weighted means (:mod:`.birkhoff`; <T*> past the record's
        first :data:`WASH_PERIODS`, as the zero's): plain means, off by the record's ends
        (1.3e-3 against 1e-8 at mmd m* = 7.08, A* = 4.539), swept the speed by a ramp as large
        as the fast motion itself. The imposed speed alone leaves this motion out, and its drift
        was 2e-4 to 5e-4 (relative) from brute force at m* = 5.5 to 22
        (:func:`~.imposed_weighted.weighted_zero`)."""
        self.clear_fast_motion()
        force = self._series(v, self.a.size)
        h = 1.0 / self.k
        accel = -(self.mu / self.m) * (force - weighted_mean(force[WASH_PERIODS * self.k:]))
        rate = np.concatenate(([0.0], np.cumsum(0.5 * h * (accel[1:] + accel[:-1]))))
        rate -= weighted_mean(rate)
        shift = np.concatenate(([0.0], np.cumsum(0.5 * h * (rate[1:] + rate[:-1]))))
        self.fast = (shift[self._keep], rate[self._keep])
        self._fast_version += 1

    def clear_fast_motion(self) -> None:
        """Drive the law along the imposed speed alone again (:meth:`add_fast_motion`); the last
        evaluation stands where it already was so driven."""
        if self.fast is not None:
            self.fast = None
            self._fast_version += 1

    def _length(self, periods: int | None) -> int:
        return self.a.size if periods is None else min(self.a.size, periods * self.k)

    def mean_friction(self, v: float, periods: int | None = None) -> float:
        """<T*> along the record (its first ``periods``) at the imposed speed ``v``, past its
        first :data:`WASH_PERIODS`: the mean of :meth:`friction`, summed over the kept steps
        (T* = 0 on the others)."""
        n = self._length(periods)
        m, t_kept = self._kept_friction(v, n)
        wash = WASH_PERIODS * self.k
        first = int(np.searchsorted(self._keep[:m], wash))
        return float(np.sum(t_kept[first:])) / (n - wash)

    def friction(self, v: float, periods: int | None = None) -> np.ndarray:
        """T*(t*) along the record (its first ``periods``) at the imposed speed ``v``, past its
        first :data:`WASH_PERIODS`. The law is driven over the kept steps only
        (:func:`_contact_steps`): T* = 0 on the others."""
        return self._series(v, self._length(periods))[WASH_PERIODS * self.k:]

    def _series(self, v: float, n: int) -> np.ndarray:
        """T* at each of the record's first ``n`` steps at the imposed speed ``v`` (the kept
        steps' values, 0 on the others)."""
        m, t_kept = self._kept_friction(v, n)
        out = np.zeros(n)
        out[self._keep[:m]] = t_kept
        return out


def record_columns(stepper: Stepper, periods: int) -> np.ndarray:
    """x*, y*, y*', a*, b* of every step of the next ``periods`` periods (rows of 5), the run
    advanced through them chunk by chunk: a chunk's rows fit in the cache, where whole-record
    row blocks (11 columns) cost more to fill and copy than to integrate."""
    cols, _samples = _advance_recorded(stepper, periods)
    return cols


def _advance_recorded(stepper: Stepper, periods: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`record_columns` and the state (x*, x*', y*, y*') at the end of each period, as
    :meth:`~.stepper.Stepper.advance_periods` gives it (the rows at the period boundaries)."""
    k = stepper.k_per
    cols = np.empty((5, periods * k))
    samples = np.empty((periods, 4))
    done = 0
    for first in range(0, periods, CHUNK):
        p = min(CHUNK, periods - first)
        rows: list[np.ndarray] = []
        stepper.advance(p * k, rows=rows)
        block = rows[0] if len(rows) == 1 else np.concatenate(rows)
        cols[:, done:done + block.shape[0]] = block[:, _RECORDED].T
        done += block.shape[0]
        # a row holds the state before its step: row j k is the end of the chunk's period j
        samples[first:first + p - 1] = block[k:p * k:k, 1:5]
        samples[first + p - 1] = stepper.y[:4]
    return cols[:, :done], samples


def _contact_steps(a: np.ndarray, model) -> np.ndarray:
    """Indices of the record's steps the contact law must see: every step in contact, and the
    first and last of each flight (where the law lets go, and the step it takes into the next
    contact from). A law that passes the conformance check ``contact_loss_reset`` is a fresh
    history after contact is lost, and without adhesion it carries no force out of contact, so
    the steps inside a flight give T* = 0 and change nothing: a heavy bouncer spends most of its
    record in flight (87 % at m* 300, A* 6), which the law need not be driven through. A law
    that declares a deviation from that check sees every step."""
    declared = {name for name, _ in model.declared_deviations()}
    if "contact_loss_reset" in declared:
        return np.arange(a.size)
    touching = a > 0.0
    keep = touching.copy()
    keep[1:] |= touching[:-1]  # the first step of a flight
    keep[:-1] |= touching[1:]  # and its last: the law steps from there into the next contact
    keep[0] = True
    return np.flatnonzero(keep)


def imposed_drift(stepper: Stepper, scene, speed: float, scale: np.ndarray | None = None,
                  evidence: int = 0, record: int = 0) -> tuple[BatchMeans | None, Window | None]:
    """The long-time mean drift (x* per period) and its error at an imposed speed along the
    run's own recorded vertical motion (module docstring); None without a zero of <T*>(V).

    The record holds at least ``record`` periods (a run that heads for a slowly modulated
    motion, :func:`~.floquet.reaches_orbit`: one decay time of the modulation). With ``scale``
    and ``evidence`` periods, the record's
    first :data:`BRACKET_PERIODS` give the zero the secants start from before the rest is
    recorded, and the rest, at that zero's speed, is measured as a window too
    (:func:`~.window.measure_window`): the regime's evidence at the drift, returned with the
    mean where it holds at least ``evidence`` periods and the secants did start there (else
    None, and the caller measures one at the mean's speed). The vertical motion does not depend
    on the horizontal one, so the record is the same to the last bit whatever the speed it was
    recorded at, and the mean the same to rounding (the first part's own contact steps end
    where it ends: 43 of the 1681 drifts of the default 41 x 41 mmd sweep moved, by at most
    3.5e-14). An irregular heavy bouncer runs 400 periods fewer.
    """
    m = scene.particle.m_star
    periods = max(scene.numerics.mean_periods, 2 * full_window_length(m, scene.theta, 1), record)
    rest = periods - BRACKET_PERIODS
    if scale is None or evidence <= 0 or rest < evidence:
        return _solve(_Pushes(_Record(stepper, record_columns(stepper, periods)), speed)), None
    first = record_columns(stepper, BRACKET_PERIODS)
    head = _Pushes(_Record(stepper, first), speed)
    r0 = _first_zero(head, None) if np.any(head.rec.a > 0.0) else None
    window = None
    if r0 is None:
        cols = record_columns(stepper, rest)
    else:
        shift_speed(stepper, r0 * speed - stepper.y[1])
        box: list[np.ndarray] = []

        def advance(n: int) -> np.ndarray:
            cols, samples = _advance_recorded(stepper, n)
            box.append(cols)
            return samples

        window = measure_window(stepper, rest, speed, scale, advance=advance)
        cols = box[0]
    # the first part's evaluations are the whole record's over its first BRACKET_PERIODS
    push = _Pushes(_Record(stepper, np.concatenate((first, cols), axis=1)), speed,
                   {(d, BRACKET_PERIODS): f for (d, _span), f in head.known.items()})
    mean = _solve(push)
    return mean, window if push.span == BRACKET_PERIODS else None


class _Pushes:
    """-<T*> along a record at drift ratios d, each (d, span) computed once (the bracket's ends
    are asked for again for the first secant); ``span``: the periods the bracket was searched
    on (:func:`_solve`)."""

    def __init__(self, rec: _Record, speed: float,
                 known: dict[tuple[float, int | None], float] | None = None):
        self.rec, self.speed = rec, speed
        self.known = {} if known is None else known
        self.span: int | None = None

    def __call__(self, d: float, span: int | None = None) -> float:
        if (d, span) not in self.known:
            self.known[(d, span)] = -self.rec.mean_friction(d * self.speed, span) + self.rec.offset
        return self.known[(d, span)]


def _solve(push: _Pushes) -> BatchMeans | None:
    """The zero of ``push`` on its whole record met from rest, its batch-means error
    (:func:`imposed_drift`); None without one."""
    rec, speed = push.rec, push.speed
    touching = rec.a > 0.0
    if not np.any(touching):
        return None  # one flight through the whole record: no friction to balance
    # the bracket is searched on the record's start if it touches as often as the whole (a
    # thrown particle can spend hundreds of periods in one flight)
    short = BRACKET_PERIODS * rec.k
    span = BRACKET_PERIODS if touching[:short].mean() >= 0.5 * touching.mean() else None
    push.span = span
    bracket = _bracket(push, span)
    if bracket is None:
        return None
    lo, hi = bracket
    found = _secant_zero(push, lo, hi, span) if span is not None else None
    if found is None:
        found = _bracketed_zero(push, lo, hi)
    if found is None:
        return None
    root, slope = found
    per_period = rec.friction(root * speed).reshape(-1, rec.k).mean(axis=1)
    _mean, se_force, batches = blocked_error(per_period, coarse=True)
    quasi = weighted_zero(push, root, slope, se_force)
    if quasi is not None:
        return BatchMeans(quasi[0] * speed, quasi[1] * speed, batches, int(per_period.size))
    se = se_force / abs(slope) if slope != 0.0 else float("inf")
    return BatchMeans(root * speed, se * speed, batches, int(per_period.size))


def _bracket(push: _Pushes, span: int | None) -> tuple[float, float] | None:
    """The bracket (low, high drift ratio) of the first zero of ``push`` over ``span`` periods
    met from rest in the direction the mean force pushes; None where the particle is held at
    rest both ways (not an irregular drift) or no zero is met."""
    eps = 1e-7
    up, down = push(eps, span), push(-eps, span)
    if up < 0.0 < down:
        return None  # held at rest both ways: not an irregular drift
    sign = 1.0 if up > 0.0 and (down >= 0.0 or up >= -down) else -1.0
    # the speed would fall back past the zero: sign * push < 0
    bracket = first_passed(lambda d: push(d, span), [sign * g for g in GRID], sign * eps,
                           lambda f: sign * f < 0.0)
    if bracket is None:
        return None
    lo, hi = sorted(bracket)
    return lo, hi


def _first_zero(push: _Pushes, span: int | None,
                bracket: tuple[float, float] | None = None) -> float | None:
    """The zero on the record's first ``span`` periods the secants of :func:`_secant_zero` start
    from (Brent's method in ``bracket``, by default :func:`_bracket`'s, to :data:`START_XTOL`),
    or None."""
    bracket = _bracket(push, span) if bracket is None else bracket
    if bracket is None:
        return None
    try:
        return brentq(lambda d: push(d, span), *bracket, xtol=START_XTOL, rtol=1e-10)
    except ValueError:
        return None


#: secant steps on the whole record at most, from the zero on its first part
SECANT_STEPS = 8


def _secant_zero(push, lo: float, hi: float, span: int) -> tuple[float, float] | None:
    """The zero of -<T*> on the whole record by the secant method, started from the zero on its
    first ``span`` periods (Brent's method in the bracket found there) with that part's slope
    across the bracket; returns the zero and the slope d(-<T*>)/d(drift ratio) of the first
    secant on the whole record, or None where the steps leave the bracket widened by its width
    on each side or do not converge to :data:`ROOT_XTOL`. Three or four evaluations of the whole
    record instead of Brent's six to eight and a bracket of its own."""
    # the first part's zero is only the secants' start: they move it by that part's error
    r0 = _first_zero(push, span, (lo, hi))
    if r0 is None:
        return None
    s0 = (push(hi, span) - push(lo, span)) / (hi - lo)
    if not s0 < 0.0:
        return None
    f0 = push(r0)
    r1 = r0 - f0 / s0
    width = hi - lo
    slope = None
    for _ in range(SECANT_STEPS):
        if not lo - width <= r1 <= hi + width:
            return None
        f1 = push(r1)
        if f1 == f0:
            return None
        secant = (f1 - f0) / (r1 - r0)
        slope = secant if slope is None else slope
        if abs(r1 - r0) <= ROOT_XTOL:
            return r1, slope
        r0, f0, r1 = r1, f1, r1 - f1 / secant
    return None


def _bracketed_zero(push, lo: float, hi: float) -> tuple[float, float] | None:
    """The zero of -<T*> on the whole record by Brent's method, the bracket of its first part
    widened until it holds on the whole; returns the zero and the slope across the bracket."""
    f_lo, f_hi = push(lo), push(hi)
    while f_lo < 0.0 or f_hi > 0.0:
        width = hi - lo
        lo, hi = lo - width if f_lo < 0.0 else lo, hi + width if f_hi > 0.0 else hi
        f_lo, f_hi = push(lo), push(hi)
        if hi - lo > 4.0:
            return None
    root = brentq(push, lo, hi, xtol=ROOT_XTOL, rtol=1e-10, fa=f_lo, fb=f_hi)
    return root, (f_hi - f_lo) / (hi - lo)
