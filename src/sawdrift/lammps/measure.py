"""What a mixture run measured: the dump's positions, the touching pairs, per species drifts.

Outputs (:class:`ManyResult`). Unwrapped x positions are dumped once per period. Per species: the
mean drift V_s over the last ``measure_periods`` periods (m/s, and as a ratio to the surface speed
2 pi f r A_y, the single particle's ``drift_ratio``), and its spread, the standard deviation of
the particles' own drift velocities over that window. The segregation index

    S(t) = (<dx>_1(t) - <dx>_2(t)) / (|<dx>_1(t)| + |<dx>_2(t)|)

of the species' mean displacements <dx>_s since the start, in [-1, 1]: 0 while the species move
together, +-1 when one stays or the two move apart in opposite directions. It compares
velocities, not places: the segregation of the positions themselves is
:mod:`sawdrift.mixture.segregation`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import SawdriftError
from ..result.runner import run
from ..scene.schema import Scene
from .placement import Particles, Species, species_scene
from .realize import Realization


@dataclass
class ManyResult:
    """What a many-particle run measured (module docstring)."""

    species: list[dict[str, Any]]
    times: np.ndarray  # t* at each dump (once per period)
    segregation: np.ndarray  # S(t), NaN with one species
    mean_x: np.ndarray  # (dumps, species) mean displacement, m
    steps_per_period: int
    periods: float
    measure_periods: int
    steps: int
    wall_time_s: float
    processes: int
    count: int
    box: tuple[float, float]
    surface_speed: float  # 2 pi f r A_y, m/s
    script: str = field(repr=False, default="")
    packing: str = "lattice"
    contact_times: np.ndarray = field(default_factory=lambda: np.empty(0))  # t* at each period's end
    contact_pairs: np.ndarray = field(default_factory=lambda: np.empty(0))  # mean touching pairs
    window_pairs: float = 0.0  # mean touching pairs over the measuring window
    frequency: float = 0.0  # the wave's, Hz

    def summary(self) -> dict[str, Any]:
        """JSON-ready summary: per species, the segregation index (last and over time), the cost."""
        seg = float(self.segregation[-1]) if np.isfinite(self.segregation[-1]) else None
        return {
            "engine": "lammps", "count": self.count, "processes": self.processes,
            "steps_per_period": self.steps_per_period, "periods": self.periods,
            "frequency_hz": self.frequency,
            "measure_periods": self.measure_periods, "steps": self.steps,
            "wall_time_s": self.wall_time_s,
            "particle_periods_per_s": self.count * self.periods / self.wall_time_s,
            "box_m": list(self.box), "surface_speed_m_s": self.surface_speed,
            "packing": self.packing, "touching_pairs": self.window_pairs,
            "segregation_index": seg, "species": self.species,
            "over_time": {
                "t": self.times.tolist(),
                "segregation_index": [float(v) if np.isfinite(v) else None for v in self.segregation],
                "mean_displacement_m": self.mean_x.T.tolist(),
                "touching_pairs": {"t": self.contact_times.tolist(),
                                   "mean": self.contact_pairs.tolist()},
            },
        }


def read_dump(path: Path, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(steps, types, xu[steps, atoms], contacts[steps, atoms]) of a custom dump sorted by id."""
    steps, blocks, touching = [], [], []
    with open(path) as fh:
        lines = fh.read().splitlines()
    i = 0
    types = None
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            steps.append(int(lines[i + 1]))
            i += 2
        elif lines[i].startswith("ITEM: ATOMS"):
            block = np.array([row.split() for row in lines[i + 1:i + 1 + count]], dtype=float)
            types = block[:, 1].astype(int)
            blocks.append(block[:, 2])
            touching.append(block[:, 3])
            i += 1 + count
        else:
            i += 1
    if types is None:
        raise SawdriftError("LAMMPS wrote no positions; the run did not start")
    return np.asarray(steps), types, np.vstack(blocks), np.vstack(touching)


def read_contacts(path: Path) -> np.ndarray:
    """(step, mean touching pairs) rows of the fix ave/time file (empty before the first period)."""
    if not path.exists():
        return np.empty((0, 2))
    return np.loadtxt(path, comments="#", ndmin=2).reshape(-1, 2)


def summarize(scene: Scene, spec: Particles, species: list[Species], real: Realization,
               steps: np.ndarray, types: np.ndarray, xu: np.ndarray, touching: np.ndarray,
               pairs: np.ndarray, k_per: int, n_total: int, periods: int, wall: float, procs: int,
               box: tuple[float, float], script: str) -> ManyResult:
    times = steps / k_per
    disp = xu - xu[0]
    f = real.frequency
    surface = 2.0 * math.pi * f * real.ratio * real.amplitude * real.horizontal
    # the window: the last `periods` whole periods (dumps are one period apart)
    j1 = len(times) - 1
    j0 = max(0, j1 - periods)
    span = (times[j1] - times[j0]) / f
    rows, means = [], []
    for k, sp in enumerate(species):
        sel = types == k + 1
        own = (disp[j1, sel] - disp[j0, sel]) / span if span > 0 else np.zeros(sel.sum())
        v = float(own.mean())
        means.append(disp[:, sel].mean(axis=1))
        rows.append({
            "radius_m": sp.radius, "count": int(sel.sum()), "m_star": sp.m_star,
            "amplitude": sp.amplitude, "a0_m": sp.a0, "drift_speed_m_s": v,
            "drift_ratio": v / surface if surface > 0 else None,
            "drift_spread_m_s": float(own.std(ddof=1)) if own.size > 1 else 0.0,
            # pair contacts per sphere of this species, sampled once a period over the window
            "contacts_per_sphere": float(touching[j0 + 1:j1 + 1, sel].mean()) if j1 > j0 else
            float(touching[j1, sel].mean()),
        })
    mean_x = np.column_stack(means)
    if len(species) == 2:
        diff = mean_x[:, 0] - mean_x[:, 1]
        scale = np.abs(mean_x[:, 0]) + np.abs(mean_x[:, 1])
        seg = np.divide(diff, scale, out=np.zeros_like(diff), where=scale > 0.0)
    else:
        seg = np.full(len(times), math.nan)
    # touching pairs averaged over each period, at the period's end (t* = 1, 2, ...)
    pair_t = pairs[:, 0] / k_per
    pair_n = pairs[:, 1]
    in_window = pair_t > times[j0]
    return ManyResult(
        species=rows, times=times, segregation=seg, mean_x=mean_x, steps_per_period=k_per,
        periods=n_total / k_per, measure_periods=j1 - j0, steps=n_total, wall_time_s=wall,
        processes=procs, count=spec.count, box=box, surface_speed=surface, script=script,
        packing=spec.packing, contact_times=pair_t, contact_pairs=pair_n,
        window_pairs=float(pair_n[in_window].mean()) if in_window.any() else 0.0, frequency=f,
    )


def dilute_prediction(scene: Scene, result: ManyResult) -> list[dict[str, Any]]:
    """Each species' single-particle native drift (hertz_mindlin_dem), against the mixture's.

    The single run uses the mixture's steps per period and periods; ``relative_difference`` is
    (V_mixture - V_single) / |V_single| of the drift ratios.
    """
    out = []
    for row in result.species:
        sp = Species(row["radius_m"], 0.0, row["a0_m"], row["m_star"], row["amplitude"], row["count"])
        single = species_scene(scene, sp).with_updates(**{
            "numerics.steps_per_period": result.steps_per_period,
            "numerics.periods": result.periods, "numerics.settle": False,
            "numerics.measure_periods": result.measure_periods})
        native = run(single)
        ratio = row["drift_ratio"]
        rel = ((ratio - native.drift_ratio) / abs(native.drift_ratio)
               if ratio is not None and native.drift_ratio else None)
        out.append({"radius_m": row["radius_m"], "single_drift_ratio": native.drift_ratio,
                    "mixture_drift_ratio": ratio, "relative_difference": rel,
                    "single_regime": native.regime})
    return out
