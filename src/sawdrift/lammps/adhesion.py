"""An adhesive particle on the wave-driven plane through LAMMPS, in the wall's frame.

The LAMMPS counterpart of an adhesive ``hertz_mindlin_dem`` scene (:mod:`sawdrift.contact.adhesion`)
is ``pair granular`` ``jkr`` or ``dmt`` with ``tangential mindlin_rescale/force``, no damping::

    jkr E_w 0 nu_w c tangential mindlin_rescale/force 8 G* 0 mu      (dmt alike)

with LAMMPS' cohesion argument c = w / 2 (its JKR pull-off is 3 pi c R, its DMT pull-off
4 pi c R), w from the scene's pull-off force (1.5 pi R w for JKR, 2 pi R w for DMT). LAMMPS
breaks a JKR contact at the overlap of the largest pull, which is the native
``effects.adhesion_detach = "pulloff"``; :func:`native_twin` makes that scene.

A moving ``wall/gran/region`` loses an adhesive contact at zero overlap, so the wall here is a
still ``zplane`` and the particle carries the inertial force of the wall's motion instead (the
wall frame): with the wall's displacement u(t) = R(t) g(t) (ramp R, the orbit g of
:func:`sawdrift.lammps.single.wave_variables`), ``fix addforce`` applies
-m f^2 (R'' g + 2 R' g' + R g'') beside the weight and the load. Positions are relative to the
wall; over whole periods after the ramp the wall returns, so the drift is the same.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from ..contact.adhesion import Adhesion, adhesion_of
from ..dynamics.assembly import steps_per_period
from ..errors import SawdriftError, SceneError
from ..result.runner import run
from ..scene.schema import Scene
from .engine import open_lammps
from .realize import WALL_NU, Realization, realize

#: pull-off force over pi R w of each law (Johnson, Kendall, Roberts 1971; Derjaguin et al. 1975)
PULLOFF_OVER_PI_R_W = {"jkr": 1.5, "dmt": 2.0}


def native_twin(scene: Scene) -> Scene:
    """The native scene LAMMPS reproduces: a JKR contact broken at the pull-off overlap."""
    if scene.effects.adhesion == "jkr":
        return scene.with_updates(**{"effects.adhesion_detach": "pulloff"})
    return scene


def contact_string(scene: Scene, real: Realization) -> str:
    """The ``granular`` model string of the adhesive contact (module text)."""
    adhesion = adhesion_of(scene)
    if adhesion is None or scene.model != "hertz_mindlin_dem":
        raise SceneError("the adhesive LAMMPS run needs model hertz_mindlin_dem with "
                         "effects.adhesion = 'jkr' or 'dmt'")
    w = adhesion.pulloff * real.weight / (PULLOFF_OVER_PI_R_W[adhesion.law] * math.pi * real.radius)
    return (f"{adhesion.law} {real.wall_modulus!r} 0.0 {WALL_NU!r} {0.5 * w!r} tangential "
            f"mindlin_rescale/force {real.k_t!r} 0.0 {real.mu!r}")


def frame_forces(real: Realization) -> list[str]:
    """Equal-style variables: the inertial force of the wall's motion (module text), N."""
    tr = real.ramp_periods
    amp = real.amplitude
    two_pi = 2.0 * math.pi
    bx = amp * real.ratio * real.horizontal * -real.sin_phase  # g_x = bx sin + cx cos
    cx = amp * real.ratio * real.horizontal * real.cos_phase
    az = -amp * real.vertical  # g_z = az cos (the wall's height)
    k = math.pi / (2.0 * tr) if tr > 0.0 else 0.0
    scale = real.mass * real.frequency**2
    ramp = (lambda on, off: f"ternary(v_ts<{tr!r},{on},{off})") if tr > 0.0 else (
        lambda on, off: off)
    w = f"{two_pi!r}*v_ts"
    return [
        "variable ts equal step/{KPER}",
        f"variable r0 equal {ramp(f'sin({k!r}*v_ts)^2', '1.0')}",
        f"variable r1 equal {ramp(f'{k!r}*sin({2 * k!r}*v_ts)', '0.0')}",
        f"variable r2 equal {ramp(f'{2 * k * k!r}*cos({2 * k!r}*v_ts)', '0.0')}",
        f"variable gx equal {bx!r}*sin({w})+{cx!r}*cos({w})",
        f"variable gx1 equal {two_pi * bx!r}*cos({w})-{two_pi * cx!r}*sin({w})",
        f"variable gz equal {az!r}*cos({w})",
        f"variable gz1 equal {-two_pi * az!r}*sin({w})",
        f"variable ax equal v_r2*v_gx+2.0*v_r1*v_gx1-{two_pi**2!r}*v_r0*v_gx",
        f"variable az equal v_r2*v_gz+2.0*v_r1*v_gz1-{two_pi**2!r}*v_r0*v_gz",
        f"variable fx equal {real.load!r}-{scale!r}*v_ax",
        f"variable fz equal {-real.weight!r}-{scale!r}*v_az",
    ]


def input_script(scene: Scene, k_per: int, rest_overlap: float) -> tuple[str, Realization]:
    """The LAMMPS input (SI) of the adhesive particle in the wall frame, without the runs."""
    real = realize(scene, wall_frame=True)
    model = contact_string(scene, real)
    big = 1e3 * real.radius
    z0 = real.radius - rest_overlap * real.a0
    lines = [
        "units si", "atom_style sphere", "atom_modify map array", "dimension 3",
        "boundary p p f", "newton off", "comm_modify vel yes",
        f"region box block {-big!r} {big!r} {-big!r} {big!r} {-10 * real.radius!r} "
        f"{1e4 * real.radius!r}",
        "create_box 1 box", f"create_atoms 1 single 0.0 0.0 {z0!r}",
        f"set atom 1 diameter {2.0 * real.radius!r} density {real.density!r}",
        "velocity all set 0.0 0.0 0.0",
        "pair_style granular", f"pair_coeff * * {model}",
        *(line.replace("{KPER}", str(k_per)) for line in frame_forces(real)),
        f"fix wall all wall/gran granular {model} zplane 0.0 NULL",
        "fix push all addforce v_fx 0.0 v_fz",
        "fix move all nve",
        f"timestep {1.0 / (real.frequency * k_per)!r}",
        "variable x equal x[1]", "variable z equal z[1]", "thermo 0",
    ]
    return "\n".join(lines) + "\n", real


def run_wall_frame(scene: Scene, periods: int) -> dict[str, Any]:
    """Run ``scene`` (adhesive, hertz_mindlin_dem) in LAMMPS; per-period x*, and a* per step.

    Returns ``{"x": x* at the end of every period, "a": a* at every step, "k_per", "real"}``.
    """
    adhesion = adhesion_of(scene)
    if adhesion is None:
        raise SceneError("the scene has no adhesion")
    k_per = steps_per_period(scene)
    rest = Adhesion(adhesion.law, adhesion.pulloff, "pulloff").rest_overlap()
    script, real = input_script(scene, k_per, rest)
    lmp = open_lammps()
    with tempfile.TemporaryDirectory(prefix="sawdrift-lammps-") as tmp:
        path = Path(tmp) / "record.txt"
        try:
            lmp.commands_string(script)
            lmp.command(f"fix rec all ave/time 1 1 1 v_x v_z file {path} format ' %.17g'")
            lmp.command(f"run {periods * k_per}")
        except Exception as exc:  # noqa: BLE001 - LAMMPS reports its errors as Exception
            raise SawdriftError(f"LAMMPS failed: {str(exc).splitlines()[0]}") from None
        finally:
            lmp.close()
        table = np.loadtxt(path, comments="#", ndmin=2)
    _, first = np.unique(table[:, 0], return_index=True)
    table = table[first]
    steps = table[:, 0].astype(int)
    a = (real.radius - table[:, 2]) / real.a0
    ends = np.isin(steps, np.arange(0, periods + 1) * k_per)
    return {"x": table[ends, 1] / real.a0, "a": a, "steps": steps, "k_per": k_per, "real": real}


def compare(scene: Scene, periods: int = 60) -> dict[str, float]:
    """Drift per period (x* over the second half of the run) in LAMMPS and natively, and whether
    each is out of contact for the whole second half (removed)."""
    twin = native_twin(scene).with_updates(**{"numerics.periods": periods,
                                              "numerics.settle": False})
    lam = run_wall_frame(twin, periods)
    half = periods // 2
    x = lam["x"]
    drift_lammps = float((x[periods] - x[half]) / (periods - half))
    detach = twin.effects.adhesion == "jkr" and adhesion_of(twin).detach_overlap or 0.0
    tail = lam["a"][lam["steps"] >= half * lam["k_per"]]
    native = run(twin.with_updates(**{"numerics.measure_periods": periods - half}))
    return {"drift_lammps": drift_lammps, "drift_native": float(native.drift_velocity),
            "removed_lammps": bool(np.all(tail <= detach)),
            "removed_native": bool(native.out_of_contact_fraction == 1.0)}
