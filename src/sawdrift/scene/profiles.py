"""Normal contact laws N*(a*) of axisymmetric profiles, normalized as in ../shared/physics.md.

For a power-law profile the Hertz-type normal law is N*(a*) = a*^p (N* = N / (M g), a* = a / a0):
sphere p = 3/2 (Hertz 1882; the paper's eq. 7 without its stray mu), cone p = 2, flat punch
p = 1. N* = 0 for a* <= 0 (contact lost).
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field

_NAMED_EXPONENTS = {"sphere": 1.5, "cone": 2.0, "flat": 1.0}


class Profile(BaseModel):
    """Axisymmetric profile of the particle, given by the exponent of its normal law.

    Parameters
    ----------
    shape
        ``sphere`` (p = 3/2), ``cone`` (p = 2), ``flat`` (flat punch, p = 1) or ``power``
        (give ``exponent``).
    exponent
        Power p >= 1 of N*(a*) = a*^p; required for ``power``, ignored otherwise.
    """

    model_config = ConfigDict(frozen=True, extra="forbid")

    shape: Literal["sphere", "cone", "flat", "power"] = "sphere"
    exponent: Annotated[float, Field(ge=1.0, le=10.0)] | None = None

    @property
    def p(self) -> float:
        """The exponent p of N*(a*) = a*^p."""
        if self.shape == "power":
            if self.exponent is None:
                raise ValueError("profile.exponent is required when profile.shape = 'power'")
            return float(self.exponent)
        return _NAMED_EXPONENTS[self.shape]


def normal_force(a: float, p: float) -> float:
    """N*(a*) = a*^p for a* > 0, else 0 (Hertz law for a power-law profile)."""
    return a**p if a > 0.0 else 0.0


def normal_stiffness(a: float, p: float) -> float:
    """dN*/da* = p a*^(p-1) for a* > 0, else 0."""
    return p * a ** (p - 1.0) if a > 0.0 else 0.0
