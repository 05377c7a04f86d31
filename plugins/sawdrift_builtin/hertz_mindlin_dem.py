"""The tangential law of discrete-element codes: an incremental Mindlin spring with a Coulomb cap.

This is the "Hertz-Mindlin (no-slip)" contact of DEM codes (LAMMPS ``pair granular ... tangential
mindlin/force`` and ``mindlin_rescale/force``; LIGGGHTS ``tangential history``; Thornton et al.
2013, Powder Technol. 233, 30-46, eq. 18). In the normalized variables of docs/physics.md:

    dT* = k_t(a*) db*,   k_t(a*) = N*'(a*) = p a*^(p-1)   (Mindlin 1949 initial stiffness),
    |T*| <= N*(a*) = a*^p,  a spring that would exceed the cap is reset onto it.

Normal damping. With a normal damping (``material.restitution``, ``effects.normal_damping``, or a
damping slot such as ``hertz_tsuji``'s) N* is the total normal force, N*(a*) plus the dashpot,
clamped at 0, and the *stored* spring is bounded by it, |T*| <= N*: LAMMPS bounds the history of
``mindlin*/force`` by mu |Fntot|, Fntot the normal plus the damping force after
``limit_damping`` (src/GRANULAR/granular_model.cpp, ``set_fncrit``). While the contact loads,
the dashpot raises the bound and a slipping contact carries more friction than N*(a*); while it
unloads fast, the bound drops and the spring is cut back to it. The slots hand the step that
total force (:func:`sawdrift.contact.slots.takes_normal`; the scene's damping is moved into the
contact for it, :mod:`sawdrift.contact.scene_damping`). Without damping it is N*(a*).

This is the rule of this law only. The memory-diagram laws (``mmd``, ``mdr``, ``jaeger``) keep
their history against the elastic local limits |v(z)| <= a* - z (Mindlin and Deresiewicz's
limits of the elastic pressure at each radius) and have only their transmitted force capped by
the total one. The restitution damping is one lumped force, chosen for its rebound ratio; it
says nothing about where in the contact it acts, and bounding the strips by it needs such a
distribution: scaling every strip's limit by N*_total / N*(a*) gives limits steeper than the
unit slope the diagram's clip relies on, shifting them uniformly gives the strips at the edge a
negative limit while the contact unloads, and a dashpot on every strip damps in proportion to
N*'(a*), not to the sqrt(m* N*') that makes the rebound ratio speed-independent. The DEM spring
has one stored force and one bound, so none of these choices arises, and it is the rule the
LAMMPS comparison checks (docs/lammps.md).

With ``rescale = True`` the stored force is also scaled with the stiffness when the contact
shrinks (LAMMPS ``mindlin_rescale``, which multiplies the stored tangential history by a/a_old,
the contact-radius ratio, i.e. by k_t(new)/k_t(old) for a Hertz contact; here generalized to
k_t = N*'(a*) for every profile): while a* decreases, dT* = k_t db* + T* d ln k_t. Loading never
rescales.

Straight-path exactness. The step (:func:`sawdrift_builtin.dem_kernel.dem_step`, the tangential
slot of :mod:`sawdrift.contact.slots`) integrates the law exactly along the straight path from the
committed (a*, b*), which makes the result independent of how a straight move is split:

* without rescaling, the elastic increment is integral k_t db* = (db*/da*) [N*(a1) - N*(a0)]
  (= k_t db* at fixed a*); a path that reaches the cap stays on it (the elastic rate points out
  of the admissible set on both the loading and the unloading side), so the end value is the
  elastic trial clipped to [-N*, N*];
* with rescaling on an unloading path, T*/k_t is a displacement that moves with b* and the cap
  is |T*/k_t| <= a*/p, both linear along the path, so T1 = k1 clip(T0/k0 + db*, +-a1/p). This is
  exactly the LAMMPS update (rescale, add k_t(new) db*, cap), which is therefore path-exact.

LAMMPS without rescaling adds k_t(a_new) db* per step instead of the path integral; the two
differ by O(da* db*) per step and agree as the step shrinks.

What it does not have, compared with Mindlin & Deresiewicz (1953) (the ``mmd`` / ``jaeger``
laws): the tangential stiffness is Mindlin's *initial* stiffness for all |T*| < N*, so there is
no partial slip and no dissipation below the Coulomb limit. Under a displacement cycle of
amplitude B at fixed a*, its hysteresis loop is the elastic-perfectly-plastic parallelogram

    W*_DEM = 4 N* (B - N*/k_t) if B > N*/k_t = a*/p, else 0,

whereas the Mindlin-Masing loop dissipates at every amplitude. Oblique loading from zero along
b* = lambda a* (|lambda| <= 1) gives T* = lambda N*, the Mindlin-Deresiewicz value.
"""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np
from pydantic import BaseModel, ConfigDict, Field

from sawdrift.contact import Capabilities
from sawdrift.contact.slots import LazyFunction, TangentialLaw, takes_normal
from sawdrift.hookspecs import hookimpl


class HertzMindlinDEMParams(BaseModel):
    """Parameters of the DEM incremental Hertz-Mindlin tangential law."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    rescale: bool = Field(
        True,
        description=(
            "Scale the stored tangential force by k_t(new)/k_t(old) = N*'(a_new)/N*'(a_old) "
            "when the contact shrinks (LAMMPS mindlin_rescale/force): passive. false gives "
            "LAMMPS mindlin/force, which can create energy on closed (a*, b*) cycles."
        ),
    )


@takes_normal
def reference_step(ts, is_, law, tp, a0: float, b0: float, a: float, b: float,
                   n_total: float) -> float:
    """Readable pure-Python tangential step (power laws; the python engine's reference).

    ``law[0]`` is the exponent p of N* = a*^p, ``tp[0]`` the rescale flag, ``n_total`` the total
    normal force (a*^p, plus the normal damping if any), which bounds the stored force.
    """
    p = float(law[0])

    def stiffness(x: float) -> float:  # Mindlin's initial stiffness k_t = N*'(a*)
        return p * x ** (p - 1.0)

    if tp[0] != 0.0 and a < a0:
        t = ts[0] * stiffness(a) / stiffness(a0) + stiffness(a) * (b - b0)
    elif a == a0:
        t = ts[0] + stiffness(a) * (b - b0)
    elif a0 <= 0.0:
        # a new contact: integral of N*'(a) db along the line from a* = 0 is (db/da) N*(a)
        t = (b - b0) / a * a**p
    else:
        # integral of N*'(a) db along the line: (db/da) [N*(a) - N*(a0)], free of cancellation
        h = a - a0
        t = ts[0] + (b - b0) * a0**p * math.expm1(p * math.log1p(h / a0)) / h
    bound = max(n_total, 0.0)  # the Coulomb bound of the stored force (module docstring)
    ts[0] = min(max(t, -bound), bound)
    return ts[0]


def reference_reset(ts, is_, law, tp) -> None:
    """Empty history: no stored force."""
    ts[:] = 0.0


class HertzMindlinDEM(TangentialLaw):
    """Incremental Hertz-Mindlin spring with a Coulomb cap, as in DEM codes (module docstring).

    Mindlin (1949) initial stiffness, no partial slip; compare with Mindlin & Deresiewicz (1953).
    """

    name: ClassVar[str] = "hertz_mindlin_dem"
    summary: ClassVar[str] = (
        "DEM tangential spring (LAMMPS mindlin/force, LIGGGHTS tangential history): stiffness "
        "N*'(a*), Coulomb cap |T*| <= N*, mindlin_rescale by default (passive)"
    )
    Params: ClassVar[type[BaseModel]] = HertzMindlinDEMParams
    capabilities: ClassVar[Capabilities] = Capabilities(
        rigid=False, compiled=True, history=True, uses_velocity=False, straight_path_exact=True,
        profiles=("sphere", "cone", "flat", "power", "table"),
    )
    step: ClassVar[LazyFunction] = LazyFunction("sawdrift_builtin.dem_kernel", "dem_step")
    #: with effects.adhesion (sawdrift.contact.adhesion): LAMMPS mindlin_rescale/force on jkr/dmt
    adhesive_step: ClassVar[LazyFunction] = LazyFunction("sawdrift_builtin.adhesive_kernels",
                                                         "dem_adhesive_step")
    adhesive_summary: ClassVar[str] = (
        "dmt, jkr: stiffness 1.5 c* (8 G* c, c the adhesive contact radius), sliding at "
        "|N* + 2 F*_pull|, stored force rescaled by c/c_old while the contact shrinks (LAMMPS "
        "jkr/dmt with tangential mindlin_rescale/force)")
    adhesive_deviations: ClassVar[tuple[tuple[str, str], ...]] = (
        ("split_invariance", "with adhesion the stiffness is taken at the step's end, as LAMMPS "
         "does: a straight move split in steps differs by O(dc* db*) per step"),)

    def declared_deviations(self) -> tuple[tuple[str, str], ...]:
        """Without rescaling: not passive. With it, on a tabulated law: split-dependent at the cap."""
        out: tuple[tuple[str, str], ...] = ()
        if not self.params.rescale:
            out += (("passivity", "rescale = false (LAMMPS mindlin/force) keeps the stored force "
                     "while a* falls, so closed (a*, b*) cycles can create energy; rescale = true "
                     "(the default) is passive"),)
        elif self.profile.shape == "table":
            out += (("split_invariance", "a step that leaves the Coulomb cap while unloading is "
                     "resolved at its end, exact only where N*/N*' is linear in a* (power laws): "
                     "up to 3e-5 (1 + N*) on a tabulated law"),)
        return out

    def tangential_sizes(self) -> tuple[int, int]:
        """Float state: the stored T*; no integer state."""
        return 1, 0

    def tangential_params(self) -> np.ndarray:
        """[rescale (0 or 1)]."""
        return np.array([1.0 if self.params.rescale else 0.0], dtype=np.float64)

    def reference_step(self):
        """The readable step for power laws; a table runs the kernel's own Python code."""
        if self.profile.law()[0] > 0.0:
            return reference_step, reference_reset
        return None


@hookimpl
def sawdrift_contact_models() -> list[type[TangentialLaw]]:
    """Register the ``hertz_mindlin_dem`` model."""
    return [HertzMindlinDEM]
