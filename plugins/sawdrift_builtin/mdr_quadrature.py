"""The scale of mdr's tangential force: the strips' quadrature Q = sum_j m_j (a* - c_j)^+ of
N*(a*) falls short of it by O(dz^2) (the cell the contact edge cuts), so a full slide stopped
short of |T*| = N*; T* is taken on the scale N*(a*) / Q, at most :data:`SCALE_CAP` (N*/Q grows
without bound just after the first strip enters, where Q -> 0). Shared by the kernel
(:mod:`sawdrift_builtin.mdr_kernel`) and the reference (:mod:`sawdrift_builtin.mdr`)."""

from __future__ import annotations

__all__ = ["SCALE_CAP"]

#: most a step's T* is scaled by N*(a*) / Q: 1.0002 at a* = 0.08 on 256 strips, 1.02 at 0.01,
#: beyond it only within the first cell
SCALE_CAP = 1.05
