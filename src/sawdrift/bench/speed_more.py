"""Speed targets of the second round: cold start, steady drift of heavy particles, adaptive diagrams.

Used by :func:`sawdrift.bench.speed` beside the first round's targets; each returns a
:class:`~sawdrift.bench.Target`.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from ..result.runner import run
from ..scene.schema import Scene
from ..study.adaptive import adaptive_sweep, misclassified_area
from ..study.sweep import sweep
from .targets import Target, _target


def _process_seconds(args: list[str], repeats: int) -> float:
    """Median wall time of ``python -m sawdrift ARGS`` as a whole process (after one warm-up)."""
    cmd = [sys.executable, "-m", "sawdrift", *args]
    subprocess.run(cmd, capture_output=True, check=True)  # warm the disk caches
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(cmd, capture_output=True, check=True)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def speed_cold_start(quick: bool = False) -> list[Target]:
    """`--help` <= 0.5 s, `models` <= 0.6 s, `run --model mmd --json` <= 1.2 s, whole processes."""
    repeats = 3 if quick else 5
    rows = [("help", ["--help"], 0.5), ("models", ["models"], 0.6),
            ("run", ["run", "--model", "mmd", "--json"], 1.2)]
    out = []
    for name, args, limit in rows:
        t = _process_seconds(args, repeats)
        out.append(_target(f"cold_{name}", f"`sawdrift {' '.join(args)}` as a whole process, warm "
                           f"disk cache (median of {repeats})", t, "s", limit, "<=",
                           {"repeats": repeats}))
    return out


def speed_steady(quick: bool = False) -> Target:
    """--settle on a heavy particle (mmd, m* = 3000, A* = 0.7, mu = 0.1): reported run time."""
    m = 300.0 if quick else 3000.0
    scene = Scene(model="mmd", particle={"m_star": m}, material={"mu": 0.1},
                  drive={"amplitude": 0.7}, numerics={"settle": True, "max_periods": 1e6})
    run(scene.with_updates(**{"numerics.settle": False, "numerics.periods": 2}))  # compile
    res = run(scene)
    return _target("steady", f"--settle, mmd, m* = {m:g}, A* = 0.7, mu = 0.1: run time "
                   f"(settled = {res.settled}, drift ratio {res.drift_ratio:.4f}, "
                   f"{res.settle_periods:.0f} periods)", res.wall_time_s, "s", 1.5, "<=",
                   {"drift_ratio": res.drift_ratio, "periods": res.settle_periods},
                   extra_ok=bool(res.settled))


def speed_adaptive(quick: bool = False, progress: bool = True) -> Target:
    """Adaptive diagram vs a uniform grid: misclassified area < 1 % with <= 15 % of the cells.

    Full: mmd, m* in [1e-3, 1e4], A* in [1e-2, 10], uniform 161 x 161 against a 21 x 21 base
    refined three times. Quick (a smoke test): the material point on a 33 x 33 grid from a 9 x 9
    base, with 45 % of the cells and a 5 % limit (a coarse base grid misses small regions).
    """
    model, m_rng, a_rng = ("material_point", (1e-3, 1e2), (1e-2, 10.0)) if quick else (
        "mmd", (1e-3, 1e4), (1e-2, 10.0))
    base, levels = (9, 2) if quick else (21, 3)
    n = (base - 1) * 2**levels + 1
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        uniform = sweep([model], f"{m_rng[0]}:{m_rng[1]}:{n}", f"{a_rng[0]}:{a_rng[1]}:{n}",
                        table=Path(tmp) / "u.parquet", progress=progress)
        t_uniform = time.perf_counter() - t0
        t0 = time.perf_counter()
        share_limit, area_limit = (0.45, 5.0) if quick else (0.15, 1.0)
        points = adaptive_sweep(model, m_rng, a_rng, budget=int(share_limit * n * n), base=base,
                                levels=levels, table=Path(tmp) / "a.parquet", progress=progress)
        t_adaptive = time.perf_counter() - t0
    share = int((~points["inferred"]).sum()) / (n * n)
    err = misclassified_area(points, uniform)
    return _target("adaptive", f"adaptive {model} diagram vs uniform {n} x {n}: misclassified "
                   f"area, with {share:.1%} of the cells ({t_adaptive:.1f} s vs {t_uniform:.1f} s)",
                   err * 100.0, "%", area_limit, "<", {"share": share, "adaptive_s": t_adaptive,
                                                        "uniform_s": t_uniform},
                   extra_ok=share <= share_limit)
