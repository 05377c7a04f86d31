"""Hertz contact with viscous normal damping in the style of Tsuji, Tanaka & Ishida (1992).

Tsuji, Tanaka & Ishida (1992), Powder Technol. 71, 239-250, damp the Hertz normal force with a
dashpot whose coefficient grows with the overlap as delta^(1/4), eta = alpha sqrt(m k_n) delta^(1/4),
so that the coefficient of restitution does not depend on the impact velocity. Normalized as in
sawdrift (N* = N / (M g), a* = a / a0, derivative with respect to t* = f t):

    N* = max(a*^p + c a*^((p - 1)/2) a*', 0)       (a* > 0; N* = 0 otherwise)

with c = ``damping``. For the sphere (p = 3/2) the exponent is Tsuji's 1/4; (p - 1)/2 is the
exponent that keeps the restitution velocity independent for every power law (it scales like
sqrt(m* dN*/da*)), and the restitution then depends on c / sqrt(m*) only. The clamp expresses that
a contact cannot pull: late in the rebound the dashpot would otherwise make N* negative.

The tangential law is the ``hertz_mindlin_dem`` kernel, imported, not copied: an incremental
Mindlin spring of stiffness N*'(a*) capped at the *elastic* normal force a*^p (the dashpot does not
move the Coulomb limit; LAMMPS by default caps with the total normal force instead).
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np
from pydantic import BaseModel, Field

from sawdrift import Capabilities, KernelPair, hookimpl
from sawdrift_builtin.hertz_mindlin_dem import (
    HertzMindlinDEM,
    HertzMindlinDEMParams,
    HertzMindlinDEMReference,
)


class HertzTsujiParams(HertzMindlinDEMParams):
    """The DEM tangential parameters plus the normal damping coefficient."""

    damping: float = Field(
        0.1,
        ge=0.0,
        description="Normalized Tsuji dashpot c in N* = a*^p + c a*^((p-1)/2) a*' (0: elastic).",
    )


class HertzTsujiReference(HertzMindlinDEMReference):
    """Pure-Python reference: the DEM reference plus the clamped Tsuji dashpot."""

    def __init__(self, p: float, rescale: bool, damping: float) -> None:
        super().__init__(p, rescale)
        self.damping = damping

    def force(
        self, a: float, b: float, adot: float = 0.0, bdot: float = 0.0
    ) -> tuple[float, float]:
        """Advance along a straight path to (a*, b*), commit, and return (N*, T*)."""
        n_el, t = super().force(a, b, adot, bdot)
        if a <= 0.0:
            return 0.0, 0.0
        return max(n_el + self.damping * a ** (0.5 * (self.p - 1.0)) * adot, 0.0), t


class HertzTsuji(HertzMindlinDEM):
    """Hertz normal law with Tsuji et al. (1992, Powder Technol. 71) damping; DEM tangential law."""

    name: ClassVar[str] = "hertz_tsuji"
    summary: ClassVar[str] = (
        "Hertz + Tsuji (1992) viscous normal damping, clamped at N* >= 0; DEM Mindlin spring "
        "(example third-party plugin)"
    )
    Params: ClassVar[type[BaseModel]] = HertzTsujiParams
    capabilities: ClassVar[Capabilities] = Capabilities(uses_velocity=True)
    kernel: ClassVar[KernelPair] = KernelPair.lazy("sawdrift_tsuji.kernel", "dem_reset", "tsuji_force")

    def packed_params(self) -> np.ndarray:
        """[p, rescale, damping]: the DEM kernel reads the first two."""
        return np.append(super().packed_params(), float(self.params.damping))

    def normal_law(self):
        """The clamped Tsuji normal law alone (kept when friction is off)."""
        from .kernel import tsuji_normal

        return tsuji_normal, self.packed_params()

    def reference(self) -> HertzTsujiReference:
        """A fresh pure-Python reference contact (empty history)."""
        params = self.params
        return HertzTsujiReference(self.profile.p, bool(params.rescale), float(params.damping))


@hookimpl
def sawdrift_contact_models() -> list[type[HertzMindlinDEM]]:
    """Register ``hertz_tsuji`` with sawdrift (entry point group ``sawdrift.models``)."""
    return [HertzTsuji]
