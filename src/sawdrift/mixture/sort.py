"""Sorting times of a mixture: an ensemble of random placements moved by the slow model of chains.

For each placement seed the scene's ``[particles]`` table places the beads (random species order,
:func:`sawdrift.lammps.placement.placement`), the slow model moves them (``geometry="plane"``:
in 2-D on the plate, :mod:`.plane`, where a bead slides round another; ``"line"``: in lanes
along the wave from contact to contact, :mod:`.events`), and the segregation of the positions
(:mod:`.segregation`: the purity of the best interface, its index against random orders, the
Lacey index) is measured at sample times spaced logarithmically from one period to the end.
Over the ensemble: the mean and the spread (standard deviation) of each measure against time,
in wave periods and in seconds of device time, the time from which the purity, oriented with the
species the wave drives to +x on the right, stays at or above a target in each placement (linear
between samples), and the final state (chains or clusters of
touching beads, their sizes, each species' mean speed).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import SceneError
from ..lammps.placement import Particles, check_many, parse_particles, placement, species_of
from ..lammps.realize import realize
from ..scene.schema import Scene
from .chains import Bead
from .curves import Source, curves_for
from .events import SlowModel, SlowRun
from .plane import PUSHED_APART, TOLERANCE, PlaneModel, PlaneRun, jitter, worst_overlap
from .segregation import lacey_segregation, purity, purity_index

__all__ = ["PLANE", "VALIDATED", "SortResult", "slow_window", "sort_mixture", "time_to"]

GEOMETRIES = ("plane", "line")

#: what the checks against damped LAMMPS showed (docs/lammps.md, validation case lammps_chains)
VALIDATED = (
    "accuracy (chains placed by hand in damped LAMMPS, curves of LAMMPS's Coulomb rule, "
    "docs/mixtures.md): the large beads' speed within 0.2 % at e = 0.5 (six chains) and 1.9 % at "
    "e = 0.9; their slowdown by the small beads within 1 % (10 small + 1 large, e = 0.5), 9 % "
    "(the same, e = 0.9) and 25 % (a mixed chain of 20, e = 0.9). Not in the model: at e = 0.9 "
    "LAMMPS's first impact knocks a small bead behind a large one into a backward drift (-0.96) "
    "instead of a chain; the native curves and LAMMPS's rule agree on the free beads (on "
    "examples/mixture.toml's 1 mm bead: -0.3187 native, -0.3189 LAMMPS's rule at e = 0.9)")

#: the warning of a run whose bead contacts are undamped (no restitution below 1, no damping)
UNDAMPED = ("undamped contacts: in LAMMPS the first touch throws a small bead into bouncing; the "
            "slow model assumes steady contacts and was checked at e = 0.5 and 0.9 only: give "
            "material.restitution (--restitution) below 1")

#: what the 2-D model assumes beyond the checked chains (docs/mixtures.md, "The 2-D model")
PLANE = (
    "2-D: a line of beads along the wave moves as the checked chains (within 0.02 % of their "
    "common speed); across the wave a bead moves at its transverse mobility, assumed to be the "
    "secant of its own force-velocity curve through its free drift (not computed by the planar "
    "engine; scaling it by 0.3 or 3 changes the time to 90 % purity of examples/mixture.toml by "
    "{sensitivity}; this run: x {perp:g}); rows are broken by a jitter of {jitter:g} small radii "
    "across the wave")

#: measured: time to 90 % purity of examples/mixture.toml with the transverse mobility x 0.3, x 3
SENSITIVITY = "+74 % and -18 % (2.82e7 and 1.32e7 against 1.61e7 periods)"
LINE = ("1-D: beads in lanes along the wave cannot pass each other; the y part of an off-centre "
        "contact is left out")

MEASURES = ("purity", "purity_index", "lacey")


#: the largest --jitter, in small radii: a nudge that breaks exactly head-on rows, not a new
#: placement (1e308 ran, with beads thrown 1e305 m apart)
MAX_JITTER = 1.0


def time_to(times: np.ndarray, values: np.ndarray, target: float) -> float:
    """The time from which ``values`` stays at or above ``target`` to the end (linear between
    samples); NaN where the last value is below it. A bed that reaches the purity and loses it
    again is not sorted at that time (nor at all, if it ends below)."""
    below = np.flatnonzero(~(values >= target))
    if below.size and below[-1] == values.size - 1:
        return math.nan
    k = int(below[-1]) + 1 if below.size else 0
    if k == 0:
        return float(times[0])
    v0, v1 = values[k - 1], values[k]
    return float(times[k - 1] + (times[k] - times[k - 1]) * (target - v0) / (v1 - v0))


@dataclass
class SortResult:
    """An ensemble of slow runs and its statistics (module docstring)."""

    periods: np.ndarray  # sample times, wave periods
    frequency: float
    seeds: list[int]
    measures: dict[str, np.ndarray]  # name -> (seeds, samples)
    target: float
    runs: list[SlowRun] = field(repr=False, default_factory=list)
    species: list[dict[str, Any]] = field(default_factory=list)
    wall_time_s: float = 0.0
    curve_source: str = "native"
    curve_wall_s: float = 0.0
    geometry: str = "plane"
    jitter: float = 0.0
    perp: float = 1.0
    #: where the scene leaves the model's checked range (:data:`UNDAMPED`)
    warnings: tuple[str, ...] = ()
    #: the species the wave drives to +x (the larger free drift): the purity's orientation
    right: int | None = None
    #: stopped by Ctrl-C: ``seeds`` are the placements that ended before it
    interrupted: bool = False

    @property
    def seconds(self) -> np.ndarray:
        return self.periods / self.frequency

    def times_to_target(self) -> np.ndarray:
        """Periods from which the purity stays at or above the target, per seed (NaN: not within
        the run, :func:`time_to`)."""
        return np.array([time_to(self.periods, p, self.target) for p in self.measures["purity"]])

    def summary(self) -> dict[str, Any]:
        """JSON-ready: measures' mean and spread against time, time to the target, final state."""
        hit = self.times_to_target()
        ok = hit[np.isfinite(hit)]

        def stat(v: np.ndarray) -> dict[str, Any]:
            return {"mean": float(v.mean()) if v.size else None,
                    "std": float(v.std(ddof=1)) if v.size > 1 else None}

        final_chains = [len(r.chains) for r in self.runs]
        sizes = [len(c) for r in self.runs for c in r.chains]
        if self.geometry == "line":
            cost = {"merges": stat(np.array([r.merges for r in self.runs], dtype=float)),
                    "splits": stat(np.array([r.splits for r in self.runs], dtype=float))}
        else:
            cost = {"steps": stat(np.array([r.steps for r in self.runs], dtype=float)),
                    "largest_overlap_over_tolerance": float(max(r.max_overlap
                                                                for r in self.runs))}
        return {
            "seeds": self.seeds, "count": int(self.runs[0].kinds.size) if self.runs else 0,
            "frequency_hz": self.frequency, "periods": self.periods.tolist(),
            "seconds": self.seconds.tolist(),
            # one placement has no spread: null, not NaN (which strict JSON refuses)
            "over_time": {k: {"mean": v.mean(axis=0).tolist(),
                              "std": v.std(axis=0, ddof=1).tolist() if v.shape[0] > 1 else None}
                          for k, v in self.measures.items()},
            "target_purity": self.target,
            "time_to_target": {
                "reached": int(ok.size), "of": int(hit.size),
                "periods": stat(ok), "seconds": stat(ok / self.frequency),
                "per_seed_periods": [float(h) if math.isfinite(h) else None for h in hit]},
            "final": {**{k: stat(v[:, -1]) for k, v in self.measures.items()},
                      "chains": stat(np.array(final_chains, dtype=float)),
                      "mean_chain_size": float(np.mean(sizes)) if sizes else None,
                      "largest_chain": int(max(sizes)) if sizes else None, **cost},
            "species": self.species, "curve_source": self.curve_source,
            "curve_wall_time_s": self.curve_wall_s, "wall_time_s": self.wall_time_s,
            "geometry": self.geometry, "jitter_small_radii": self.jitter,
            "interrupted": self.interrupted,
            "transverse_mobility_factor": self.perp,
            "validated": VALIDATED,
            "warnings": list(self.warnings),
            "assumed": PLANE.format(sensitivity=SENSITIVITY, jitter=self.jitter, perp=self.perp)
            if self.geometry == "plane" else LINE,
        }


def _sample_periods(periods: float, per_decade: int) -> np.ndarray:
    """0, then ``per_decade`` times a decade from 1 period (every decade itself) to ``periods``."""
    grid = 10.0 ** (np.arange(0, int(math.floor(math.log10(periods) * per_decade + 1e-9)) + 1)
                    / per_decade)
    return np.concatenate(([0.0], grid, [periods] if grid[-1] < periods * (1 - 1e-12) else []))


def _check_jitter(spec: Particles, species: list, beads: list[Bead], seeds: list[int],
                  jitter_radii: float) -> None:
    """Refuse, before any curve is computed, a ``--jitter`` that presses the beads of a 2-D
    placement together by more than the model pushes apart (:data:`~.plane.PUSHED_APART`
    tolerances, 0.1 small radius): close rows (a small ``particles.spacing``) moved across the
    wave by a large jitter (spacing 1.05 with a jitter of 0.3 ended in an internal failure)."""
    r_min = min(sp.radius for sp in species)
    rad = np.array([b.radius for b in beads])
    hgt = np.array([b.height for b in beads])
    allowed = PUSHED_APART * TOLERANCE * r_min
    for seed in seeds:
        xy, kinds, _, _ = placement(spec.model_copy(update={"seed": seed}), species)
        y = jitter(xy[:, 1], jitter_radii * r_min, seed)
        ov, i, j = worst_overlap(xy[:, 0], y, np.asarray(kinds, dtype=np.int64), rad, hgt)
        if ov > allowed:
            raise SceneError(
                f"--jitter = {jitter_radii:g}: it presses beads {i} and {j} of placement {seed} "
                f"together by {ov / r_min:.2g} small radii, more than the "
                f"{PUSHED_APART * TOLERANCE:g} the 2-D model pushes apart; give a smaller "
                "--jitter or a larger particles.spacing")


#: the most random placements of one sort (or LAMMPS ensemble): each is a run of its own
MAX_SEEDS = 10_000


def sort_mixture(scene: Scene, particles: Particles | dict[str, Any], *, seeds: int = 20,
                 periods: float = 1e9, samples: int = 12, target: float = 0.9,
                 source: Source = "native", geometry: str = "plane", perp: float = 1.0,
                 jitter_radii: float = 1e-3, workers: int = 2,
                 progress: Callable[[str], None] | None = None) -> SortResult:
    """Run ``seeds`` random placements of ``particles`` on ``scene`` with the slow model.

    Parameters
    ----------
    scene
        A device scene (the slow model works in SI units) with a LAMMPS-style contact law.
    particles
        The ``[particles]`` table; its ``seed`` is the first placement's, then seed + 1, ...
        Explicit positions run once (they have no seed).
    seeds
        Placements, >= 1 (>= 20 for a spread worth quoting).
    periods
        Length of each run in wave periods (the slow model's cost does not grow with it).
    samples
        Sample times per decade of periods after t = 0, from one period.
    target
        Purity from which on the time is reported (:func:`time_to`), in (0.5, 1].
    source
        ``"native"`` (the engine's force-velocity curves) or ``"lammps_rule"`` (LAMMPS's Coulomb
        rule for the stored spring, :mod:`sawdrift.lammps.damped`).
    geometry
        ``"plane"`` (2-D, :mod:`.plane`) or ``"line"`` (lanes along the wave, :mod:`.events`).
    perp
        Factor on the transverse mobility of the 2-D model (1: its stated assumption).
    jitter_radii
        2-D: each bead moved across the wave by this many smallest radii times a standard normal
        number (seeded by the placement), so that rows along the wave are not exactly head-on.
    workers
        Placements run at once (2-D; threads).
    """
    spec = particles if isinstance(particles, Particles) else parse_particles(particles)
    if scene.device is None:
        raise SceneError("sort needs a device scene ([device]): the slow model works in SI units")
    check_many(scene)
    if len(spec.radius) != 2:
        raise SceneError("particles.radius: sorting needs two species (two radii)")
    r0, r1 = spec.radii_m()
    if math.isclose(r0, r1, rel_tol=1e-9):
        raise SceneError(f"particles.radius = {list(spec.radius)}: sorting needs two different "
                         "radii (one species cannot segregate from itself)")
    if not 0.5 < target <= 1.0:
        raise SceneError(f"--purity = {target!r}: give a purity in (0.5, 1]")
    if not periods >= 1.0 or not math.isfinite(periods):
        raise SceneError(f"--until = {periods!r}: give at least 1 wave period")
    if not 1 <= seeds <= MAX_SEEDS:
        # 1e14 reached the placements' arrays as "out of memory ... fewer periods, cells"
        raise SceneError(f"--seeds = {seeds}: give 1 to {MAX_SEEDS} placements")
    if geometry not in GEOMETRIES:
        raise SceneError(f"--geometry = {geometry!r}: use 'plane' or 'line'")
    if not (perp > 0.0 and math.isfinite(perp)):
        raise SceneError(f"--transverse = {perp!r}: give a positive factor")
    if not 0.0 <= jitter_radii <= MAX_JITTER:
        raise SceneError(f"--jitter = {jitter_radii!r}: give a number of small radii in [0, "
                         f"{MAX_JITTER:g}] (a nudge that breaks exactly head-on rows)")
    _both_species(spec)
    real = realize(scene)
    species = species_of(scene, spec, real)
    g = scene.device.gravity
    beads = [Bead(s.radius, s.a0, s.mass * g) for s in species]
    seed_list = [spec.seed] if spec.positions is not None else list(range(spec.seed, spec.seed + seeds))
    r_min = min(sp.radius for sp in species)
    if geometry == "plane":
        _check_jitter(spec, species, beads, seed_list, jitter_radii)
    t0 = time.perf_counter()
    curves = curves_for(scene, [s.radius for s in species], source=source, progress=progress)
    curve_wall = time.perf_counter() - t0
    u = 2.0 * math.pi * real.frequency * real.ratio * real.amplitude * real.horizontal
    right = 1 if curves[1].free > curves[0].free else 0  # driven to +x: the purity's orientation
    grid = _sample_periods(periods, samples)
    cache: dict[tuple, Any] = {}

    def one(seed: int) -> tuple[np.ndarray, SlowRun | PlaneRun]:
        xy, kinds, _, _ = placement(spec.model_copy(update={"seed": seed}), species)
        if geometry == "line":
            run: SlowRun | PlaneRun = SlowModel(xy[:, 0], xy[:, 1], kinds, beads, curves, u,
                                                cache=cache).run(grid / real.frequency)
        else:
            y = jitter(xy[:, 1], jitter_radii * r_min, seed)
            run = PlaneModel(xy[:, 0], y, kinds, beads, curves, u,
                             perp=perp).run(grid / real.frequency)
        if progress is not None:  # as each placement ends (they were told after the last)
            what = (f"{run.merges} merges, {run.splits} splits" if isinstance(run, SlowRun)
                    else f"{run.steps} steps")
            progress(f"seed {seed} of {seed_list[0]}-{seed_list[-1]}: {what}, "
                     f"{run.wall_time_s:.2g} s")
        return kinds, run

    done = _placements(one, seed_list, workers if geometry == "plane" else 1)
    ended = seed_list[:len(done)]  # all of them, unless Ctrl-C stopped the rest
    runs, values = [], {k: [] for k in MEASURES}
    for kinds, run in done:
        runs.append(run)
        values["purity"].append([purity(row, kinds, right) for row in run.x])
        values["purity_index"].append([purity_index(row, kinds, right) for row in run.x])
        values["lacey"].append([lacey_segregation(row, kinds) for row in run.x])
    rows = []
    for k, (sp, cv) in enumerate(zip(species, curves, strict=True)):
        final = np.concatenate([r.speeds[r.kinds == k] for r in runs])
        rows.append({"radius_m": sp.radius, "count": sp.count, "free_drift_ratio": cv.free,
                     "free_speed_m_s": cv.free * u,
                     "final_mean_drift_ratio": float(final.mean()),
                     "carried_against_own_drift": float(np.mean(np.sign(final) != np.sign(cv.free)))})
    return SortResult(periods=grid, frequency=real.frequency, seeds=ended,
                      measures={k: np.array(v) for k, v in values.items()}, target=target,
                      runs=runs, species=rows, wall_time_s=time.perf_counter() - t0,
                      curve_source=source, curve_wall_s=curve_wall, geometry=geometry,
                      jitter=jitter_radii if geometry == "plane" else 0.0, perp=perp,
                      warnings=_warnings(scene), right=right,
                      interrupted=len(ended) < len(seed_list))


def _placements(one: Callable[[int], Any], seeds: list[int], workers: int) -> list[Any]:
    """``one(seed)`` of each seed, in order, ``workers`` at once (threads). Ctrl-C keeps the
    placements that ended (the ensemble of those is reported, marked interrupted); with none,
    it goes on up. A sort stopped after 3 of 20 placements threw all of them away."""
    done: list[Any] = []
    try:
        if workers > 1 and len(seeds) > 1:
            pool = ThreadPoolExecutor(max_workers=workers)
            try:
                for item in pool.map(one, seeds):
                    done.append(item)
            finally:
                pool.shutdown(wait=False, cancel_futures=True)
        else:
            for seed in seeds:
                done.append(one(seed))
    except KeyboardInterrupt:
        if not done:
            raise
    return done


def _both_species(spec: Particles) -> None:
    """One line, before any curve is computed, where the placement has beads of one species only
    (explicit positions that name one; a random placement has at least one of each): nothing to
    sort (it printed NaN)."""
    present = [k for k, n in enumerate(spec.counts()) if n > 0]
    if len(present) < 2:
        only = ", ".join(str(k) for k in present) or "none"
        raise SceneError(f"particles: the placement has beads of species {only} only; sorting "
                         "needs beads of both species (0 and 1)")


def _warnings(scene: Scene) -> tuple[str, ...]:
    """Where the scene leaves what the slow model was checked on: undamped bead contacts."""
    e = scene.material.restitution
    damped = (e is not None and e < 1.0) or scene.effects.normal_damping > 0.0
    return () if damped else (UNDAMPED,)


def slow_window(scene: Scene, spec: Particles, result: SortResult, periods: int) -> dict[str, Any]:
    """The placement of ``spec`` moved by the 1-D slow model for ``periods`` periods, measured
    like a LAMMPS run: each species' mean drift ratio over the last half, the purity at the end, the
    chains (``result`` provides nothing but the scene's curves, already cached on disk)."""
    real = realize(scene)
    species = species_of(scene, spec, real)
    g = scene.device.gravity if scene.device is not None else 9.81
    beads = [Bead(s.radius, s.a0, s.mass * g) for s in species]
    curves = curves_for(scene, [s.radius for s in species], source=result.curve_source)  # type: ignore[arg-type]
    u = 2.0 * math.pi * real.frequency * real.ratio * real.amplitude * real.horizontal
    xy, kinds, _, _ = placement(spec, species)
    half = max(1, periods // 2)
    t0 = time.perf_counter()
    # in lanes (1-D) whatever the ensemble's geometry: over a window this short no bead gets
    # round another (that takes about 1e6 periods), and the 2-D model's penalty contacts need
    # delta_tol / speed (about 2600 periods for examples/mixture.toml) to take up their load
    run = SlowModel(xy[:, 0], xy[:, 1], kinds, beads, curves, u).run(
        np.array([periods - half, periods], dtype=float) / real.frequency)
    disp = (run.x[1] - run.x[0]) * real.frequency / half / u
    return {"drift_ratio": [float(disp[kinds == k].mean()) for k in range(len(species))],
            "purity": purity(run.x[1], kinds, result.right), "chains": len(run.chains),
            "wall_time_s": time.perf_counter() - t0}
