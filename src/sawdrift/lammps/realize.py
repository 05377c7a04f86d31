"""An SI realization of a scene for LAMMPS, and which scenes have a LAMMPS equivalent.

A normalized scene (docs/physics.md) fixes m*, A*, theta, mu, r, the orbit phase, the ramp and
the load; any sphere, modulus and frequency that reproduce them give the same normalized motion.
A device scene carries its own SI values (sawdrift.scene.device), which are used as they are.
With R, the particle mass m, the normal load M g and the static compression a0:

    E* = (9 (M g)^2 / (16 R a0^3))^(1/2)     (Hertz, a0 = (9 (M g)^2 / (16 R E*^2))^(1/3))
    G* = E* / (4 theta)                       (theta = E*/(4 G*))
    f  = (m* M g / (a0 m))^(1/2)              (m* = a0 m f^2 / (M g))
    A_y = A* a0

A normalized scene is realized as a sphere of R = 1 mm and density 2500 kg/m^3 under gravity
9.81 m/s^2 (with its preload, M g = m g (1 + preload)) and a0 = 1e-5 R.

LAMMPS's ``fix wall/gran`` mixes the wall's material with itself (measured on LAMMPS 2025.7:
the normal stiffness is (4/3) E/(2 (1 - nu^2)) sqrt(R delta) for the wall's E and nu, LAMMPS
issue 4141), so the equivalent single material of the wall has E_w = 2 (1 - nu_w^2) E*; its
tangential stiffness is given directly, k_t = 8 G* (``mindlin_rescale/force k_t``: the spring
is k_t a with the contact radius a = sqrt(R delta), Mindlin's 8 G* a), so any theta works.

Dissipation. The native restitution damping (``material.restitution`` e) is the force
beta sqrt(m dF/d delta) delta' with beta = zeta(e) sqrt(2 (p + 1) / p), zeta(e) the damping ratio
of the clamped linear dashpot that rebounds with e
(:func:`sawdrift.dynamics.adams_bashforth.restitution_damping`, after Tsuji et al. 1992 and
Antypov and Elliott 2011). For Hertz (p = 3/2, dF/d delta = (3/2) F/delta) that is
sqrt(5) zeta(e) sqrt(m F/delta) delta'. LAMMPS's ``damping coeff_restitution e'`` is the same
force, eta_n = sqrt(5) zeta' sqrt(m_eff F/delta) with zeta' = -ln e' / sqrt(pi^2 + ln^2 e') (the
unclamped linear dashpot's relation; pair granular's Tsuji prefactor, LAMMPS
src/GRANULAR/gran_sub_mod_damping.cpp). The bridge therefore passes
e' = exp(-pi zeta(e) / sqrt(1 - zeta(e)^2)), which exists for zeta < 1, i.e. e > exp(-2) =
0.135 (:data:`MIN_LAMMPS_RESTITUTION`); ``limit_damping`` clamps the total normal force at
zero and LAMMPS caps the tangential force by it, as the native loop does. Between two spheres
LAMMPS uses m_eff = m1 m2 / (m1 + m2): the same e for every pair. ``effects.normal_damping`` c
(N* += c a*') is ``damping velocity`` with eta_n = c M g / (a0 f) (one particle only).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..dynamics.adams_bashforth import damping_ratio
from ..dynamics.drives.travelling import phase_of, unit_phase
from ..errors import SceneError
from ..scene.device import normalized
from ..scene.schema import Scene, Wave

#: models with a LAMMPS equivalent (pair granular hertz/material + mindlin_rescale/force or
#: mindlin/force, damped or not) and the LAMMPS tangential model of each
LAMMPS_EQUIVALENT = {"hertz_mindlin_dem": "mindlin_rescale/force"}

#: Poisson's ratio of the equivalent wall material (it only enters E_w, see the module docstring)
WALL_NU = 0.3

#: realization of a normalized scene: radius (m), density (kg/m^3), gravity (m/s^2), a0 / R
NORMALIZED_RADIUS = 1e-3
NORMALIZED_DENSITY = 2500.0
NORMALIZED_GRAVITY = 9.81
NORMALIZED_A0_OVER_R = 1e-5

#: the smallest restitution with a LAMMPS equivalent: coeff_restitution's damping ratio stays
#: below 1 (the native clamped dashpot reaches zeta = 1 at e = exp(-2))
MIN_LAMMPS_RESTITUTION = math.exp(-2.0)


def lammps_restitution(e: float) -> float:
    """The e' of LAMMPS ``damping coeff_restitution`` that damps as the native restitution ``e``.

    e' = exp(-pi zeta / sqrt(1 - zeta^2)) with zeta = zeta(e) of the clamped linear dashpot
    (module docstring); e' < e (the unclamped dashpot rebounds lower at the same damping).
    """
    if e >= 1.0:
        return 1.0
    zeta = damping_ratio(e)
    if zeta >= 1.0:
        raise SceneError(f"material.restitution = {e:g} has no LAMMPS equivalent: give e above "
                         f"{MIN_LAMMPS_RESTITUTION:.4g} (LAMMPS coeff_restitution damps at most "
                         "critically)")
    return math.exp(-math.pi * zeta / math.sqrt(1.0 - zeta * zeta))


@dataclass(frozen=True)
class Realization:
    """The SI quantities of one particle's scene (see the module docstring)."""

    radius: float  # m
    mass: float  # kg
    weight: float  # M g, the static normal load, N
    a0: float  # m
    e_star: float  # Pa
    g_star: float  # Pa
    frequency: float  # Hz
    amplitude: float  # A_y, m
    ratio: float  # r
    sin_phase: float
    cos_phase: float
    ramp_periods: float
    horizontal: float  # 1 or 0 (effects.horizontal_wave)
    vertical: float  # 1 or 0
    mu: float
    load: float  # tangential force along +x, N
    rotation: bool
    m_star: float
    theta: float
    restitution: float | None = None  # the native e (None: undamped)
    normal_damping: float = 0.0  # eta_n of effects.normal_damping, N s/m (0: off)

    @property
    def density(self) -> float:
        """Density of the sphere (kg/m^3) that has this mass."""
        return self.mass / (4.0 / 3.0 * math.pi * self.radius**3)

    @property
    def wall_modulus(self) -> float:
        """E_w = 2 (1 - nu_w^2) E*: LAMMPS mixes the wall with itself."""
        return 2.0 * (1.0 - WALL_NU**2) * self.e_star

    @property
    def k_t(self) -> float:
        """Mindlin's k_t = 8 G* (pressure units; the spring is k_t times the contact radius)."""
        return 8.0 * self.g_star

    @property
    def speed(self) -> float:
        """a0 f: the unit of x*' in m/s."""
        return self.a0 * self.frequency


def adhesion_refusal(scene: Scene) -> str | None:
    """Why the moving-wall LAMMPS run cannot carry ``scene``'s adhesion (one line), or None.

    ``fix wall/gran/region`` on a moving region loses an adhesive contact at zero overlap, which
    drops the tensile branch: the particle would fly off where the native one is held. Only the
    wall-frame bridge :mod:`sawdrift.lammps.adhesion` (a still wall, the wall's inertial force on
    the particle) runs an adhesive particle.
    """
    law = scene.effects.adhesion
    if law == "none":
        return None
    return (f"effects.adhesion = {law!r}: this LAMMPS run moves its wall as a region, which loses "
            "an adhesive contact's tensile branch; one adhesive particle runs in LAMMPS only "
            "through the wall-frame bridge sawdrift.lammps.adhesion.compare (validation case "
            "lammps_adhesion, docs/adhesion.md), or set effects.adhesion = 'none'")


def refusal(scene: Scene, *, wall_frame: bool = False) -> str | None:
    """Why ``scene`` has no LAMMPS equivalent (one line), or None if it has one.

    ``wall_frame``: for the wall-frame bridge of :mod:`sawdrift.lammps.adhesion`, which carries
    an adhesive contact; every other LAMMPS run refuses adhesion (:func:`adhesion_refusal`).
    """
    if scene.model not in LAMMPS_EQUIVALENT:
        return (f"model = {scene.model!r} has no LAMMPS equivalent; the LAMMPS engine runs "
                + ", ".join(LAMMPS_EQUIVALENT) + " (pair granular hertz/material, "
                "mindlin_rescale/force or mindlin/force, damped by material.restitution or not)")
    if not isinstance(scene.drive, Wave):
        return f"drive.kind = {scene.drive.kind!r}: the LAMMPS engine runs a wave drive only"
    d = scene.drive
    if d.backward > 0.0 or d.wavelength is not None or d.position != 0.0 or d.backward_phase_rate:
        return "drive: the LAMMPS engine runs one travelling wave's local orbit (no backward " \
               "wave, position, wavelength or phase rate)"
    shape = scene.particle.profile.shape
    if shape != "sphere":
        return f"particle.profile.shape = {shape!r}: LAMMPS has spheres only (Hertz, p = 3/2)"
    eff = scene.effects
    if not eff.friction:
        return "effects.friction = false has no LAMMPS equivalent here; keep friction on"
    e = scene.material.restitution
    if e is not None and e < 1.0 and e <= MIN_LAMMPS_RESTITUTION:
        return (f"material.restitution = {e:g} has no LAMMPS equivalent: give e above "
                f"{MIN_LAMMPS_RESTITUTION:.4g} (LAMMPS coeff_restitution damps at most critically)")
    if eff.rolling_resistance > 0.0:
        return "effects.rolling_resistance has no LAMMPS equivalent here; set it to 0"
    if eff.air_drag > 0.0:
        # not in the input scripts: it ran drag-free and compared 0.4238 against 0.0301
        return "effects.air_drag has no LAMMPS equivalent here; set it to 0"
    if wall_frame and eff.rotation:
        return ("effects.rotation: the wall-frame bridge of an adhesive contact integrates the "
                "centre only (fix nve); set effects.rotation = false")
    if eff.rotation and scene.particle.gyration != 0.4:
        return (f"particle.gyration = {scene.particle.gyration:g}: LAMMPS spheres are solid "
                "(kappa = 0.4); use 0.4")
    if scene.device is not None and scene.device.particle.shape != "sphere":
        return f"device.particle.shape = {scene.device.particle.shape!r}: LAMMPS has spheres only"
    return None if wall_frame else adhesion_refusal(scene)


def check_equivalent(scene: Scene, *, wall_frame: bool = False) -> None:
    """Raise a one-line SceneError if ``scene`` has no LAMMPS equivalent (see :func:`refusal`)."""
    why = refusal(scene, wall_frame=wall_frame)
    if why is not None:
        raise SceneError(why)


def realize(scene: Scene, *, wall_frame: bool = False) -> Realization:
    """The SI realization of ``scene`` (module docstring): the device's values, or a chosen one.

    ``wall_frame`` admits an adhesive scene, for :mod:`sawdrift.lammps.adhesion` only.
    """
    check_equivalent(scene, wall_frame=wall_frame)
    m_star = scene.particle.m_star
    theta = scene.theta
    if scene.device is not None:
        norm = normalized(scene.device)
        radius = float(scene.device.particle.radius)
        mass, weight, a0 = norm["mass_kg"], norm["weight_n"], norm["a0_m"]
        frequency = norm["frequency_hz"]
    else:
        radius = NORMALIZED_RADIUS
        mass = NORMALIZED_DENSITY * 4.0 / 3.0 * math.pi * radius**3
        weight = mass * NORMALIZED_GRAVITY * (1.0 + scene.particle.preload)
        a0 = NORMALIZED_A0_OVER_R * radius
        frequency = math.sqrt(m_star * weight / (a0 * mass))
    e_star = math.sqrt(9.0 * weight**2 / (16.0 * radius * a0**3))
    s, c = unit_phase(phase_of(scene))
    eff = scene.effects
    return Realization(
        radius=radius, mass=mass, weight=weight, a0=a0, e_star=e_star,
        g_star=e_star / (4.0 * theta), frequency=frequency,
        amplitude=scene.drive.amplitude * a0, ratio=scene.horizontal_ratio, sin_phase=s,
        cos_phase=c, ramp_periods=scene.drive.ramp_periods,
        horizontal=1.0 if eff.horizontal_wave else 0.0, vertical=1.0 if eff.vertical_wave else 0.0,
        mu=scene.material.mu, load=scene.particle.load * weight, rotation=eff.rotation,
        m_star=m_star, theta=theta,
        restitution=scene.material.restitution if scene.material.restitution not in (None, 1.0)
        else None,
        normal_damping=eff.normal_damping * weight / (a0 * frequency),
    )
