"""The outcome of one run: summary metrics always, the trajectory only when asked for."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

import pandas as pd

#: Summary fields written by ``sawdrift run --json`` and by sweeps, in this order.
SUMMARY_FIELDS = (
    "model",
    "engine",
    "m_star",
    "amplitude",
    "mu",
    "nu",
    "horizontal_ratio",
    "profile",
    "steps_per_period",
    "periods",
    "ramp_periods",
    "measure_periods",
    "drift_velocity",
    "drift_ratio",
    "regime",
    "contact_lost",
    "out_of_contact_fraction",
    "min_compression",
    "steps",
    "wall_time_s",
)


@dataclass
class Result:
    """Summary of a run (see :data:`SUMMARY_FIELDS`) and, optionally, its trajectory.

    ``drift_velocity`` is the mean x*' over the last ``measure_periods`` whole periods
    (x* sampled at the same wave phase at both ends), ``drift_ratio`` that velocity over the
    horizontal surface-speed amplitude 2 pi r A* (0 when A* = 0).
    """

    model: str
    engine: str
    m_star: float
    amplitude: float
    mu: float
    nu: float
    horizontal_ratio: float
    profile: str
    steps_per_period: int
    periods: float
    ramp_periods: float
    measure_periods: int
    drift_velocity: float
    drift_ratio: float
    regime: str
    contact_lost: bool
    out_of_contact_fraction: float
    min_compression: float
    steps: int
    wall_time_s: float
    trajectory: pd.DataFrame | None = field(default=None, repr=False)
    extra: dict[str, Any] = field(default_factory=dict, repr=False)

    def summary(self) -> dict[str, Any]:
        """The summary fields as JSON-ready Python values (NaN becomes None)."""
        data = asdict(self)
        out: dict[str, Any] = {}
        for key in SUMMARY_FIELDS:
            value = data[key]
            if isinstance(value, float) and not math.isfinite(value):
                value = None
            out[key] = value
        for key, value in self.extra.items():
            if isinstance(value, float) and not math.isfinite(value):
                value = None
            out[key] = value
        return out
