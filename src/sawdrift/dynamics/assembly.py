"""What a run computes, decided once from the scene (LAMMPS-style slots), and its description.

:func:`assemble` picks the scheme (compliant Adams-Bashforth, rigid events, prescribed history,
free impact), the engine and the slots that are on; an empty slot is never computed.
:func:`explain` prints the same decisions, so ``--explain`` cannot differ from what runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ..contact.adhesion import adhesive_stiffness
from ..contact.base import ContactModel
from ..contact.binding import bind, describe_body, model_for
from ..contact.registry import get_model, plugin_failures
from ..errors import SceneError
from ..scene.adhesion import explain_adhesion
from ..scene.device import explain_device
from ..scene.parts import FINEST_STEPS
from ..scene.schema import Impact, Prescribed, Scene, Wave
from ..scene.validity import device_warnings
from . import air_drag
from .adams_bashforth import (
    MIN_RESTITUTION,
    damping_ratio,
    horizontal_inertia,
    restitution_damping,
)
from .drives import DRIVES, Drive, drive_of
from .impact_scale import STEPS_PER_IMPACT, impact_compression, impact_duration

Engine = Literal["compiled", "python"]

__all__ = ["Assembly", "Engine", "assemble", "explain", "steps_per_period"]


def steps_per_period(scene: Scene, rigid: bool | None = None) -> int:
    """Steps per wave period: the scene's ``numerics.steps_per_period``, or the automatic default.

    For a rigid model the default is 256 (nothing stiff to resolve; events are located by
    bisection inside steps). Otherwise it resolves the contact's small-amplitude natural frequency
    omega = sqrt(k / m*) (per unit t*, docs/physics.md) with h omega <= 0.06, where
    k = p a_ref^(p-1) max(1, c/theta) bounds the normal and tangential stiffness at the largest
    expected compression a_ref = 1 + 2 A* (c = 1 + 1/kappa with rotation, else 1), keeps
    h c / m* <= 0.1 for a viscous normal damping c (the scene's and the model's own,
    :func:`model_dashpot`) and for the air drag c on the smaller of m* and the horizontal inertia
    a settling run may integrate (:func:`~.adams_bashforth.horizontal_inertia`), and never goes
    below 128 per period.
    ``rigid`` is the model's capability (looked up when not given).
    """
    if scene.numerics.steps_per_period is not None:
        return scene.numerics.steps_per_period
    if rigid is None:
        rigid = get_model(scene.model).capabilities.rigid
    if rigid:
        return 256
    p = scene.particle.profile.p
    amp = scene.drive.amplitude if isinstance(scene.drive, Wave) else _vertical_amplitude(scene)
    a_ref = 1.0 + 2.0 * amp
    impact = 0
    if isinstance(scene.drive, Impact):
        a_ref = impact_compression(scene)
        # the contact's start and end (N* ~ a*^p, the damping ~ a*^((p-1)/2) a*') converge
        # slowly: the rebound ratio needs STEPS_PER_IMPACT steps in contact to 1e-4
        impact = math.ceil(STEPS_PER_IMPACT / impact_duration(scene, a_ref))
    # a rolling contact point is lighter by c = 1 + 1/kappa: its tangential frequency is
    # sqrt(c) higher
    c = 1.0 + 1.0 / scene.particle.gyration if scene.effects.rotation else 1.0
    k = p * a_ref ** (p - 1.0) * max(1.0, c / scene.theta)
    if scene.effects.adhesion != "none":
        # the adhesive contact's stiffness, about 1.5 c* (sawdrift.contact.adhesion_law)
        k = adhesive_stiffness(scene, amp) * max(1.0, c / scene.theta)
    if scene.effects.rotation and scene.effects.rolling_resistance > 0.0:
        # the rolling spring 2.25 mu_r^2 dN*/da* acts on the rotational inertia kappa m*
        mu_r = scene.effects.rolling_resistance
        k_r = 2.25 * mu_r**2 * p * a_ref ** (p - 1.0) / scene.particle.gyration
        need = math.sqrt(k_r / scene.particle.m_star) / 0.06
        if need > FINEST_STEPS and scene.numerics.steps_per_period is None:
            # named as normal damping is: a non-finite state blamed m* and A*
            raise SceneError(
                f"effects.rolling_resistance = {mu_r:g}: its rolling spring on m* = "
                f"{scene.particle.m_star:g} needs {need:.2g} steps a period for a stable step; "
                f"allowed: up to {FINEST_STEPS:.0e} (mu_r is about sqrt(a0/R), of order 1e-3 "
                "for a millimetre ball; or a heavier particle)")
        k = max(k, k_r)
    omega = math.sqrt(k / scene.particle.m_star)
    # viscous normal damping c: the explicit step is stable for h c / m* below about 0.3
    # (measured: mmd, m* = 0.01, c = 1 goes wrong at 295 steps); h c / m* <= 0.1 is kept
    # a model's own dashpot (a normal-damping slot: hertz_tsuji's damping = 100 ran at 128 steps
    # a period into a numerical blow-up reported as an ejection) counts as the scene's does
    viscous = scene.effects.normal_damping + model_dashpot(scene, a_ref)
    damping = 10.0 * viscous / scene.particle.m_star
    if damping > FINEST_STEPS and scene.numerics.steps_per_period is None:
        raise SceneError(
            f"normal damping: a dashpot of {viscous:.3g} (effects.normal_damping plus the "
            f"model's own) on m* = {scene.particle.m_star:g} needs {damping:.2g} steps a period "
            f"for a stable step (h c / m* <= 0.1); allowed: up to {FINEST_STEPS:.0e} (a smaller "
            f"damping or a heavier particle)")
    # on the smaller of m* and the horizontal inertia a settling run may integrate
    drag = 10.0 * scene.effects.air_drag / horizontal_inertia(scene.particle.m_star, False)
    if drag > FINEST_STEPS and scene.numerics.steps_per_period is None:
        # as a dashpot: --air-drag 1e308 blew the state up, blamed on the step and the model
        raise SceneError(
            f"effects.air_drag = {scene.effects.air_drag:g} on m* = {scene.particle.m_star:g} "
            f"needs {drag:.2g} steps a period for a stable step (h c / m* <= 0.1); allowed: up "
            f"to {FINEST_STEPS:.0e} (c a0 f / (M g) of a real particle is far below 1)")
    return int(min(FINEST_STEPS, max(128, math.ceil(omega / 0.06), math.ceil(damping),
                                     math.ceil(drag), impact)))


def ramp_end_step(ramp: float, k_per: int) -> int:
    """The first step after the drive's start-up ramp of ``ramp`` periods (evidence is taken
    from there; a window within the ramp takes its own, :func:`~.window.measure_window`)."""
    return math.ceil(ramp * k_per - 1e-9)


def model_dashpot(scene: Scene, a: float) -> float:
    """dN*/da*' of the model's own normal law at the compression ``a`` (0 for a model whose
    forces do not depend on the velocity): its dashpot coefficient, from the law itself (its
    normal law with any normal-damping slot, evaluated at two approach speeds), so that a
    plugin's damping sets the step as ``effects.normal_damping`` does."""
    if not get_model(scene.model).capabilities.uses_velocity:
        return 0.0
    model = model_for(scene)
    law, pp = model.normal_law()
    force = getattr(law, "py_func", law)
    n_float, n_int = model.state_sizes()
    fs, is_ = np.zeros(max(n_float, 1)), np.zeros(max(n_int, 1), dtype=np.int64)
    speed = 1e-6
    # a plugin's law that raises here, where the step is chosen (a run's size estimate too),
    # is the plugin's failure (it was an internal failure, exit 3: KeyError '__builtins__')
    with plugin_failures(scene.model):
        slow = force(fs, is_, pp, a, 0.0, 0.0, 0.0)[0]
        fast = force(fs, is_, pp, a, 0.0, speed, 0.0)[0]
    return max(0.0, float(fast - slow) / speed)


def _vertical_amplitude(scene: Scene) -> float:
    """The registered drive's vertical amplitude (0 for a drive without one, e.g. prescribed)."""
    part = DRIVES.get(scene.drive.kind)
    return part.vertical_amplitude(scene) if part is not None else 0.0


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
    #: the constant tangential load L on the centre (particle.load), in M g
    load: float = 0.0
    #: the restitution in force: a compliant contact's damped e (None: undamped), or the rigid
    #: point's Newton restitution
    restitution: float | None = None
    #: C of a compliant contact's restitution damping N* += C a*^((p-1)/2) a*' (0: off)
    restitution_damping: float = 0.0
    #: the scheme's named parameters (adams_bashforth.PRM_NAMES, and the rigid scheme's
    #: rigid.RIGID_PRM_NAMES), in that order: what the loop runs with
    params: tuple[tuple[str, float], ...] = ()

    def param(self, name: str) -> float:
        """The scheme parameter ``name`` (KeyError if this assembly has none of that name)."""
        return dict(self.params)[name]


def assemble(scene: Scene, engine: Engine = "compiled", model: ContactModel | None = None) -> Assembly:
    """Decide the scheme, the slots that are on, and the engine for ``scene``.

    ``model`` is the scene's model instance when the caller has already built it
    (:func:`sawdrift.contact.binding.model_for`).
    """
    if engine not in ("compiled", "python"):
        raise SceneError(f"engine = {engine!r} is not allowed; use 'compiled' or 'python'")
    if model is None:
        model = model_for(scene)
    caps = model.capabilities
    eff = scene.effects
    drive = scene.drive
    if engine == "compiled" and not caps.compiled:
        engine = "python"
    name = scene.model
    kernel = f"{name}.kernel.force" if engine == "compiled" else f"{name}.reference().force"
    if isinstance(drive, Prescribed):
        return _prescribed(scene, engine, kernel)
    part = drive_of(scene)
    ramp = part.ramp_periods(scene)
    k_per = steps_per_period(scene, caps.rigid)
    slot = _damping_slot(scene, model)
    load = scene.particle.load
    restitution, rest_c, rest_lines = _restitution(scene, model, slot)
    if caps.rigid:
        scheme = "rigid"
        equations, calls = _rigid_lines(scene, rest_lines)
    else:
        scheme = "impact" if isinstance(drive, Impact) else "adams-bashforth"
        equations, calls = _compliant_lines(scene, kernel, slot, rest_lines, k_per)
        if eff.rotation and eff.friction:
            equations += _rotation_lines(scene)
    equations += part.describe(scene)
    if isinstance(drive, Impact):
        equations.append(f"start at a* = 0 with a*' = {drive.velocity:g}")
    params = _params(scene, k_per, ramp, rest_c)
    params[air_drag.PARAM] = air_drag.parameter(scene, caps.rigid)  # a force: its module decides
    params["surface_bound"] = part.surface_bound(scene)  # high flights go at once (.flight)
    equations += air_drag.describe(scene)
    if caps.rigid:
        # material.restitution, or the model's own parameter (_restitution checks they agree)
        e = restitution if restitution is not None else model.params.restitution
        params.update({"restitution": e, "vertical_inertia": 1.0 if eff.vertical_inertia else 0.0,
                       "x_q": 0.0, "u_y": part.vertical_amplitude(scene)})
    return Assembly(
        scheme, engine, eff.friction, eff.friction and not caps.rigid, eff.normal_damping,
        isinstance(drive, Wave) and eff.horizontal_wave, isinstance(drive, Wave) and eff.vertical_wave,
        ramp, tuple(equations), tuple(calls), _outputs(scene), part, k_per,
        load, restitution, rest_c, tuple((k, float(v)) for k, v in params.items()),
    )


def _prescribed(scene: Scene, engine: Engine, kernel: str) -> Assembly:
    """The assembly of a prescribed contact history: the kernel alone, no dynamics."""
    for field, value, off in (("particle.load", scene.particle.load, 0.0),
                              ("material.restitution", scene.material.restitution, None)):
        if value != off:
            raise SceneError(f"{field} = {value!r} acts on the particle's motion; a prescribed "
                             "contact history has none (leave it unset)")
    assert isinstance(scene.drive, Prescribed)
    return Assembly(
        "prescribed", engine, False, True, 0.0, False, False, 0.0,
        ("a*(k), b*(k) prescribed (" + scene.drive.waveform + "); no dynamics",),
        (f"{kernel}(a*, b*) once per sample, committing the history",),
        ("N*(k)", "T*(k)", "dissipated work = sum of T* db*"),
    )


def _damping_slot(scene: Scene, model: ContactModel) -> object:
    """The model's own normal-damping slot (None: none); refused beside effects.normal_damping."""
    slot = getattr(type(model), "damping", None)
    damping = scene.effects.normal_damping
    if slot is not None and damping > 0.0:
        raise SceneError(
            f"effects.normal_damping = {damping:g} would stack a second normal damping "
            f"on model {scene.model!r}, which has its own normal-damping slot ({slot.name!r}); use one: "
            "set effects.normal_damping = 0, or pick a model without a damping slot"
        )
    return slot


def _rigid_lines(scene: Scene, rest_lines: list[str]) -> tuple[list[str], list[str]]:
    """The rigid scheme's equations and calls (docs/physics.md, the rigid point)."""
    eff = scene.effects
    equations = ["a* = 0 in contact; flight m* y*'' = 1 when N* < 0; impact with restitution"
                 + (rest_lines[0] if rest_lines else ""),
                 "N* = 1 - m* u_y''" if eff.vertical_inertia else "N* = 1 (vertical inertia off)"]
    if scene.particle.load != 0.0:
        equations += _rigid_load_lines(scene)
    elif eff.friction and eff.rotation:
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
    calls = ["closed-form N*(t), slip velocity and event bisection (sawdrift.dynamics.rigid)"
             + ("; within a step on the contact point s*, between steps the state is the "
                "centre x* (the drive is evaluated there)" if eff.rotation else "")]
    return equations, calls


def _compliant_lines(scene: Scene, kernel: str, slot: object, rest_lines: list[str],
                     k_per: int) -> tuple[list[str], list[str]]:
    """The compliant (Adams-Bashforth) scheme's equations and calls, rotation aside."""
    eff = scene.effects
    load = scene.particle.load
    normal = f"{scene.model} normal law" + ("" if eff.friction else " alone (its normal slot)")
    if eff.adhesion != "none":
        pull = scene.material.adhesion
        normal = (f"{eff.adhesion.upper()} adhesive normal law (pull-off F*_pull = {pull:.6g}, "
                  f"N* >= -F*_pull; the contact breaks on retraction"
                  + (" at the pull-off" if eff.adhesion_detach == "pulloff" else "")
                  + "); |T*| <= |N* + 2 F*_pull|, the friction cap with adhesion")
    equations = [f"m* y*'' = 1 - N*(a*), a* = y* - u_y; N* from the {normal}"]
    calls: list[str] = []
    if eff.normal_damping > 0.0:
        equations.append(f"N* += {eff.normal_damping:g} a*' while a* > 0, N* >= 0 (viscous "
                         "normal damping); |T*| <= N*, the total normal force")
    elif rest_lines:
        equations += rest_lines
    elif slot is not None:
        equations.append(f"N* from the normal-damping slot {getattr(slot, 'name', '?')!r} "
                         f"({slot.__doc__.strip().splitlines()[0] if slot.__doc__ else ''}); "
                         "|T*| <= N*, the total normal force")
    if eff.friction:
        equations.append("m* x*'' = -mu T*(b*, a*)" + (" + L" if load != 0.0 else "") + (
            " (x* the centre)" if eff.rotation else ", theta mu b* = x* - u_x"))
        calls.append(f"{kernel}(a*, b*, a*', b*') once per step, committing the history")
    elif load != 0.0:
        equations.append("m* x*'' = L (friction off); the tangential law is never called")
    else:
        equations.append("x* not integrated (friction off); the tangential law is never called")
    if load != 0.0:
        equations.append(_LOAD_LINE.format(load=load))
    calls.append(f"Adams-Bashforth order {scene.numerics.order}, {k_per} steps per period")
    return equations, calls


def _rotation_lines(scene: Scene) -> list[str]:
    """The compliant scheme's rotation equations (docs/physics.md, Rotation)."""
    eff = scene.effects
    load = scene.particle.load
    kappa = scene.particle.gyration
    c = 1.0 + 1.0 / kappa
    if load != 0.0 and eff.rolling_resistance == 0.0:
        return [f"rotation: I phi'' = -R T with I = kappa m R^2, kappa = {kappa:.6g}; "
                "the load pulls the centre without turning it: kappa m* psi'' = "
                "-mu T*, psi = R phi / a0, theta mu b* = s* - u_x with s* = x* + psi",
                "the centre keeps m* x*'' = -mu T* + L; spin R phi' / a0 = psi'"]
    centre = "m* x*'' = -mu T* + L" if load != 0.0 else "m* x*'' = -mu T*"
    if eff.rolling_resistance > 0.0:
        # the rolling torque turns the sphere apart from friction: s = (1 + 1/kappa) x no longer
        mu_r = eff.rolling_resistance
        return [f"rotation: I phi'' = -R T + M_r with I = kappa m R^2, kappa = {kappa:.6g}",
                "rolling resistance (elastic-plastic spring, Ai et al. 2011): "
                "kappa m* psi'' = -mu T* + m_r, psi = R phi / a0, s* = x* + psi, "
                "m_r = -2.25 mu_r^2 (dN*/da*) psi_e - C_r psi' (C_r while elastic), "
                f"capped at mu_r N*, mu_r = {mu_r:g}",
                f"theta mu b* = s* - u_x; the centre keeps {centre}"]
    lines = [f"rotation: I phi'' = -R T with I = kappa m R^2, kappa = {kappa:.6g}; "
             f"from rest the contact point s = x + R phi = (1 + 1/kappa) x = {c:.6g} x"]
    lines.append("theta mu b* = s* - u_x: the contact point moves like a mass "
                 f"m* kappa / (1 + kappa) = {scene.particle.m_star / c:.6g}; the "
                 f"centre keeps {centre}; spin R phi' = x*' / kappa")
    return lines


def _outputs(scene: Scene) -> tuple[str, ...]:
    """What a run of ``scene`` reports."""
    if isinstance(scene.drive, Impact):
        return ("rebound speed ratio", "contact duration", "max compression")
    return (("drift_velocity", "drift_ratio", "regime", "contact_lost", "min_compression",
             "gross_slip_fraction", "liftoffs_per_period", "hop_period", "lyapunov", "settled")
            + (("spin_rate",) if scene.effects.rotation else ()))


def _params(scene: Scene, k_per: int, ramp: float, rest_c: float) -> dict[str, float]:
    """The compliant scheme's named parameters (adams_bashforth.PRM_NAMES), by name."""
    eff = scene.effects
    m = scene.particle.m_star
    return {
        "m": m, "mu": scene.material.mu, "theta": scene.theta, "h": 1.0 / k_per,
        "order": scene.numerics.order, "friction": 1.0 if eff.friction else 0.0,
        "damping": eff.normal_damping, "p": scene.particle.profile.p,
        "k_ramp": ramp_end_step(ramp, k_per),
        "roll": 1.0 + 1.0 / scene.particle.gyration if eff.rotation else 0.0,
        "rolling_resistance": eff.rolling_resistance if eff.rotation else 0.0,
        "m_x": m, "load": scene.particle.load, "restitution_damping": rest_c,
        "pulloff": scene.material.adhesion,
    }


_LOAD_LINE = ("L = {load:g}: particle.load, a constant tangential force on the centre in units of "
              "M g (positive along +x), applied from t* = 0")


def _rigid_load_lines(scene: Scene) -> list[str]:
    """The rigid scheme's tangential equations with the load L (docs/physics.md)."""
    load = scene.particle.load
    eff = scene.effects
    if not eff.friction:
        return ["m* x*'' = L (friction off: no tangential force)", _LOAD_LINE.format(load=load)]
    if not eff.rotation:
        return ["Coulomb with the load: stick x*'' = u_x'' while |m* u_x'' - L|/mu <= N*, else "
                "m* x*'' = -mu N* sgn(x*' - u_x') + L; in flight m* x*'' = L",
                _LOAD_LINE.format(load=load)]
    kappa = scene.particle.gyration
    c = 1.0 + 1.0 / kappa
    m_s = scene.particle.m_star / c
    return [f"rotation: I phi'' = -R T, I = kappa m R^2, kappa = {kappa:.6g}; the load acts on the "
            f"centre only: the contact point s = x + R phi has the mass m_s = m* / (1 + 1/kappa) = "
            f"{m_s:.6g} and the load L / (1 + 1/kappa) = {scene.particle.load / c:.6g}",
            "Coulomb on the contact point: stick s*'' = u_x'' while |m_s u_x'' - L/(1 + 1/kappa)|/mu "
            "<= N*, else m_s s*'' = -mu N* sgn(s*' - u_x') + L/(1 + 1/kappa); centre "
            "m* x*'' = -mu T* + L, so (1 + 1/kappa) x* - s* grows as (1/kappa) L t*^2 / (2 m*)",
            _LOAD_LINE.format(load=load)]


def _restitution(scene: Scene, model: ContactModel,
                 slot: object) -> tuple[float | None, float, list[str]]:
    """(restitution in force, C of the compliant restitution damping, its equation lines).

    ``material.restitution`` is the one name of the restitution for every model: on a compliant
    contact a normal damping that rebounds a free impact with ratio e at any speed; on the rigid
    point its Newton restitution (``model_params.restitution`` may only repeat it).
    """
    e = scene.material.restitution
    if model.capabilities.rigid:
        given = getattr(model.params, "restitution", None)  # the model's, defaults filled
        if e is None:
            return (float(given) if given is not None else None), 0.0, []
        field = type(model).Params.model_fields.get("restitution")
        default = field.default if field is not None else None
        if given is not None and given != default and given != e:
            raise SceneError(f"material.restitution = {e:g} and model_params.restitution = "
                             f"{given:g} disagree; give one of them (material.restitution is "
                             "the restitution of every model)")
        return e, 0.0, [f" e = {e:g} (material.restitution)"]
    if e is None:
        return None, 0.0, []
    eff = scene.effects
    if eff.normal_damping > 0.0:
        raise SceneError(f"material.restitution = {e:g} and effects.normal_damping = "
                         f"{eff.normal_damping:g} would be two normal dampings; use one of them")
    if slot is not None:
        raise SceneError(f"material.restitution = {e:g} would stack a second normal damping on "
                         f"model {scene.model!r}, which has its own normal-damping slot "
                         f"({getattr(slot, 'name', '?')!r}); use a model without one")
    profile = scene.particle.profile
    if profile.shape == "table":
        raise SceneError(f"material.restitution = {e:g} needs a power-law profile (sphere, cone, "
                         "flat, power): a tabulated normal law has no speed-independent "
                         "restitution damping")
    if e < MIN_RESTITUTION:
        raise SceneError(f"material.restitution = {e:g} is below {MIN_RESTITUTION:g}, the "
                         "smallest a compliant contact takes (its damping would exceed the "
                         "explicit scheme's stability); give e in [0.05, 1]")
    p = profile.p
    m = scene.particle.m_star
    c = restitution_damping(e, p, m)
    zeta = damping_ratio(e)
    line = (f"N* += beta sqrt(m* dN*/da*) a*' = C a*^((p-1)/2) a*' while a* > 0, N* >= 0: a free "
            f"impact rebounds with e = {e:g} at any speed (damping ratio zeta = {zeta:.6g}, beta = "
            f"zeta sqrt(2 (p+1)/p), C = zeta sqrt(2 (p+1) m*) = {c:.6g}); |T*| <= N*, the total "
            "normal force")
    return e, c, [line]


def explain(scene: Scene, engine: Engine = "compiled") -> str:
    """A readable description of the system :func:`run` assembles for ``scene``."""
    scene = bind(scene)  # checked as a run checks it (one line)
    plan = assemble(scene, engine)
    lines = [f"model {scene.model!r} ({describe_body(scene)}), scheme {plan.scheme}, engine {plan.engine}",
             "equations:"]
    lines += [f"  {eq}" for eq in plan.equations]
    lines.append("calls:")
    lines += [f"  {c}" for c in plan.calls]
    if plan.params:
        lines.append("scheme parameters: " + ", ".join(f"{k} = {v:.6g}" for k, v in plan.params
                                                       if k != "x_q"))
    lines.append("outputs: " + ", ".join(plan.outputs))
    if scene.device is not None:
        lines += explain_device(scene.device, scene.material.mu,
                                tuple(device_warnings(scene.device, scene.effects.adhesion)))
        lines += explain_adhesion(scene.device, scene.effects.adhesion, scene.material.mu)
    return "\n".join(lines)
