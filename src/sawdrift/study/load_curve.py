"""Load curves: drift speed and output power against a tangential load, up to the stall load.

A particle (a motor's slider, a grain on a conveyor) drifts at V0 without load. A constant
tangential load F against that drift (``particle.load``, in units of the static normal load M g;
``device.load`` in newtons on a device scene) slows it, and from the stall load F_s on it no
longer advances (docs/physics.md, "Loads, inclines and restitution"). :func:`load_curve`

1. runs the scene without load (the direction of the drift, V0);
2. brackets the stall load in [0, F_max], F_max = mu + (the scene's own load along the drift,
   an incline's pull): against a load of mu M g or more nothing can advance, since the
   period-averaged normal force is M g and friction is at most mu times it (with adhesion, which
   caps friction at mu |N* + 2 F*_pull|, mu (1 + 2 F*_pull) in place of mu); F_max itself is not
   run (it is known not to advance), and the bracket is narrowed by k-section, k - 1 runs in
   parallel per round (bisection with one worker), to ``tolerance`` F_max;
3. runs ``loads`` loads evenly from 0 to the stall load (in parallel), and reports the speed,
   the output power P = F v and its largest sampled value.

"Advances" means a drift along the unloaded direction above the scene's
``numerics.drift_tolerance`` times the smaller of the horizontal surface speed 2 pi r A* (the
regime classifier's threshold for "stick") and the unloaded drift itself, but not below the
accuracy of a run, the settling's absolute floor (2e-5 of the surface speed by default,
:func:`~sawdrift.dynamics.approach.relative_bound`); the loaded runs are
classified with that threshold too. Against the surface speed alone a slow drift stalled early:
a 10 um silica sphere (DMT) on a 20 MHz lithium niobate line drifting at 5.3e-3 of the surface
speed was called stalled, and its run "stick", at 29 % of its free speed, 30 % short of the load that
stops it (:func:`_advance_tolerance`). A drift that is a long-time mean (a chaotic or irregular
bouncer) carries its standard error; an unloaded one within three errors of zero gives no
direction to load against, and so no stall load (``free_state``, :data:`FREE_STATES`). Device
scenes are reported in mN, m/s and mW as well, with the start-up acceleration F_s / m (the net
force on the unloaded slider at rest is the stall load, by its definition).
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import partial
from typing import Any

import numpy as np

from ..contact.binding import bind
from ..dynamics.approach import relative_bound
from ..dynamics.drives import drive_of
from ..dynamics.steady import holding_bound
from ..errors import SceneError
from ..result.result import json_value
from ..result.runner import run
from ..scene.device import normalized
from ..scene.schema import Scene, Wave
from .executor import Executor

__all__ = ["LoadCurve", "load_curve"]

#: summary fields kept of each run
_KEPT = ("drift_velocity", "drift_ratio", "regime", "settled", "settle_periods", "drift_ratio_se",
         "chaotic", "warnings")

G_N = 9.80665  # standard gravity, for start-up accelerations in g

#: what the unloaded run says (``LoadCurve.free_state``): ``settled`` (a steady drift),
#: ``mean`` (a long-time mean told apart from zero by more than three standard errors),
#: ``not_settled`` (a drift whose run ended before it settled, without an error), ``no_drift``
#: (no drift above the stick threshold: nothing to stall, stall load 0), ``zero_within_error``
#: (a long-time mean within three standard errors of zero: no direction, stall load unknown) and
#: ``no_steady_state`` (a runaway or an ejected particle: no drift at all)
FREE_STATES = ("settled", "mean", "not_settled", "no_drift", "zero_within_error",
               "no_steady_state")


def _run_load(scene_json: str, engine: str) -> dict[str, Any]:
    """Run one loaded scene (in a worker process) and keep its summary fields."""
    result = run(Scene.model_validate_json(scene_json), engine=engine)  # type: ignore[arg-type]
    summary = result.summary()
    return {key: summary.get(key) for key in _KEPT}


@dataclass(frozen=True)
class LoadCurve:
    """Drift speed and output power against the load, and the stall load.

    Loads ``F`` are magnitudes against the unloaded drift, in units of the static normal load
    M g; the applied ``particle.load`` is ``-direction F``. Velocities are drift velocities
    (x* per period, i.e. in units of a0 f) along the unloaded drift: positive while the particle
    advances (along +x where there is no direction). Power is F v in units of M g a0 f.
    ``velocity_se`` is the standard error of a velocity that is a long-time mean, NaN where it
    settled. ``stall_load`` is NaN where the unloaded drift is zero within its error or there is
    none (``free_state``), so that no stall load or power is quoted from noise.
    """

    direction: int
    loads: np.ndarray
    velocities: np.ndarray
    regimes: tuple[str, ...]
    settled: tuple[bool, ...]
    stall_load: float
    stall_bracket: tuple[float, float]
    max_load: float
    threshold: float
    m_star: float
    runs: int
    wall_time_s: float
    #: device scenes: newtons per unit load (M g), m/s per unit velocity (a0 f), particle mass
    device: dict[str, float] | None = None
    #: every run made, {load: summary}
    table: dict[float, dict[str, Any]] = field(default_factory=dict, repr=False)
    #: standard errors of ``velocities`` (a0 f), NaN where the drift settled
    velocity_se: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: each point's warnings (a lower-bound error, a motion still heating up)
    warnings: tuple[tuple[str, ...], ...] = ()
    #: the unloaded drift velocity along +x (a0 f), its standard error, what it says
    free_drift: float = math.nan
    free_drift_se: float = math.nan
    free_state: str = "settled"

    @property
    def power(self) -> np.ndarray:
        """Output power F v (M g a0 f); negative where the particle is pushed back."""
        return self.loads * self.velocities + 0.0  # + 0.0: no -0 at zero load

    @property
    def stall_load_se(self) -> float:
        """Standard error of the stall load where the speed at it is a long-time mean: that
        speed's error over the curve's mean slope, se(v_s) F_s / (v(0) - v_s); NaN where the
        speed at the stall settled (or the curve does not end at the stall)."""
        se = self._se()
        if (self.loads.size < 2 or self.loads[-1] != self.stall_load
                or not math.isfinite(se[-1])):
            return math.nan
        drop = float(self.velocities[0] - self.velocities[-1])
        return float(se[-1] * self.stall_load / drop) if drop > 0.0 else math.nan

    @property
    def max_power(self) -> tuple[float, float]:
        """(largest sampled power, its load); NaN where the stall load is unknown."""
        if not math.isfinite(self.stall_load):
            return math.nan, math.nan
        if self.loads.size == 0:
            return 0.0, 0.0
        i = int(np.argmax(self.power))
        return float(self.power[i]), float(self.loads[i])

    def to_json(self) -> dict[str, Any]:
        """The curve as plain JSON values (NaN as None), with device units on a device."""
        p_max, at = self.max_power
        out: dict[str, Any] = {
            "direction": {1: "+x", -1: "-x"}.get(self.direction, "none"),
            "free_state": self.free_state,
            # along the drift, as the curve is (it was along x: -0.479 beside a curve that
            # starts at +0.479 for a drift to -x)
            "free_drift_velocity": json_value(self._free_along()),
            "free_drift_velocity_se": json_value(self.free_drift_se),
            "loads": self.loads.tolist(),
            "applied_load": (0.0 - self.direction * self.loads).tolist(),
            "drift_velocity": self.velocities.tolist(),
            "drift_velocity_se": [json_value(x) for x in self._se()],
            "power": self.power.tolist(),
            "regimes": list(self.regimes),
            "settled": list(self.settled),
            "warnings": [list(w) for w in self.warnings],
            "stall_load": json_value(self.stall_load),
            "stall_load_se": json_value(self.stall_load_se),
            "stall_bracket": [json_value(x) for x in self.stall_bracket],
            "max_power": json_value(p_max),
            "load_at_max_power": json_value(at),
            "start_acceleration": json_value(self.stall_load / self.m_star),
            "units": {"load": "M g", "drift_velocity": "a0 f", "power": "M g a0 f",
                      "start_acceleration": "a0 f^2",
                      "frame": "loads, drift_velocity and free_drift_velocity along the drift "
                               "(direction); applied_load along +x"},
            "advance_threshold": self.threshold,
            "max_load": self.max_load,
            "runs": self.runs,
            "wall_time_s": self.wall_time_s,
        }
        if self.device is not None:
            out["device"] = self._device_json(p_max, at)
        return out

    def _free_along(self) -> float:
        """The free drift along the drift's direction (as it is, where there is none)."""
        return self.direction * self.free_drift if self.direction else self.free_drift

    def _se(self) -> np.ndarray:
        return self.velocity_se if self.velocity_se.size else np.full(self.loads.size, math.nan)

    def _device_json(self, p_max: float, at: float) -> dict[str, Any]:
        """The curve in mN, m/s and mW (None where a value is unknown)."""
        assert self.device is not None
        force, speed = self.device["force_n"], self.device["speed_m_s"]
        start = force * self.stall_load / self.device["mass_kg"]
        return {
            "loads_mN": (1e3 * force * self.loads).tolist(),
            "speed_m_s": (speed * self.velocities).tolist(),
            "speed_se_m_s": [json_value(speed * x) for x in self._se()],
            "power_mW": (1e3 * force * speed * self.power).tolist(),
            "stall_load_mN": json_value(1e3 * force * self.stall_load),
            "stall_load_se_mN": json_value(1e3 * force * self.stall_load_se),
            "max_power_mW": json_value(1e3 * force * speed * p_max),
            "load_at_max_power_mN": json_value(1e3 * force * at),
            "free_speed_m_s": json_value(speed * self._free_along()),
            "free_speed_se_m_s": json_value(speed * self.free_drift_se),
            "start_acceleration_m_s2": json_value(start),
            "start_acceleration_g": json_value(start / G_N),
            "normal_load_mN": 1e3 * force,
        }


def _value(x: Any) -> float:
    """A run's summary number, NaN for None (no value: no steady state, or settled for an
    error)."""
    return float(x) if x is not None else math.nan


class _Runner:
    """Runs loaded copies of a scene, in parallel where asked, remembering every result."""

    def __init__(self, scene: Scene, engine: str, workers: int) -> None:
        self.scene = scene
        self.engine = engine
        self.workers = workers
        self.table: dict[float, dict[str, Any]] = {}
        #: ``numerics.drift_tolerance`` of the loaded runs (None: the scene's own)
        self.tolerance: float | None = None
        #: the study executor, its process pool kept from round to round
        self.executor = Executor(workers)
        dev = scene.device
        if dev is not None:
            norm = normalized(dev)
            self.newtons = norm["weight_n"]
            self.background = norm["load"] - dev.load / norm["weight_n"]
        else:
            self.newtons = 0.0
            self.background = 0.0

    def loaded(self, applied: float) -> Scene:
        """The scene with the external load ``applied`` (units of M g, signed along +x) and the
        curve's drift tolerance, where set."""
        updates: dict[str, Any] = ({"device.load": applied * self.newtons}
                                   if self.scene.device is not None else
                                   {"particle.load": applied})
        if self.tolerance is not None:
            updates["numerics.drift_tolerance"] = self.tolerance
        return self.scene.with_updates(**updates)

    def run(self, applied: Sequence[float]) -> list[dict[str, Any]]:
        """The summaries of the runs at the loads ``applied``; each run that ends is kept in
        :attr:`table` at once (a Ctrl-C keeps them: :class:`CurveInterrupted`)."""
        todo = [a for a in dict.fromkeys(applied) if a not in self.table]
        scenes = [self.loaded(a).model_dump_json() for a in todo]
        for i, result in self.executor.imap(partial(_run_load, engine=self.engine), scenes):
            if i is not None:
                self.table[todo[i]] = result
        return [self.table[a] for a in applied]

    def interrupted(self) -> CurveInterrupted:
        """What a Ctrl-C leaves: the runs that ended, by load (:class:`CurveInterrupted`)."""
        return CurveInterrupted(dict(self.table), self.newtons)

    def close(self) -> None:
        self.executor.close()


class CurveInterrupted(KeyboardInterrupt):
    """Ctrl-C during a load or force-velocity curve, with the loaded runs that ended: ``table``
    maps each applied load (units of M g, signed along +x) to its run's summary; ``newtons`` is
    M g in N for a device (0 otherwise). A KeyboardInterrupt still, for a caller that does not
    look."""

    def __init__(self, table: dict[float, dict[str, Any]], newtons: float) -> None:
        super().__init__(f"{len(table)} loaded runs ended")
        self.table = table
        self.newtons = newtons


def _surface_speed(scene: Scene) -> float:
    """The regime classifier's velocity scale, asked of the drive: its horizontal surface speed
    (2 pi r A* for the travelling wave), or 2 pi times its vertical amplitude without one."""
    drive = scene.drive
    if not isinstance(drive, Wave):
        raise SceneError(f"drive.kind = {drive.kind!r}: a load curve needs a wave drive")
    part = drive_of(scene)
    u = part.horizontal_speed(scene)
    return u if u > 0.0 else 2.0 * math.pi * part.vertical_amplitude(scene)


def load_curve(
    scene: Scene,
    *,
    loads: int = 16,
    settle: bool | None = None,
    tolerance: float = 1e-3,
    workers: int | None = None,
    engine: str = "compiled",
    progress: Callable[[str], None] | None = None,
) -> LoadCurve:
    """Drift speed and output power of ``scene`` against a tangential load, up to the stall load.

    Parameters
    ----------
    scene
        A wave scene (normalized or a device). Its own ``particle.load`` (``device.load``) is
        replaced by the curve's loads; a device's incline stays (its pull is part of the scene).
    loads
        Points of the curve, evenly from 0 to the stall load (both included), >= 2.
    settle
        Override ``numerics.settle`` (None keeps the scene's): heavy particles need it.
    tolerance
        Width of the final stall bracket, relative to the largest possible stall load F_max.
    workers
        Local processes (default: all cores); 1 runs everything in this process.
    engine
        ``"compiled"`` or ``"python"``.
    progress
        Called with a short line after each stage (the command line prints it).

    Raises
    ------
    SceneError
        One line: fewer than 2 loads, a tolerance outside (0, 0.5), a drive that is not a wave.
    """
    if not isinstance(loads, int) or loads < 2:
        raise SceneError(f"loads = {loads!r}: a load curve needs at least 2 loads (an integer)")
    if not 0.0 < tolerance < 0.5:
        raise SceneError(f"tolerance = {tolerance!r} is outside (0, 0.5)")
    if engine not in ("compiled", "python"):
        raise SceneError(f"engine = {engine!r} is not allowed; use 'compiled' or 'python'")
    speed = _surface_speed(scene)
    if settle is not None:
        scene = scene.with_updates(**{"numerics.settle": bool(settle)})
    scene = bind(scene)  # a wrong model parameter: one line before any run
    workers = max(1, int(workers if workers is not None else (os.cpu_count() or 1)))
    t0 = time.perf_counter()
    runner = _Runner(scene, engine, workers)
    note = progress or (lambda _line: None)
    try:
        curve = _curve(scene, runner, speed, loads, tolerance, note)
    except KeyboardInterrupt:
        raise runner.interrupted() from None
    finally:
        runner.close()
    return LoadCurve(**curve, runs=len(runner.table), wall_time_s=time.perf_counter() - t0,
                     device=_device_scales(scene), table=dict(runner.table))


def _free_state(free: dict[str, Any], threshold: float, speed: float) -> tuple[int, str, float]:
    """(direction, state, standard error in a0 f) of the unloaded run (:data:`FREE_STATES`)."""
    v0 = _value(free["drift_velocity"])
    se = _value(free.get("drift_ratio_se")) * speed
    if not math.isfinite(v0):
        return 0, "no_steady_state", se
    if math.isfinite(se) and abs(v0) <= 3.0 * se:
        return 0, "zero_within_error", se
    if abs(v0) <= threshold:
        return 0, "no_drift", se
    state = "settled" if free["settled"] else ("mean" if math.isfinite(se) else "not_settled")
    return (1 if v0 > 0.0 else -1), state, se


def _advance_tolerance(scene: Scene, free_drift: float, speed: float) -> float:
    """The drift tolerance of a load curve's loaded runs: the scene's ``drift_tolerance`` times
    the unloaded drift over the surface speed ``speed``, so that "advances" means a drift above
    that fraction of the free drift, but not below the absolute accuracy a run settles its drift
    ratio to (:func:`~sawdrift.dynamics.approach.relative_bound` of a zero drift, 2e-5 by
    default, as the validation family "steady drift against full-inertia brute force" holds it;
    the SAW motor at 5 nm, free drift ratio 4.2e-3, has settled drifts of +-8.8e-6 about zero
    from 0.02 to 0.17 mN), nor above the scene's own tolerance, which also bounds that floor."""
    tol = scene.numerics.drift_tolerance
    floor = relative_bound(0.0, scene.numerics.settle_tolerance)
    return min(tol, max(tol * abs(free_drift) / speed, floor))


def _curve(scene: Scene, runner: _Runner, speed: float, n: int, tolerance: float,
           note: Callable[[str], None]) -> dict[str, Any]:
    free = runner.run([0.0])[0]
    v0 = _value(free["drift_velocity"])
    tol = scene.numerics.drift_tolerance
    direction, state, se0 = _free_state(free, tol * speed, speed)
    if direction != 0:
        runner.tolerance = tol = _advance_tolerance(scene, v0, speed)
    threshold = tol * speed
    note(f"without load: drift velocity {v0:.6g} ({free['regime']})")
    f_max = holding_bound(scene) + direction * runner.background
    if scene.effects.rotation and holding_bound(scene) <= 0.0:
        note("a sphere free to turn with no rolling resistance holds no load: the least load "
             "rolls it away, so the stall load is 0")
    common = {"threshold": threshold, "m_star": scene.particle.m_star, "free_drift": v0,
              "free_drift_se": se0, "free_state": state}
    if direction == 0 or f_max <= 0.0:
        # nothing to hold against: the curve is the single unloaded point; its stall load is 0
        # where there is no drift, unknown (NaN) where the drift is zero only within its error
        stall = 0.0 if state == "no_drift" or direction != 0 else math.nan
        return {"direction": direction, "loads": np.zeros(1),
                "velocities": np.array([abs(v0) if direction else v0]),
                "velocity_se": np.array([se0]), "warnings": (_warnings(free),),
                "regimes": (str(free["regime"]),), "settled": (bool(free["settled"]),),
                "stall_load": stall, "stall_bracket": (stall, stall),
                "max_load": max(f_max, 0.0), **common}

    def advances(f: float) -> bool:
        # a load that runs away (no drift velocity) holds the particle back for good
        return direction * _value(runner.table[-direction * f]["drift_velocity"]) > threshold

    lo, hi = 0.0, f_max  # advances at lo; at hi (= F_max) nothing can advance
    k = runner.workers + 1
    while hi - lo > tolerance * f_max:
        points = [lo + (hi - lo) * j / k for j in range(1, k)]
        runner.run([-direction * f for f in points])
        for f in points:
            if advances(f):
                lo = f
            else:
                hi = f
                break
        note(f"stall load in [{lo:.6g}, {hi:.6g}] M g")
    stall = hi
    # the curve ends at the stall load; if the particle advanced at every load tried, the stall
    # is F_max by the bound above, which is not run (against it the particle accelerates back
    # for ever and never settles): the curve then ends at the largest load tried
    grid = np.linspace(0.0, hi if hi < f_max else lo, n)
    rows = runner.run([-direction * float(f) for f in grid])
    note(f"{n} loads from 0 to the stall load {stall:.6g} M g")
    return {
        "direction": direction, "loads": grid,
        "velocities": np.array([direction * _value(r["drift_velocity"]) for r in rows]),
        "velocity_se": np.array([_value(r.get("drift_ratio_se")) * speed for r in rows]),
        "warnings": tuple(_warnings(r) for r in rows),
        "regimes": tuple(str(r["regime"]) for r in rows),
        "settled": tuple(bool(r["settled"]) for r in rows),
        "stall_load": stall, "stall_bracket": (lo, hi), "max_load": f_max, **common,
    }


def _warnings(row: dict[str, Any]) -> tuple[str, ...]:
    return tuple(str(w) for w in row.get("warnings") or ())


def _device_scales(scene: Scene) -> dict[str, float] | None:
    if scene.device is None:
        return None

    norm = normalized(scene.device)
    return {"force_n": norm["weight_n"], "speed_m_s": norm["a0_m"] * norm["frequency_hz"],
            "mass_kg": norm["mass_kg"]}
