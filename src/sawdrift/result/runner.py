"""Run one scene: assemble only what its effects need, integrate, and summarize in a Result.

The dynamics layer integrates and measures (:mod:`sawdrift.dynamics.integrate`, the prescribed
scheme of :mod:`sawdrift.dynamics.prescribed`); this module names the regime from those
measurements (:func:`~sawdrift.result.regimes.classify`), adds a device's SI outputs and builds
the :class:`~sawdrift.result.Result`.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import replace
from typing import Any

from .._texts import HEATING, STILL_MOVING
from ..contact.binding import bind, model_for
from ..contact.registry import plugin_failures
from ..dynamics.assembly import Engine, assemble, ramp_end_step
from ..dynamics.batch_means import HALVES_Z, TREND_Z
from ..dynamics.drives import Drive
from ..dynamics.impact import (
    IMPACT_DURATIONS,
    MAX_IMPACT_STEPS,
    ImpactRun,
    integrate_impact,
)
from ..dynamics.integrate import FLIGHTS_PER_MEAN, MOST_FLIGHT_BUDGETS, WaveRun, integrate_wave
from ..dynamics.prescribed import PrescribedRun, run_prescribed
from ..dynamics.steady import holding_bound, load_is_neutral, runs_away
from ..dynamics.window import Window, ballistic_return, in_flight
from ..errors import SceneError
from ..scene.device import device_outputs
from ..scene.schema import Scene
from ..scene.validity import device_warnings
from .regimes import classify, outcome
from .result import Result

__all__ = ["run"]


def run(
    scene: Scene,
    *,
    trajectory: bool = False,
    engine: Engine = "compiled",
    record_every: int | None = None,
) -> Result:
    """Run ``scene`` and return its :class:`~sawdrift.result.Result`.

    Parameters
    ----------
    scene
        The experiment.
    trajectory
        Also return the time series (t, x, vx, y, vy, a, b, N, T) as a DataFrame.
    engine
        ``"compiled"`` (numba kernels) or ``"python"`` (the readable reference implementations).
    record_every
        Record the trajectory every this many steps (default: about 200 samples per period).
    """
    if record_every is not None and not (isinstance(record_every, numbers.Integral)
                                         and record_every >= 1):
        raise SceneError(f"record_every = {record_every!r} must be a whole number of steps >= 1 "
                         "(or None: about 200 samples a period)")
    scene = bind(scene)
    with plugin_failures(scene.model):
        return _run(scene, trajectory, engine, record_every)


def _run(scene: Scene, trajectory: bool, engine: Engine, record_every: int | None) -> Result:
    model = model_for(scene)
    plan = assemble(scene, engine, model)
    if plan.scheme == "prescribed":
        return _prescribed_result(scene, plan.engine, run_prescribed(scene, model, plan.engine))
    if plan.scheme == "impact":
        return _impact_result(scene, plan.engine, integrate_impact(scene, model, plan), trajectory)
    return _wave_result(scene, plan.engine, plan.drive,
                        integrate_wave(scene, model, plan, trajectory, record_every))


def _wave_result(scene: Scene, engine: str, drive: Drive, out: WaveRun) -> Result:
    """The Result of a periodic drive's run: the regime named from the window's evidence."""
    wave = scene.drive
    assert hasattr(wave, "amplitude") and hasattr(wave, "ramp_periods")  # any periodic drive
    win, settling = out.window, out.settling
    hop_period = out.hop_period
    t90 = settling.t90_periods if out.settle_on else math.nan
    solved = settling.drift if out.speed > 0.0 else None
    # the regime reads the drift reported: a long-time mean's, not its last window's (mmd
    # m* = 0.0042, A* = 0.89 in contact: 0.0082 +- 0.0027 was called oscillating_slip)
    mean = out.long_mean.mean if out.long_mean is not None and out.speed > 0.0 else None
    read = solved if solved is not None else mean
    drift_ratio, regime = _regime(scene, drive, win, out.speed, hop_period,
                                  None if read is None else read / out.speed)
    acceleration = mean_acceleration(win.positions)
    stepper = out.stepper
    ret = ballistic_return(float(stepper.y[2]), float(stepper.y[3]), scene.particle.m_star,
                           drive.vertical_amplitude(scene))
    ending = outcome(scene.particle.load, holding_bound(scene), scene.effects.friction,
                     scene.effects.air_drag, in_flight(win) and out.long_mean is None, ret,
                     stepper.step / stepper.k_per,
                     win.drift, acceleration, out.speed)
    drift, drift_ratio, drift_se = _reported_drift(out, drift_ratio, solved)
    settled = settling.settled
    detach = math.nan
    if ending:
        regime, drift, drift_ratio, settled = ending, math.nan, math.nan, False
        t90 = math.nan
        detach = out.last_liftoff if ending == "ejected" else math.nan
    extra: dict[str, object] = {}
    settled, warnings = _verdict(scene, out, ending, settled, drift_se, ret)
    if not settled:
        t90 = math.nan  # the time to 90 % of a speed never reached (it was quoted unsettled)
    runaway = runaway_acceleration(scene, acceleration) if ending == "runaway" else math.nan
    if scene.device is not None:
        extra.update(device_outputs(scene.device, drift, regime, t90 if out.settle_on else None,
                                    detach, drift_se * out.speed, runaway))
    k_per = stepper.k_per
    steps = out.steps  # a long-time mean's twin ran on after the window: its steps count
    return Result(
        **_window_fields(out, ending == "ejected"),
        model=scene.model,
        engine=engine,
        m_star=scene.particle.m_star,
        amplitude=wave.amplitude,
        mu=scene.material.mu,
        nu=scene.material.nu,
        horizontal_ratio=scene.horizontal_ratio,
        profile=scene.particle.profile.shape,
        steps_per_period=k_per,
        periods=steps / k_per,
        ramp_periods=wave.ramp_periods,
        measure_periods=win.periods,
        drift_velocity=drift,
        drift_ratio=drift_ratio,
        regime=regime,
        orbit=drive.orbit_name(scene),
        steps=steps,
        wall_time_s=out.wall_time_s,
        gross_slip_fraction=_gross_slip(scene, win, out.speed),
        scene=scene.model_dump(mode="json"),
        trajectory=out.trajectory,
        compile_s=out.compile_s,
        settled=settled,
        settle_method=settling.method,
        settle_periods=(settling.periods if out.long_mean is None
                        else max(settling.periods, steps / k_per)),
        t90_periods=t90,
        horizontal_inertia=settling.horizontal_inertia if out.settle_on else math.nan,
        mean_acceleration=runaway,
        drift_ratio_se=drift_se,
        detach_time=detach,
        warnings=warnings,
        detach_phase=detach % 1.0 if math.isfinite(detach) and detach >= 0.0 else math.nan,
        extra=extra,
    )


def _window_fields(out: WaveRun, ejected: bool) -> dict[str, object]:
    """The Result's fields read off the run's measuring window: contact, lift-offs and their
    phases, spin, periodicity, the Lyapunov exponent, events. A free flight's window has no
    motion to be chaotic or periodic in (an ejected 'silica bead on quartz' reported a Lyapunov
    exponent 0.0137 and periodicity 0.47): NaN for an ejected particle."""
    win, sync, hop_period = out.window, out.window.sync, out.hop_period
    return dict(
        contact_lost=win.contact_lost,
        out_of_contact_fraction=win.out_of_contact_fraction,
        min_compression=win.min_compression,
        liftoffs_per_period=win.liftoffs_per_period,
        hop_period=hop_period,
        liftoff_phase=sync.phase,
        liftoff_phase_spread=sync.spread,
        lyapunov=math.nan if ejected else out.lyapunov,
        spin_rate=win.spin_rate,
        periodicity=math.nan if ejected else win.periodicity,
        event_rows=win.events,
        chaotic=out.chaotic,
        events_dropped=win.events_dropped,
        orbit_period=win.orbit_period,
        liftoffs_per_hop=sync.liftoffs_per_hop if hop_period else math.nan,
        liftoff_phases=sync.phases if hop_period else (),
    )


def _verdict(scene: Scene, out: WaveRun, ending: str, settled: bool, drift_se: float,
             ret: float) -> tuple[bool, tuple[str, ...]]:
    """Whether a periodic drive's run counts as settled, and its warnings: a runaway's or an
    ejection's (no steady drift), a neutral load (nothing restores the speed), a run within the
    drive's start-up ramp, or the reason a settling run did not settle."""
    wave = scene.drive
    stepper = out.stepper
    # a runaway or an ejection has no steady drift: nothing of a long-time mean to warn about
    warnings = _warnings(scene, replace(out, long_mean=None) if ending else out, drift_se)
    if ending == "ejected":
        frequency = scene.device.frequency if scene.device is not None else None
        warnings += (ejected_landing(stepper.step / stepper.k_per, ret, frequency),)
    if not ending and load_is_neutral(scene.particle.load, holding_bound(scene),
                                      scene.effects.friction, scene.effects.air_drag):
        # friction at its bound balances the load exactly once the particle slides on: nothing
        # pulls its speed back (mmd m* 1, A* 0.5, mu = L = 0.1 settled at 1.0088, brute force
        # went on to 1.0170 over 4e4 periods)
        settled = False
        warnings += ("not settled: the load equals the most friction can hold, mu (1 + 2 F*_pull)"
                     ": nothing restores the mean speed, which drifts on (neutral), no steady "
                     "drift",)
    elif not ending and stepper.step <= ramp_end_step(wave.ramp_periods, stepper.k_per):
        # the whole run within the drive's start-up ramp: the wave was still growing
        settled = False
        warnings += (f"not settled: the run ended within the drive's start-up ramp "
                     f"(numerics.periods = {stepper.step / stepper.k_per:g}, drive.ramp_periods = "
                     f"{wave.ramp_periods:g}): its window saw the wave still growing, no steady "
                     "motion; give more periods or a shorter ramp (--ramp-periods)",)
    elif not settled and not ending and out.long_mean is None and scene.numerics.settle is not False:
        warnings += (_unsettled_reason(out, scene.numerics.settle is True),)
    return settled, warnings


def _reported_drift(out: WaveRun, drift_ratio: float,
                    solved: float | None) -> tuple[float, float, float]:
    """(drift, drift ratio, its standard error) a run reports: the window's; the drift solved
    directly (dynamics.direct: the window is one sample of the slow vertical modulation, the
    solved drift its mean); or an irregular motion's long-time mean with its batch-means error,
    not one window's sample. A mean still moving at the end of its extensions has no error: it
    is the mean of its last stretch, not a long-time mean (the warnings say so)."""
    drift = out.window.drift if solved is None else solved
    if out.long_mean is not None and out.speed > 0.0:
        drift = out.long_mean.mean
        se = math.nan if out.long_mean.moving else out.long_mean.se / out.speed
        return drift, drift / out.speed, se
    return drift, drift_ratio, math.nan


def _table_warning(scene: Scene) -> tuple[str, ...]:
    """A tabulated normal law that ends below the compression the drive reaches, about 1 + 2 A*
    (the weight's compression and twice the vertical amplitude): beyond its last
    point N* follows the table's last tangent, which nothing said (a table ending at a* = 1.5
    gave N* = 6.39 at a* = 3.3 where the law it tabulated gives 8.42)."""
    profile = scene.particle.profile
    amplitude = getattr(scene.drive, "amplitude", None)
    if profile.shape != "table" or amplitude is None:
        return ()
    law = profile.law()
    end = float(law[1] * law[2])  # cells times the cell width: the table's last a*
    reach = 1.0 + 2.0 * float(amplitude)
    if reach <= end:
        return ()
    return (f"profile table: it ends at a* = {end:.3g} and the drive compresses to about a* = "
            f"{reach:.3g}; beyond its last point N* follows the table's last tangent (extend the "
            "table to cover the compressions)",)


def ejected_landing(now: float, return_time: float, frequency: float | None = None) -> str:
    """The warning of an ejected particle: when, in free flight under gravity and the preload
    alone, it can touch the surface again (``return_time`` periods after ``now``,
    :func:`~sawdrift.dynamics.window.ballistic_return`; in seconds too on a device of wave
    ``frequency``). A rigid point at m* = 4.13, A* = 2170 was ejected after 3489 periods, "a
    longer run would not settle it", and landed at t* = 16321 and bounced on."""
    if not math.isfinite(return_time):
        return "ejected: in free flight it never reaches the surface again"
    land = now + return_time
    seconds = f", {land / frequency:.3g} s" if frequency else ""
    return (f"ejected: in free flight it cannot reach the surface before t* = {land:.6g} "
            f"(ballistic{seconds}); a run of more than {math.ceil(land)} periods (--periods, "
            "--max-periods) follows it to its landing and the bounces after it")


def _warnings(scene: Scene, out: WaveRun, drift_se: float) -> tuple[str, ...]:
    """A device scene's validity warnings, a long-time mean's whose error is a lower bound,
    whose halves differ (the error then half their difference) or whose bounces heat up, and
    a measuring window too long for all its events to be kept."""
    warnings = (tuple(device_warnings(scene.device, scene.effects.adhesion))
                if scene.device is not None else ())
    warnings += _table_warning(scene)
    if out.settling.unstable > 0.0:
        warnings += (_unstable_warning(out, scene.numerics.settle is False),)
    if out.long_mean is not None and out.long_mean.approaching and out.speed > 0.0:
        periods = out.stepper.step / out.stepper.k_per
        warnings += (f"not settled: {STILL_MOVING}: its windows still moved one way when they "
                     f"stopped after {periods:.0f} periods (a slow approach; the drift is the "
                     f"mean of the {out.long_mean.periods} periods after them, not a steady one); "
                     "a longer mean (numerics.mean_periods, --mean-periods) follows it further",)
    elif out.long_mean is not None and out.long_mean.moving and out.speed > 0.0:
        warnings += (f"not settled: {STILL_MOVING} over its last "
                     f"{out.long_mean.periods} periods (its two halves differ by more than "
                     f"{HALVES_Z:g} errors: a slow approach); numerics.mean_periods "
                     "(--mean-periods) runs it longer",)
    elif out.long_mean is not None and out.long_mean.rising and out.speed > 0.0:
        warnings += (f"long-time mean: its batch-means error still grew with the batch length "
                     f"at {out.long_mean.periods} periods, so +-{drift_se:.2g} is a lower bound "
                     f"(correlations longer than the run)",)
    if out.long_mean is not None and out.long_mean.few_flights > 0.0 and out.speed > 0.0:
        warnings += (f"long-time mean of bounces over about {out.long_mean.few_flights:.1f} of its "
                     f"longest flights only ({FLIGHTS_PER_MEAN} asked for; its budget is at most "
                     f"{MOST_FLIGHT_BUDGETS} times numerics.mean_periods): its sign may be that "
                     "of a few flights; --mean-periods for more",)
    if (out.long_mean is not None and out.long_mean.trend and not out.long_mean.moving
            and out.speed > 0.0):
        warnings += (f"long-time mean: its two halves differ by more than {TREND_Z:g} errors "
                     f"(a slow approach or drift may go on past the {out.long_mean.periods} "
                     "periods of the mean), so its error is half that difference; "
                     "numerics.mean_periods (--mean-periods) runs it longer",)
    if out.long_mean is not None and out.long_mean.heating is not None:
        low, high = out.long_mean.heating
        warnings += (f"long-time mean: {HEATING} (the vertical energy, as a height, "
                     f"rose from {low:.3g} to {high:.3g} between the two halves of the mean, "
                     f"more than {HALVES_Z:g} errors): a motion still gaining energy has no "
                     "steady drift yet, and its mean depends on how long it is run "
                     "(numerics.mean_periods)",)
    shed = out.window.events_shed
    if shed > 0:
        warnings += (f"the measuring window's first {shed} events (lift-offs, landings, slip "
                     f"changes) are not kept, only its last {out.window.events.shape[0]}; its "
                     "counts (lift-offs, contact loss, gross slip) cover the whole window",)
    return warnings


def _unstable_warning(out: WaveRun, fixed: bool) -> str:
    """Why a run that kept contact on its vertical orbit is not settled there: the orbit is
    unstable at half the wave's frequency (:mod:`~sawdrift.dynamics.half_resonance`)."""
    why = (f"the contact's free vertical oscillation is unstable at half the wave's frequency "
           f"(a parametric resonance: a disturbance grows by "
           f"{100.0 * math.expm1(out.settling.unstable):.2g} % a period)")
    if out.settling.settled:  # the growth ended on a periodic orbit (.transient)
        return (f"{why}: the steady contact of the run's first periods was not its steady "
                "state; the run followed the disturbance to the periodic orbit it grows into")
    what = ("this fixed run's window is a sample of it before it grew; the default run (without "
            "--no-settle) follows it and reports the long-time mean of what it grows into"
            if fixed else "the drift is the long-time mean of the motion it grows into")
    return (f"not settled: {why}, so the steady contact its first periods showed is no steady "
            f"state; {what}")


def _unsettled_reason(out: WaveRun, settling: bool) -> str:
    """Why a run that was to settle did not: its drift still moving when its periods ran out, or
    a contact that slid again after a hold, a slow beat later (``settling``: it was asked to
    settle, and only a higher cap runs it longer)."""
    history = out.settling.history
    periods = out.stepper.step / out.stepper.k_per
    longer = ("numerics.max_periods (--max-periods)" if settling else
              "numerics.settle = true (--settle) with numerics.max_periods (--max-periods)")
    beat = out.settling.slip_beat
    if out.settling.uncertain > 0.0:
        return (f"not settled: the drift solved directly under the load averages the undamped "
                f"free vertical oscillation's slow cycle, and near the load's holding limit "
                f"that average may be off by about {out.settling.uncertain:.1g} in drift ratio, "
                f"beyond the tolerance; brute force (--no-settle, some 40 m*/mu periods) "
                f"decides")
    if out.settling.slow_vertical > 0.0:
        return (f"not settled: put on the damped orbit its drift was solved for, it did not "
                f"stay there by its evidence window; its windows from its own state agreed after "
                f"{periods:.0f} periods, but its vertical motion relaxes over about "
                f"{out.settling.slow_vertical:.0f} periods, so their drift need not be the steady "
                f"one; brute force (--no-settle, several times that) decides")
    if out.settling.leaving:
        return (f"not settled: its take-offs still moved away from repeating when the run "
                f"stopped after {periods:.0f} periods (an orbit losing its stability, as at a "
                f"period doubling: the hop period and phases are those of the orbit it leaves); "
                f"{longer} runs it longer")
    if beat > 0.0:
        return (f"not settled: its contact held for a while and then slid again, as its undamped "
                f"free vertical oscillation beats against the wave over about {beat:.0f} periods "
                f"(near a vertical resonance); the drift of its last window, when the run stopped "
                f"after {periods:.0f} periods, is one phase of that beat; {longer} runs it longer")
    if len(history) >= 2:
        change = f"changed by {history[-1] - history[-2]:+.2g} in drift ratio over its last window"
    else:
        change = "was not confirmed by its window"
    return (f"not settled: the drift {change} when the run stopped after {periods:.0f} periods "
            f"(a slow approach, or a growing motion); {longer} runs it longer")


def runaway_acceleration(scene: Scene, fitted: float) -> float:
    """A runaway's mean acceleration, x* per period squared, in closed form where it has one,
    else ``fitted``, the window's.

    Once the particle outruns the surface its relative velocity keeps one sign, the friction is
    mu N* against it and the period-averaged normal force is the weight, so m* <x*''> = L -
    mu sign(L) exactly; that is the long-time mean acceleration (L / m* without friction). A
    window early in the run sees the stick-slip before that (mmd m* = 100, A* = 1, L = 0.2,
    mu = 0.1: 0.0021 from the fit over periods 33 to 60, 0.0010 over a 2000-period run).

    A sphere free to turn (:func:`rolling_runaway`) rolls away under smaller loads. An adhesive
    contact's friction bound is not mu times the weight: it keeps the window's fit."""
    eff, load = scene.effects, scene.particle.load
    if not runs_away(scene) or eff.adhesion != "none":
        return fitted
    if not eff.friction:
        return load / scene.particle.m_star
    if eff.rotation:
        return rolling_runaway(load, scene.material.mu, eff.rolling_resistance,
                               scene.particle.gyration, scene.particle.m_star)
    return (load - math.copysign(scene.material.mu, load)) / scene.particle.m_star


def rolling_runaway(load: float, mu: float, mu_r: float, kappa: float, m_star: float) -> float:
    """The long-time mean acceleration of a sphere free to turn under a load it cannot hold.

    Centre and spin obey m* x*'' = L - F and kappa m* psi'' = -F + M_r (F the friction, M_r the
    rolling torque per R, both per M g). While the contact point's slip stays bounded, psi' =
    -x*' up to bounded terms, so m* (1 + kappa) <x*''> = L - <M_r>, and the rolling spring, turned
    one way for ever, sits at its cap: <M_r> = mu_r sign(L) (its cap mu_r N*, the mean normal
    force the weight). That takes the mean friction (kappa |L| + mu_r) / (1 + kappa), at
    most mu: beyond |L| = mu (1 + 1/kappa) - mu_r / kappa the contact point slides for ever and
    the centre accelerates at (L - mu sign L) / m*, as a sphere that does not turn."""
    if abs(load) > mu * (1.0 + 1.0 / kappa) - mu_r / kappa:
        return (load - math.copysign(mu, load)) / m_star
    return (load - math.copysign(mu_r, load)) / (m_star * (1.0 + kappa))


def mean_acceleration(positions) -> float:
    """Mean horizontal acceleration over a window, per period squared: twice the quadratic
    coefficient of a least-squares fit to the positions at the period ends.

    With the times centred, t_i = i - (n - 1)/2, the polynomials 1, t and t^2 - <t^2> are
    orthogonal over the samples, so the coefficient is sum (t^2 - <t^2>) x / sum (t^2 - <t^2>)^2
    (the fit ``numpy.polyfit(t, x, 2)`` makes, without its matrix factorisation).
    """
    import numpy as np

    x = np.asarray(positions, dtype=float)
    if x.size < 3:
        return math.nan
    t = np.arange(x.size) - 0.5 * (x.size - 1)
    q = t * t
    q -= q.mean()
    return float(2.0 * np.dot(q, x - x[0]) / np.dot(q, q))


def _regime(scene: Scene, drive: Drive, win: Window, speed: float,
            hop_period: int, solved: float | None = None) -> tuple[float, str]:
    """(drift ratio, regime) of the measured window, or of its drift ratio ``solved`` directly.

    Without horizontal surface motion (r = 0) the drift ratio is undefined: it is reported as
    null (nan), and the regime reads the drift against the vertical surface speed instead.
    """
    own = win.drift_ratio if solved is None else solved
    drift_ratio = own if speed > 0.0 else math.nan
    vertical = 2.0 * math.pi * drive.vertical_amplitude(scene)
    ratio_for_regime = (own if speed > 0.0
                        else (win.drift / vertical if vertical > 0.0 else 0.0))
    regime = classify(win.contact_lost, ratio_for_regime, scene.numerics.drift_tolerance,
                      gross_slip_fraction=_gross_slip(scene, win, speed), hop_period=hop_period)
    return drift_ratio, regime


def _gross_slip(scene: Scene, win: Window, speed: float) -> float:
    """The window's fraction in gross slip; without friction, its time in contact while the
    surface moves under the particle (nothing holds a frictionless contact: it was named
    'stick', gross slip 0, with the surface sliding under it all period)."""
    if scene.effects.friction or speed <= 0.0:
        return win.gross_slip_fraction
    return 1.0 - win.out_of_contact_fraction


def _impact_result(scene: Scene, engine: str, out: ImpactRun, trajectory: bool) -> Result:
    """The Result of a free normal impact: its rebound ratio, contact time and deepest overlap."""
    nan = math.nan
    stepper = out.stepper
    return Result(
        model=scene.model, engine=engine, m_star=scene.particle.m_star, amplitude=0.0,
        mu=scene.material.mu, nu=scene.material.nu, horizontal_ratio=nan,
        profile=scene.particle.profile.shape, steps_per_period=stepper.k_per,
        periods=stepper.step / stepper.k_per, ramp_periods=0.0, measure_periods=0,
        drift_velocity=nan, drift_ratio=nan, regime="impact", contact_lost=out.separated,
        out_of_contact_fraction=nan, min_compression=nan, steps=stepper.step,
        wall_time_s=out.wall_time_s, scene=scene.model_dump(mode="json"),
        trajectory=out.trajectory if trajectory else None,
        extra={"rebound_ratio": out.rebound_ratio, "contact_duration": out.contact_duration,
               "max_compression": float(out.trajectory["a"].max())},
        warnings=() if out.separated else (_held_impact(scene, stepper),),
    )


def _held_impact(scene: Scene, stepper: Any) -> str:
    """Why an impact has no rebound ratio: its contact outlasted the run."""
    limit = (f"numerics.periods or {IMPACT_DURATIONS:g} estimated contact times, the longer; "
             "numerics.periods (--periods) runs it longer")
    return (f"contact not lost after {stepper.step / stepper.k_per:.4g} periods: no rebound "
            f"ratio; the contact held the particle (damped to rest under gravity) or outlasted "
            f"the run ({limit}; at most {MAX_IMPACT_STEPS:.0e} steps)")


def _prescribed_result(scene: Scene, engine: str, out: PrescribedRun) -> Result:
    """The Result of a prescribed history: the sampled forces and the dissipated work."""
    nan = math.nan
    a = out.a
    return Result(
        model=scene.model, engine=engine, m_star=scene.particle.m_star, amplitude=nan,
        mu=scene.material.mu, nu=scene.material.nu, horizontal_ratio=nan,
        profile=scene.particle.profile.shape, steps_per_period=0, periods=0.0, ramp_periods=0.0,
        measure_periods=0, drift_velocity=nan, drift_ratio=nan, regime="prescribed",
        contact_lost=bool((a <= 0.0).any()), out_of_contact_fraction=float((a <= 0.0).mean()),
        min_compression=float(a.min()) if a.size else nan, steps=int(a.size),
        wall_time_s=out.wall_time_s, scene=scene.model_dump(mode="json"), trajectory=out.frame,
        extra={"dissipated_work": out.dissipated_work},
    )
