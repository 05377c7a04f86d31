"""Readable pure-Python reference of the Method of Memory Diagrams (docs/physics.md).

Follows the four rules of the memory diagram literally on a list of kinks (z, v) of the piecewise-linear
strip displacement v(z), and recomputes T* by summing every segment at each call, O(kinks):
clarity over speed. The compiled kernel (:mod:`sawdrift_builtin.mmd_kernel`) must agree with it.

References
----------
Aleshin, Bou Matar, Van Den Abeele (2015), "Method of memory diagrams for mechanical frictional
contacts subject to arbitrary 2D loading", Int. J. Solids Struct. 60-61, 84-95.
Mindlin & Deresiewicz (1953), "Elastic spheres in contact under varying oblique forces",
J. Appl. Mech. 20, 327-344.
"""

from __future__ import annotations

import numpy as np

from sawdrift.scene.profiles import normal_force
from sawdrift.scene.profiles import normal_stiffness as normal_slope

Kink = tuple[float, float]


def segment_integral(z1: float, v1: float, z2: float, v2: float, p: float) -> float:
    """integral_(z1, z2] v dN*' for v linear from (z1, v1) to (z2, v2) (docs/physics.md).

    Integration by parts: [v N*'] from z1 to z2 minus (dv/dz) [N*(z2) - N*(z1)]. A segment
    starting at z1 = 0 uses N*'(0-) = 0, so it includes the point mass of a flat punch.
    """
    if z2 <= z1:
        return 0.0
    slope = (v2 - v1) / (z2 - z1)
    return (
        v2 * normal_slope(z2, p)
        - v1 * normal_slope(z1, p)
        - slope * (normal_force(z2, p) - normal_force(z1, p))
    )


def tangential_force(kinks: list[Kink], p: float) -> float:
    """T* = integral_[0, a*] v dN*' for the piecewise-linear diagram through ``kinks``."""
    return sum(
        segment_integral(z1, v1, z2, v2, p)
        for (z1, v1), (z2, v2) in zip(kinks[:-1], kinks[1:], strict=True)
    )


def _value_at(kinks: list[Kink], z: float) -> float:
    """Linear interpolation of the diagram at level z (inside its range)."""
    for (z1, v1), (z2, v2) in zip(kinks[:-1], kinks[1:], strict=True):
        if z1 <= z <= z2:
            return v1 if z2 == z1 else v1 + (v2 - v1) * (z - z1) / (z2 - z1)
    raise ValueError(f"level {z} outside the diagram")


def _clip_to_bound(kinks: list[Kink], a: float, s: float) -> list[Kink]:
    """Clip v to s v <= a - z (s = +1: upper bound, s = -1: lower bound).

    The clipped function is piecewise linear with kinks at the old kinks and at the crossings
    of each segment with the bound line; runs of points lying on the bound are thinned to their
    two ends.
    """
    out: list[Kink] = []
    on_bound: list[bool] = []

    def excess(z: float, v: float) -> float:
        return s * v - (a - z)

    for i, (z, v) in enumerate(kinks):
        g = excess(z, v)
        if i > 0:
            zl, vl = kinks[i - 1]
            gl = excess(zl, vl)
            if (gl < 0.0 < g) or (g < 0.0 < gl):
                zx = zl + (z - zl) * gl / (gl - g)
                if zl < zx < z:
                    out.append((zx, s * (a - zx)))
                    on_bound.append(True)
        if g >= 0.0:
            out.append((z, s * (a - z)))
            on_bound.append(True)
        else:
            out.append((z, v))
            on_bound.append(False)
    keep = [
        not (0 < i < len(out) - 1 and on_bound[i - 1] and on_bound[i] and on_bound[i + 1])
        for i in range(len(out))
    ]
    return [k for k, flag in zip(out, keep, strict=True) if flag]


class StraightPathReference:
    """Readable contact entry and loss around a tangential ``step``: the references' oracle.

    Written out plainly, apart from the compiled contact slots (:mod:`sawdrift.contact.slots`) the
    kernels run in, so that comparing the two checks the slots' bookkeeping as well: a* <= 0
    forgets the history (N* = T* = 0); a straight path from a* <= 0 enters contact where it
    crosses a* = 0, and the law starts there with ``a0 = 0``; N* = N*(a*) of the profile.
    Subclasses provide ``p``, :meth:`forget` and :meth:`step`.
    """

    p: float | np.ndarray
    a: float = 0.0
    b: float = 0.0

    def forget(self) -> None:
        """Erase the tangential history (out of contact)."""
        raise NotImplementedError

    def step(self, a0: float, b0: float, a: float, b: float) -> float:
        """T* after the straight path (a0, b0) -> (a, b) in contact; ``a0 = 0``: a new contact."""
        raise NotImplementedError

    def reset(self) -> None:
        """Forget all history: out of contact at (a*, b*) = (0, 0)."""
        self.a = 0.0
        self.b = 0.0
        self.forget()

    def force(self, a: float, b: float, adot: float = 0.0, bdot: float = 0.0) -> tuple[float, float]:
        """Advance along the straight path to (a*, b*), commit, and return (N*, T*).

        ``adot`` and ``bdot`` are ignored (the laws are rate independent).
        """
        a, b = float(a), float(b)
        a0, b0 = self.a, self.b
        self.a, self.b = a, b
        if not a > 0.0:
            self.forget()
            return 0.0, 0.0
        if a0 <= 0.0:
            # a fresh contact starts where the straight path crosses a* = 0
            if a0 < 0.0:
                b0 = b0 + (b - b0) * (-a0) / (a - a0)
            a0 = 0.0
        return normal_force(a, self.p), self.step(a0, b0, a, b)


class MemoryDiagramReference(StraightPathReference):
    """Pure-Python memory-diagram contact (Aleshin et al. 2015), for checking the kernel.

    Parameters
    ----------
    p
        Exponent of the normal law N*(a*) = a*^p (p >= 1).

    Attributes
    ----------
    a, b
        Committed contact displacements a*, b*.
    kinks
        Memory points (z, v) of the diagram, z ascending from 0 to a* (empty out of contact).
    """

    def __init__(self, p) -> None:
        # an exponent p, or a normal-law descriptor (sawdrift.contact.normal) for a table
        self.p = float(p) if np.ndim(p) == 0 else np.asarray(p, dtype=float)
        self.reset()

    @classmethod
    def from_kinks(cls, p: float, a: float, b: float, kinks: list[Kink]) -> MemoryDiagramReference:
        """A reference contact restored from a committed state (e.g. a kernel's stored kinks)."""
        ref = cls(p)
        ref.a, ref.b = float(a), float(b)
        ref.kinks = [(float(z), float(v)) for z, v in kinks] if a > 0.0 else []
        return ref

    def forget(self) -> None:
        """No memory points."""
        self.kinks: list[Kink] = []

    def tangential_force(self) -> float:
        """T* of the committed diagram, summed over all its segments."""
        return tangential_force(self.kinks, self.p)

    def step(self, a0: float, b0: float, a: float, b: float) -> float:
        """The four rules along the straight path (a0, b0) -> (a, b), a > 0; commit; T*.

        ``a0 = 0`` starts a new contact from the point diagram at z = 0 (the tangential slot's
        form, :mod:`sawdrift.contact.slots`; :meth:`force` adds contact entry and loss).
        """
        self.a, self.b = a, b
        kinks: list[Kink] = [(0.0, 0.0)] if a0 == 0.0 else list(self.kinks)
        db = b - b0
        # rule 1: strips with z >= a* leave contact and are forgotten
        if a < a0:
            va = _value_at(kinks, a)
            kinks = [(z, v) for z, v in kinks if z < a] + [(a, va)]
        # rule 3: every strip in contact shifts by delta b*
        kinks = [(z, v + db) for z, v in kinks]
        # rule 2: strips entering along the straight path: v linear from (a0, db) to (a, 0)
        if a > a0:
            kinks.append((a, 0.0))
        # rule 4: local slip
        kinks = _clip_to_bound(kinks, a, 1.0)
        kinks = _clip_to_bound(kinks, a, -1.0)
        self.kinks = kinks
        return tangential_force(kinks, self.p)
