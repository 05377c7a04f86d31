"""Run one scene: assemble only what its effects need, integrate, and summarize.

Compliant models go through the Adams-Bashforth loop of :mod:`sawdrift.dynamics.adams_bashforth`; rigid ones
through the unilateral-contact scheme of :mod:`sawdrift.dynamics.rigid`; a prescribed drive feeds a*(t*),
b*(t*) straight into the contact law.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Literal

import numpy as np
import pandas as pd
from numba import njit

from ..contact.base import ContactHistory, ContactModel
from ..errors import NonFiniteStateError, SceneError
from ..result.regimes import classify
from ..result.result import Result
from ..scene.schema import Impact, Prescribed, Scene, Wave
from . import adams_bashforth as ig
from . import rigid as rg

Engine = Literal["compiled", "python"]

#: Trajectory samples recorded per wave period (at most).
RECORDS_PER_PERIOD = 200


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
        return _run_prescribed(scene, model, plan.engine)
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
    caps = (model if model is not None else scene.model_instance()).capabilities
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
    if caps.rigid:
        scheme = "rigid"
        normal = "N* = 1 - m* u_y''" if eff.vertical_inertia else "N* = 1 (vertical inertia off)"
        equations.append("a* = 0 in contact; flight m* y*'' = 1 when N* < 0; impact with restitution")
        equations.append(normal)
        if eff.friction:
            equations.append("Coulomb: stick x*'' = u_x'' while |m* u_x''/mu| <= N*, "
                             "else m* x*'' = -mu N* sgn(x*' - u_x')")
        else:
            equations.append("x*'' = 0 (friction off: no tangential force)")
        calls.append("closed-form N*(t), slip velocity and event bisection (sawdrift.dynamics.rigid)")
    else:
        scheme = "impact" if isinstance(drive, Impact) else "adams-bashforth"
        normal = f"{name} normal law" if eff.friction else f"profile law N* = a*^{scene.particle.profile.p:g}"
        equations.append(f"m* y*'' = 1 - N*(a*), a* = y* - u_y; N* from the {normal}")
        if eff.normal_damping > 0.0:
            equations.append(f"N* += {eff.normal_damping:g} a*' while a* > 0 (viscous normal damping)")
        if eff.friction:
            equations.append("m* x*'' = -mu T*(b*, a*), theta mu b* = x* - u_x")
            calls.append(f"{kernel}(a*, b*, a*', b*') once per step, committing the history")
        else:
            equations.append("x* not integrated (friction off); the tangential law is never called")
        calls.append(f"Adams-Bashforth order {scene.numerics.order}, "
                     f"{scene.steps_per_period()} steps per period")
    if horiz:
        equations.append(f"u_x = -A* r R(t*) sin(2 pi t*), A* = {drive.amplitude:g}, "
                         f"r = {scene.horizontal_ratio:.6g}")
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
              "periodicity", "liftoffs_per_period")
    )
    return Assembly(
        scheme, engine, eff.friction, eff.friction and not caps.rigid, eff.normal_damping,
        horiz, vert, ramp, tuple(equations), tuple(calls), outputs,
    )


def explain(scene: Scene, engine: Engine = "compiled") -> str:
    """A readable description of the system :func:`run` assembles for ``scene``."""
    plan = assemble(scene, engine)
    lines = [f"model {scene.model!r}, scheme {plan.scheme}, engine {plan.engine}", "equations:"]
    lines += [f"  {eq}" for eq in plan.equations]
    lines.append("calls:")
    lines += [f"  {c}" for c in plan.calls]
    lines.append("outputs: " + ", ".join(plan.outputs))
    return "\n".join(lines)


class _Stepper:
    """One integration, advanced in segments so that x* can be read between them."""

    def __init__(
        self, scene: Scene, model: ContactModel, plan: Assembly, record: bool, preload: bool = True
    ):
        self.scene = scene
        wave = scene.drive
        amplitude = wave.amplitude if isinstance(wave, Wave) else 0.0
        ramp = plan.ramp_periods
        engine = plan.engine
        self.k_per = scene.steps_per_period()
        self.h = 1.0 / self.k_per
        self.rigid = model.capabilities.rigid
        eff = scene.effects
        prm = np.zeros(rg.N_PRM_RIGID)
        prm[ig.P_M] = scene.particle.m_star
        prm[ig.P_A] = amplitude
        prm[ig.P_R] = scene.horizontal_ratio if isinstance(wave, Wave) else 0.0
        prm[ig.P_MU] = scene.material.mu
        prm[ig.P_THETA] = scene.theta
        prm[ig.P_RAMP] = ramp
        prm[ig.P_H] = self.h
        prm[ig.P_ORDER] = scene.numerics.order
        prm[ig.P_FRICTION] = 1.0 if plan.integrate_x else 0.0
        prm[ig.P_DAMP] = plan.normal_damping
        prm[ig.P_P] = scene.particle.profile.p
        prm[ig.P_HORIZ] = 1.0 if plan.horizontal_wave else 0.0
        prm[ig.P_VERT] = 1.0 if plan.vertical_wave else 0.0
        prm[ig.P_KRAMP] = math.ceil(ramp * self.k_per - 1e-9)
        self.st = np.zeros(ig.N_ST)
        self.st[ig.S_AMIN] = np.inf
        self.st[ig.S_PREVIN] = 1.0
        self.y = np.zeros(4)
        self.record = record
        self.rec_every = max(1, self.k_per // RECORDS_PER_PERIOD) if record else 0
        self.rec_chunks: list[np.ndarray] = []
        if self.rigid:
            prm[rg.P_RESTITUTION] = float(model.params.restitution)
            prm[rg.P_VINERTIA] = 1.0 if eff.vertical_inertia else 0.0
            self.ctr = np.zeros(5, dtype=np.int64)
            self.ctr[3] = 1  # starts stuck to the substrate at rest
            self.prm = prm
            # the python engine runs the same scheme uncompiled (its helpers stay compiled)
            self.loop = rg.rigid_loop if engine == "compiled" else rg.rigid_loop.py_func
        else:
            self.prm = prm[: ig.N_PRM]
            self.ctr = np.zeros(3, dtype=np.int64)
            self.fh = np.zeros((4, 4))
            # a* = 1: static compression under M g (physics.md section 1); an impact starts at 0
            self.y[2] = 1.0 if preload else 0.0
            compiled = engine == "compiled"
            if plan.tangential_law:
                history = ContactHistory(model, engine)
                if preload:
                    history.advance(1.0, 0.0)
                force, self.fs, self.is_, self.pp = history.kernel_call()
            else:
                # Friction off: the tangential law is never called (not even compiled in).
                self.fs = np.zeros(1)
                self.is_ = np.zeros(1, dtype=np.int64)
                self.pp = np.zeros(1)
                force = _no_tangential_law
            self.loop = ig.wave_loop(force, compiled)

    @property
    def step(self) -> int:
        return int(self.ctr[0])

    def advance(self, n_steps: int) -> None:
        if n_steps <= 0:
            return
        n_rec = n_steps // self.rec_every + 2 if self.record else 0
        rec = np.zeros((n_rec, ig.N_REC))
        self.ctr[2] = 0
        if self.rigid:
            self.loop(self.y, self.ctr, self.prm, n_steps, rec, self.rec_every, self.st)
        else:
            self.loop(
                self.y, self.fh, self.ctr, self.fs, self.is_, self.pp, self.prm, n_steps,
                rec, self.rec_every, self.st,
            )
        if self.record:
            self.rec_chunks.append(rec[: self.ctr[2]].copy())
        if self.st[ig.S_BAD] > 0.0:
            k = int(self.st[ig.S_BADSTEP])
            m = self.scene.particle.m_star
            raise NonFiniteStateError(
                f"non-finite state at t* = {k * self.h:.6g} (step {k}; x* = {self.y[0]:.6g}, "
                f"x*' = {self.y[1]:.6g}, y* = {self.y[2]:.6g}, y*' = {self.y[3]:.6g}): the step "
                f"1/{self.k_per} is likely too coarse for m* = {m:g}; try a larger "
                "--steps-per-period or a lower Adams-Bashforth order"
            )

    def trajectory(self) -> pd.DataFrame:
        data = np.concatenate(self.rec_chunks) if self.rec_chunks else np.zeros((0, ig.N_REC))
        return pd.DataFrame(data, columns=list(ig.REC_COLUMNS))


@njit(cache=True)
def _no_tangential_law(fs, is_, pp, a, b, adot, bdot):  # pragma: no cover - never called
    # Stands in for the model with friction off; the loop never reaches it (see Effects).
    if a == a:
        raise RuntimeError("the tangential law must not be called with friction off")
    return 0.0, 0.0


def _measure(stepper: _Stepper, periods: int) -> tuple[float, list[np.ndarray]]:
    """Advance ``periods`` whole periods; return Delta x* and the stroboscopic samples."""
    x0 = stepper.y[0]
    samples = []
    for _ in range(periods):
        stepper.advance(stepper.k_per)
        samples.append(stepper.y.copy())
    return stepper.y[0] - x0, samples


def periodicity(samples: list[np.ndarray], amp: float, r: float, last: int = 10) -> float:
    """Largest scaled change of the stroboscopic state between consecutive periods.

    The state (x*', y*, y*') is sampled at the same wave phase once per period; each component
    is scaled by its natural size (2 pi r A*, 1 + A*, 2 pi (1 + A*)). A periodic motion of period
    one gives 0.
    """
    if len(samples) < 2:
        return math.inf
    s = np.array(samples[-last - 1 :])
    scale = np.array([2 * math.pi * max(r * amp, 1e-12), 1.0 + amp, 2 * math.pi * (1.0 + amp)])
    diffs = np.abs(np.diff(s[:, 1:4], axis=0)) / scale
    return float(diffs.max())


def _run_wave(
    scene: Scene, model: ContactModel, trajectory: bool, plan: Assembly, record_every: int | None
) -> Result:
    wave = scene.drive
    assert isinstance(wave, Wave)
    t0 = time.perf_counter()
    num = scene.numerics
    engine = plan.engine
    stepper = _Stepper(scene, model, plan, trajectory)
    if trajectory and record_every is not None:
        stepper.rec_every = max(1, int(record_every))
    k_per = stepper.k_per
    n_periods = scene.measure_periods()
    n_measure = n_periods * k_per
    n_total = max(int(round(num.periods * k_per)), n_measure)
    n_max = max(n_total, int(round(num.max_periods * k_per)))
    stepper.advance(n_total - n_measure)
    speed = 2.0 * math.pi * scene.horizontal_ratio * wave.amplitude

    def measure() -> tuple[float, float, list[np.ndarray]]:
        # one measurement window: mean x*' over it, its drift ratio, the stroboscopic samples
        stepper.st[ig.S_LIFTS] = 0.0
        dx, samples = _measure(stepper, n_periods)
        drift = dx / n_periods
        return drift, (drift / speed if speed > 0.0 else 0.0), samples

    drift, ratio, samples = measure()
    if num.settle:
        previous = math.inf
        while abs(ratio - previous) > num.settle_tolerance and stepper.step + n_measure <= n_max:
            previous = ratio
            drift, ratio, samples = measure()
    st = stepper.st
    lost = bool(st[ig.S_LOST] > 0.0)
    count = max(st[ig.S_COUNT], 1.0)
    lifts = float(st[ig.S_LIFTS]) / n_periods
    period_change = periodicity(samples, wave.amplitude, scene.horizontal_ratio)
    return Result(
        model=scene.model,
        engine=engine,
        m_star=scene.particle.m_star,
        amplitude=wave.amplitude,
        mu=scene.material.mu,
        nu=scene.material.nu,
        horizontal_ratio=scene.horizontal_ratio,
        profile=scene.particle.profile.shape,
        steps_per_period=k_per,
        periods=stepper.step / k_per,
        ramp_periods=wave.ramp_periods,
        measure_periods=n_periods,
        drift_velocity=float(drift),
        drift_ratio=float(ratio),
        regime=classify(lost, ratio, num.drift_tolerance, lifts, period_change,
                        num.periodic_tolerance),
        contact_lost=lost,
        out_of_contact_fraction=float(st[ig.S_OUT] / count),
        min_compression=float(st[ig.S_AMIN]) if math.isfinite(st[ig.S_AMIN]) else math.nan,
        steps=stepper.step,
        wall_time_s=time.perf_counter() - t0,
        trajectory=stepper.trajectory() if trajectory else None,
        extra={"periodicity": period_change, "liftoffs_per_period": lifts},
    )


def prescribed_history(drive: Prescribed) -> tuple[np.ndarray, np.ndarray]:
    """The sampled a*(k), b*(k) of a prescribed drive (see :class:`~sawdrift.scene.Prescribed`)."""
    n = drive.samples_per_segment

    def path(vertices: list[tuple[float, float]]) -> tuple[np.ndarray, np.ndarray]:
        av, bv = [vertices[0][0]], [vertices[0][1]]
        for (a0, b0), (a1, b1) in zip(vertices[:-1], vertices[1:], strict=True):
            s = np.arange(1, n + 1) / n
            av.extend(a0 + (a1 - a0) * s)
            bv.extend(b0 + (b1 - b0) * s)
        return np.asarray(av), np.asarray(bv)

    if drive.waveform == "samples":
        return np.asarray(drive.a, dtype=float), np.asarray(drive.b, dtype=float)
    if drive.waveform == "proportional":
        return path([(0.0, 0.0), (drive.a_max, drive.slope * drive.a_max)])
    if drive.waveform == "mindlin_loop":
        am, bb = drive.a_max, drive.b_amplitude
        vertices = [(0.0, 0.0), (am, 0.0), (am, bb)]
        for _ in range(drive.cycles):
            vertices += [(am, -bb), (am, bb)]
        return path(vertices)
    rng = np.random.default_rng(drive.seed)
    m = 10 * drive.cycles
    a_v = drive.a_max * rng.uniform(-0.3, 1.5, size=m)
    b_v = np.cumsum(drive.a_max * rng.normal(0.0, 0.5, size=m))
    return path([(0.0, 0.0), *zip(a_v.tolist(), b_v.tolist(), strict=True)])


def _run_prescribed(scene: Scene, model: ContactModel, engine: Engine) -> Result:
    drive = scene.drive
    assert isinstance(drive, Prescribed)
    t0 = time.perf_counter()
    a, b = prescribed_history(drive)
    history = ContactHistory(model, engine)
    n_f, t_f = history.drive(a, b)
    bad = ~np.isfinite(n_f + t_f)
    if bad.any():
        k = int(np.argmax(bad))
        raise NonFiniteStateError(
            f"model {scene.model!r} returned a non-finite force at sample {k} "
            f"(a* = {a[k]:.6g}, b* = {b[k]:.6g})"
        )
    # dissipated work: the integral of T* db*, trapezoidal over the sampled path
    work = float(np.sum(0.5 * (t_f[1:] + t_f[:-1]) * np.diff(b))) if a.size > 1 else 0.0
    frame = pd.DataFrame({"t": np.arange(a.size, dtype=float), "a": a, "b": b, "N": n_f, "T": t_f})
    nan = math.nan
    return Result(
        model=scene.model,
        engine=engine,
        m_star=scene.particle.m_star,
        amplitude=nan,
        mu=scene.material.mu,
        nu=scene.material.nu,
        horizontal_ratio=nan,
        profile=scene.particle.profile.shape,
        steps_per_period=0,
        periods=0.0,
        ramp_periods=0.0,
        measure_periods=0,
        drift_velocity=nan,
        drift_ratio=nan,
        regime="prescribed",
        contact_lost=bool(np.any(a <= 0.0)),
        out_of_contact_fraction=float(np.mean(a <= 0.0)),
        min_compression=float(a.min()) if a.size else nan,
        steps=int(a.size),
        wall_time_s=time.perf_counter() - t0,
        trajectory=frame,
        extra={"dissipated_work": work},
    )


def _run_impact(scene: Scene, model: ContactModel, plan: Assembly, trajectory: bool) -> Result:
    """A free normal impact: integrate from first touch until contact is lost again."""
    drive = scene.drive
    assert isinstance(drive, Impact)
    t0 = time.perf_counter()
    stepper = _Stepper(scene, model, plan, record=True, preload=False)
    stepper.rec_every = 1
    stepper.y[:] = (0.0, drive.tangential_velocity, 0.0, drive.velocity)
    chunk = max(8, stepper.k_per // 8)
    n_max = int(round(scene.numerics.periods * stepper.k_per))
    separated = False
    while stepper.step < n_max and not separated:
        stepper.advance(chunk)
        separated = stepper.y[2] < 0.0 and stepper.step > 1
    tr = stepper.trajectory()
    rebound = math.nan
    duration = math.nan
    if separated:
        a = tr["a"].to_numpy()
        k = int(np.nonzero((a[:-1] > 0.0) & (a[1:] <= 0.0))[0][-1])
        w = a[k] / (a[k] - a[k + 1])
        v_out = (1 - w) * tr["vy"].iloc[k] + w * tr["vy"].iloc[k + 1]
        rebound = abs(v_out) / drive.velocity
        duration = float((k + w) * stepper.h)
    nan = math.nan
    return Result(
        model=scene.model, engine=plan.engine, m_star=scene.particle.m_star, amplitude=0.0,
        mu=scene.material.mu, nu=scene.material.nu, horizontal_ratio=nan,
        profile=scene.particle.profile.shape, steps_per_period=stepper.k_per,
        periods=stepper.step / stepper.k_per, ramp_periods=0.0, measure_periods=0,
        drift_velocity=nan, drift_ratio=nan, regime="impact", contact_lost=separated,
        out_of_contact_fraction=nan, min_compression=nan, steps=stepper.step,
        wall_time_s=time.perf_counter() - t0, trajectory=tr if trajectory else None,
        extra={"rebound_ratio": rebound, "contact_duration": duration,
               "max_compression": float(tr["a"].max())},
    )

