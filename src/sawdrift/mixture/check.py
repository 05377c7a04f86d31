"""Chains placed by hand, run in LAMMPS and predicted by the slow model: the common speed and the
slowdown of the large beads.

Each chain is a row of beads touching at rest at zero force (:func:`sawdrift.lammps.placement.
touching_row`), in a given order along the wave. LAMMPS runs it with the scene's damping for a
short time (the chain's speed is steady after a few tens of periods); the slow model solves the
same chain (:func:`.chains.split_chain`). Compared per species: the mean drift ratio of its beads
(one number for a chain that holds, each part's speed for a chain that splits), and the slowdown
of the large beads, their speed in the chain minus their free speed, each engine against its own
free speed (LAMMPS: the beads alone in the same run length; the model: its curves at no load).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..lammps.many import run_particles
from ..lammps.placement import parse_particles, species_of, touching_row
from ..lammps.realize import realize
from ..scene.device import to_si
from ..scene.schema import Scene
from .chains import Bead
from .curves import SpeciesCurves
from .events import SlowModel

__all__ = ["CHAINS", "ChainCheck", "beads_of", "chain_positions", "lammps_chain", "model_chain"]


def _mixed(n_small: int, n_large: int, seed: int) -> list[int]:
    kinds = np.repeat([0, 1], [n_small, n_large])
    np.random.default_rng(seed).shuffle(kinds)
    return kinds.tolist()


#: the chains of the check: 0 the small species, 1 the large one, in order along +x
CHAINS: dict[str, list[int]] = {
    "small-large": [0, 1],
    "large-small": [1, 0],
    "2 small + 1 large": [0, 0, 1],
    "1 small + 2 large": [0, 1, 1],
    "10 small + 1 large": [0] * 10 + [1],
    "mixed 20": _mixed(10, 10, 0),
}


@dataclass
class ChainCheck:
    """One chain in both engines: per species drift ratios, the large beads' slowdowns."""

    name: str
    order: list[int]
    lammps: list[float]
    model: list[float]
    lammps_free: list[float]
    model_free: list[float]
    lammps_s: float
    model_s: float
    parts: int  # chains of the slow model at the end of the window

    @property
    def common_error(self) -> float:
        """Relative difference of the large beads' mean drift ratio (the chain's common speed
        where they lead a chain), model against LAMMPS."""
        return abs(self.model[1] / self.lammps[1] - 1.0)

    @property
    def slowdowns(self) -> tuple[float, float]:
        """(LAMMPS, model) slowdown of the large beads: chain speed minus free speed."""
        return (self.lammps[1] - self.lammps_free[1], self.model[1] - self.model_free[1])

    @property
    def slowdown_error(self) -> float:
        lam, mod = self.slowdowns
        return abs(mod / lam - 1.0) if lam != 0.0 else math.inf

    def to_json(self) -> dict[str, Any]:
        lam, mod = self.slowdowns
        return {"name": self.name, "order": self.order, "lammps": self.lammps, "model": self.model,
                "lammps_free": self.lammps_free, "model_free": self.model_free,
                "slowdown_lammps": lam, "slowdown_model": mod,
                "common_error": self.common_error, "slowdown_error": self.slowdown_error,
                "parts": self.parts, "lammps_s": self.lammps_s, "model_s": self.model_s}


def beads_of(scene: Scene, radii: list[str]) -> tuple[list[Bead], list[Any]]:
    """The species' geometry (radius, static compression, weight) and their Species records."""
    spec = parse_particles({"radius": radii, "positions": [[0.0, 0.0, 0]]})
    species = species_of(scene, spec)
    g = scene.device.gravity if scene.device is not None else 9.81
    return [Bead(s.radius, s.a0, s.mass * g) for s in species], species


def chain_positions(scene: Scene, radii: list[str], order: list[int],
                    offset: float = 1e-3) -> dict[str, Any]:
    """A ``[particles]`` table of beads touching at rest in ``order`` along x (one lane)."""
    _, species = beads_of(scene, radii)
    xs = touching_row(species, order)
    return {"radius": list(radii),
            "positions": [[float(x) + offset, offset, k] for x, k in zip(xs, order, strict=True)]}


def lammps_chain(scene: Scene, radii: list[str], order: list[int]) -> tuple[list[float], float]:
    """(mean drift ratio of each species, wall time) of the chain run in LAMMPS."""

    result = run_particles(scene, chain_positions(scene, radii, order), processes=1,
                           progress=False)
    return [row["drift_ratio"] if row["count"] else math.nan for row in result.species], \
        result.wall_time_s


def lammps_free(scene: Scene, radii: list[str]) -> tuple[list[float], float]:
    """(free drift ratio of each species, wall time): one bead of each, far apart, in LAMMPS."""

    spread = 10.0 * max(_length(r) for r in radii)
    table = {"radius": list(radii),
             "positions": [[spread, spread * (1 + k), k] for k in range(len(radii))]}
    result = run_particles(scene, table, processes=1, progress=False)
    return [row["drift_ratio"] for row in result.species], result.wall_time_s


def _length(value: str) -> float:

    return to_si(value, "length")


def model_chain(scene: Scene, radii: list[str], curves: list[SpeciesCurves], order: list[int]
                ) -> tuple[list[float], int, float]:
    """(mean drift ratio of each species, chains, wall time) of the chain in the slow model.

    The beads start where LAMMPS places them (:func:`chain_positions`) and move in slow time
    (:class:`.events.SlowModel`) over the same window as the LAMMPS run, the last
    ``measure_periods`` of ``numerics.periods``: a small bead in the gap under two large ones
    that touch each other drifts alone until it reaches one of them, in both engines.
    """

    t0 = time.perf_counter()
    beads, _ = beads_of(scene, radii)
    table = chain_positions(scene, radii, order)
    xy = np.array([p[:2] for p in table["positions"]], dtype=float)
    real = realize(scene)
    u = 2.0 * math.pi * real.frequency * real.ratio * real.amplitude * real.horizontal
    periods = scene.numerics.periods
    window = scene.measure_periods()
    model = SlowModel(xy[:, 0], xy[:, 1], np.asarray(order), beads, curves, u)
    run = model.run(np.array([periods - window, periods]) / real.frequency)
    speed = (run.x[1] - run.x[0]) * real.frequency / window / u
    kinds = np.asarray(order)
    out = [float(speed[kinds == s].mean()) if (kinds == s).any() else math.nan
           for s in range(len(curves))]
    return out, len(run.chains), time.perf_counter() - t0


#: wave periods of each LAMMPS run (the last half measured): a chain's speed is steady after
#: about 100 periods; the mixed chain of 20 relaxes for about 250 (e = 0.5: its large beads at
#: 0.3087, 0.3063, 0.3047 in the windows 30-60, 120-150 and 240-960)
PERIODS = {"mixed 20": 480}
DEFAULT_PERIODS = 240


def check_chains(scene: Scene, radii: list[str], curves: list[SpeciesCurves],
                 chains: dict[str, list[int]] | None = None,
                 progress: Callable[[str], None] | None = None) -> list[ChainCheck]:
    """Every chain of ``chains`` (default :data:`CHAINS`) in LAMMPS and in the slow model, each
    run for :data:`PERIODS` (default :data:`DEFAULT_PERIODS`) periods, the last half measured."""
    def timed(name: str) -> Scene:
        p = PERIODS.get(name, DEFAULT_PERIODS)
        return scene.with_updates(**{"numerics.periods": float(p), "numerics.measure_periods": p // 2})

    free_l, _ = lammps_free(timed(""), radii)
    free_m = [c.free for c in curves]
    out = []
    for name, order in (chains or CHAINS).items():
        lam, lam_s = lammps_chain(timed(name), radii, order)
        mod, parts, mod_s = model_chain(timed(name), radii, curves, order)
        if progress is not None:
            progress(f"{name}: LAMMPS {lam[0]:+.4f} {lam[1]:+.4f} ({lam_s:.3g} s), slow model "
                     f"{mod[0]:+.4f} {mod[1]:+.4f}")
        out.append(ChainCheck(name, order, lam, mod, free_l, free_m, lam_s, mod_s, parts))
    return out
