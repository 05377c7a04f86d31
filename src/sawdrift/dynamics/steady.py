"""Steady drift: a fast approach at reduced horizontal inertia, then windows at full inertia.

From m* = 5 up the approach is usually not run at all: :func:`settle` first tries to solve
the drift directly (:mod:`.separated`, :mod:`.torus`; a creeping contact goes straight to
full-inertia windows, an irregular bouncer to :mod:`.imposed`), and the stages below are what
is left where that does not apply.

Two stages. The first (below) brings the mean speed near its steady value at a cost independent
of m*; the second (:mod:`sawdrift.dynamics.full_inertia`) puts the full m* back and measures
there until the drift has settled, so the reported drift is always the full-inertia one (the
reduced inertia alone biased sliding drifts by up to 1 % and creep near the stick boundary by
10-70 times).

A heavy particle changes its horizontal velocity by O(mu / m*) per period, so it needs of order
m* / mu periods to reach its steady drift (docs/physics.md, "Heavy particles"). Two things make
``numerics.settle`` give that steady drift at a cost independent of m*:

First stage:

1. **Separation of motions** (vibrational mechanics, Blechman 2000, the paper's ref. [5]). For
   m* >> 1 the horizontal velocity hardly changes within a wave period, and the steady drift is
   the velocity v at which the period-averaged friction force <T*>(v) vanishes. That condition
   does not contain the horizontal inertia: m*_x only sets how fast x*' relaxes towards v. The
   normal equation m* y*'' = 1 - N*(a*) does not depend on x* at all. So the run integrates
   ``m*_x x*'' = -mu T*`` with m*_x = min(m*, :data:`~.adams_bashforth.HEAVY_MASS`) and the
   full m* in the normal equation: the fixed point is the same, the approach is m* / m*_x times
   shorter. With m*_x = 100 the fast motion is still heavy, but not the particle's: its
   horizontal oscillation about the mean speed is m*/m*_x times too large, which is why the
   second stage exists.
2. **A criterion that follows the approach.** The drift is measured in windows of W periods, W
   growing with m*_x / mu. Successive window means v1, v2, v3 of a relaxation approach
   v_inf + c q^k; the remaining distance is estimated by Aitken's extrapolation,
   (v3 - v2) q / (1 - q) with q = (v3 - v2) / (v2 - v1), and the run stops when both the last change
   and that remainder are below ``numerics.settle_tolerance`` (in drift-ratio units).

The time to reach 90 % of the steady speed is read from the windows and scaled back by
m* / m*_x (the relaxation rate is inversely proportional to the horizontal inertia).

A run of fixed length (``numerics.settle`` off) is assessed after the fact by
:func:`assess_fixed` (a periodic orbit, sticking, or a change between the thirds of its window
small against the relaxation time m* / mu), so every result says whether its drift is the
steady one.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..errors import SceneError
from . import adams_bashforth as ig
from .adams_bashforth import horizontal_inertia
from .approach import relative_bound
from .direct import SentBack, settle_direct
from .evidence import EV_LANDING
from .full_inertia import (
    held,
    on_orbit,
    relaxation_rate,
    settle_full,
    tapered_drift_ratio,
)
from .separated import SOLVED_MIN_MASS, STUCK, solvable
from .settling import SLOPE, Settling
from .slip_return import free_vertical_period
from .stepper import Stepper
from .window import Window, in_flight, measure_window

__all__ = ["SLOPE", "Settling", "settle", "settles", "assess_fixed"]


#: Longest relaxation time (periods, at the integrated inertia) that ``numerics.settle`` left
#: unset settles by default (:func:`settles`): its cap, 50 of them, is then at most 5e5 periods.
AUTO_SETTLE_PERIODS = 1e4


def relaxation_periods(scene, m_x: float, speed: float) -> float:
    """Periods the drift needs to relax to its steady value, tau (0: nothing to relax).

    Friction changes the horizontal velocity by at most mu / m*_x per period (the period-averaged
    normal force is the weight), and the velocities at stake are of the order of the horizontal
    surface speed U = 2 pi r A*: the approach takes of order U m*_x / mu periods. For U >= 1 the
    scale is m*_x / mu, measured on ``benchmarks/bench_steady.py`` (time to 90 % of the steady drift
    2.7 to 7.7 m*/mu on cells with U = 1.0 to 2.9); below, tau = U m*_x / mu, so a heavy particle
    shaken by a tiny wave is not run for m*/mu periods it does not need.

    With rolling resistance the rolling spring has a free mode of frequency
    omega_r = sqrt(K_r / (kappa m*_x)) (K_r = 2.25 mu_r^2 N*'(1)), damped by the spring's viscous
    term at the ratio eta_r (:data:`~sawdrift.dynamics.adams_bashforth.ROLL_DAMPING`): it decays
    in 1 / (eta_r omega_r) periods, and tau is at least that.
    """
    tau = horizontal_relaxation(scene, m_x, speed)
    omega = rolling_frequency(scene, m_x)
    if omega > 0.0:
        tau = max(tau, 1.0 / (ig.ROLL_DAMPING * omega))
    return tau


def settles(scene, speed: float, rigid: bool) -> bool:
    """Whether a run settles its drift: never where a load runs away (:func:`runs_away`: no
    steady drift), else ``numerics.settle``, or by default where it must and can.

    Unset, a run settles when its horizontal relaxation time (:func:`horizontal_relaxation`, of
    order m*/mu periods) exceeds a third of ``numerics.periods``: a fixed run that short would end
    before the drift had relaxed (the same bound :func:`assess_fixed` holds a fixed run to). It
    does not where even the reduced inertia (:func:`horizontal_inertia`) leaves a relaxation
    longer than :data:`AUTO_SETTLE_PERIODS` (a vanishing friction, mu = 1e-6: 1e5 periods, a cap
    of millions): that run stays fixed and reports ``settled = false``; ``settle = true`` asks
    for it anyway. Where the drift can be solved directly (:func:`~.separated.solvable`, from
    ``SOLVED_MIN_MASS`` up) the run settles however fast it relaxes.
    """
    if runs_away(scene):  # asked for or not: a runaway with settle = true ran its 1e6-period cap
        return False
    given = scene.numerics.settle
    if given is not None:
        return bool(given)
    m = scene.particle.m_star
    if horizontal_relaxation(scene, horizontal_inertia(m, rigid), speed) > AUTO_SETTLE_PERIODS:
        return False
    if m >= SOLVED_MIN_MASS and solvable(scene, rigid):
        # where the drift can be solved directly it is, however fast it relaxes: at m* = 5 to
        # 10, mu = 0.5 a fixed window ended 1e-3 to 2e-3 from brute force
        return True
    return 3.0 * horizontal_relaxation(scene, m, speed) > scene.numerics.periods


def runs_away(scene) -> bool:
    """:func:`load_runs_away` of the scene's load, holding bound (:func:`holding_bound`) and
    air drag."""
    eff = scene.effects
    return load_runs_away(scene.particle.load, holding_bound(scene), eff.friction, eff.air_drag)


def holding_bound(scene) -> float:
    """The largest load |L| (in M g) the particle can hold on average: :func:`friction_bound`,
    and for a sphere free to turn (``effects.rotation``) at most mu_r, its rolling resistance.

    The load acts on the centre and has no moment about it; friction, the one force at the
    contact that has, turns the sphere. Held on average, the sphere's mean spin acceleration
    vanishes, so the mean rolling torque (per R and M g) balances the mean friction, which
    balances the load: |L| <= mu_r <N*> = mu_r (the rolling spring is capped at mu_r N*, and
    the mean normal force is the weight; with adhesion the cap is mu_r (N* + 2 F*_pull), as
    friction's, and the bound mu_r (1 + 2 F*_pull)). Without rolling resistance no load is held:
    the sphere rolls away under any load (docs/physics.md, "Loads")."""
    bound = friction_bound(scene)
    if scene.effects.rotation:
        bound = min(bound, scene.effects.rolling_resistance * (1.0 + 2.0 * _pulloff(scene)))
    return bound


def refuse_free_spin(scene, curve: str) -> None:
    """A one-line SceneError where the scene holds no load at all (:func:`holding_bound` 0: a
    sphere free to turn with no rolling resistance), so that ``curve`` (a load curve, a
    force-velocity curve) has nothing to compute."""
    if scene.effects.rotation and holding_bound(scene) <= 0.0:
        raise SceneError("effects.rotation: a sphere free to turn with no rolling resistance "
                         f"holds no load (the least load rolls it away), so it has no {curve}; "
                         "give effects.rolling_resistance > 0 (--rolling-resistance)")


def _pulloff(scene) -> float:
    """F*_pull of the scene's adhesive law (material.adhesion), 0 without adhesion."""
    return scene.material.adhesion if scene.effects.adhesion != "none" else 0.0


def friction_bound(scene) -> float:
    """The largest period-averaged friction force, in M g: mu (1 + 2 F*_pull).

    Friction is capped at mu |N* + 2 F*_pull| (F*_pull the adhesive law's pull-off force, 0
    without adhesion), and the period-averaged normal force N* is the weight, 1: a contact held
    all the time can resist mu (1 + 2 F*_pull) on average, one that lifts off less. Adhesion with
    F*_pull = 1 and mu = 0.3 holds a load of 0.89 and slides at 0.91, against mu = 0.3 without it.
    """
    return scene.material.mu * (1.0 + 2.0 * _pulloff(scene))


def load_runs_away(load: float, mu: float, friction: bool, air_drag: float) -> bool:
    """A tangential load that friction cannot hold on average: |L| > mu (the period-averaged normal
    force is the weight; ``mu`` is the scene's :func:`holding_bound`, mu (1 + 2 F*_pull) with
    adhesion, at most mu_r for a sphere free to turn), or any load without friction, and no air
    drag to bound the speed."""
    if load == 0.0 or air_drag > 0.0:
        return False
    return (not friction) or abs(load) > mu


#: relative distance of |L| from the friction bound within which the load is the bound itself
NEUTRAL_LOAD = 1e-9


def load_is_neutral(load: float, mu: float, friction: bool, air_drag: float) -> bool:
    """A load equal to the holding bound ``mu`` (:func:`holding_bound`), with friction on and
    no air drag: once the particle slides on, its mean force vanishes at every speed, so nothing
    restores it (the edge of :func:`load_runs_away`)."""
    return (load != 0.0 and friction and air_drag == 0.0
            and abs(abs(load) - mu) <= NEUTRAL_LOAD * mu)


def horizontal_relaxation(scene, m_x: float, speed: float) -> float:
    """U m*_x / mu periods (U = min(1, speed)): the approach of the horizontal velocity alone.

    The part of :func:`relaxation_periods` that makes a particle heavy; a rolling spring's slow
    mode (there too) does not decide the default of ``numerics.settle``: a spring of negligible
    strength rings for ever without changing the drift.
    """
    mu = scene.material.mu
    return m_x / mu * min(1.0, speed) if mu > 0.0 else 0.0


def rolling_frequency(scene, m_x: float) -> float:
    """omega_r = sqrt(K_r / (kappa m*_x)) of the rolling spring at a* = 1 (rad per period), or 0."""
    eff = scene.effects
    if not (eff.rotation and eff.rolling_resistance > 0.0):
        return 0.0
    k_r = 2.25 * eff.rolling_resistance**2 * scene.particle.profile.p
    return math.sqrt(k_r / (scene.particle.gyration * m_x))


def window_length(m_star: float, tau: float, minimum: int, rigid: bool = False,
                  rolling: float = 0.0) -> int:
    """Periods per settle window, at least ``minimum``.

    A tenth of the relaxation time ``tau`` (:func:`relaxation_periods`); for a compliant contact
    at least three periods of the free vertical oscillation 2 pi sqrt(m* / N*'(1)) =
    2 pi sqrt(m* / 1.5) (in wave periods), which never decays (the normal equation has no
    damping) and modulates the friction: a window shorter than it would see that modulation as a
    change of the drift (a rigid point has no such oscillation); and with rolling resistance at
    least one period 2 pi / omega_r of the rolling spring's damped mode (``rolling`` = omega_r),
    which modulates the drift in the same way while it decays.
    """
    vertical = free_vertical_period(m_star) if (m_star > 1.0 and not rigid) else 0.0
    roll = 2.0 * math.pi / rolling if rolling > 0.0 else 0.0
    return max(int(minimum), int(math.ceil(0.1 * tau)), int(math.ceil(3.0 * vertical)),
               int(math.ceil(roll)))


def default_max_periods(m_star: float, tau: float, rigid: bool, minimum_window: int,
                        rolling: float = 0.0) -> float:
    """The settle cap when ``numerics.max_periods`` is not given.

    max(5000, 50 tau + 20 windows), tau from :func:`relaxation_periods` at the integrated inertia.
    The time to 90 % of the steady drift, read at window ends, was 2.7 to 7.7 m*/mu on eight
    cells of ``benchmarks/bench_steady.py`` (m* = 30 to 3000, scaled back from the reduced
    inertia), so the cap is at least six such times plus room for the settle test's windows; a
    light particle keeps the old cap of 5000 periods.
    """
    return max(5000.0, 50.0 * tau
               + 20.0 * window_length(m_star, tau, minimum_window, rigid, rolling))


def settle(stepper: Stepper, scene, speed: float, scale: np.ndarray, minimum_window: int,
           max_steps: int) -> tuple[Window, Settling]:
    """Measure windows until the drift has settled (see the module docstring).

    The settling's ``periods`` are the run's own periods when it ended, the stretch before the
    settling began included (the run's ``periods``, as a fixed run counts them; the points of a
    force-velocity curve run on copies and are not the particle's time)."""
    got = settle_direct(stepper, scene, speed, scale, minimum_window, max_steps)
    if isinstance(got, tuple):
        return got
    # a sticking or creeping contact (STUCK) returns to its drift within a window from any
    # start, held by its tangential stiffness (the creep scales as m*^(-1/2) at full inertia):
    # no approach at reduced inertia, windows at full inertia from here
    start = stepper.step
    win, info = _approach(stepper, scene, speed, scale, minimum_window, max_steps,
                          reduce=got != STUCK)
    if isinstance(got, SentBack) and info.settled and stepper.step - start < got.tau * stepper.k_per:
        # sent back from its damped orbit: windows that settle before its vertical motion can
        # have relaxed are not a steady drift (.direct.SentBack)
        info = replace(info, settled=False, slow_vertical=got.tau)
    return win, replace(info, periods=stepper.step / stepper.k_per)


def _approach(stepper: Stepper, scene, speed: float, scale: np.ndarray, minimum_window: int,
              max_steps: int, reduce: bool = True) -> tuple[Window, Settling]:
    """The approach by windows: a reduced-inertia stage (m* > 100, if ``reduce``), then
    full-inertia windows."""
    m = scene.particle.m_star
    m_x = horizontal_inertia(m, stepper.rigid) if reduce else m
    start = stepper.step
    if m_x < m:
        values, w, t90, last = _reduced_stage(stepper, scene, speed, scale, minimum_window,
                                              max_steps, m_x)
        lam = relaxation_rate(tuple(values), w, m_x, m, scene.material.mu)
        stepper.set_horizontal_inertia(m)
    else:
        # no reduction to make: the full-inertia stage's jumps do the approach from rest; its
        # windows span the rolling spring's mode too, which modulates the drift while it decays
        values, t90, last = [], math.nan, None
        lam = SLOPE * scene.material.mu / m if scene.material.mu > 0.0 else 0.0
        omega = rolling_frequency(scene, m)
        if omega > 0.0:
            minimum_window = max(minimum_window, int(math.ceil(2.0 * math.pi / omega)))
    win, full = settle_full(stepper, scene, speed, scale, minimum_window, max_steps, lam,
                            last=last)
    if m_x == m and 0.0 < full.ratio < 1.0 and full.jumps > 0:
        # the approach a free particle would make: ln 10 / lambda with the rate measured
        t90 = math.log(10.0) * full.window_periods / -math.log(full.ratio)
    method = "reduced_then_full" if m_x < m else "windows_full"
    info = Settling(full.settled, method, m_x, full.window_periods,
                    (stepper.step - start) / stepper.k_per, t90, tuple(values) + full.history,
                    drift=full.drift(speed), slip_beat=full.slip_beat, to_go=full.to_go)
    return win, info


def _reduced_stage(stepper: Stepper, scene, speed: float, scale: np.ndarray, minimum_window: int,
                   max_steps: int, m_x: float) -> tuple[list[float], int, float, Window]:
    """The first stage: windows at the reduced inertia ``m_x`` until their means converge.

    Returns the window means, the window length, the time to 90 % of the drift scaled back to the
    full inertia, and the last window.
    """
    m = scene.particle.m_star
    stepper.set_horizontal_inertia(m_x)
    w = window_length(m, relaxation_periods(scene, m_x, speed), minimum_window, stepper.rigid,
                      rolling_frequency(scene, m_x))
    tol = scene.numerics.settle_tolerance
    values: list[float] = []
    ends: list[float] = []
    win = measure_window(stepper, w, speed, scale)
    values.append(win.drift_ratio)
    ends.append(stepper.step / stepper.k_per)
    while stepper.step + w * stepper.k_per <= max_steps:
        win = measure_window(stepper, w, speed, scale)
        values.append(win.drift_ratio)
        ends.append(stepper.step / stepper.k_per)
        if in_flight(win):
            continue  # one flight longer than the window: its constant drift says nothing
        if len(values) >= 3 and _converged(values[-3:], tol):
            break  # near the steady drift: the full-inertia stage decides whether it settled
    return values, w, _t90(values, ends) * (m / m_x), win


def _converged(v: list[float], tol: float) -> bool:
    d1, d2 = v[1] - v[0], v[2] - v[1]
    if abs(d2) > tol:
        return False
    if d1 == 0.0 or d2 == 0.0:
        return True
    q = d2 / d1
    if not 0.0 < q < 1.0:
        return abs(d2) <= 0.1 * tol  # not monotone: only a change far below tol counts
    return abs(d2 * q / (1.0 - q)) <= tol


def _t90(values: list[float], ends: list[float]) -> float:
    """First window end at which the drift reached 90 % of the final value (NaN if no drift)."""
    final = values[-1]
    if final == 0.0:
        return math.nan
    for v, t in zip(values, ends, strict=True):
        if v / final >= 0.9:
            return t
    return ends[-1]

def growing(samples: np.ndarray, scale: np.ndarray | None) -> bool:
    """Whether the period-to-period change of the stroboscopic state (y*, y*', scaled) grows
    across a window: its largest value over the last third above 1.05 times that over the first
    (a growing orbit, like a period doubling still unfolding, is not a steady motion)."""
    samples = np.asarray(samples)
    if samples.ndim != 2 or samples.shape[0] < 7:
        return False
    unit = np.asarray(scale)[1:3] if scale is not None else np.ones(2)
    s = samples[:, 2:4] / unit
    d = np.abs(np.diff(s, axis=0)).max(axis=1)
    third = d.size // 3
    return float(d[-third:].max()) > 1.05 * float(d[:third].max())


#: relaxation times a drifting run must last before its window change is believed (see below)
APPROACH_TIMES = 3.0


def assess_fixed(win: Window, speed: float, tol: float, tau: float, periods_run: float,
                 chaotic: bool = False, before: float | None = None) -> Settling:
    """Whether a fixed-length run ended at its steady drift (``method = "fixed"``).

    A run is steady when one of these holds:

    1. its stroboscopic state (x*', y*, y*') repeats after some periods (``win.orbit_period``,
       see :func:`~sawdrift.dynamics.window.orbit_period`): the motion is on a periodic orbit,
       and the drift of a periodic orbit is its steady drift;
    2. its contact held: no gross slip and no contact loss in the window, and the window's
       tapered mean (:func:`~.full_inertia.tapered_drift_ratio`) at the accuracy's floor
       (:func:`~.full_inertia.held`); that mean is the drift reported (``drift``). A window
       whose contact never slid but whose tapered mean is larger (a creep, or the ringing on the
       tangential stiffness near the contact resonances, which a box mean over 27 periods
       reports as a drift of up to 1e-2) is not steady here, whatever its thirds say (letting
       the thirds judge it settled 19 of 72 light sweep cells 3e-5 to 1.2e-4 from stuck brute
       force; a sphere rolling without slip is not called steady either, conservatively, and a
       default run's windows then settle it);
    3. its drift ratio changed by d between the last two thirds (n periods each, whole orbits
       if the motion is periodic) of the window,
       and the distance still to go, estimated as |d| max(1, tau / n) with the relaxation time
       ``tau`` (:func:`relaxation_periods`), is at most ``tol`` relative to the drift ratio
       (:func:`~.approach.relative_bound`, the windows' floor), and the run lasted at least
       :data:`APPROACH_TIMES` tau. The horizontal velocity changes by at most of order mu / m*
       per period (the period-averaged normal force is the weight, so the averaged friction is
       at most mu times it, in contact or in impacts alike); a heavy particle on its slow
       approach changes little per window, and this bound keeps that from passing for steady.
       Where the run measured the window before this one (``before``, its tapered mean: a
       default run's first window after the ramp, or the last but one of its search for an
       orbit), the two must also agree within that bound.

    A settled window's drift, as a default run reports it (``drift``), is its tapered mean
    (:func:`~.full_inertia.tapered_drift_ratio`): on 260 light cells of the default 41 x 41
    mmd sweep settled here, 241 were within 1e-3 relative or 2e-5 absolute of brute force
    (2000 periods) against 216 for the box mean (a slow beat of the vertical mode leaks into a
    box mean as P / W, into the tapered one as (P / W)^3: mmd m* = 0.0178, A* = 0.53: box
    -0.634024, tapered -0.635157, brute force -0.635151); a fixed run reports its box mean.

    In cases 1 and 3 the drift reported for the whole window must also agree with its last third
    within that bound (an early part of the window still on the transient would bias it), and if the
    particle flies, each of the last two thirds must contain a landing (a flight spanning both
    would show a constant drift that says nothing). A chaotic window, or one spent in a single
    flight, is never steady. Otherwise this is deliberately conservative: a run it
    calls unsettled may be steady, which ``numerics.settle`` then confirms.
    """
    # the drift a default run reports where the window settles (the box mean over whole orbits
    # for a periodic orbit of several periods)
    d = tapered_drift_ratio(win, speed)
    if on_orbit(win) and not chaotic:
        # an exact periodic orbit (the stroboscopic state repeats to round-off, x*' included):
        # its drift, measured over whole orbits, is the steady one
        return Settling(True, "fixed", math.nan, win.periods, periods_run, math.nan, (d,),
                        drift=d * speed)
    if win.contact_lost and not chaotic and growing(win.samples, win.scale):
        # lost contact, regular, no orbit, and the stroboscopic state moves more from period
        # to period at the window's end than at its start: still leaving (a growing alternation)
        return Settling(False, "fixed", math.nan, win.periods, periods_run, math.nan, ())
    if win.gross_slip_fraction == 0.0 and not win.contact_lost and not in_flight(win):
        # a contact that never slid as a whole: held (its tapered mean at the accuracy's floor,
        # the drift reported) or not settled here. Near the contact resonances its box mean is
        # its ringing on the tangential stiffness, not a drift (mmd m* = 0.042, A* = 0.024: -0.0118
        # over 27 periods, 6.9e-5 over 2000), and window thirds of that ringing can agree
        ok = held(win, d, tol) and not chaotic
        return Settling(ok, "fixed", math.nan, win.periods, periods_run, math.nan, (d,),
                        drift=d * speed if ok else None)
    values, n, start = _thirds(win, speed)
    # the tolerance relative to the drift ratio, with the windows' floor: absolute, it let a
    # partly sliding contact still relaxing settle 1.4 % from its drift (mmd m* = 1.78,
    # A* = 0.188: 0.05739 after 60 periods, 0.058188 from 300 on)
    eps = relative_bound(d, tol)
    ok = (bool(values) and not chaotic and not in_flight(win)
          and _steady_thirds(win, values, n, start, eps, tau, periods_run,
                             None if before is None else abs(before - d)))
    # the tapered mean, which a slow beat does not leak into: where it differs from the box
    # mean by more than the tolerance, the beat is too slow for the window to settle anything
    # (mmd m* = 0.042, A* = 0.11: box 0.27496, tapered 0.26435, brute force 0.26673)
    ok = ok and abs(d - win.drift_ratio) <= eps
    drift = d * speed if ok else None
    return Settling(ok, "fixed", math.nan, win.periods, periods_run, math.nan, values,
                    drift=drift)


def _thirds(win: Window, speed: float) -> tuple[tuple[float, ...], int, int]:
    """The drift ratios of the window's last three thirds (n periods each, whole orbits if the
    motion is periodic; none in a window too short), n, and the period the first begins at."""
    unit = max(win.orbit_period, 1)
    parts = (win.periods // unit) // 3
    n = parts * unit
    start = win.periods - 3 * n
    x = win.positions
    values = tuple(float((x[start + (k + 1) * n] - x[start + k * n]) / n / speed)
                   if speed > 0.0 else 0.0 for k in range(3)) if parts > 0 else ()
    return values, n, start


def _steady_thirds(win: Window, values: tuple[float, ...], n: int, start: int, tol: float,
                   tau: float, periods_run: float, before_gap: float | None = None) -> bool:
    """Cases 1 and 3 of :func:`assess_fixed`, with the window's consistency checks.

    ``before_gap``: how far the window before (where the run measured one) is from this one, in
    tapered drift ratio; it must be within the bound too: two windows in a row, as the
    full-inertia windows are asked for. Thirds of nine
    periods can agree on a beat far slower than the window. On the 715 light cells of the
    default 41 x 41 mmd sweep settled by their first windows, the three settled by thirds
    outside 1e-3 relative (or 2e-5 absolute) of brute force fail it and go on: m* = 0.75,
    A* = 1.50 (0.696735, the window before 0.682993) then settles at 0.698192 (brute force
    0.698193), m* = 0.42, A* = 5.96 (0.856233, before 0.855348; brute force 0.854386) is a
    long-time mean, 0.820 +- 0.026. So do 48 cells that were within the bound: 47 settle in
    windows, their median error against brute force 2.5e-5 -> 4.6e-7 relative.
    """
    if before_gap is not None and before_gap > tol:
        return False
    remaining = abs(values[2] - values[1]) * max(1.0, tau / n)
    changes = remaining <= tol and periods_run >= APPROACH_TIMES * tau
    if not (win.orbit_period > 0 or changes):
        return False
    # the reported drift spans the whole window: its early part must not still be transient
    if abs(win.drift_ratio - values[2]) > tol:
        return False
    if not win.contact_lost:
        return True
    # each compared third must hold a landing, not one long flight
    t0 = win.t_start + start
    lands = win.events[win.events[:, 1] == EV_LANDING, 0] if win.events.size else np.zeros(0)
    return all(bool(np.any((lands >= t0 + k * n) & (lands < t0 + (k + 1) * n))) for k in (1, 2))
