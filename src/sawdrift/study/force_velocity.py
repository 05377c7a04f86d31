"""Force-velocity curves: the mean friction force against the steady drift speed it allows.

For a particle on the vibrating surface the period-averaged friction force <F> is a function of
the particle's mean horizontal speed v: the force-velocity curve of the contact under that wave
(vibrational mechanics, Blechman 2000). Its zero, approached from rest, is the free steady drift;
a constant tangential load L holds the particle at the speed where <F>(v) = L, so a load curve is
the same curve read the other way, and the stall load is the force at v = 0 (docs/physics.md,
"Heavy particles and the steady drift", "Loads, inclines and restitution").

:func:`force_velocity` samples it by imposing loads: each run holds a constant load L, strictly
inside (-mu, mu) M g (beyond, no steady speed exists: the mean friction is at most mu times the
weight, and the run is a ``runaway``; with adhesion mu (1 + 2 F*_pull), friction being capped at
mu |N* + 2 F*_pull|), and reports its steady drift at full inertia (the default
settle, :mod:`sawdrift.dynamics.full_inertia`). Every point is therefore a steady state of the
particle's own dynamics, with its fast horizontal oscillation and contact memory at the full m*.
Where the contact sticks the curve is vertical: a range of loads holds the particle at v = 0
(static friction); partial slip gives the creep branch of small speeds near it.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..contact.binding import bind
from ..dynamics.steady import holding_bound, refuse_free_spin
from ..result.result import json_value
from ..scene.schema import Scene
from .load_curve import _device_scales, _Runner, _surface_speed

__all__ = ["ForceVelocity", "force_velocity"]


@dataclass(frozen=True)
class ForceVelocity:
    """The sampled curve: loads (the mean friction force they balance) against steady speeds.

    ``forces`` are the total tangential loads on the particle in units of the static normal load
    M g (the applied load plus a device's incline pull): at a steady state the period-averaged
    friction force balances them, mu <T*> = force. ``velocities`` are the steady drift
    velocities (x* per period, units a0 f), NaN where the run found no steady state.
    ``velocity_se`` is the standard error of a velocity that is a long-time mean (a chaotic or
    irregular point, ``drift_ratio_se`` times the surface speed), NaN where the drift settled;
    ``warnings`` are each run's (a lower-bound error, a motion still heating up).
    """

    forces: np.ndarray
    velocities: np.ndarray
    drift_ratios: np.ndarray
    regimes: tuple[str, ...]
    settled: tuple[bool, ...]
    mu: float
    surface_speed: float
    free_drift: float
    wall_time_s: float
    device: dict[str, float] | None = None
    drift_ratio_se: np.ndarray = field(default_factory=lambda: np.zeros(0))
    warnings: tuple[tuple[str, ...], ...] = ()
    #: standard error of the free drift (a0 f), NaN where it settled
    free_drift_se: float = math.nan
    #: the most friction can hold on average, in M g: mu, or mu (1 + 2 F*_pull) with adhesion
    #: (:func:`~sawdrift.dynamics.steady.holding_bound`); NaN: mu
    bound: float = math.nan

    @property
    def friction_bound(self) -> float:
        """The most friction can hold on average (M g): :attr:`bound`, or mu if not given."""
        return self.mu if math.isnan(self.bound) else self.bound

    @property
    def velocity_se(self) -> np.ndarray:
        """Standard errors of the velocities (a0 f): NaN where the drift settled."""
        return self.drift_ratio_se * self.surface_speed

    @property
    def free_drift_resolved(self) -> bool:
        """Whether the free drift is told apart from zero: settled, or a long-time mean more than
        three standard errors from zero (False where it is zero within its error)."""
        se = self.free_drift_se
        return math.isfinite(self.free_drift) and not abs(self.free_drift) <= 3.0 * se

    @property
    def zero(self) -> float:
        """The speed where the sampled force crosses zero (linear interpolation between the two
        samples around it), NaN if it does not: the free drift read off the curve."""
        f, v = self.forces, self.velocities
        ok = np.isfinite(v)
        f, v = f[ok], v[ok]
        for i in range(f.size - 1):
            if f[i] == 0.0:
                return float(v[i])
            if f[i] * f[i + 1] < 0.0:
                w = f[i] / (f[i] - f[i + 1])
                return float(v[i] + w * (v[i + 1] - v[i]))
        return math.nan

    def to_json(self) -> dict[str, Any]:
        """The curve as plain JSON values (NaN as None), with SI columns on a device."""
        def plain(x: np.ndarray) -> list[float | None]:
            return [json_value(a) for a in x]

        out: dict[str, Any] = {
            "force": plain(self.forces),
            "drift_velocity": plain(self.velocities),
            "drift_velocity_se": plain(self.velocity_se),
            "drift_ratio": plain(self.drift_ratios),
            "drift_ratio_se": plain(self.drift_ratio_se),
            "regimes": list(self.regimes),
            "settled": list(self.settled),
            "warnings": [list(w) for w in self.warnings],
            "mu": self.mu,
            "friction_bound": self.friction_bound,
            "free_drift_velocity": self.free_drift,
            "free_drift_velocity_se": None if math.isnan(self.free_drift_se) else self.free_drift_se,
            "free_drift_resolved": self.free_drift_resolved,
            "zero_of_curve": None if math.isnan(self.zero) else self.zero,
            "units": {"force": "M g", "drift_velocity": "a0 f"},
            "wall_time_s": self.wall_time_s,
        }
        if self.device is not None:
            out["device"] = {"force_mN": plain(1e3 * self.device["force_n"] * self.forces),
                             "speed_m_s": plain(self.device["speed_m_s"] * self.velocities),
                             "speed_se_m_s": plain(self.device["speed_m_s"] * self.velocity_se)}
        return out


def force_velocity(
    scene: Scene,
    *,
    points: int = 21,
    workers: int | None = None,
    engine: str = "compiled",
    progress: Callable[[str], None] | None = None,
) -> ForceVelocity:
    """Sample the force-velocity curve of ``scene`` at ``points`` loads (module docstring).

    Parameters
    ----------
    scene
        A wave scene, normalized or a device. Its own load is replaced by each sampled one; a
        device's incline stays (its pull is part of every force).
    points
        Loads, evenly spaced strictly inside (-mu, mu) M g (mu (1 + 2 F*_pull) with adhesion),
        plus the unloaded run.
    workers
        Local processes (default: all cores).
    engine
        ``"compiled"`` or ``"python"``.
    progress
        Called with a short line after each batch.
    """
    import os

    scene = bind(scene)
    if points < 3:
        raise ValueError(f"points = {points}: a force-velocity curve needs at least 3")
    speed = _surface_speed(scene)
    mu = scene.material.mu
    # mu, or mu (1 + 2 F*_pull) with adhesion; a sphere free to turn holds at most mu_r (1 + 2
    # F*_pull): its loads were spread over (-mu, mu), most of them runaways
    refuse_free_spin(scene, "force-velocity curve")
    bound = holding_bound(scene)
    t0 = time.perf_counter()
    runner = _Runner(scene, engine, workers or os.cpu_count() or 1)
    try:
        applied = list(bound * np.linspace(-1.0, 1.0, points + 2)[1:-1])
        if 0.0 not in applied:
            applied.append(0.0)
        applied.sort()
        rows = runner.run(applied)
    except KeyboardInterrupt:
        raise runner.interrupted() from None
    finally:
        runner.close()
    if progress is not None:
        progress(f"force-velocity: {len(applied)} loads run")
    forces = np.array(applied) + runner.background
    vel = np.array([_value(r["drift_velocity"]) for r in rows])
    ratio = np.array([_value(r["drift_ratio"]) for r in rows])
    se = np.array([_value(r.get("drift_ratio_se")) for r in rows])
    free = applied.index(0.0)
    return ForceVelocity(
        forces=forces, velocities=vel, drift_ratios=ratio,
        regimes=tuple(str(r["regime"]) for r in rows),
        settled=tuple(bool(r["settled"]) for r in rows), mu=mu, surface_speed=speed,
        free_drift=float(vel[free]), wall_time_s=time.perf_counter() - t0,
        device=_device_scales(scene), drift_ratio_se=se,
        warnings=tuple(tuple(str(w) for w in r.get("warnings") or ()) for r in rows),
        free_drift_se=float(se[free] * speed), bound=bound)


def _value(x: Any) -> float:
    return float(x) if x is not None else math.nan
