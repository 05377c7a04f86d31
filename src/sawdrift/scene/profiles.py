"""Axisymmetric profiles and their normal contact laws N*(a*), normalized (docs/physics.md).

For a power-law profile the Hertz-type normal law is N*(a*) = a*^p (N* = N / (M g), a* = a / a0):
sphere p = 3/2 (Hertz 1882; the paper's eq. 7 without its stray mu), cone p = 2, flat punch
p = 1. Any other axisymmetric profile enters through its normal law, tabulated in a CSV file with
columns ``a`` and ``N`` (``shape = "table"``). N* = 0 for a* <= 0 (contact lost).
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path
from typing import Annotated, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, model_validator

from .bounds import bounded
from .normal_law import law_normal, law_slope, read_table, table_descriptor

_NAMED_EXPONENTS = {"sphere": 1.5, "cone": 2.0, "flat": 1.0}


@lru_cache(maxsize=32)
def _table_law(path: str, mtime_ns: int) -> tuple[float, ...]:  # noqa: ARG001 - cache key
    a, n = read_table(path)
    return tuple(table_descriptor(a, n).tolist())


class Profile(BaseModel):
    """Axisymmetric profile of the particle, given by its normal law.

    Attributes
    ----------
    shape
        ``sphere`` (p = 3/2), ``cone`` (p = 2), ``flat`` (flat punch, p = 1), ``power`` (give
        ``exponent``) or ``table`` (give ``file``).
    exponent
        Power p in [1, 10] of N*(a*) = a*^p; required for ``power``, and refused with any
        other shape (which has its own law).
    file
        CSV file with a header and columns ``a`` and ``N`` (normalized: N = 1 at a = 1), for
        ``table``. A relative path is resolved against the scene file's folder when the scene is
        read from TOML, else against the working directory.
    """

    model_config = ConfigDict(frozen=True, extra="forbid")

    shape: Literal["sphere", "cone", "flat", "power", "table"] = "sphere"
    exponent: Annotated[float, bounded(1.0, 10.0)] | None = Field(
        None, description="p of N* = a*^p for shape 'power'"
    )
    file: str | None = None

    @model_validator(mode="after")
    def _table_readable(self) -> Profile:
        if self.exponent is not None and self.shape != "power":
            # a named shape has its own exponent and a table its own law: a second one would be
            # stored with the scene but not used
            own = (f"p = {_NAMED_EXPONENTS[self.shape]:g}" if self.shape in _NAMED_EXPONENTS
                   else "its law from profile.file")
            raise ValueError(f"profile.exponent = {self.exponent:g} is used only with "
                             f"profile.shape = 'power'; shape {self.shape!r} has {own} (set "
                             "profile.shape = 'power', --profile power, or drop the exponent)")
        if self.file is not None and self.shape != "table":
            # as the exponent: a table stored with the scene but not used (it was ignored)
            raise ValueError(f"profile.file = {self.file!r} is used only with profile.shape = "
                             f"'table'; shape {self.shape!r} has its own law (set profile.shape "
                             "= 'table', --profile table, or drop the file)")
        if self.shape == "table":
            if not self.file:
                raise ValueError("profile.file is required when profile.shape = 'table'")
            self.law()  # read and check the table now: errors name the file
        return self

    @property
    def p(self) -> float:
        """The exponent p of N*(a*) = a*^p; for a table its local exponent N*'(1) / N*(1)."""
        if self.shape == "power":
            if self.exponent is None:
                raise ValueError("profile.exponent is required when profile.shape = 'power'")
            return float(self.exponent)
        if self.shape == "table":
            return normal_stiffness(1.0, self.law())
        return _NAMED_EXPONENTS[self.shape]

    def law(self) -> np.ndarray:
        """The normal-law descriptor of :mod:`.normal_law` (``[p]`` for a power law)."""
        if self.shape != "table":
            return np.array([self.p], dtype=np.float64)
        path = Path(self.file or "")
        try:
            mtime = path.stat().st_mtime_ns
        except OSError:
            mtime = -1
        return np.array(_table_law(str(path), mtime), dtype=np.float64)


def normal_force(a: float, law: float | np.ndarray) -> float:
    """N*(a*) for a* > 0, else 0; ``law`` is an exponent p or a normal-law descriptor."""
    if np.ndim(law) == 0:
        return a ** float(law) if a > 0.0 else 0.0
    return float(law_normal(a, law, 0))


def normal_stiffness(a: float, law: float | np.ndarray) -> float:
    """dN*/da* for a* > 0, else 0; ``law`` is an exponent p or a normal-law descriptor."""
    if np.ndim(law) == 0:
        p = float(law)
        return p * a ** (p - 1.0) if a > 0.0 else 0.0
    return float(law_slope(a, law, 0))
