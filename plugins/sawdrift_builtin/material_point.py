"""The rigid material point of Verma and DasGupta (Phys. Rev. E 88, 052915, 2013).

Paper section 4: the particle cannot be strained and strains nothing, so a* = 0 in contact and
the friction is Coulomb's law for concentrated forces. The runner integrates it with the
unilateral-contact scheme of :mod:`sawdrift.dynamics.rigid`.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field

from sawdrift.contact import Capabilities, ContactModel
from sawdrift.hookspecs import hookimpl


class MaterialPointParams(BaseModel):
    """Parameters of the material point."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    restitution: Annotated[float, Field(ge=0.0, le=1.0)] = Field(
        0.0, description="Newton restitution coefficient at re-contact, in [0, 1]"
    )


class MaterialPoint(ContactModel):
    """Rigid point with Coulomb friction and unilateral contact (paper section 4)."""

    name = "material_point"
    summary = "Rigid material point, Coulomb friction, unilateral contact (Verma & DasGupta 2013)"
    Params = MaterialPointParams
    capabilities = Capabilities(rigid=True, profiles=("sphere", "cone", "flat", "power"),
                                compiled=True, history=False)


@hookimpl
def sawdrift_contact_models() -> list[type[ContactModel]]:
    """Register the material point."""
    return [MaterialPoint]
