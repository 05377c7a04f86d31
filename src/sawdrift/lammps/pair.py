"""Two spheres pressed together in LAMMPS: the particle-particle law against Hertz and Mindlin.

The spheres of a mixture (:mod:`.many`) touch each other through ``pair granular`` with the same
model string as the wall (:func:`.single.granular_model`: ``hertz/material E_w 0 nu_w tangential
mindlin_rescale/force k_t 0 mu``). For two spheres of one material LAMMPS mixes E_w with itself,
E_w / (2 (1 - nu_w^2)) = E*, and uses R_eff = R1 R2 / (R1 + R2), so two spheres pressed together
by a normal force F overlap by Hertz's

    delta = (9 F^2 / (16 R_eff E*^2))^(1/3),

and a tangential force T < mu F then displaces one against the other by Mindlin's
xi = T / (8 G* a), a = sqrt(R_eff delta) (``k_t`` = 8 G* is given directly; no slip).

:func:`press_pair` measures both: sphere 1 is held, sphere 2 (no rotation, ``fix nve``) starts
touching on top of it and is pushed down by F (``fix addforce``) with a viscous drag near the
critical damping of the contact (``fix viscous``: the contact itself is undamped), until it rests;
then T is added along x and it rests again. The drag does no work at rest, so the end states are
the static ones.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..scene.schema import Scene
from .engine import open_lammps
from .realize import realize
from .single import granular_model


@dataclass(frozen=True)
class PairCheck:
    """What :func:`press_pair` measured, with the closed forms (SI units)."""

    radii: tuple[float, float]
    force: float  # F, N
    shear: float  # T, N
    delta: float  # the overlap LAMMPS gives, m
    delta_hertz: float  # (9 F^2 / (16 R_eff E*^2))^(1/3), m
    xi: float  # the tangential displacement LAMMPS gives, m
    xi_mindlin: float  # T / (8 G* sqrt(R_eff delta_hertz)), m
    steps: int

    @property
    def delta_error(self) -> float:
        """(delta - delta_hertz) / delta_hertz."""
        return (self.delta - self.delta_hertz) / self.delta_hertz

    @property
    def xi_error(self) -> float:
        """(xi - xi_mindlin) / xi_mindlin."""
        return (self.xi - self.xi_mindlin) / self.xi_mindlin


def press_pair(scene: Scene, radii: tuple[float, float], force: float, shear: float = 0.0,
               steps: int = 5000) -> PairCheck:
    """Press two spheres of ``scene``'s material together in LAMMPS (module docstring).

    Parameters
    ----------
    scene
        A scene with a LAMMPS equivalent: its E*, G* and mu (``realize``) set the contact.
    radii
        (R1, R2) in m: sphere 1 is held, sphere 2 is pressed onto it.
    force
        The normal force F (N) pressing sphere 2 onto sphere 1.
    shear
        A tangential force T (N) added along x after the normal rest (0: none); keep T < mu F.
    steps
        Steps of each stage (the time step is 1/40 of the contact's period at F).
    """
    real = realize(scene)
    r1, r2 = radii
    r_eff = r1 * r2 / (r1 + r2)
    e_star, g_star = real.e_star, real.g_star
    delta_h = (9.0 * force**2 / (16.0 * r_eff * e_star**2)) ** (1.0 / 3.0)
    a_h = math.sqrt(r_eff * delta_h)
    xi_m = shear / (8.0 * g_star * a_h)
    mass = real.density * 4.0 / 3.0 * math.pi * r2**3
    k_n = 2.0 * e_star * a_h  # dF/d delta at F
    k_t = 8.0 * g_star * a_h
    k = max(k_n, k_t)
    period = 2.0 * math.pi * math.sqrt(mass / k)
    dt = period / 40.0
    gamma = 2.0 * math.sqrt(min(k_n, k_t) * mass)  # about critical for the softer direction
    big = 4.0 * max(r1, r2)
    model = granular_model(real, bool(scene.model_params.get("rescale", True)))
    z2 = r1 + r2  # touching, no overlap
    lmp = open_lammps()
    try:
        lmp.commands_string("\n".join([
            "units si", "atom_style sphere", "atom_modify map array", "dimension 3",
            "boundary f f f", "newton off", "comm_modify vel yes",
            f"region box block {-big!r} {big!r} {-big!r} {big!r} {-big!r} {big!r}",
            "create_box 1 box",
            "create_atoms 1 single 0.0 0.0 0.0", f"create_atoms 1 single 0.0 0.0 {z2!r}",
            f"set atom 1 diameter {2.0 * r1!r} density {real.density!r}",
            f"set atom 2 diameter {2.0 * r2!r} density {real.density!r}",
            "group held id 1", "group free id 2",
            "velocity all set 0.0 0.0 0.0",
            "pair_style granular", f"pair_coeff * * {model}",
            "fix move free nve", f"fix drag free viscous {gamma!r}",
            f"fix push free addforce 0.0 0.0 {-force!r}",
            f"timestep {dt!r}", "thermo 0",
            f"run {steps}",
        ]))
        x = lmp.numpy.extract_atom("x")
        delta = r1 + r2 - float(x[1, 2] - x[0, 2])
        x_before = float(x[1, 0])
        xi = 0.0
        if shear:
            lmp.commands_string("\n".join([
                "unfix push", f"fix push free addforce {shear!r} 0.0 {-force!r}", f"run {steps}"]))
            x = lmp.numpy.extract_atom("x")
            xi = float(x[1, 0]) - x_before
    finally:
        lmp.close()
    return PairCheck(radii=(r1, r2), force=force, shear=shear, delta=delta, delta_hertz=delta_h,
                     xi=xi, xi_mindlin=xi_m, steps=steps)
