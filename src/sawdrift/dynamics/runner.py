"""Run one scene: assemble only what its effects need, integrate, and summarize.

Compliant models go through the Adams-Bashforth loop of :mod:`sawdrift.dynamics.adams_bashforth`; rigid ones
through the unilateral-contact scheme of :mod:`sawdrift.dynamics.rigid`; a prescribed drive feeds a*(t*),
b*(t*) straight into the contact law (:mod:`sawdrift.dynamics.prescribed`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ..contact.base import ContactModel
from ..errors import SceneError
from ..result.regimes import classify
from ..result.result import Result
from ..scene.schema import Impact, Prescribed, Scene, Wave
from .prescribed import prescribed_history, run_prescribed
from .steady import (
    assess_fixed,
    default_max_periods,
    horizontal_inertia,
    relaxation_periods,
    rolling_frequency,
    settle,
)
from .stepper import Stepper
from .window import lyapunov, measure_window, state_scale

Engine = Literal["compiled", "python"]

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


@dataclass(frozen=True)
class Assembly:
    """What a run computes, decided once from the scene's effects (LAMMPS-style slots).

    The runner builds exactly this; :func:`explain` prints it. An empty slot is never computed.
    """

    scheme: str
    engine: Engine
    integrate_x: bool
    tangential_law: bool
    normal_damping: float
    horizontal_wave: bool
    vertical_wave: bool
    ramp_periods: float
    equations: tuple[str, ...]
    calls: tuple[str, ...]
    outputs: tuple[str, ...]


def assemble(scene: Scene, engine: Engine = "compiled", model: ContactModel | None = None) -> Assembly:
    """Decide the scheme, the slots that are on, and the engine for ``scene``.

    ``model`` is the scene's model instance when the caller has already built it.
    """
    if engine not in ("compiled", "python"):
        raise SceneError(f"engine = {engine!r} is not allowed; use 'compiled' or 'python'")
    if model is None:
        model = scene.model_instance()
    caps = model.capabilities
    eff = scene.effects
    drive = scene.drive
    if engine == "compiled" and not caps.compiled:
        engine = "python"
    name = scene.model
    kernel = f"{name}.kernel.force" if engine == "compiled" else f"{name}.reference().force"
    if isinstance(drive, Prescribed):
        return Assembly(
            "prescribed", engine, False, True, 0.0, False, False, 0.0,
            ("a*(k), b*(k) prescribed (" + drive.waveform + "); no dynamics",),
            (f"{kernel}(a*, b*) once per sample, committing the history",),
            ("N*(k)", "T*(k)", "dissipated work = sum of T* db*"),
        )
    horiz = isinstance(drive, Wave) and eff.horizontal_wave
    vert = isinstance(drive, Wave) and eff.vertical_wave
    ramp = drive.ramp_periods if isinstance(drive, Wave) else 0.0
    equations: list[str] = []
    calls: list[str] = []
    slot = getattr(type(model), "damping", None)
    if slot is not None and eff.normal_damping > 0.0:
        raise SceneError(
            f"effects.normal_damping = {eff.normal_damping:g} would stack a second normal damping "
            f"on model {name!r}, which has its own normal-damping slot ({slot.name!r}); use one: "
            "set effects.normal_damping = 0, or pick a model without a damping slot"
        )
    if caps.rigid:
        scheme = "rigid"
        normal = "N* = 1 - m* u_y''" if eff.vertical_inertia else "N* = 1 (vertical inertia off)"
        equations.append("a* = 0 in contact; flight m* y*'' = 1 when N* < 0; impact with restitution")
        equations.append(normal)
        if eff.friction and eff.rotation:
            kappa = scene.particle.gyration
            equations.append("rotation: I phi'' = -R T, I = kappa m R^2, kappa = "
                             f"{kappa:.6g}: the contact point s = x + R phi = (1 + 1/kappa) x has "
                             f"the mass m_s = m* kappa / (1 + kappa) = "
                             f"{scene.particle.m_star * kappa / (1 + kappa):.6g}")
            equations.append("Coulomb on the contact point: stick s*'' = u_x'' while "
                             "|m_s u_x''/mu| <= N*, else m_s s*'' = -mu N* sgn(s*' - u_x'); "
                             "centre x* = s* kappa / (1 + kappa)")
        elif eff.friction:
            equations.append("Coulomb: stick x*'' = u_x'' while |m* u_x''/mu| <= N*, "
                             "else m* x*'' = -mu N* sgn(x*' - u_x')")
        else:
            equations.append("x*'' = 0 (friction off: no tangential force)")
        calls.append("closed-form N*(t), slip velocity and event bisection (sawdrift.dynamics.rigid)")
    else:
        scheme = "impact" if isinstance(drive, Impact) else "adams-bashforth"
        normal = f"{name} normal law" + ("" if eff.friction else " alone (its normal slot)")
        equations.append(f"m* y*'' = 1 - N*(a*), a* = y* - u_y; N* from the {normal}")
        if eff.normal_damping > 0.0:
            equations.append(f"N* += {eff.normal_damping:g} a*' while a* > 0, N* >= 0 (viscous "
                             "normal damping); |T*| <= N*, the total normal force")
        elif slot is not None:
            equations.append(f"N* from the normal-damping slot {slot.name!r} "
                             f"({slot.__doc__.strip().splitlines()[0] if slot.__doc__ else ''}); "
                             "|T*| <= N*, the total normal force")
        if eff.friction:
            equations.append("m* x*'' = -mu T*(b*, a*)" + (
                " (x* the centre)" if eff.rotation else ", theta mu b* = x* - u_x"))
            calls.append(f"{kernel}(a*, b*, a*', b*') once per step, committing the history")
        else:
            equations.append("x* not integrated (friction off); the tangential law is never called")
        calls.append(f"Adams-Bashforth order {scene.numerics.order}, "
                     f"{scene.steps_per_period()} steps per period")
    if eff.rotation and eff.friction and not caps.rigid:
        kappa = scene.particle.gyration
        c = 1.0 + 1.0 / kappa
        equations.append(f"rotation: I phi'' = -R T with I = kappa m R^2, kappa = {kappa:.6g}; "
                         f"from rest the contact point s = x + R phi = (1 + 1/kappa) x = {c:.6g} x")
        if eff.rolling_resistance > 0.0:
            mu_r = eff.rolling_resistance
            equations.append("rolling resistance (elastic-plastic spring, Ai et al. 2011): "
                             "kappa m* psi'' = -mu T* + m_r, psi = R phi / a0, s* = x* + psi, "
                             f"m_r = -2.25 mu_r^2 (dN*/da*) psi_e capped at mu_r N*, mu_r = {mu_r:g}")
            equations.append("theta mu b* = s* - u_x; the centre keeps m* x*'' = -mu T*")
        else:
            equations.append("theta mu b* = s* - u_x: the contact point moves like a mass "
                             f"m* kappa / (1 + kappa) = {scene.particle.m_star / c:.6g}; the "
                             "centre keeps m* x*'' = -mu T*; spin R phi' = x*' / kappa")
    if horiz and drive.orbit == "retrograde":
        equations.append(f"u_x = +A* r R(t*) sin(2 pi t*), A* = {drive.amplitude:g}, "
                         f"r = {scene.horizontal_ratio:.6g} (retrograde orbit: at the crest the "
                         "surface moves against the propagation direction, -x)")
    elif horiz:
        equations.append(f"u_x = -A* r R(t*) sin(2 pi t*), A* = {drive.amplitude:g}, "
                         f"r = {scene.horizontal_ratio:.6g}")
    if horiz and drive.orbit == "prograde":
        equations.append("prograde orbit (eq. 1 as printed, y* into the substrate): at the crest "
                         "the surface moves with the wave, +x")
    if vert:
        equations.append(f"u_y = A* R(t*) cos(2 pi t*), A* = {drive.amplitude:g}")
    if isinstance(drive, Wave) and not (horiz or vert):
        equations.append("substrate at rest (both wave components off)")
    if isinstance(drive, Wave):
        equations.append(f"R(t*) = sin^2(pi t* / (2 x {ramp:g})) ramp" if ramp > 0 else "no ramp")
    if isinstance(drive, Impact):
        equations.append(f"substrate at rest; start at a* = 0 with a*' = {drive.velocity:g}")
    outputs = (
        ("rebound speed ratio", "contact duration", "max compression")
        if isinstance(drive, Impact)
        else ("drift_velocity", "drift_ratio", "regime", "contact_lost", "min_compression",
              "gross_slip_fraction", "liftoffs_per_period", "hop_period", "lyapunov", "settled")
        + (("spin_rate",) if eff.rotation else ())
    )
    return Assembly(
        scheme, engine, eff.friction, eff.friction and not caps.rigid, eff.normal_damping,
        horiz, vert, ramp, tuple(equations), tuple(calls), outputs,
    )


def explain(scene: Scene, engine: Engine = "compiled") -> str:
    """A readable description of the system :func:`run` assembles for ``scene``."""
    plan = assemble(scene, engine)
    lines = [f"model {scene.model!r} ({scene.body}), scheme {plan.scheme}, engine {plan.engine}",
             "equations:"]
    lines += [f"  {eq}" for eq in plan.equations]
    lines.append("calls:")
    lines += [f"  {c}" for c in plan.calls]
    lines.append("outputs: " + ", ".join(plan.outputs))
    if scene.device is not None:
        from ..scene.device import explain_device

        lines += explain_device(scene.device, scene.material.mu)
    return "\n".join(lines)

def _run_wave(
    scene: Scene, model: ContactModel, trajectory: bool, plan: Assembly, record_every: int | None
) -> Result:
    wave = scene.drive
    assert isinstance(wave, Wave)
    num = scene.numerics
    n_periods = scene.measure_periods()
    stepper = Stepper(scene, model, plan, trajectory, event_periods=n_periods)
    compile_s = stepper.warm_up()  # compilation or disk-cache load, reported apart
    t0 = time.perf_counter()
    if trajectory and record_every is not None:
        stepper.rec_every = max(1, int(record_every))
    k_per = stepper.k_per
    n_measure = n_periods * k_per
    n_total = max(int(round(num.periods * k_per)), n_measure)
    speed = 2.0 * math.pi * scene.horizontal_ratio * wave.amplitude
    m_star = scene.particle.m_star
    cap = num.max_periods
    if cap is None:
        m_x = horizontal_inertia(m_star, stepper.rigid) if num.settle else m_star
        cap = default_max_periods(m_star, relaxation_periods(scene, m_x, speed), stepper.rigid,
                                  n_periods, rolling_frequency(scene, m_x))
    n_max = max(n_total, int(round(cap * k_per)))
    stepper.advance(n_total - n_measure)
    scale = state_scale(wave.amplitude, scene.horizontal_ratio)
    settling = None
    if num.settle:
        win, settling = settle(stepper, scene, speed, scale, n_periods, n_max)
    else:
        win = measure_window(stepper, n_periods, speed, scale)
    lyap, chaotic = lyapunov(win, scale) if win.contact_lost else (math.nan, False)
    sync = win.sync
    hop_period = sync.hop_period if not chaotic else 0
    if settling is None:
        settling = assess_fixed(win, speed, num.settle_tolerance,
                                relaxation_periods(scene, m_star, speed), stepper.step / k_per,
                                chaotic)
    t90 = settling.t90_periods if num.settle else math.nan
    regime = classify(win.contact_lost, win.drift_ratio, num.drift_tolerance,
                      gross_slip_fraction=win.gross_slip_fraction, hop_period=hop_period)
    extra: dict[str, object] = {}
    if scene.device is not None:
        from ..scene.device import device_outputs

        extra.update(device_outputs(scene.device, win.drift, regime, t90 if num.settle else None))
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
        drift_ratio=win.drift_ratio,
        regime=regime,
        orbit=wave.orbit,
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
        horizontal_inertia=settling.horizontal_inertia if num.settle else math.nan,
        liftoffs_per_hop=sync.liftoffs_per_hop if sync.hop_period else math.nan,
        extra=extra,
    )


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

