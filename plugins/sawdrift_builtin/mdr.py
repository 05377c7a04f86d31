"""Contact model ``mdr``: Popov's Method of Dimensionality Reduction with N discrete strips.

The memory-diagram rules of docs/physics.md applied to a fixed grid of strips (MDR springs)
instead of an exact piecewise-linear diagram: Popov & Hess (2015), "Method of Dimensionality
Reduction in Contact Mechanics and Friction", Springer; its continuous limit is the Method of Memory
Diagrams (Aleshin et al. 2015, Int. J. Solids Struct. 60-61) of model ``mmd``, which it
converges to as the number of strips grows. It is the independent cross-check of ``mmd``.
Discretization and state layout: :mod:`sawdrift_builtin.mdr_kernel`.
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np
from pydantic import BaseModel, ConfigDict, Field

from sawdrift.contact import Capabilities
from sawdrift.contact.slots import LazyFunction, TangentialLaw
from sawdrift.hookspecs import hookimpl
from sawdrift.scene.profiles import normal_force, normal_stiffness

from .mdr_quadrature import SCALE_CAP
from .mmd_reference import StraightPathReference


class MdrParams(BaseModel):
    """Parameters of the ``mdr`` model."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    strips: int = Field(256, ge=2, le=65536,
                        description="number of strips (MDR springs) on the grid, 2 to 65536")
    z_max: float = Field(
        2.0,
        gt=0.0,
        le=1e6,
        description="initial extent of the strip grid in a*; it doubles (cells merged in pairs) "
        "when a* exceeds it",
    )


def strip_grid(strips: int, dz: float, p) -> tuple[np.ndarray, np.ndarray]:
    """Centroids c_j and weights m_j of the cells [j dz, (j+1) dz] under the measure dN*'.

    m_j = N*'(e1) - N*'(e0) with N*'(0-) = 0; c_j = integral z dN*' / m_j = ([z N*'] - [N*]) / m_j
    (the cell midpoint where m_j = 0, as for a flat punch beyond cell 0).
    """
    e0 = np.arange(strips, dtype=np.float64) * dz
    e1 = (np.arange(strips, dtype=np.float64) + 1.0) * dz

    if np.ndim(p) == 0:

        def dn(z: np.ndarray) -> np.ndarray:
            return np.where(z > 0.0, p * np.where(z > 0.0, z, 1.0) ** (p - 1.0), 0.0)

        def nn(z: np.ndarray) -> np.ndarray:
            return np.where(z > 0.0, z, 0.0) ** p
    else:  # a normal-law descriptor (tabulated profile)

        def dn(z: np.ndarray) -> np.ndarray:
            return np.array([normal_stiffness(float(v), p) for v in z])

        def nn(z: np.ndarray) -> np.ndarray:
            return np.array([normal_force(float(v), p) for v in z])

    m = dn(e1) - dn(e0)
    moment = e1 * dn(e1) - e0 * dn(e0) - (nn(e1) - nn(e0))
    c = np.where(m > 0.0, moment / np.where(m > 0.0, m, 1.0), 0.5 * (e0 + e1))
    return c, m


class MdrReference(StraightPathReference):
    """Readable numpy MDR contact: N strips following the memory-diagram rules.

    Parameters
    ----------
    p
        Exponent of the normal law N*(a*) = a*^p (p >= 1).
    strips
        Number of strips N.
    z_max
        Initial grid extent; dz = z_max / N.
    """

    def __init__(self, p: float, strips: int = 256, z_max: float = 2.0) -> None:
        self.p = float(p) if np.ndim(p) == 0 else np.asarray(p, dtype=float)
        self.strips = int(strips)
        self.z_max = float(z_max)
        self._set_grid(self.z_max / self.strips)
        self.reset()

    def forget(self) -> None:
        """Every strip at rest, on the initial grid."""
        self.v = np.zeros(self.strips)
        if self.dz != self.z_max / self.strips:
            self._set_grid(self.z_max / self.strips)

    def _set_grid(self, dz: float) -> None:
        self.dz = dz
        self.c, self.m = strip_grid(self.strips, dz, self.p)

    def _coarsen(self, a0: float) -> None:
        """Double dz; carry the diagram (strips in contact, closed by v(a0) = 0) over by
        linear interpolation."""
        inside = self.c < a0
        zs = np.append(self.c[inside], a0)
        vs = np.append(self.v[inside], 0.0)
        self._set_grid(2.0 * self.dz)
        self.v = np.where(self.c < a0, np.interp(self.c, zs, vs), 0.0)

    def step(self, a0: float, b0: float, a: float, b: float) -> float:
        """Every strip along the straight path (a0, b0) -> (a, b), a > 0; commit; T*.

        ``a0 = 0`` is a new contact (every strip enters), the tangential slot's form
        (:mod:`sawdrift.contact.slots`); :meth:`force` adds contact entry and loss.
        """
        while a > self.strips * self.dz:
            self._coarsen(a0)
        db = b - b0
        c = self.c
        was_in = c < a0
        now_in = c < a
        entering = now_in & ~was_in
        v = np.where(was_in, self.v + db, 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            v = np.where(entering, db * (a - c) / (a - a0), v)
        lim = np.where(now_in, a - c, 0.0)
        self.v = np.where(now_in, np.clip(v, -lim, lim), 0.0)
        # on the scale of N*(a*): the strips' quadrature sum m_j (a* - c_j) falls short of it by
        # O(dz^2), and full sliding then stopped short of |T*| = N* (mdr_kernel)
        quadrature = float(np.sum(self.m * lim))
        t = float(np.sum(self.m * self.v))
        if quadrature > 0.0:
            t *= min(self._normal(a) / quadrature, SCALE_CAP)  # the kernel's cap (mdr_step)
        return t

    def _normal(self, a: float) -> float:
        """N*(a*) of the profile's law (a power law, or a tabulated descriptor)."""
        if np.ndim(self.p) == 0:
            return float(a) ** self.p
        return float(normal_force(float(a), self.p))


class MdrModel(TangentialLaw):
    """MDR contact (Popov 2015) with N discrete strips; converges to ``mmd`` as N grows.

    A tangential law in the contact slots (:mod:`sawdrift.contact.slots`): N* is the profile's.

    Parameters
    ----------
    params
        An :class:`MdrParams`.
    profile
        The particle's profile; any power law p >= 1 (flat punch included).
    """

    name: ClassVar[str] = "mdr"
    summary: ClassVar[str] = (
        "Method of Dimensionality Reduction (Popov 2015) on N strips: O(N) per step, "
        "converges to mmd"
    )
    Params: ClassVar[type[BaseModel]] = MdrParams
    capabilities: ClassVar[Capabilities] = Capabilities(
        profiles=("sphere", "cone", "flat", "power", "table"), straight_path_exact=True,
        deviations=(("split_invariance", "the strip grid is coarsened at the committed point of a "
                     "step that passes its end (z_max, then 2 z_max, ...), so such a step depends "
                     "on how it is cut: up to 4e-7 (1 + N*) on histories to a* = 20; exact below "
                     "z_max"),),
    )
    step: ClassVar[LazyFunction] = LazyFunction("sawdrift_builtin.mdr_kernel", "mdr_step")
    reset_state: ClassVar[LazyFunction] = LazyFunction("sawdrift_builtin.mdr_kernel", "mdr_reset")

    def tangential_sizes(self) -> tuple[int, int]:
        """Sizes of the strips' state (layout in :mod:`sawdrift_builtin.mdr_kernel`)."""
        from . import mdr_kernel

        return mdr_kernel.state_sizes(self.params.strips)

    def tangential_params(self) -> np.ndarray:
        """``[strips, z_max]``."""
        return np.array([float(self.params.strips), self.params.z_max], dtype=np.float64)

    def reference_step(self) -> MdrReference:
        """A fresh numpy MDR contact, driven through its ``step`` by the python engine."""
        law = self.profile.law()
        return MdrReference(law[0] if law.size == 1 else law, self.params.strips, self.params.z_max)


@hookimpl
def sawdrift_contact_models() -> list[type[TangentialLaw]]:
    """Register the ``mdr`` model."""
    return [MdrModel]
