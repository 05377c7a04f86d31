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
from ..study.adaptive import adaptive_sweep
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


#: the cold-start targets: (name, command-line arguments, limit in s)
COLD_START: tuple[tuple[str, list[str], float], ...] = (
    ("help", ["--help"], 0.5), ("models", ["models"], 0.6),
    ("run", ["run", "--model", "mmd", "--json"], 1.2),
)


def speed_cold_start(quick: bool = False) -> list[Target]:
    """`--help` <= 0.5 s, `models` <= 0.6 s, `run --model mmd --json` <= 1.2 s, whole processes
    (one target each, :data:`COLD_START`)."""
    repeats = 3 if quick else 5
    out = []
    for name, args, limit in COLD_START:
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
    """The adaptive steady map: mmd, m* in [1e-3, 1e4], A* in [1e-2, 10] at 161 x 161 resolution
    (a 21 x 21 base refined three times), default numerics; quick (a smoke test): 9 x 9 (a 5 x 5
    base refined once) over m* in [1e-3, 1].

    Target: within 30 s with at least 97 % of the computed cells resolved (``resolved_as`` not
    ``not_settled``: a settled fixed point or periodic orbit, a chaotic mean with its error, or a
    named runaway or ejection). No uniform grid is run (it took 1016 s at 161 x 161).
    """
    m_rng = (1e-3, 1.0) if quick else (1e-3, 1e4)
    base, levels = (5, 1) if quick else (21, 3)
    n = (base - 1) * 2**levels + 1
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        points = adaptive_sweep("mmd", m_rng, (1e-2, 10.0), budget=n * n, base=base,
                                levels=levels, table=Path(tmp) / "a.parquet", progress=progress)
        wall = time.perf_counter() - t0
    computed = points[~points["inferred"]]
    how = computed["resolved_as"].value_counts().to_dict() if len(computed) else {}
    share = 1.0 - how.get("not_settled", 0) / max(len(computed), 1)
    return _target("adaptive", f"adaptive mmd steady map, m* {m_rng[0]:g}..{m_rng[1]:g}, "
                   f"A* 0.01..10, {n} x {n} resolution: wall time ({len(computed)} cells computed, "
                   f"{share:.1%} resolved)", wall, "s", 30.0, "<=",
                   {"computed": int(len(computed)), "resolved_share": share,
                    "resolved_as": {str(k): int(v) for k, v in how.items()}},
                   extra_ok=share >= 0.97)
