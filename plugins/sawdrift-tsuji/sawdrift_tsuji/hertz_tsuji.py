"""Viscous normal damping in the style of Tsuji, Tanaka & Ishida (1992), as a normal-damping slot.

Tsuji, Tanaka & Ishida (1992), Powder Technol. 71, 239-250, damp the Hertz normal force with a
dashpot whose coefficient grows with the overlap as delta^(1/4), eta = alpha sqrt(m k_n) delta^(1/4),
so that the coefficient of restitution does not depend on the impact velocity. Normalized as in
sawdrift (N* = N / (M g), a* = a / a0, derivative with respect to t* = f t), with the normal
stiffness k_n = N*'(a*) of whatever profile the scene uses:

    N* = max(N*(a*) + c sqrt(N*'(a*) / N*'(1)) a*', 0)       (a* > 0; N* = 0 otherwise)

with c = ``damping``. For a power law N* = a*^p the factor is a*^((p - 1)/2): Tsuji's 1/4 for the
sphere, and the restitution then depends on c / sqrt(m*) only. The clamp expresses that a contact
cannot pull: late in the rebound the dashpot would otherwise make N* negative.

This package adds only the damping slot: one parameter schema and one compiled function
(:func:`sawdrift_tsuji.kernel.tsuji_damp`). The model ``hertz_tsuji`` is the built-in
``hertz_mindlin_dem`` tangential law with this slot filled. Its stored tangential spring is
bounded by the *total* normal force, |T*| <= N* with the dashpot included (as LAMMPS bounds its
tangential history), so a fast unloading that lowers N* also lowers the largest friction force,
and a loading that raises it lets a slipping contact carry more than the elastic N*(a*).
"""

from __future__ import annotations

from typing import ClassVar

from pydantic import BaseModel, ConfigDict, Field

from sawdrift import hookimpl
from sawdrift.contact.slots import LazyFunction, NormalDamping, TangentialLaw
from sawdrift_builtin.hertz_mindlin_dem import HertzMindlinDEM


class TsujiParams(BaseModel):
    """The normal damping coefficient."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    damping: float = Field(
        0.1,
        ge=0.0,
        description="Normalized Tsuji dashpot c in N* = a*^p + c a*^((p-1)/2) a*' (0: elastic).",
    )


class TsujiDamping(NormalDamping):
    """Tsuji et al. (1992, Powder Technol. 71) dashpot, clamped at N* >= 0."""

    name: ClassVar[str] = "tsuji"
    Params: ClassVar[type[BaseModel]] = TsujiParams
    damp: ClassVar[LazyFunction] = LazyFunction("sawdrift_tsuji.kernel", "tsuji_damp")


HertzTsuji = HertzMindlinDEM.with_damping(
    TsujiDamping,
    name="hertz_tsuji",
    summary="Hertz + Tsuji (1992) viscous normal damping, clamped at N* >= 0; DEM Mindlin spring "
    "(example third-party plugin)",
)
HertzTsujiParams = HertzTsuji.Params


@hookimpl
def sawdrift_contact_models() -> list[type[TangentialLaw]]:
    """Register ``hertz_tsuji`` with sawdrift (entry point group ``sawdrift.models``)."""
    return [HertzTsuji]
