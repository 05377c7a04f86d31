"""Adhesive contact as a part: the scene's adhesion, and a tangential law made adhesive.

A scene with ``effects.adhesion = "dmt"`` or ``"jkr"`` and ``material.adhesion`` = F*_pull (the
law's pull-off force over M g) replaces the elastic normal slot of a compliant contact by the
adhesive law of :mod:`sawdrift.contact.adhesion_law` and its tangential law by the law's adhesive
step (:mod:`sawdrift.contact.adhesion_kernels` for the protocol). A law is adhesive-capable when
its class names that step::

    adhesive_step: ClassVar[LazyFunction]     # step(ts, is_, law, tp, a0, b0, a, b, c0, c1, cap)
    adhesive_reset: ClassVar[LazyFunction]    # optional; default: zero the state
    adhesive_summary: ClassVar[str]           # what the step assumes (``sawdrift models``)
    def adhesive_sizes(self) -> (nf, ni)      # optional; default: tangential_sizes()

:func:`adhesive_model` derives, once per class, the adhesive variant of such a law: the same
parameters, its kernel composed from the adhesive normal law and that step, its python engine the
same composition run as Python, its friction-off normal slot the adhesive law alone (with its
hysteresis). Without adhesion none of this is built: an elastic scene runs what it ran before.

What the adhesive laws share (LAMMPS ``pair granular`` ``dmt``/``jkr`` with ``tangential
mindlin*``): the tangential stiffness is Mindlin's 8 G* c with c the adhesive contact radius
(normalized dT*/db* = 1.5 c*), and full sliding occurs at |T| = mu |F_n + 2 F_pull| (Thornton
1991, J. Phys. D 24, 1942: the adhesive contact slides as a Hertz contact under the load
F_n + 2 F_pull), with F_n the net (attractive or repulsive) normal force.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from . import adhesion_law
from .base import ContactModel, KernelPair, LazyFunction
from .history import KernelReference

__all__ = ["Adhesion", "adhesion_of", "adhesive_model", "rest_compression", "supports_adhesion"]


@dataclass(frozen=True)
class Adhesion:
    """An adhesive normal law: ``law`` (``"dmt"``/``"jkr"``), ``pulloff`` = F*_pull (F / (M g)),
    ``detach`` (JKR: ``"instability"`` or ``"pulloff"``, where a receding contact breaks)."""

    law: str
    pulloff: float
    detach: str = "instability"

    def descriptor(self) -> np.ndarray:
        """``ad`` of :mod:`.adhesion_law`."""
        return adhesion_law.descriptor(self.law, self.pulloff, self.detach)

    @property
    def detach_overlap(self) -> float:
        """a* at or below which a contact breaks (0 for DMT, negative for JKR)."""
        return float(self.descriptor()[2])

    def rest_overlap(self, load: float = 1.0) -> float:
        """a* at which the contact carries N* = ``load`` (1: at rest under M g)."""
        return adhesion_law.rest_overlap(self.descriptor(), load)


def adhesion_of(scene: Any) -> Adhesion | None:
    """The scene's :class:`Adhesion`, or None when ``effects.adhesion = "none"``."""
    eff = scene.effects
    if eff.adhesion == "none":
        return None
    return Adhesion(eff.adhesion, float(scene.material.adhesion), eff.adhesion_detach)


def supports_adhesion(cls: type[ContactModel]) -> bool:
    """Whether a model class has an adhesive tangential step."""
    return getattr(cls, "adhesive_step", None) is not None and not cls.capabilities.rigid


def _load(func: Any) -> Any:
    return func.load() if isinstance(func, LazyFunction) else func


class _AdhesiveKernel:
    """``kernel`` of an adhesive variant: the composition of :mod:`.adhesion_kernels`."""

    def __get__(self, obj: Any, owner: type) -> KernelPair:
        pair = owner.__dict__.get("_pair")
        if pair is None:
            from .adhesion_kernels import compiled

            ns = compiled(*owner._adhesive_functions())
            pair = KernelPair(ns["adhesive_reset"], ns["adhesive_force"])
            owner._pair = pair
        return pair


class AdhesiveReference(KernelReference):
    """The python engine of an adhesive variant: the composition run as plain Python."""

    def __init__(self, model: ContactModel) -> None:
        from .adhesion_kernels import python

        ns = python(*type(model)._adhesive_functions())
        super().__init__(model, ns["adhesive_reset"], ns["adhesive_force"])


_VARIANTS: dict[type, type] = {}


def adhesive_model(cls: type[ContactModel]) -> type[ContactModel]:
    """The adhesive variant of the model class ``cls`` (module text), built once per class.

    Instances take ``(params, profile, adhesion)``; ``adhesion`` defaults to a JKR law whose
    pull-off is the weight.
    """
    if not supports_adhesion(cls):
        raise ValueError(f"model {getattr(cls, 'name', cls)!r} has no adhesive tangential law")
    found = _VARIANTS.get(cls)
    if found is not None:
        return found
    from .adhesion_kernels import ADH_HEADER, LAW

    def __init__(self, params=None, profile=None, adhesion: Adhesion | None = None) -> None:
        cls.__init__(self, params, profile)
        self.adhesion = adhesion if adhesion is not None else Adhesion("jkr", 1.0)

    @classmethod
    def _adhesive_functions(owner) -> tuple[Any, Any, Any]:
        step = _load(owner.adhesive_step)
        reset = getattr(owner, "adhesive_reset", None)
        if reset is None:
            from .slot_kernels import zero_reset

            reset = zero_reset
        # ``adhesive_law``: another normal law (N*, c*) = law(a*, ad) in place of
        # adhesion_law.adhesive_normal (the conformance tests' wrong laws)
        return step, _load(reset), getattr(owner, "adhesive_law", None)

    def state_sizes(self) -> tuple[int, int]:
        sizes = getattr(self, "adhesive_sizes", None)
        nf, ni = sizes() if sizes is not None else self.tangential_sizes()
        return ADH_HEADER + int(nf), max(int(ni), 1)

    def live_sizes(self, fs: np.ndarray, is_: np.ndarray) -> tuple[int, int]:
        nf, ni = cls.live_sizes(self, fs, is_)
        extra = ADH_HEADER - 3 + getattr(self, "adhesive_extra", 0)
        return min(fs.size, nf + extra), ni

    def packed_params(self) -> np.ndarray:
        law = np.asarray(self.profile.law(), dtype=np.float64)
        tp = np.asarray(self.tangential_params(), dtype=np.float64)
        ad = self.adhesion.descriptor()
        it = LAW + law.size
        return np.concatenate([[float(it), float(it + tp.size)], law, tp, ad])

    def normal_law(self):
        from .adhesion_kernels import normal_only

        return normal_only, self.adhesion.descriptor()

    def reference(self) -> AdhesiveReference:
        return AdhesiveReference(self)

    def declared_deviations(self) -> tuple[tuple[str, str], ...]:
        own = dict(cls.declared_deviations(self))
        own.update(dict(getattr(self, "adhesive_deviations", ())))
        return tuple(own.items())

    attrs: dict[str, Any] = {
        "__init__": __init__, "_adhesive_functions": _adhesive_functions,
        "state_sizes": state_sizes, "live_sizes": live_sizes, "packed_params": packed_params,
        "normal_law": normal_law, "reference": reference,
        "declared_deviations": declared_deviations, "kernel": _AdhesiveKernel(),
        "adhesive": True, "__module__": cls.__module__,
        "__doc__": f"{cls.__name__} with an adhesive normal law (sawdrift.contact.adhesion).",
    }
    variant = type(f"Adhesive{cls.__name__}", (cls,), attrs)
    _VARIANTS[cls] = variant
    return variant


def rest_compression(model: ContactModel) -> float:
    """a* of the contact at rest under M g: 1 (the scale a0), or the adhesive law's."""
    adhesion = getattr(model, "adhesion", None)
    return adhesion.rest_overlap() if isinstance(adhesion, Adhesion) else 1.0


def pulloff(model: ContactModel) -> float:
    """F*_pull of an adhesive model (0 for an elastic one): the sliding limit is N* + 2 F*_pull."""
    adhesion = getattr(model, "adhesion", None)
    return adhesion.pulloff if isinstance(adhesion, Adhesion) else 0.0


def adhesive_stiffness(scene: Any, amplitude: float) -> float:
    """A bound of the adhesive contact's stiffness over the run: 1.5 c* at a* = a*_rest + 2 A*.

    1.5 c* is the tangential stiffness (8 G* c) and bounds the normal one away from the JKR
    instability (0.9 c* at zero load); ``amplitude`` is the drive's vertical amplitude A*.
    """
    adhesion = adhesion_of(scene)
    if adhesion is None:
        raise ValueError("the scene has no adhesion")
    ad = adhesion.descriptor()
    a_ref = adhesion_law.rest_overlap(ad) + 2.0 * amplitude
    return 1.5 * adhesion_law.adhesive_normal(a_ref, ad)[1]
