"""What a run computes, decided once from the scene (LAMMPS-style slots), and its description.

:func:`assemble` picks the scheme (compliant Adams-Bashforth, rigid events, prescribed history,
free impact), the engine and the slots that are on; an empty slot is never computed.
:func:`explain` prints the same decisions, so ``--explain`` cannot differ from what runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

from ..contact.base import ContactModel
from ..errors import SceneError
from ..scene.schema import Impact, Prescribed, Scene, Wave
from .drives import Drive, drive_of

Engine = Literal["compiled", "python"]

__all__ = ["Assembly", "Engine", "assemble", "explain", "steps_per_period"]


#: scene fields whose physics is being built: a value other than the default is refused in one
#: line rather than silently ignored (each entry goes when its part runs)
_UNBUILT = {
    "particle.load": ("particle", "load", 0.0),
    "material.restitution": ("material", "restitution", None),
}


def _refuse_unbuilt(scene: Scene) -> None:
    for dotted, (part, field, default) in _UNBUILT.items():
        value = getattr(getattr(scene, part), field, default)
        if value != default:
            raise SceneError(f"{dotted} = {value!r} is not computed by this version of sawdrift; "
                             f"leave it at {default!r}")


def steps_per_period(scene: Scene, rigid: bool | None = None) -> int:
    """Steps per wave period: the scene's ``numerics.steps_per_period``, or the automatic default.

    For a rigid model the default is 256 (nothing stiff to resolve; events are located by
    bisection inside steps). Otherwise it resolves the contact's small-amplitude natural frequency
    omega = sqrt(k / m*) (per unit t*, docs/physics.md) with h omega <= 0.06, where
    k = p a_ref^(p-1) max(1, c/theta) bounds the normal and tangential stiffness at the largest
    expected compression a_ref = 1 + 2 A* (c = 1 + 1/kappa with rotation, else 1), and never goes
    below 128 per period. ``rigid`` is the model's capability (looked up when not given).
    """
    if scene.numerics.steps_per_period is not None:
        return scene.numerics.steps_per_period
    if rigid is None:
        from ..contact.registry import get_model

        rigid = get_model(scene.model).capabilities.rigid
    if rigid:
        return 256
    p = scene.particle.profile.p
    amp = scene.drive.amplitude if isinstance(scene.drive, Wave) else 0.0
    a_ref = 1.0 + 2.0 * amp
    if isinstance(scene.drive, Impact):
        # largest compression from the energy balance with gravity:
        # a^(p+1) / (p+1) - a = m* v^2 / 2, solved by fixed-point iteration
        energy = 0.5 * scene.particle.m_star * scene.drive.velocity**2
        a_ref = 1.0
        for _ in range(60):
            a_ref = ((p + 1.0) * (energy + a_ref)) ** (1.0 / (p + 1.0))
    # a rolling contact point is lighter by c = 1 + 1/kappa: its tangential frequency is
    # sqrt(c) higher
    c = 1.0 + 1.0 / scene.particle.gyration if scene.effects.rotation else 1.0
    k = p * a_ref ** (p - 1.0) * max(1.0, c / scene.theta)
    if scene.effects.rotation and scene.effects.rolling_resistance > 0.0:
        # the rolling spring 2.25 mu_r^2 dN*/da* acts on the rotational inertia kappa m*
        mu_r = scene.effects.rolling_resistance
        k = max(k, 2.25 * mu_r**2 * p * a_ref ** (p - 1.0) / scene.particle.gyration)
    omega = math.sqrt(k / scene.particle.m_star)
    return int(min(10_000_000, max(128, math.ceil(omega / 0.06))))


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
    #: the substrate's motion (sawdrift.dynamics.drives); None for a prescribed contact history
    drive: Drive | None = None
    #: the integration step is 1 / steps_per_period (0 for a prescribed history)
    steps_per_period: int = 0


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
    _refuse_unbuilt(scene)
    horiz = isinstance(drive, Wave) and eff.horizontal_wave
    vert = isinstance(drive, Wave) and eff.vertical_wave
    part = drive_of(scene)
    ramp = part.ramp_periods(scene)
    k_per = steps_per_period(scene, caps.rigid)
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
        calls.append(f"Adams-Bashforth order {scene.numerics.order}, {k_per} steps per period")
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
    equations += part.describe(scene)
    if isinstance(drive, Impact):
        equations.append(f"start at a* = 0 with a*' = {drive.velocity:g}")
    outputs = (
        ("rebound speed ratio", "contact duration", "max compression")
        if isinstance(drive, Impact)
        else ("drift_velocity", "drift_ratio", "regime", "contact_lost", "min_compression",
              "gross_slip_fraction", "liftoffs_per_period", "hop_period", "lyapunov", "settled")
        + (("spin_rate",) if eff.rotation else ())
    )
    return Assembly(
        scheme, engine, eff.friction, eff.friction and not caps.rigid, eff.normal_damping,
        horiz, vert, ramp, tuple(equations), tuple(calls), outputs, part, k_per,
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
