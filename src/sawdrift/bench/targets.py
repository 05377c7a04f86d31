"""A speed target of ``sawdrift bench speed``: what was measured, the limit and the verdict.

Its own module, so that every group of targets (:mod:`.bench_speed`, :mod:`.speed_more`) imports
it without importing another group.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any


@dataclass
class Target:
    """One speed target: what was measured, the limit and the verdict."""

    name: str
    description: str
    measured: float
    unit: str
    limit: float
    comparison: str  # "<=", "<" or ">="
    passed: bool
    details: dict[str, Any]

    def line(self) -> str:
        """One report line: verdict, measured value and target."""
        verdict = "PASS" if self.passed else "FAIL"
        return (f"[{verdict}] {self.description}: {self.measured:.4g} {self.unit} "
                f"(target {self.comparison} {self.limit:g} {self.unit})")


def _target(name: str, description: str, measured: float, unit: str, limit: float,
            comparison: str, details: dict[str, Any], extra_ok: bool = True) -> Target:
    ok = {"<=": measured <= limit, "<": measured < limit, ">=": measured >= limit}[comparison]
    return Target(name, description, float(measured), unit, float(limit), comparison,
                  bool(ok and extra_ok and math.isfinite(measured)), details)
