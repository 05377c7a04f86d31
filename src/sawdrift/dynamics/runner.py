"""Run one scene: assemble only what its effects need, integrate, and summarize.

Compliant models go through the Adams-Bashforth loop of :mod:`sawdrift.dynamics.adams_bashforth`; rigid ones
through the unilateral-contact scheme of :mod:`sawdrift.dynamics.rigid`; a prescribed drive feeds a*(t*),
b*(t*) straight into the contact law (:mod:`sawdrift.dynamics.prescribed`).
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..contact.base import ContactModel
from ..result.regimes import classify
from ..result.result import Result
from ..scene.device import device_outputs
from ..scene.schema import Impact, Scene
from .assembly import Assembly, Engine, assemble, explain
from .drives import Drive
from .prescribed import prescribed_history, run_prescribed
from .steady import (
    Settling,
    assess_fixed,
    default_max_periods,
    horizontal_inertia,
    relaxation_periods,
    rolling_frequency,
    settle,
    settles,
)
from .stepper import Stepper
from .window import Window, lyapunov, measure_window

__all__ = ["Assembly", "Engine", "assemble", "explain", "prescribed_history", "run"]


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
    model = scene.model_instance()
    plan = assemble(scene, engine, model)
    if plan.scheme == "prescribed":
        return run_prescribed(scene, model, plan.engine)
    if plan.scheme == "impact":
        return _run_impact(scene, model, plan, trajectory)
    return _run_wave(scene, model, trajectory, plan, record_every)


def _run_wave(
    scene: Scene, model: ContactModel, trajectory: bool, plan: Assembly, record_every: int | None
) -> Result:
    wave = scene.drive
    assert hasattr(wave, "amplitude") and hasattr(wave, "ramp_periods")  # any registered periodic drive
    num = scene.numerics
    n_periods = scene.measure_periods()
    stepper = Stepper(scene, model, plan, trajectory, event_periods=n_periods)
    compile_s = stepper.warm_up()  # compilation or disk-cache load, reported apart
    t0 = time.perf_counter()
    if trajectory and record_every is not None:
        stepper.rec_every = max(1, int(record_every))
    k_per = stepper.k_per
    drive = plan.drive
    m_star = scene.particle.m_star
    speed = drive.horizontal_speed(scene)
    scale = drive.state_scale(scene)
    settle_on = settles(scene, speed, stepper.rigid)
    win, settling = _measure(stepper, scene, speed, scale, settle_on)
    lyap, chaotic = lyapunov(win, scale) if win.contact_lost else (math.nan, False)
    sync = win.sync
    hop_period = sync.hop_period if not chaotic else 0
    if settling is None:
        settling = assess_fixed(win, speed, num.settle_tolerance,
                                relaxation_periods(scene, m_star, speed), stepper.step / k_per,
                                chaotic)
    t90 = settling.t90_periods if settle_on else math.nan
    drift_ratio, regime = _regime(scene, drive, win, speed, hop_period)
    extra: dict[str, object] = {}
    if scene.device is not None:
        extra.update(device_outputs(scene.device, win.drift, regime, t90 if settle_on else None))
    return Result(
        model=scene.model,
        engine=plan.engine,
        m_star=scene.particle.m_star,
        amplitude=wave.amplitude,
        mu=scene.material.mu,
        nu=scene.material.nu,
        horizontal_ratio=scene.horizontal_ratio,
        profile=scene.particle.profile.shape,
        steps_per_period=k_per,
        periods=stepper.step / k_per,
        ramp_periods=wave.ramp_periods,
        measure_periods=win.periods,
        drift_velocity=win.drift,
        drift_ratio=drift_ratio,
        regime=regime,
        orbit=drive.orbit_name(scene),
        contact_lost=win.contact_lost,
        out_of_contact_fraction=win.out_of_contact_fraction,
        min_compression=win.min_compression,
        steps=stepper.step,
        wall_time_s=time.perf_counter() - t0,
        gross_slip_fraction=win.gross_slip_fraction,
        liftoffs_per_period=win.liftoffs_per_period,
        hop_period=hop_period,
        liftoff_phase=sync.phase,
        liftoff_phase_spread=sync.spread,
        lyapunov=lyap,
        spin_rate=win.spin_rate,
        periodicity=win.periodicity,
        scene=scene.model_dump(mode="json"),
        trajectory=stepper.trajectory() if trajectory else None,
        event_rows=win.events,
        chaotic=chaotic,
        events_dropped=win.events_dropped,
        compile_s=compile_s,
        orbit_period=win.orbit_period,
        settled=settling.settled,
        settle_method=settling.method,
        settle_periods=settling.periods,
        t90_periods=t90,
        horizontal_inertia=settling.horizontal_inertia if settle_on else math.nan,
        liftoffs_per_hop=sync.liftoffs_per_hop if hop_period else math.nan,
        liftoff_phases=sync.phases if hop_period else (),
        extra=extra,
    )


def _measure(stepper: Stepper, scene: Scene, speed: float, scale: np.ndarray,
             settle_on: bool) -> tuple[Window, Settling | None]:
    """Run to the measuring window and measure it: settled windows (``numerics.settle``, up to
    the period cap) or the fixed run's last window. The settling is None for a fixed run."""
    num = scene.numerics
    n_periods = scene.measure_periods()
    k_per = stepper.k_per
    n_measure = n_periods * k_per
    n_total = max(int(round(num.periods * k_per)), n_measure)
    m_star = scene.particle.m_star
    cap = num.max_periods
    if cap is None:
        m_x = horizontal_inertia(m_star, stepper.rigid) if settle_on else m_star
        cap = default_max_periods(m_star, relaxation_periods(scene, m_x, speed), stepper.rigid,
                                  n_periods, rolling_frequency(scene, m_x))
    n_max = max(n_total, int(round(cap * k_per)))
    stepper.advance(n_total - n_measure)
    if settle_on:
        return settle(stepper, scene, speed, scale, n_periods, n_max)
    return measure_window(stepper, n_periods, speed, scale), None


def _regime(scene: Scene, drive: Drive, win: Window, speed: float,
            hop_period: int) -> tuple[float, str]:
    """(drift ratio, regime) of the measured window.

    Without horizontal surface motion (r = 0) the drift ratio is undefined: it is reported as
    null (nan), and the regime reads the drift against the vertical surface speed instead.
    """
    drift_ratio = win.drift_ratio if speed > 0.0 else math.nan
    vertical = 2.0 * math.pi * drive.vertical_amplitude(scene)
    ratio_for_regime = (win.drift_ratio if speed > 0.0
                        else (win.drift / vertical if vertical > 0.0 else 0.0))
    regime = classify(win.contact_lost, ratio_for_regime, scene.numerics.drift_tolerance,
                      gross_slip_fraction=win.gross_slip_fraction, hop_period=hop_period)
    return drift_ratio, regime


def _run_impact(scene: Scene, model: ContactModel, plan: Assembly, trajectory: bool) -> Result:
    """A free normal impact: integrate from first touch until contact is lost again."""
    drive = scene.drive
    assert isinstance(drive, Impact)
    t0 = time.perf_counter()
    stepper = Stepper(scene, model, plan, record=True, preload=False)
    stepper.rec_every = 1
    stepper.y[:4] = (0.0, drive.tangential_velocity, 0.0, drive.velocity)
    chunk = max(8, stepper.k_per // 8)
    n_max = int(round(scene.numerics.periods * stepper.k_per))
    separated = False
    while stepper.step < n_max and not separated:
        stepper.advance(chunk)
        separated = bool(stepper.y[2] < 0.0 and stepper.step > 1)
    if separated:
        stepper.advance(1)  # records the first state out of contact (rows are taken before a step)
    tr = stepper.trajectory()
    rebound = math.nan
    duration = math.nan
    if separated:
        a = tr["a"].to_numpy()
        k = int(np.nonzero((a[:-1] > 0.0) & (a[1:] <= 0.0))[0][-1])
        w = a[k] / (a[k] - a[k + 1])
        v_out = (1 - w) * tr["vy"].iloc[k] + w * tr["vy"].iloc[k + 1]
        rebound = float(abs(v_out) / drive.velocity)
        duration = float((k + w) * stepper.h)
    nan = math.nan
    return Result(
        model=scene.model, engine=plan.engine, m_star=scene.particle.m_star, amplitude=0.0,
        mu=scene.material.mu, nu=scene.material.nu, horizontal_ratio=nan,
        profile=scene.particle.profile.shape, steps_per_period=stepper.k_per,
        periods=stepper.step / stepper.k_per, ramp_periods=0.0, measure_periods=0,
        drift_velocity=nan, drift_ratio=nan, regime="impact", contact_lost=separated,
        out_of_contact_fraction=nan, min_compression=nan, steps=stepper.step,
        wall_time_s=time.perf_counter() - t0, scene=scene.model_dump(mode="json"),
        trajectory=tr if trajectory else None,
        extra={"rebound_ratio": rebound, "contact_duration": duration,
               "max_compression": float(tr["a"].max())},
    )

