"""The outcome of one run: summary metrics always, the trajectory only when asked for."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .._version import __version__
from .regimes import creep

if TYPE_CHECKING:
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
    "orbit",
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
    "gross_slip_fraction",
    "creep",
    "liftoffs_per_period",
    "hop_period",
    "liftoff_phase",
    "liftoff_phase_spread",
    "lyapunov",
    "periodicity",
    "spin_rate",
    "version",
)


#: Typed evidence beside the summary fields (also written by ``run --json``; None where a field
#: does not apply, e.g. ``t90_periods`` of a fixed-length run).
EVIDENCE_FIELDS = (
    "chaotic",
    "events_dropped",
    "compile_s",
    "orbit_period",
    "settled",
    "settle_method",
    "settle_periods",
    "t90_periods",
    "horizontal_inertia",
    "liftoffs_per_hop",
    "liftoff_phases",
    "drift_ratio_se",
    "mean_acceleration",
    "detach_time",
    "detach_phase",
    "warnings",
)


def _package_version() -> str:
    return __version__


@dataclass
class Result:
    """Summary of a run (see :data:`SUMMARY_FIELDS`) and, optionally, its trajectory and events.

    ``drift_velocity`` is the mean x*' over the last ``measure_periods`` whole periods
    (x* sampled at the same wave phase at both ends), ``drift_ratio`` that velocity over the
    horizontal surface-speed amplitude 2 pi r A* (0 when A* = 0). Every piece of evidence
    (contact loss, gross slip, lift-offs and their phases, the Lyapunov estimate, the events)
    comes from that same window; see :mod:`sawdrift.result.regimes`. ``version`` is the sawdrift
    version that computed it and ``scene`` the whole scene (provenance).
    ``creep`` (a property) is true for a drift with no gross slip in the window
    (:func:`sawdrift.result.regimes.creep`).
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
    orbit: str = "prograde"
    gross_slip_fraction: float = math.nan
    liftoffs_per_period: float = math.nan
    hop_period: int = 0
    liftoff_phase: float = math.nan
    liftoff_phase_spread: float = math.nan
    lyapunov: float = math.nan
    periodicity: float = math.nan
    spin_rate: float = math.nan
    version: str = field(default_factory=_package_version)
    #: the window's motion is chaotic (largest Lyapunov exponent > 0, see result.regimes)
    chaotic: bool = False
    #: events that did not fit the event log: always 0 (a run that would drop one fails instead)
    events_dropped: int = 0
    #: seconds spent compiling or loading the compiled loop, apart from wall_time_s
    compile_s: float = math.nan
    #: p when the stroboscopic state repeats after p periods (a periodic orbit), else 0
    orbit_period: int = 0
    #: whether the reported drift is the steady one (see dynamics.steady)
    settled: bool | None = None
    #: how ``settled`` was decided: "fixed" (a run of fixed length, judged after the fact; a
    #: default light run whose first window after the ramp held its contact ends there),
    #: "windows_full" (windows at full inertia), "fixed_then_windows" (a default fixed run its own
    #: window could not confirm, continued in such windows), "reduced_then_full" (a reduced-inertia
    #: approach, then windows at full inertia; see dynamics.full_inertia), "solved" (the drift
    #: solved directly, checked by one evidence window; see dynamics.direct), "orbit_then_full"
    #: (windows at full inertia started at the drift solved directly: numerics.confirm_solved)
    #: "imposed_speed" (an irregular heavy bouncer's long-time mean from the friction at an
    #: imposed speed; see dynamics.imposed) or "mean_then_orbit" (an irregular motion that fell
    #: onto a periodic orbit during its long-time mean: the orbit's window; see
    #: dynamics.transient)
    settle_method: str | None = None
    #: periods after which the drift was assessed (settle runs: periods spent settling)
    settle_periods: float = math.nan
    #: settle runs: periods to reach 90 % of the steady drift (full inertia)
    t90_periods: float = math.nan
    #: settle runs: the horizontal (and rotational) inertia m*_x of the first, approaching stage
    #: (the drift is always measured at the full m*)
    horizontal_inertia: float = math.nan
    #: hopping: lift-offs in one hop period
    liftoffs_per_hop: float = math.nan
    #: hopping: the wave phase t* mod 1 of each lift-off of a hop period, in order (a period-2
    #: orbit has two take-off phases; ``liftoff_phase`` is the first)
    liftoff_phases: tuple[float, ...] = ()
    #: standard error of ``drift_ratio`` (irregular motion: batch means over decorrelated
    #: windows; an irregular heavy bouncer whose record is quasi-periodic: its weighted mean's
    #: error, :mod:`sawdrift.dynamics.imposed_weighted`); NaN where the drift is a fixed
    #: point's or a periodic orbit's
    drift_ratio_se: float = math.nan
    #: ``runaway``: the long-time mean horizontal acceleration, x* per period squared:
    #: (L - mu sign L) / m* where the load exceeds friction, (L - mu_r sign L) / (m* (1 + kappa))
    #: for a sphere free to turn that rolls away; with adhesion the window's (a fit to its
    #: positions)
    mean_acceleration: float = math.nan
    #: ``ejected``: t* of the last lift-off (the detachment) and its wave phase t* mod 1
    detach_time: float = math.nan
    detach_phase: float = math.nan
    #: conditions under which the model's assumptions are stretched or do not hold (a device's
    #: compression below 1 nm, strain or speed near their bounds), one sentence each
    warnings: tuple[str, ...] = ()
    scene: dict[str, Any] = field(default_factory=dict, repr=False)
    trajectory: pd.DataFrame | None = field(default=None, repr=False)
    event_rows: np.ndarray | None = field(default=None, repr=False)
    extra: dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def creep(self) -> bool:
        """A drift in permanent contact with no gross slip in the window: partial slip alone."""
        return creep(self.regime, self.gross_slip_fraction)

    @property
    def events(self) -> pd.DataFrame | None:
        """The measurement window's events as a DataFrame (columns t, kind, x, vx, y, vy, a).

        Kinds: lift_off, landing, slip_start, slip_end, stick_start
        (:mod:`sawdrift.dynamics.evidence`); None for runs without a window.
        """
        if self.event_rows is None:
            return None
        import pandas as pd

        from ..dynamics.evidence import EVENT_COLUMNS, EVENT_KINDS

        rows = self.event_rows
        frame = pd.DataFrame(rows, columns=list(EVENT_COLUMNS))
        kinds = np.asarray(EVENT_KINDS)
        frame["kind"] = pd.Categorical(kinds[rows[:, 1].astype(int)], categories=list(kinds))
        return frame

    def __getattr__(self, name: str) -> Any:
        # model- or drive-specific outputs (impact rebound, device units) live in ``extra``
        if name.startswith("__") or name == "extra":
            raise AttributeError(name)
        try:
            return self.extra[name]
        except KeyError:
            raise AttributeError(f"Result has no field {name!r}") from None

    def summary(self) -> dict[str, Any]:
        """The summary fields, the evidence, the extras and the scene as JSON-ready values.

        NaN becomes None.
        """
        out: dict[str, Any] = {}
        for key in SUMMARY_FIELDS + EVIDENCE_FIELDS:
            out[key] = json_value(getattr(self, key))
        for key, value in self.extra.items():
            out[key] = json_value(value)
        out["scene"] = self.scene
        return out


def json_value(value: Any) -> Any:
    """A JSON-ready value: numpy scalars become Python ones, non-finite floats None, tuples lists."""
    if isinstance(value, tuple):
        return [json_value(v) for v in value]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
