"""One branch of a bifurcation diagram: each value run to its attractor, warm-started from the last.

A branch walks the axis values in one direction with a single integration: at each value the
:class:`~sawdrift.dynamics.stepper.Stepper` is continued (:meth:`Stepper.continued`) from the
previous value's final state, with the state shifted so that the particle keeps its position and
velocity *relative to the surface* (a*, a*', b*, x*' - u_x') across the change: a parameter
continuation. :func:`attractor` then runs whole periods until the stroboscopic state repeats (or
provably converges, :mod:`sawdrift.study.orbits`), and reads the Poincare section, the period,
the multiplier, the largest Lyapunov exponent and the contact evidence from the last window.

:func:`save_state` / :func:`load_state` serialize the integration between values, so an
interrupted branch continues bit for bit; :func:`refine` bisects between two neighbouring values.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..contact.binding import bind, model_for
from ..dynamics.assembly import assemble
from ..dynamics.drives import drive_of
from ..dynamics.steady import default_max_periods, relaxation_periods, rolling_frequency
from ..dynamics.stepper import Stepper, StepperState
from ..dynamics.window import (
    Window,
    grows_steadily,
    hop_liftoffs,
    lag_change,
    measure_window,
    stretching_logs,
)
from ..scene.schema import Scene, Wave
from .orbits import LONGEST, OrbitClass, alternation_side, classify, nearest

#: Periods run at each value before its first window (after the warm start).
TRANSIENT = 100

#: Shortest analysis window (periods): enough for periods up to LONGEST and the decay fits.
MIN_WINDOW = 48

#: A motion that loses contact "sticks" (rests on the surface for a finite time each period)
#: when its fraction of time in contact exceeds this; an impact alone lasts no time.
STICK_FRACTION = 1e-9

#: Largest Lyapunov exponent (per period) above which a motion that is not yet periodic is not
#: taken to converge to a periodic orbit (chaotic motions of the diagrams here: 0.05 to 1).
CHAOS_EXPONENT = 0.02

#: Columns of one Poincare sample (one row per period of the last window).
SAMPLE_COLUMNS = ("sample", "t", "a_star", "a_rate", "v_rel", "liftoff_phase", "liftoffs")


@dataclass
class Point:
    """The attractor reached at one value of the axis.

    Attributes
    ----------
    value
        The axis value.
    period, exact, multiplier
        The orbit's class (:class:`~sawdrift.study.orbits.OrbitClass`): the period it repeats on
        or converges to (0: none), whether it already repeats to round-off, and the estimated
        multiplier of its slowest transient (NaN once converged).
    lyapunov
        Largest Lyapunov exponent per period over the last window (finite-time estimate of
        :func:`sawdrift.dynamics.window.lyapunov`; -inf when an inelastic landing erases a
        perturbation).
    contact_lost, contact_fraction
        Whether contact was lost in the last window, and the fraction of it spent in contact.
    periods
        Periods run at this value.
    samples
        The last K periods: rows of :data:`SAMPLE_COLUMNS`.
    """

    value: float
    period: int
    exact: bool
    multiplier: float
    lyapunov: float
    contact_lost: bool
    contact_fraction: float
    periods: float
    samples: np.ndarray = field(repr=False)
    error: str | None = None

    @classmethod
    def failed(cls, value: float, error: str) -> Point:
        """A value whose integration could not go on (one row of NaN samples, the error)."""
        rows = np.full((1, len(SAMPLE_COLUMNS)), math.nan)
        rows[0, 0] = 0.0
        return cls(float(value), 0, False, math.nan, math.nan, False, math.nan, 0.0, rows,
                   error.splitlines()[0] if error else "failed")

    @property
    def contact(self) -> str:
        """``"contact"`` (never lifts), ``"sticking"`` (lifts and rests a while), ``"impacts"``."""
        if self.error is not None:
            return "failed"
        if not self.contact_lost:
            return "contact"
        return "sticking" if self.contact_fraction > STICK_FRACTION else "impacts"

    def summary(self) -> dict[str, Any]:
        """JSON-ready numbers of this point (non-finite numbers become None; ``erased`` says
        where a Lyapunov exponent of -inf, a perturbation erased, became None: a reader could
        not tell it from one not computed)."""
        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        return {"value": self.value, "period": self.period, "exact": self.exact,
                "multiplier": num(self.multiplier), "lyapunov": num(self.lyapunov),
                "erased": self.lyapunov == -math.inf,
                "contact_lost": self.contact_lost,
                "contact_fraction": num(self.contact_fraction), "contact": self.contact,
                "periods": self.periods, "error": self.error}

    def to_json(self) -> dict[str, Any]:
        """Everything, for the journal (``samples`` as nested lists; NaN/inf as strings)."""
        out = self.summary()
        out["multiplier"], out["lyapunov"] = repr(self.multiplier), repr(self.lyapunov)
        out["contact_fraction"] = repr(self.contact_fraction)
        out["samples"] = [[repr(float(x)) for x in row] for row in self.samples]
        return out

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Point:
        """Inverse of :meth:`to_json`."""
        samples = np.array([[float(x) for x in row] for row in data["samples"]], dtype=float)
        return cls(float(data["value"]), int(data["period"]), bool(data["exact"]),
                   float(data["multiplier"]), float(data["lyapunov"]), bool(data["contact_lost"]),
                   float(data["contact_fraction"]), float(data["periods"]),
                   samples.reshape(-1, len(SAMPLE_COLUMNS)), data.get("error"))


# -- the integration ---------------------------------------------------------------------------


def new_stepper(scene: Scene, engine: str = "compiled") -> Stepper:
    """A stepper at t* = 0 for ``scene``, as the runner builds it (compiled or loaded)."""
    scene = bind(scene)
    model = model_for(scene)
    stepper = Stepper(scene, model, assemble(scene, engine, model), record=False,  # type: ignore[arg-type]
                      event_periods=MIN_WINDOW)
    stepper.warm_up()
    return stepper


def continue_to(stepper: Stepper, scene: Scene) -> Stepper:
    """``stepper.continued(scene)`` with the state moved along with the surface.

    At integer t* the surface is at (0, A*) with velocity (-s 2 pi r A*, 0) (docs/physics.md); a
    new amplitude or ratio moves it. The particle is shifted by the same amount
    (:meth:`Stepper.follow_surface`), so a*, a*', b* and x*' - u_x' - and with them the contact
    history - carry over unchanged.
    """
    before = stepper.surface()
    scene = bind(scene)
    new = stepper.continued(scene, model_for(scene))
    new.follow_surface(before)
    return new


def save_state(stepper: Stepper) -> str:
    """The integration's state (mechanical state, derivative history, contact memory) as text."""
    return stepper.save().to_text()


def load_state(scene: Scene, text: str, engine: str = "compiled") -> Stepper:
    """A stepper for ``scene`` holding a state written by :func:`save_state` (same model)."""
    stepper = new_stepper(scene, engine)
    stepper.restore(StepperState.from_text(text))
    return stepper


# -- one value ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class Budget:
    """How long one value may run: ``transient`` periods, windows of ``window``, at most ``cap``."""

    samples: int
    transient: int
    window: int
    cap: float

    @classmethod
    def for_scene(cls, scene: Scene, samples: int, transient: int | None = None) -> Budget:
        """The default budget: numerics.max_periods, else the settle cap of the scene."""
        window = max(int(samples), MIN_WINDOW)
        cap = scene.numerics.max_periods
        if cap is None:
            rigid = model_for(scene).capabilities.rigid
            speed = drive_of(scene).horizontal_speed(scene) if isinstance(scene.drive, Wave) else 0.0
            m = scene.particle.m_star
            cap = default_max_periods(m, relaxation_periods(scene, m, speed), rigid, window,
                                      rolling_frequency(scene, m))
        trans = TRANSIENT if transient is None else int(transient)
        return cls(int(samples), trans, window, float(max(cap, trans + window)))


def _scaled(win: Window, scale: np.ndarray) -> np.ndarray:
    return win.samples[:, 1:4] / scale


def attractor(stepper: Stepper, scene: Scene, budget: Budget, value: float) -> Point:
    """Run ``stepper`` (already at ``scene``, the axis at ``value``) to its attractor.

    Runs ``budget.transient`` periods, then windows of ``budget.window`` periods. A motion that
    seems to converge to a periodic orbit (:func:`~sawdrift.study.orbits.classify`) is run on,
    as far as its fitted decay says it needs (at most four times the periods run so far, and
    ``budget.cap`` in all), and must then go on decaying as fitted (:func:`_confirms`); one that
    does not (a quasi-periodic beat that only looked like a decay) is not periodic. A motion
    that shows no period and no decay runs on while it comes closer to repeating
    (:func:`~sawdrift.study.orbits.nearest` halves from window to window), and two more windows
    after that. The Poincare samples are the last ``budget.samples`` periods of the last window.
    """
    speed = stepper.drive.horizontal_speed(scene)
    scale = stepper.drive.state_scale(scene)
    k = stepper.k_per
    start = stepper.step
    stepper.advance(budget.transient * k)
    win = measure_window(stepper, budget.window, speed, scale)
    cls = classify(_scaled(win, scale))
    tries = 0
    steps = [lag_change(_scaled(win, scale), 1)]
    while not cls.exact:
        used = (stepper.step - start) / k
        left = budget.cap - used - budget.window
        if left < 1:
            break
        if cls.period == 0:
            before = nearest(_scaled(win, scale))
            win = measure_window(stepper, budget.window, speed, scale)
            cls = classify(_scaled(win, scale))
            steps.append(lag_change(_scaled(win, scale), 1))
            if nearest(_scaled(win, scale)) > 0.5 * before and not _departing(steps):
                tries += 1  # no progress towards any period: two more windows at most
                if tries > 2:
                    break
            continue
        jump = int(min(left, 4.0 * used, max(0.0, 1.1 * cls.remaining - budget.window)))
        stepper.advance(jump * k)
        win = measure_window(stepper, budget.window, speed, scale)
        new = classify(_scaled(win, scale))
        if not new.exact and new.period == cls.period and not _confirms(cls, new, jump + budget.window):
            cls = OrbitClass(0, False, math.nan, math.inf)  # no real decay: not periodic
            break
        cls = new
    return _point(stepper, value, win, cls, scale, (stepper.step - start) / k, budget.samples)


def _departing(steps: list[float]) -> bool:
    """Whether the motion leaves an unstable orbit at a steady rate: its period-to-period change
    grew steadily over the last two windows (:func:`~sawdrift.dynamics.window.grows_steadily`).
    Just past the inelastic ball's period doubling (Gamma 3.7263, multiplier -1.003) the
    alternation grows 4 % a window for hundreds of periods and never comes closer to repeating:
    it was cut off after two windows and called period 0, with the unstable orbit's positive
    exponent, where it settles on the orbit of 2."""
    return grows_steadily(steps, 2)


def _confirms(before: OrbitClass, after: OrbitClass, periods: float) -> bool:
    """True if a decay claimed ``periods`` earlier went on as fitted.

    The differences must have fallen by at least half the predicted amount, exp(eps n / p) with
    n = ``periods``, and the new fit must give a rate within a factor 4 of the old one. A slow
    quasi-periodic beat of the differences fails this within a few runs; a linear transient
    passes every time.
    """
    expected = before.rate * periods / before.period  # < 0
    fell = math.log(max(after.amplitude, 1e-300) / before.amplitude)
    if not math.isfinite(after.rate):
        return fell <= 0.5 * expected  # fallen to round-off: no rate left to compare
    ratio = after.rate / before.rate
    return fell <= 0.5 * expected and 0.25 <= ratio <= 4.0


def largest_lyapunov(stepper: Stepper, scale: np.ndarray, periods: int, d0: float = 1e-8) -> float:
    """Largest Lyapunov exponent per period, renormalized each period (Benettin et al. 1980).

    The mean of :func:`~sawdrift.dynamics.window.stretching_logs` after
    :data:`~sawdrift.dynamics.lyapunov.ALIGN_PERIODS`: ln |lambda| on a stable periodic orbit,
    > 0 on a chaotic one, -inf when an inelastic landing or a sticking phase erases the
    perturbation (a superstable orbit). ``stepper`` itself is not advanced.
    """
    logs = stretching_logs(stepper, scale, periods, d0=d0)
    # summed in order, as the running total it replaces (bifurcation tables keep their bits)
    return -math.inf if np.isneginf(logs).any() else sum(logs.tolist(), 0.0) / max(periods, 1)


def _point(stepper: Stepper, value: float, win: Window, cls: OrbitClass, scale: np.ndarray,
           periods: float, n: int) -> Point:
    lyap = largest_lyapunov(stepper, scale, max(n, 32))
    if not cls.exact and lyap > CHAOS_EXPONENT:
        # nearby states separate: the motion does not converge to an orbit, whatever the
        # differences seemed to do
        cls = OrbitClass(0, False, math.nan, math.inf)
    surface = stepper.drive.functions()[0]
    rows = np.empty((n, len(SAMPLE_COLUMNS)))
    first = win.periods - n
    t0 = win.t_start
    lifts = hop_liftoffs(win.events, t0, t0 + win.periods)
    slot = np.floor(lifts - t0).astype(int)
    for j in range(n):
        t = t0 + first + j + 1
        x = win.samples[first + j]
        ux, uxd, uy, uyd = surface(t, x[0], stepper.dp)
        here = lifts[slot == first + j]
        rows[j] = (j, t, x[2] - uy, x[3] - uyd, x[1] - uxd,
                   (here[0] % 1.0) if here.size else math.nan, here.size)
    return Point(float(value), cls.period, cls.exact, cls.multiplier, lyap, win.contact_lost,
                 1.0 - win.out_of_contact_fraction, periods, rows)


# -- bisection between two neighbours ------------------------------------------------------------


def transitions(below: Point, above: Point) -> list[str]:
    """What changes between two neighbouring points (ordered by value).

    ``period_doubling`` (p <-> 2p) or ``other`` (any other change of period, 0 included); and
    ``lift_off``/``contact_regained`` (contact lost above/below), ``sticking_lost``/
    ``sticking_regained`` (a resting phase below/above, contact lost on both sides). Nothing
    between a failed value and its neighbours.
    """
    if below.error is not None or above.error is not None:
        return []
    out = []
    if below.period != above.period:
        p, q = sorted((below.period, above.period))
        out.append("period_doubling" if p > 0 and q == 2 * p else "other")
    a, b = below.contact, above.contact
    if a != b and "contact" in (a, b):
        out.append("lift_off" if a == "contact" else "contact_regained")
    elif a != b:
        out.append("sticking_lost" if a == "sticking" else "sticking_regained")
    return out


def _same_side(kind: str, prev: Point, point: Point) -> bool:
    if kind in ("period_doubling", "other"):
        return point.period == prev.period
    return point.contact == prev.contact


def refine(scene_at: Callable[[float], Scene], state: str, prev: Point, nxt: Point, kind: str,
           budget: Budget, tolerance: float, engine: str = "compiled", fraction: float = 0.5,
           ahead: Sequence[float] = ()) -> dict[str, Any]:
    """Bisect between neighbours ``prev`` and ``nxt`` (branch order) to the relative ``tolerance``.

    Each midpoint is warm-started from the state on ``prev``'s side (``state`` at first: the
    branch's state at ``prev``), as the branch itself would reach it: in steps that shrink with
    the bracket, like a slow sweep. A period doubling p <-> 2p is decided by
    :func:`~sawdrift.study.orbits.alternation_side` (does the p-alternation die out or not), run
    on until it tells; anything else by :func:`attractor` at the midpoint. The bracket is cut at
    ``fraction`` of its width (0.5: bisection).

    If every midpoint stays on ``prev``'s side, ``nxt`` itself is run again from the closest
    midpoint: the branch may have left the attractor only because its step was too large (near a
    saddle-node the basin shrinks). If ``nxt`` is then on ``prev``'s side too, the search moves on
    to the next values of the branch, ``ahead``; the result counts these moves (``moved``).
    """
    lo, hi = prev.value, nxt.value
    stepper = load_state(scene_at(lo), state, engine)
    q = min(prev.period, nxt.period)
    steps = moved = 0
    ahead = list(ahead)
    # a change of contact takes the orbit periods met closest to it on each side (a coarse
    # bracket can hold a doubling besides it: its ends' periods named a sticking regained on the
    # period-2 orbit "1 -> 2"); a change of period keeps the bracket's ends, whose periods are
    # the branch's own (those met beside a change into irregular motion differ with the step)
    sides: dict[bool, int] = {}
    contact_kind = kind not in ("period_doubling", "other")

    def same_at(value: float) -> tuple[bool, Stepper]:
        scene = scene_at(value)
        trial = continue_to(stepper, scene)
        if kind == "period_doubling":
            side = _flip_side(trial, scene, q, budget)
            return (side == prev.period if side is not None else True), trial
        point = attractor(trial, scene, budget, value)
        same = _same_side(kind, prev, point)
        if contact_kind:
            sides[same] = point.period
        return same, trial

    while True:
        end = hi
        while abs(hi - lo) > tolerance * max(abs(lo), abs(hi), 1e-300):
            mid = lo + fraction * (hi - lo)
            same, trial = same_at(mid)
            if same:
                lo, stepper = mid, trial
            else:
                hi = mid
            steps += 1
        if hi != end or not ahead:
            break
        same, trial = same_at(end)
        if not same:
            break
        lo, stepper, hi = end, trial, ahead.pop(0)
        moved += 1
    a, b = sorted((lo, hi))
    out = {"value": 0.5 * (lo + hi), "bracket": [a, b], "steps": steps, "moved": moved}
    if True in sides and False in sides:
        near, far = sides[True], sides[False]  # prev's side, then the other
        out["from_period"], out["to_period"] = (near, far) if lo <= hi else (far, near)
    return out


def _flip_side(stepper: Stepper, scene: Scene, q: int, budget: Budget) -> int | None:
    """Run from a state near the q-orbit until :func:`alternation_side` tells the side."""
    scale = stepper.drive.state_scale(scene)
    k = stepper.k_per
    rows: list[np.ndarray] = []
    n = max(4 * budget.window, 8 * q + 16)
    side = None
    while len(rows) < budget.cap:
        for _ in range(n):
            stepper.advance(k)
            rows.append(stepper.y[1:4] / scale)
        side = alternation_side(np.array(rows[-min(len(rows), 16 * n):]), q)
        if side is not None:
            return side
        n = len(rows)
    return side


__all__ = ["LONGEST", "SAMPLE_COLUMNS", "Budget", "Point", "attractor", "continue_to",
           "load_state", "new_stepper", "refine", "save_state", "transitions"]
