"""Contact model ``mmd``: the Method of Memory Diagrams, exact for any loading history.

The tangential law of docs/physics.md: the contact is indexed by the level z in [0, a*] of
the equivalent 1-D profile; each strip carries a displacement v(z) with |v(z)| <= a* - z, and

    N* = a*^p,        T* = integral_[0, a*] v(z) dN*'(z).

For a power-law profile and a piecewise-linear loading path this is the exact
Mindlin & Deresiewicz (1953) solution generalized to arbitrary 2-D histories by Aleshin,
Bou Matar and Van Den Abeele (2015), Int. J. Solids Struct. 60-61, 84-95 ("Method of memory
diagrams"). It is a tangential law in the contact slots (:mod:`sawdrift.contact.slots`, which
give N* and handle contact entry and loss); its compiled step (:mod:`sawdrift_builtin.mmd_kernel`)
keeps the diagram as a stack and costs O(1) amortized per step;
:mod:`sawdrift_builtin.mmd_reference` is the readable reference it is tested against.
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np
from pydantic import BaseModel, ConfigDict, Field

from sawdrift.contact import Capabilities, ContactHistory
from sawdrift.contact.slots import HEADER, LazyFunction, TangentialLaw
from sawdrift.hookspecs import hookimpl

from .mmd_reference import MemoryDiagramReference


class MemoryDiagramParams(BaseModel):
    """Parameters of the ``mmd`` model."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    max_memory_points: int = Field(
        65536,
        ge=16,
        le=10_000_000,
        description="capacity of the memory diagram (kinks), 16 to 1e7; exceeding it raises an error",
    )


class MemoryDiagramModel(TangentialLaw):
    """Memory-diagram contact (Aleshin et al. 2015), exact for piecewise-linear histories.

    Parameters
    ----------
    params
        A :class:`MemoryDiagramParams`.
    profile
        The particle's profile; any power law p >= 1 (flat punch included).
    """

    name: ClassVar[str] = "mmd"
    summary: ClassVar[str] = (
        "Method of Memory Diagrams (Aleshin et al. 2015): exact Mindlin-Deresiewicz history, "
        "O(1) amortized per step"
    )
    Params: ClassVar[type[BaseModel]] = MemoryDiagramParams
    capabilities: ClassVar[Capabilities] = Capabilities(
        profiles=("sphere", "cone", "flat", "power", "table"), straight_path_exact=True
    )
    step: ClassVar[LazyFunction] = LazyFunction("sawdrift_builtin.mmd_kernel", "mmd_step")
    reset_state: ClassVar[LazyFunction] = LazyFunction("sawdrift_builtin.mmd_kernel", "mmd_reset")
    #: |v(z)| <= a* - z on every strip bounds |T*| by N* (T* = N* in full sliding, to rounding)
    coulomb_cap: ClassVar[bool] = False
    #: with effects.adhesion (sawdrift.contact.adhesion): the diagram of the equivalent Hertz
    #: contact (sawdrift_builtin.adhesive_kernels.mmd_adhesive_step)
    adhesive_step: ClassVar[LazyFunction] = LazyFunction("sawdrift_builtin.adhesive_kernels",
                                                         "mmd_adhesive_step")
    adhesive_reset: ClassVar[LazyFunction] = LazyFunction("sawdrift_builtin.adhesive_kernels",
                                                          "mmd_adhesive_reset")
    adhesive_summary: ClassVar[str] = (
        "dmt, jkr: assumes the adhesive contact slips as the Hertz contact with its sliding "
        "force |N* + 2 F*_pull| and its initial stiffness 1.5 c* (c the adhesive contact "
        "radius): the exact diagram of that equivalent contact, its displacement scaled by "
        "c*/sqrt(a_e)")
    adhesive_deviations: ClassVar[tuple[tuple[str, str], ...]] = (
        ("split_invariance", "with adhesion the displacement scale c*/sqrt(a_e) changes along a "
         "step (taken trapezoidally): a straight move split in steps differs slightly"),)
    #: floats of the adhesive step in front of the diagram (b', a_e)
    adhesive_extra: ClassVar[int] = 2

    def adhesive_sizes(self) -> tuple[int, int]:
        """The diagram's state and the adhesive step's b' and a_e."""
        nf, ni = self.tangential_sizes()
        return nf + self.adhesive_extra, ni

    def tangential_sizes(self) -> tuple[int, int]:
        """Sizes of the diagram's state (layout in :mod:`sawdrift_builtin.mmd_kernel`)."""
        from . import mmd_kernel

        return mmd_kernel.state_sizes(self.params.max_memory_points)

    def live_sizes(self, fs: np.ndarray, is_: np.ndarray) -> tuple[int, int]:
        """The headers and the stored memory points (the rest of the stack is free)."""
        from . import mmd_kernel

        return HEADER + mmd_kernel.HEADER + mmd_kernel.RECORD * int(is_[0]), is_.size

    def compiled_live_floats(self):
        """:meth:`live_sizes`' float count, compiled (``mmd_kernel.live_floats``)."""
        from . import mmd_kernel

        return mmd_kernel.live_floats

    def reference_step(self) -> MemoryDiagramReference:
        """A fresh readable memory diagram, driven through its ``step`` by the python engine."""
        law = self.profile.law()
        return MemoryDiagramReference(law[0] if law.size == 1 else law)

    @staticmethod
    def memory_points(history: ContactHistory) -> np.ndarray:
        """The committed memory points of ``history`` as a (k, 2) array of (z, v)."""
        if history.reference is not None:
            return np.array(history.reference.readable.kinks, dtype=np.float64).reshape(-1, 2)
        from . import mmd_kernel

        state = history.state()
        return mmd_kernel.memory_points(state["fs"][HEADER:], state["is"])


@hookimpl
def sawdrift_contact_models() -> list[type[TangentialLaw]]:
    """Register the ``mmd`` model."""
    return [MemoryDiagramModel]
