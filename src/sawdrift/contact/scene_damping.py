"""The scene's normal damping in the normal-damping slot, for a law that bounds its history by N*.

A compliant run damps the normal motion in one of three ways (docs/physics.md, "Normal damping
and the Coulomb bound"): ``effects.normal_damping`` (N* += c a*'), ``material.restitution``
(N* += C a*^((p-1)/2) a*'), or a model's own normal-damping slot. The first two are the
scene's and the integration loop adds them after the contact force
(:func:`~sawdrift.contact.slot_kernels.damped_contact`): the tangential law has committed its
history by then, against the elastic N*(a*).

A law whose tangential step takes the total normal force
(:func:`~sawdrift.contact.slots.takes_normal`: the DEM spring of ``hertz_mindlin_dem``, which
bounds its stored force by it as LAMMPS does) must be handed the damped N* before it commits.
For such a law the runner moves the scene's damping into the contact: :func:`damped_law` gives
the same law with :class:`SceneDamping` in its normal-damping slot, whose force is the loop's
to the last bit (:func:`~sawdrift.contact.slot_kernels.damped_normal`), and the loop then adds
none. Every other law keeps the loop's damping (and its history as committed).
"""

from __future__ import annotations

from typing import ClassVar

from pydantic import BaseModel, ConfigDict

from .base import ContactModel, LazyFunction
from .slots import NormalDamping, TangentialLaw, _takes_normal


class SceneDampingParams(BaseModel):
    """The loop's normal damping as slot parameters (set by the runner, not by a user)."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    scene_viscous: float = 0.0  # c of effects.normal_damping (0: off)
    scene_restitution: float = 0.0  # C of material.restitution's damping (0: off)
    scene_exponent: float = 0.25  # q = (p - 1)/2 of C a*^q a*'


class SceneDamping(NormalDamping):
    """``effects.normal_damping`` or ``material.restitution`` as a normal-damping slot."""

    name: ClassVar[str] = "scene"
    Params: ClassVar[type[BaseModel]] = SceneDampingParams
    damp: ClassVar[LazyFunction] = LazyFunction("sawdrift.contact.slot_kernels", "scene_damp")


#: law class -> the same law with SceneDamping in its slot (one class per law: one composition)
_DAMPED: dict[type, type[TangentialLaw]] = {}


def damped_law(model: ContactModel, viscous: float, restitution: float,
               exponent: float, always: bool = False) -> TangentialLaw | None:
    """``model`` with the scene's normal damping in its slot, or None if the loop keeps it.

    Parameters
    ----------
    model
        The scene's contact model.
    viscous, restitution, exponent
        c of ``effects.normal_damping``, C and q = (p - 1)/2 of ``material.restitution``'s
        damping (both c and C zero: no damping).
    always
        Also for a law whose step does not take N*: the same (N*, T*) as the loop's damping and
        Coulomb cap after the contact force, in one call (the fast parts of a heavy particle's
        orbit drive the contact law alone, :mod:`sawdrift.dynamics.separated`).

    Returns
    -------
    TangentialLaw or None
        The same law, parameters and profile with :class:`SceneDamping` in its normal-damping
        slot, when its step takes N* (:func:`~sawdrift.contact.slots.takes_normal`), it has no
        damping slot of its own and a damping is on; else None.
    """
    cls = type(model)
    if (not isinstance(model, TangentialLaw) or cls.damping is not None
            or not (viscous > 0.0 or restitution > 0.0)
            or not (always or _takes_normal(cls._functions()[0]))):
        return None
    law = _DAMPED.get(cls)
    if law is None:
        law = _DAMPED[cls] = cls.with_damping(
            SceneDamping, name=cls.name,
            summary=f"{cls.summary}; the scene's normal damping in its normal-damping slot")
    params = law.Params(**model.params.model_dump(), scene_viscous=viscous,
                        scene_restitution=restitution, scene_exponent=exponent)
    return law(params, model.profile)
