"""What a run computes, decided once from the scene (LAMMPS-style slots), and its description.

:func:`assemble` picks the scheme (compliant Adams-Bashforth, rigid events, prescribed history,
free impact), the engine and the slots that are on; an empty slot is never computed.
:func:`explain` prints the same decisions, so ``--explain`` cannot differ from what runs.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from ..contact.base import ContactModel
from ..errors import SceneError
from ..scene.schema import Impact, Prescribed, Scene, Wave

Engine = Literal["compiled", "python"]

__all__ = ["Assembly", "Engine", "assemble", "explain"]


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
