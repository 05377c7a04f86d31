"""What a mixture run measured: the dump's positions, the touching pairs, per species drifts.

Outputs (:class:`ManyResult`). Unwrapped x positions are dumped once per period. Per species: the
mean drift V_s over the last ``measure_periods`` periods (m/s, and as a ratio to the surface speed
2 pi f r A_y, the single particle's ``drift_ratio``), and its spread, the standard deviation of
the particles' own drift velocities over that window. The segregation index

    S(t) = (<dx>_1(t) - <dx>_2(t)) / (|<dx>_1(t)| + |<dx>_2(t)|)

of the species' mean displacements <dx>_s since the start, in [-1, 1]: 0 while the species move
together, +-1 when one stays or the two move apart in opposite directions. It compares
velocities, not places (it is 1 for any two opposite drifts): the segregation of the positions
themselves, the best-interface purity, its index and the Lacey index of
:mod:`sawdrift.mixture.segregation`, is computed at every dump from the unwrapped x.

Contacts. A pair counts as touching when it overlaps and its normal force exceeds
:data:`FORCE_FLOOR` times the lightest sphere's weight (two resting spheres placed to touch
overlap by rounding, at forces near 1e-19 N: they are reported apart as ``zero_force_pairs``).
Pairs are sampled :data:`~sawdrift.lammps.many.CONTACT_SAMPLES` times a period, so each
period's mean and the contacts per sphere over the window are averages over the phase of the
period; ``pair_types`` splits the window's mean by the species of the two spheres.

The box. The plane moves in phase everywhere (one local orbit): the periodic box is a piece of
an unbounded plate, and its length along the wave is reported in wavelengths where the device
has one (``box_over_wavelength``; the wavelength itself would matter only with a field that
varies along x).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import SawdriftError
from ..mixture.segregation import lacey_segregation, purity, purity_index
from ..result.runner import run
from ..scene.device import device_wavelength
from ..scene.schema import Scene
from .placement import Species, species_scene
from .realize import Realization

#: a touching pair's normal force must exceed this fraction of the lightest sphere's weight
FORCE_FLOOR = 1e-6


@dataclass
class ManyResult:
    """What a many-particle run measured (module docstring)."""

    species: list[dict[str, Any]]
    times: np.ndarray  # t* at each dump (once per period)
    segregation: np.ndarray  # S(t) of the mean displacements, NaN with one species
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
    window_pairs: float = 0.0  # mean touching pairs (non-zero force) over the measuring window
    frequency: float = 0.0  # the wave's, Hz
    zero_force_pairs: float = 0.0  # mean overlapping pairs below the force floor, window
    pair_types: dict[str, float] = field(default_factory=dict)  # window mean by species pair
    positions: dict[str, np.ndarray] = field(default_factory=dict)  # purity, index, lacey (t)
    final_x: np.ndarray = field(default_factory=lambda: np.empty(0))  # unwrapped x at the end
    kinds: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=int))  # species index
    wavelength: float | None = None  # m, the device's (None: not known)

    def summary(self) -> dict[str, Any]:
        """JSON-ready summary: per species drifts and contacts, segregation of velocities and of
        positions (last and over time), touching pairs, the box and the cost."""
        seg = float(self.segregation[-1]) if np.isfinite(self.segregation[-1]) else None

        def last(key: str) -> float | None:
            v = self.positions.get(key)
            return float(v[-1]) if v is not None and v.size and np.isfinite(v[-1]) else None

        def series(v: np.ndarray) -> list[float | None]:
            return [float(x) if np.isfinite(x) else None for x in v]

        return {
            "engine": "lammps", "count": self.count, "processes": self.processes,
            "steps_per_period": self.steps_per_period, "periods": self.periods,
            "frequency_hz": self.frequency,
            "measure_periods": self.measure_periods, "steps": self.steps,
            "wall_time_s": self.wall_time_s,
            "particle_periods_per_s": self.count * self.periods / self.wall_time_s,
            "box_m": list(self.box), "wavelength_m": self.wavelength,
            "box_over_wavelength": self.box[0] / self.wavelength if self.wavelength else None,
            "surface_speed_m_s": self.surface_speed,
            "packing": self.packing, "touching_pairs": self.window_pairs,
            "zero_force_pairs": self.zero_force_pairs, "pair_types": self.pair_types,
            "segregation_index": seg, "purity": last("purity"),
            "purity_index": last("purity_index"), "lacey": last("lacey"),
            "species": self.species,
            "over_time": {
                "t": self.times.tolist(),
                "segregation_index": series(self.segregation),
                **{k: series(v) for k, v in self.positions.items()},
                "mean_displacement_m": self.mean_x.T.tolist(),
                "touching_pairs": {"t": self.contact_times.tolist(),
                                   "mean": self.contact_pairs.tolist()},
            },
        }


def read_dump(path: Path, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(steps, types, xu[steps, atoms]) of the custom dump ``id type xu`` sorted by id."""
    steps, blocks = [], []
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
            i += 1 + count
        else:
            i += 1
    if types is None:
        raise SawdriftError("LAMMPS wrote no positions; the run did not start")
    return np.asarray(steps), types, np.vstack(blocks)


def read_pairs(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """(sample steps, rows of (step, id1, id2, normal force)) of the local dump of pairs."""
    if not path.exists():
        return np.empty(0), np.empty((0, 4))
    steps, rows = [], []
    with open(path) as fh:
        lines = fh.read().splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            n = int(lines[i + 3])
            steps.append(step)
            # TIMESTEP, step, NUMBER OF ENTRIES, n, BOX BOUNDS + 3 lines, ENTRIES header
            start = i + 9
            for row in lines[start:start + n]:
                a, b, f = row.split()
                rows.append((step, float(a), float(b), float(f)))
            i = start + n
        else:
            i += 1
    return np.asarray(steps, dtype=float), np.asarray(rows, dtype=float).reshape(-1, 4)


def _pair_statistics(pairs: tuple[np.ndarray, np.ndarray], types: np.ndarray, k_per: int,
                     window_from: float, floor: float, n_species: int
                     ) -> tuple[np.ndarray, np.ndarray, float, float, dict[str, float], np.ndarray]:
    """Per-period mean touching pairs, window means, pair types and contacts per sphere.

    Returns (period ends t*, mean pairs per period, window mean, zero-force window mean, window
    mean by species pair "s1-s2", mean contacts per sphere of each species over the window).
    """
    samples, rows = pairs
    if samples.size == 0:
        return np.empty(0), np.empty(0), 0.0, 0.0, {}, np.zeros(n_species)
    step, ia, ib, force = rows.T
    on = np.abs(force) > floor
    t_sample = samples / k_per
    count_on = np.zeros(samples.size)
    count_zero = np.zeros(samples.size)
    slot = np.searchsorted(samples, step)
    np.add.at(count_on, slot[on], 1.0)
    np.add.at(count_zero, slot[~on], 1.0)
    # samples after t* = 0 belong to the period that ends at ceil(t*)
    later = t_sample > 0.0
    period = np.ceil(t_sample[later] - 1e-9).astype(int)
    ends = np.unique(period)
    mean = np.array([count_on[later][period == e].mean() for e in ends])
    in_window = t_sample > window_from
    n_win = max(1, int(in_window.sum()))
    window = float(count_on[in_window].mean()) if in_window.any() else 0.0
    zero = float(count_zero[in_window].mean()) if in_window.any() else 0.0
    sel = on & in_window[slot]
    ka = types[ia[sel].astype(int) - 1] - 1
    kb = types[ib[sel].astype(int) - 1] - 1
    kinds: dict[str, float] = {}
    for s1 in range(n_species):
        for s2 in range(s1, n_species):
            hit = ((ka == s1) & (kb == s2)) | ((ka == s2) & (kb == s1))
            kinds[f"{s1}-{s2}"] = float(hit.sum()) / n_win
    per_sphere = np.array([((ka == s).sum() + (kb == s).sum()) / n_win / max(1, (types == s + 1).sum())
                           for s in range(n_species)])
    return ends.astype(float), mean, window, zero, kinds, per_sphere


def _position_measures(xu: np.ndarray, types: np.ndarray) -> dict[str, np.ndarray]:
    """Purity, purity index and Lacey segregation of the unwrapped x at every dump (2 species)."""
    kinds = types - 1
    out = {"purity": [], "purity_index": [], "lacey": []}
    for row in xu:
        out["purity"].append(purity(row, kinds))
        out["purity_index"].append(purity_index(row, kinds))
        out["lacey"].append(lacey_segregation(row, kinds))
    return {k: np.asarray(v) for k, v in out.items()}


def summarize(scene: Scene, species: list[Species], real: Realization, steps: np.ndarray,
              types: np.ndarray, xu: np.ndarray, pairs: tuple[np.ndarray, np.ndarray], *,
              k_per: int, n_total: int, periods: int, wall: float, procs: int,
              box: tuple[float, float], script: str, packing: str) -> ManyResult:
    """The :class:`ManyResult` of a run's dumps (module docstring)."""
    times = steps / k_per
    disp = xu - xu[0]
    f = real.frequency
    surface = 2.0 * math.pi * f * real.ratio * real.amplitude * real.horizontal
    # the window: the last `periods` whole periods (dumps are one period apart)
    j1 = len(times) - 1
    j0 = max(0, j1 - periods)
    span = (times[j1] - times[j0]) / f
    g = real.weight / real.mass
    floor = FORCE_FLOOR * min(sp.mass for sp in species) * g
    ends, pair_mean, window, zero, kinds, per_sphere = _pair_statistics(
        pairs, types, k_per, times[j0], floor, len(species))
    rows, means = [], []
    for k, sp in enumerate(species):
        sel = types == k + 1
        own = (disp[j1, sel] - disp[j0, sel]) / span if span > 0 else np.zeros(sel.sum())
        v = float(own.mean()) if own.size else math.nan  # a species without spheres: NaN
        means.append(disp[:, sel].mean(axis=1) if sel.any() else np.full(len(times), math.nan))
        rows.append({
            "radius_m": sp.radius, "count": int(sel.sum()), "m_star": sp.m_star,
            "amplitude": sp.amplitude, "a0_m": sp.a0, "drift_speed_m_s": v,
            "drift_ratio": v / surface if surface > 0 else None,
            "drift_spread_m_s": float(own.std(ddof=1)) if own.size > 1 else 0.0,
            # pair contacts at non-zero force per sphere, averaged over the window's phases
            "contacts_per_sphere": float(per_sphere[k]),
        })
    mean_x = np.column_stack(means)
    two = len(species) == 2 and all((types == k + 1).any() for k in range(2))
    if two:
        diff = mean_x[:, 0] - mean_x[:, 1]
        scale = np.abs(mean_x[:, 0]) + np.abs(mean_x[:, 1])
        seg = np.divide(diff, scale, out=np.zeros_like(diff), where=scale > 0.0)
    else:
        seg = np.full(len(times), math.nan)
    return ManyResult(
        species=rows, times=times, segregation=seg, mean_x=mean_x, steps_per_period=k_per,
        periods=n_total / k_per, measure_periods=j1 - j0, steps=n_total, wall_time_s=wall,
        processes=procs, count=types.size, box=box, surface_speed=surface, script=script,
        packing=packing, contact_times=ends, contact_pairs=pair_mean, window_pairs=window,
        frequency=f, zero_force_pairs=zero, pair_types=kinds,
        positions=_position_measures(xu, types) if two else {}, final_x=xu[-1].copy(),
        kinds=types - 1,
        wavelength=device_wavelength(scene.device) if scene.device is not None else None,
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
