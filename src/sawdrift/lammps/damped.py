"""Where a damped contact bounds its friction: the two Coulomb rules, integrated independently.

With a restitution e the normal force of a compliant contact is N* = N*_el(a*) + C a*^(1/4) a*'
(Hertz, clamped at 0; :func:`sawdrift.dynamics.adams_bashforth.restitution_damping`), and the
friction force is bounded by it, |T*| <= N*. A DEM spring stores a tangential force T_s; two
rules differ in which bound they apply to the *stored* force:

* ``"total"`` (LAMMPS ``pair granular``: ``Fscrit = mu Fncrit``, Fncrit = |Fntot| after
  ``limit_damping``, caps the stored history, src/GRANULAR/granular_model.cpp and
  gran_sub_mod_tangential.cpp; and the native ``hertz_mindlin_dem``,
  :func:`sawdrift_builtin.dem_kernel.dem_step`): the spring itself is clipped to the total
  force, T* = T_s = clip(T_s, +-N*);
* ``"elastic"`` (the rule the memory-diagram laws keep for their history, and the native DEM
  spring's before it took the total force): the spring is clipped to the elastic force,
  |T_s| <= N*_el, and only the transmitted force is capped by the total one,
  T* = clip(T_s, +-N*). While the contact is loaded (a*' > 0, N* > N*_el) the friction force
  therefore never exceeds N*_el.

Without damping the two are the same law. With damping they give different drifts whenever the
spring reaches the bound while the contact is loading (gross slip in the loading half of a
period). :func:`cap_rule_drift` integrates one sphere on the wave-driven plane with either rule
(velocity Verlet, as LAMMPS, in the normalized variables of docs/physics.md; compiled with numba,
a few ms per 50 000 steps), so each engine can be checked against its own rule and the size of the
difference stated.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from numba import njit

from ..dynamics.adams_bashforth import restitution_damping
from ..dynamics.assembly import steps_per_period
from ..scene.schema import Scene
from .engine import open_lammps
from .realize import realize
from .single import granular_model

Rule = Literal["elastic", "total"]


def cap_rule_positions(scene: Scene, rule: Rule, k_per: int | None = None,
                       periods: float | None = None) -> list[float]:
    """x* at the end of every period (from x*(0) = 0) of ``scene`` integrated with ``rule``.

    The scene must have a LAMMPS equivalent (a sphere, one travelling wave, no rotation); its
    restitution sets C (none: the undamped contact, where both rules agree), its tangential
    load (``particle.load``, a device's ``device.load``) is a constant force along x.
    """
    real = realize(scene)
    k_per = steps_per_period(scene) if k_per is None else k_per
    periods = scene.numerics.periods if periods is None else periods
    m, mu, theta = real.m_star, real.mu, real.theta
    amp = real.amplitude / real.a0
    rx, sp, cp, tr = real.ratio * real.horizontal, real.sin_phase, real.cos_phase, real.ramp_periods
    ay = real.vertical
    e = real.restitution
    load = real.load / real.weight  # a constant tangential load, units of the normal load
    c_damp = restitution_damping(e, 1.5, m) if e is not None else 0.0
    xs = _integrate(m, mu, theta, amp, rx, sp, cp, tr, ay, load, c_damp, rule == "total",
                    int(k_per), int(round(periods * k_per)))
    return [float(x) for x in xs]


@njit(cache=True)
def _surface(t: float, rx: float, amp: float, sp: float, cp: float, tr: float,
             ay: float) -> tuple[float, float]:
    """(u_x*, u_y*) of the plane at t* (the wave's orbit, switched on over tr periods)."""
    ramp = math.sin(math.pi / (2.0 * tr) * t) ** 2 if t < tr else 1.0
    w = 2.0 * math.pi * t
    return rx * amp * ramp * (-sp * math.sin(w) + cp * math.cos(w)), ay * amp * ramp * math.cos(w)


@njit(cache=True)
def _integrate(m: float, mu: float, theta: float, amp: float, rx: float, sp: float, cp: float,
               tr: float, ay: float, load: float, c_damp: float, total: bool, k_per: int,
               steps: int) -> np.ndarray:
    """Velocity Verlet of one sphere with the Coulomb rule ``total`` (else elastic); x* a period."""
    h = 1.0 / k_per
    x = vx = vy = fx = fy = 0.0
    y = 1.0
    ts, a_old, b_old = 0.0, 1.0, 0.0
    uy_old = _surface(0.0, rx, amp, sp, cp, tr, ay)[1]
    out = np.zeros(steps // k_per + 1)
    for k in range(steps):
        vxh, vyh = vx + 0.5 * h * fx / m, vy + 0.5 * h * fy / m
        x += h * vxh
        y += h * vyh
        ux, uy = _surface((k + 1) * h, rx, amp, sp, cp, tr, ay)
        a = y - uy
        adot = vyh - (uy - uy_old) / h  # the relative normal velocity of the half step
        uy_old = uy
        b = (x - ux) / (theta * mu)
        n_tot, t_out = 0.0, 0.0
        if a > 0.0:
            n_el = a**1.5
            n_tot = max(0.0, n_el + c_damp * a**0.25 * adot)
            k1 = 1.5 * math.sqrt(a)
            if a < a_old:  # mindlin_rescale: the stored force shrinks with the stiffness
                trial = ts * k1 / (1.5 * math.sqrt(a_old)) + k1 * (b - b_old)
            else:  # the secant of N*_el along the path
                slope = (n_el - a_old**1.5) / (a - a_old) if a != a_old else k1
                trial = ts + (b - b_old) * slope
            bound = n_tot if total else n_el
            ts = min(max(trial, -bound), bound)
            t_out = min(max(ts, -n_tot), n_tot)
        else:
            ts = 0.0
        a_old, b_old = max(a, 0.0), b
        fx, fy = -mu * t_out + load, 1.0 - n_tot
        vx, vy = vxh + 0.5 * h * fx / m, vyh + 0.5 * h * fy / m
        if (k + 1) % k_per == 0:
            out[(k + 1) // k_per] = x
    return out


def cap_rule_drift(scene: Scene, rule: Rule, k_per: int | None = None) -> float:
    """The drift ratio over the scene's measuring window with the Coulomb ``rule`` (docstring)."""
    xs = cap_rule_positions(scene, rule, k_per)
    window = scene.measure_periods()
    real = realize(scene)
    speed = 2.0 * math.pi * real.ratio * real.horizontal * real.amplitude / real.a0
    return (xs[-1] - xs[-1 - window]) / window / speed


def free_impact(scene: Scene, speed: float = 1e-3, steps_per_contact: int = 2000) -> float:
    """Rebound ratio of one sphere of ``scene`` thrown at ``speed`` (m/s) onto a still plane in LAMMPS.

    No gravity, no wave: the contact law of the bridge alone (:func:`.single.granular_model`,
    with its damping). The time step is 1/``steps_per_contact`` of pi sqrt(m / k) at the impact's
    largest overlap; the run ends once the sphere has left the plane moving away.
    """
    real = realize(scene)
    radius, mass = real.radius, real.mass
    # Hertz: the largest overlap of an undamped impact, (15 m v^2 / (16 E* sqrt(R)))^(2/5)
    delta = (15.0 * mass * speed**2 / (16.0 * real.e_star * math.sqrt(radius))) ** 0.4
    k = 2.0 * real.e_star * math.sqrt(radius * delta)
    dt = math.pi * math.sqrt(mass / k) / steps_per_contact
    model = granular_model(real, bool(scene.model_params.get("rescale", True)))
    lmp = open_lammps()
    try:
        lmp.commands_string("\n".join([
            "units si", "atom_style sphere", "atom_modify map array", "boundary p p f",
            "newton off", "comm_modify vel yes",
            f"region box block -1.0 1.0 -1.0 1.0 {-10 * radius!r} {10 * radius!r}",
            "create_box 1 box", f"create_atoms 1 single 0.0 0.0 {radius!r}",
            f"set atom 1 diameter {2.0 * radius!r} density {real.density!r}",
            f"velocity all set 0.0 0.0 {-speed!r}", "pair_style granular",
            f"pair_coeff * * {model}", "region wall plane 0.0 0.0 0.0 0.0 0.0 1.0 side in",
            f"fix wall all wall/gran/region granular {model} region wall", "fix move all nve",
            f"timestep {dt!r}", "thermo 0", "run 0"]))
        for _ in range(40):
            lmp.command(f"run {steps_per_contact // 4} pre no post no")
            z = float(lmp.numpy.extract_atom("x")[0, 2])
            vz = float(lmp.numpy.extract_atom("v")[0, 2])
            if z > radius and vz > 0.0:
                return vz / speed
    finally:
        lmp.close()
    raise RuntimeError("the sphere did not leave the plane within 10 contact times")
