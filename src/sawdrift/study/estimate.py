"""Size before time: the work of a run or a study, estimated before it starts.

A study states its size before it computes: cells (runs), integration steps and a wall time.
The steps of one run follow from its scene as the runner plans it
(:func:`cell_steps`): ``numerics.periods`` times the steps per period of
:func:`sawdrift.dynamics.assembly.steps_per_period`, and for a settling run (a heavy particle,
:func:`sawdrift.dynamics.steady.settles`) the expected length of the settle, of order ten
relaxation times m*_x/mu of the reduced inertia plus two windows, capped by
``numerics.max_periods``; a default light run :data:`GOES_ON` times its fixed length (it goes
on where its window cannot confirm its drift); where the drift is solved directly (m* >= 5, a
plain wave scene: :mod:`sawdrift.dynamics.separated`) the fixed length and one evidence window
(one slow vertical cycle for a hopping particle), and three full-inertia windows where it is
confirmed (from m* = 3, or ``numerics.confirm_solved``). The
time divides the steps by a rate in steps per second measured on a short calibration run of the
same model and engine (:func:`calibrate`: about 2e4 steps, the compiled loop loaded first) and
by the workers (the harmonic mean over up to three sampled cells: steady slides run faster
than cells with contact loss and events), plus the fixed cost of each run.

A study whose estimate exceeds :data:`MAX_SECONDS` is refused in one line unless the user says
``--yes`` (:func:`check`); the line says what was estimated and how to make it smaller.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from ..contact.registry import get_model
from ..dynamics import steady
from ..dynamics.assembly import steps_per_period
from ..dynamics.full_inertia import full_window_length
from ..dynamics.integrate import DEFAULT_PERIODS, SETTLE_ON_PERIODS
from ..dynamics.separated import SOLVED_MIN_MASS, solvable
from ..errors import NonFiniteStateError, SawdriftError, SceneError
from ..result.runner import run
from ..scene.schema import Scene, Wave
from .executor import resolve_workers
from .progress import notice

#: estimated wall time (s) above which a command asks for --yes before it starts
MAX_SECONDS = 3600.0

#: a single run with fewer expected steps than this starts without a word (seconds of work)
QUIET_STEPS = 2e7

#: a default light run (``numerics.settle`` and ``numerics.periods`` unset) is expected to cost
#: this many times its fixed length: it goes on where its window cannot confirm its drift
#: (settled windows, a periodic orbit, a chaotic or irregular cell's 2000-period long-time
#: mean). It stands for time, not steps: a run that goes on spends more of its time outside
#: the integration (windows' evidence, the solves, the Lyapunov stretchings) than the fixed
#: calibration run the rate comes from. On the default 41 x 41 mmd sweep of ``sawdrift bench
#: speed`` (m* 1e-3..1e2, A* 1e-2..10) the estimate reads 7.7 s against 6.0 s measured, 1.4e8
#: steps against 4.8e7 (its fixed sweep: 2.3 s against 3.2 s), on the 2-core machine
#: (2026-11-28)
GOES_ON = 3.7

#: steps of a calibration run (compiled engine; the python engine runs a tenth of it)
CALIBRATION_STEPS = 20_000


@dataclass(frozen=True)
class Estimate:
    """The size of a run or study: cells, expected and largest steps, and a rate (steps/s)."""

    what: str
    cells: int
    steps: float
    most: float
    rate: float
    workers: int = 1
    unit: str = "cell"
    overhead: float = 0.0

    @property
    def seconds(self) -> float:
        """Expected wall time: (steps / rate + cells x the fixed cost of a run) over the workers
        that have cells to run."""
        busy = max(1, min(self.workers, self.cells))
        if self.rate <= 0:
            return math.inf
        return (self.steps / self.rate + self.cells * self.overhead) / busy

    def line(self) -> str:
        """``sweep: 225 cells, about 3.4e+07 steps (at most 9e+07), about 40 s on 2 workers ...``"""
        cells = (f"{self.cells} {self.unit}{'s' if self.cells != 1 else ''}, " if self.cells > 1
                 else "")
        most = f" (at most {self.most:.2g})" if self.most > 1.5 * self.steps else ""
        where = f" on {min(self.workers, self.cells)} workers" if min(self.workers, self.cells) > 1 else ""
        took = duration(self.seconds)
        took = took if took.startswith("under") else f"about {took}"
        return (f"{self.what}: {cells}about {self.steps:.2g} steps{most}, {took}{where} at "
                f"{self.rate:.3g} steps/s (calibrated)")


def duration(seconds: float) -> str:
    """``40 s``, ``12 min``, ``3.1 h``, ``52 days``."""
    if not math.isfinite(seconds):
        return "forever"
    if seconds < 1:
        return "under 1 s"
    if seconds < 120:
        return f"{seconds:.2g} s"
    if seconds < 3600:
        return f"{seconds / 60:.3g} min"
    if seconds < 172800:
        return f"{seconds / 3600:.3g} h"
    return f"{seconds / 86400:.3g} days"


def cell_steps(scene: Scene) -> tuple[float, float]:
    """(expected, largest) integration steps of one run of ``scene`` (module docstring)."""
    rigid = get_model(scene.model).capabilities.rigid
    k = steps_per_period(scene, rigid)
    num = scene.numerics
    fixed = max(num.periods, float(scene.measure_periods()))
    amp = scene.drive.amplitude if isinstance(scene.drive, Wave) else 1.0
    speed = 2.0 * math.pi * scene.horizontal_ratio * amp
    if not steady.settles(scene, speed, rigid):
        if num.settle is None and num.periods == DEFAULT_PERIODS:
            # a default run its window cannot confirm goes on (windows, a periodic orbit, a
            # long-time mean): on average GOES_ON times its fixed length, at most its budgets more
            most = fixed + SETTLE_ON_PERIODS + num.mean_periods
            return GOES_ON * fixed * k, most * k
        return fixed * k, fixed * k
    m = scene.particle.m_star
    m_x = steady.horizontal_inertia(m, rigid)
    tau = steady.relaxation_periods(scene, m_x, speed)
    window = steady.window_length(m, tau, scene.measure_periods(), rigid)
    cap = num.max_periods or steady.default_max_periods(m, tau, rigid, scene.measure_periods())
    expected = min(cap, max(fixed, num.periods + 8.0 * tau + 2.0 * window))
    if solvable(scene, rigid):
        # the drift solved directly, with one evidence window: the measuring window itself, or
        # one slow vertical cycle (about a third of a full-inertia window) for a particle that
        # hops (a heavy one loses contact where the wave outreaches its rest compression,
        # A* > 1); the confirmation asked for takes two to four full-inertia windows
        full = full_window_length(m, scene.theta, scene.measure_periods())
        extra = full / 3.0 if amp > 1.0 else 0.0
        confirm = num.confirm_solved or m < SOLVED_MIN_MASS  # below it the windows confirm
        expected = min(expected, num.periods + (3.0 * full if confirm else extra))
    return expected * k, max(fixed, cap) * k


def _rates(picked: list[Scene], sample: list[Scene], engine: str) -> list[tuple[float, float]]:
    """:func:`calibrate` of the ``picked`` cells; a cell whose model fails (its own error row in
    a sweep) is passed over for the next cell of the ``sample`` that runs: a failing probe at the
    grid's first value aborted the whole sweep, where the same cells in another order ran and
    tabled their errors. The first error is raised only where no cell of the sample runs."""
    rates, first = [], None
    for scene in [*picked, *(s for s in sample if s not in picked)]:
        if len(rates) == len(picked):
            break
        try:
            rates.append(calibrate(scene, engine))
        except SawdriftError as exc:
            first = first or exc
    if not rates:
        raise first  # type: ignore[misc]
    return rates


def calibrate(scene: Scene, engine: str = "compiled") -> tuple[float, float]:
    """(steps per second, fixed seconds per run) of ``scene``'s model on ``engine``.

    Two short runs of the same scene, about :data:`CALIBRATION_STEPS` steps each at the scene's
    steps per period (at most 4096), fixed length, no settle: the first loads the compiled loop,
    the second is timed; its integration (``Result.wall_time_s``) gives the rate, the rest of
    its call (building, binding, the summary) the fixed cost of a run. Where 4096 steps a period
    are too coarse for the contact (mmd m* = 1e-8 needs 229575: its state went non-finite at step
    48, and the CLI refused a scene ``sawdrift.run`` integrates), the probe runs at the scene's
    own step, over two periods.
    """
    own = steps_per_period(scene)
    try:
        return _timed_probe(scene, min(own, 4096), engine)
    except NonFiniteStateError:
        if own <= 4096:
            raise  # the scene's own step: the run itself would fail the same way
        return _timed_probe(scene, own, engine)


def _timed_probe(scene: Scene, k: int, engine: str) -> tuple[float, float]:
    """:func:`calibrate` at ``k`` steps per period."""
    steps = CALIBRATION_STEPS if engine == "compiled" else CALIBRATION_STEPS // 10
    # a fixed run of its own length: the scene's period cap is not its (a cap below the probe's
    # periods refused the probe, and every sweep with it)
    probe = scene.with_updates(**{"numerics.steps_per_period": k, "numerics.settle": False,
                                  "numerics.periods": max(2.0, steps / k),
                                  "numerics.measure_periods": 1, "numerics.max_periods": None})
    run(probe, engine=engine)  # type: ignore[arg-type]
    t0 = time.perf_counter()
    result = run(probe, engine=engine)  # type: ignore[arg-type]
    total = time.perf_counter() - t0
    return result.steps / max(result.wall_time_s, 1e-6), max(total - result.wall_time_s, 0.0)


def estimate(what: str, scenes: list[Scene], cells: int, workers: int = 1,
             engine: str = "compiled", runs_per_cell: float = 1.0,
             extra_steps: float = 0.0, unit: str = "cell") -> Estimate:
    """The size of ``cells`` runs like the sample ``scenes`` (their mean steps), calibrated.

    ``runs_per_cell`` counts runs per cell, ``extra_steps`` adds steps to each run (a
    bifurcation value's Poincare samples), ``unit`` names a cell (run, point, value).
    """
    if not scenes:
        raise ValueError("estimate needs at least one sample scene")
    counts = [cell_steps(s) for s in scenes]
    mean = sum(c[0] for c in counts) / len(counts) + extra_steps
    most = max(c[1] for c in counts) + extra_steps
    # the rate differs between cells (contact loss and events cost more than a steady slide):
    # calibrate on up to three sampled cells, spread over the sample
    picked = [scenes[i] for i in sorted({0, len(scenes) // 2, len(scenes) - 1})]
    # a cold cache compiles the loops here, in silence for up to half a minute before any
    # estimate: a line once it takes more than a second
    with notice(f"{what}: calibrating the size estimate (the first use after installing "
                "compiles the contact loops: up to half a minute)"):
        rates = _rates(picked, scenes, engine)
    rate = len(rates) / sum(1.0 / r for r, _ in rates)  # the mean time per step
    overhead = sum(o for _, o in rates) / len(rates)
    n = cells * runs_per_cell
    return Estimate(what, cells, mean * n, most * n, rate, workers, unit, overhead * runs_per_cell)


def check(est: Estimate, yes: bool, bound: float | None = None, smaller: str = "") -> None:
    """Refuse (one line, SceneError) an estimate above ``bound`` seconds (by default
    :data:`MAX_SECONDS`, read when called) unless ``yes``."""
    bound = MAX_SECONDS if bound is None else bound
    if yes or est.seconds <= bound:
        return
    hint = f"; or {smaller}" if smaller else ""
    raise SceneError(f"{est.line()}: above {duration(bound)}; give --yes to start it anyway{hint}")


def announce(est: Estimate) -> None:
    """Print the estimate's line on stderr."""
    sys.stderr.write(est.line() + "\n")
    sys.stderr.flush()


def size_check(what: str, scenes: list[Scene], cells: int, *, workers: int | None = None,
               engine: str = "compiled", yes: bool = False, show: bool = True,
               smaller: str = "", **kwargs: Any) -> Estimate:
    """Estimate, print (``show``) and :func:`check` a study before it starts; returns the estimate."""
    est = estimate(what, scenes, cells, resolve_workers(workers), engine, **kwargs)
    check(est, yes, smaller=smaller)  # a refusal is its one line
    if show:
        announce(est)
    return est


def _sample(values: Sequence[Any] | None) -> list[Any] | None:
    """First, middle and last of an axis's values (a sample for the size estimate)."""
    if values is None:
        return None
    values = list(values)
    picks = sorted({0, len(values) // 2, len(values) - 1})
    return [values[i] for i in picks]


def estimate_sweep(grid: Callable[..., list[Scene]], names: Sequence[str], m_star: Sequence[float] | None,
                   amplitude: Sequence[float] | None, extra_axes: dict[str, list[Any]],
                   points: Sequence[tuple[float, float]] | None, base: Scene | None,
                   overrides: dict[str, Any] | None, workers: int | None, engine: str,
                   what: str = "sweep") -> Estimate:
    """The size of a sweep before its grid is built (``grid``: :func:`sawdrift.study.sweep.grid`).

    Cells: models x every axis's length (or the points); steps: the mean over a sample of
    cells (each axis's first, middle and last value; the first model only when the sample would
    pass 64 cells); the rate from a calibration run of the first sampled cell.
    """
    lengths = [len(v) for v in extra_axes.values()]
    if points is not None:
        lengths.append(len(points))
        m_star, amplitude = [p[0] for p in points], [p[1] for p in points]
    else:
        lengths += [len(v) for v in (m_star, amplitude) if v is not None]
    cells = len(names) * math.prod(lengths)
    picked = {f: _sample(v) for f, v in extra_axes.items()}
    sample_models = list(names) if len(names) * 27 ** (len(lengths) / 3) <= 64 else list(names[:1])
    sample = grid(sample_models, _sample(m_star), _sample(amplitude), base, overrides, picked)
    return estimate(what, sample, cells, resolve_workers(workers), engine)
