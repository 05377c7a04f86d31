"""A substrate at rest: the drive of a free impact (``drive.kind = "impact"``)."""

from __future__ import annotations

from typing import Any, ClassVar

from numba import njit

from .base import Drive


class SubstrateAtRest(Drive):
    """No surface motion."""

    kind: ClassVar[str] = "impact"
    module: ClassVar[str] = __name__
    names: ClassVar[tuple[str, ...]] = ("unused",)

    def parameters(self, scene: Any) -> dict[str, float]:
        return {"unused": 0.0}

    def describe(self, scene: Any) -> list[str]:
        return ["substrate at rest"]


@njit(cache=True)
def kinematics(t, x, dp):
    """(u_x, u_x', u_x'', u_y, u_y', u_y''): all zero."""
    return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0


@njit(cache=True)
def surface(t, x, dp):
    """(u_x, u_x', u_y, u_y'): all zero."""
    return 0.0, 0.0, 0.0, 0.0
