"""Reference steady drift of heavy particles, by brute force at full inertia.

For each cell (model, m*, A*, mu) a plain run (``numerics.settle = false``, full horizontal and
vertical inertia) of N >= 40 m*/mu + 2000 periods gives the drift ratio, measured over its last
W = max(0.3 N, 3 vertical periods) periods; the vertical free oscillation of a heavy particle
has the period 2 pi sqrt(m*/1.5) and, near the stick boundary, never decays. Two checks:

(a) a run of N/2 periods (the same window fraction): if it differs from the run of N by more
    than 1e-3 relative and more than 2e-5 absolute, N is doubled (the old run of N becomes the
    new check) until the two agree, at most ``--max-doublings`` times;
(b) the run of the final N with twice the steps per period.

Each cell is labelled by what the fixed run measured: ``hopping`` (contact lost in the window),
``drifting`` (|drift ratio| above the drift tolerance 1e-3: steady sliding drift) or ``creep``
(|drift ratio| at most 1e-3 but above 1e-7, without contact loss: a partly stuck contact that
creeps, near the stick boundary); a cell below 1e-7 would be ``stick`` (none is in the list).
The stored drift ratio is the run at the default steps per period (128 for these cells), the
resolution the default run also uses. Measured on 2026-11-26: it is within 7e-4 relative of
the step-converged value on drifting cells (jaeger m* 300, A* 0.8, mu 0.5: 0.1229428 at 128,
0.1230184 at 256, 0.1230305 at 1024 steps; mmd m* 100, A* 0.5, mu 0.3: 0.1280521, 0.1280560,
0.1280563), and within 0.5 % (5e-7 absolute) on creep cells (mmd m* 300 at A* = mu = 0.5:
1.2748e-4, 1.2762e-4, 1.2808e-4 at 128, 256, 512 steps; 1.2792e-4 at 128 steps and 4x N).

Writes ``validation/data/steady_reference.json`` after every cell; cells already in the file are
skipped (the script resumes). Run from the repository root:

    PYTHONPATH=src:plugins python3 benchmarks/steady_reference.py [--only MODEL] [--dry-run]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import time
from datetime import UTC, datetime
from pathlib import Path

import sawdrift as sd

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "validation" / "data" / "steady_reference.json"

#: convergence bounds: two drift ratios agree if within REL relative or within ABS absolute
REL, ABS = 1e-3, 2e-5
#: |drift ratio| at or below this is no steady sliding drift (numerics.drift_tolerance)
DRIFT_TOL = 1e-3
#: |drift ratio| below this is stick, not creep
STICK_TOL = 1e-7

#: (model, m*, A*, mu), cheapest first. Creep cells sit at the stick boundary found by short
#: runs (mmd: A* = mu = 0.5; jaeger: A* 0.45-0.46 at mu = 0.5; hertz_mindlin_dem has none:
#: its drift grows in proportion to A* from A* = 0.01 on, without gross slip).
CELLS: list[tuple[str, float, float, float]] = [
    # hopping (contact lost, synchronous)
    ("hertz_mindlin_dem", 30.0, 1.5, 0.3),
    ("mmd", 100.0, 1.5, 0.5),
    ("jaeger", 300.0, 1.5, 0.3),
    ("hertz_mindlin_dem", 300.0, 1.2, 0.1),
    ("mmd", 1000.0, 1.5, 0.5),
    # creep near the stick boundary
    ("mmd", 30.0, 0.5, 0.5),
    ("mmd", 100.0, 0.5, 0.5),
    ("mmd", 300.0, 0.5, 0.5),
    ("jaeger", 100.0, 0.45, 0.5),
    ("jaeger", 300.0, 0.46, 0.5),
    ("mmd", 1000.0, 0.5, 0.5),
    ("jaeger", 1000.0, 0.45, 0.5),
    ("mmd", 3000.0, 0.5, 0.5),
    ("jaeger", 3000.0, 0.45, 0.5),
    # jaeger's partial-slip creep at the stick boundary, whose period-one orbit is 29 % off
    ("jaeger", 1400.0, 0.465, 0.5),
    # clear sliding drift
    ("mmd", 30.0, 0.7, 0.3),
    ("mmd", 100.0, 0.5, 0.3),
    ("jaeger", 300.0, 0.8, 0.5),
    ("hertz_mindlin_dem", 1000.0, 0.3, 0.5),
    ("jaeger", 1000.0, 0.5, 0.5),
    ("jaeger", 3000.0, 0.8, 0.5),
    ("mmd", 3000.0, 0.6, 0.3),
    ("hertz_mindlin_dem", 3000.0, 0.7, 0.3),
    # a damped normal contact (the hertz_tsuji plugin's Tsuji dashpot, c = 0.1): the free
    # vertical oscillation decays, and the run ends on the period-one orbit
    ("hertz_tsuji", 30.0, 1.5, 0.3),
    ("hertz_tsuji", 100.0, 2.4, 0.1),
    ("hertz_tsuji", 300.0, 4.5, 0.1),
    # the heaviest: 802 000 periods each
    ("mmd", 10000.0, 0.5, 0.5),
    ("mmd", 10000.0, 0.7, 0.5),
    ("hertz_mindlin_dem", 10000.0, 0.5, 0.5),
    ("jaeger", 10000.0, 0.45, 0.5),
]


def cell_key(model: str, m_star: float, amplitude: float, mu: float) -> str:
    """The identifier of a cell in the JSON file, e.g. ``"mmd/m1e+04/A0.5/mu0.5"``."""
    return f"{model}/m{m_star:g}/A{amplitude:g}/mu{mu:g}"


def base_periods(m_star: float, mu: float) -> int:
    """N = ceil(40 m*/mu) + 2000: a few m*/mu relaxation times and a start-up margin."""
    return math.ceil(40.0 * m_star / mu) + 2000


def window(periods: int, m_star: float) -> int:
    """W = max(0.3 N, 3 vertical periods 2 pi sqrt(m*/1.5)), in whole periods."""
    vertical = 2.0 * math.pi * math.sqrt(m_star / 1.5)
    return max(math.ceil(0.3 * periods), math.ceil(3.0 * vertical))


def agree(a: float, b: float) -> bool:
    """True if two drift ratios agree within REL relative or ABS absolute."""
    return abs(a - b) <= max(REL * abs(b), ABS)


def rel_diff(a: float, ref: float) -> float:
    """|a - ref| / |ref| (inf for ref = 0 and a != 0)."""
    if ref == 0.0:
        return 0.0 if a == 0.0 else math.inf
    return abs(a - ref) / abs(ref)


def brute(model: str, m_star: float, amplitude: float, mu: float, periods: int,
          steps_per_period: int | None = None) -> sd.Result:
    """One full-inertia run of ``periods`` periods, measured over :func:`window`."""
    numerics: dict = {"settle": False, "periods": periods, "measure_periods": window(periods, m_star),
                      "max_periods": periods}
    if steps_per_period is not None:
        numerics["steps_per_period"] = steps_per_period
    scene = sd.Scene(model=model, particle={"m_star": m_star}, drive={"amplitude": amplitude},
                     material={"mu": mu}, numerics=numerics)
    return sd.run(scene)


def kind_of(res: sd.Result) -> str:
    """``hopping``, ``drifting``, ``creep`` or ``stick`` from a fixed run's measurements."""
    if res.contact_lost:
        return "hopping"
    v = abs(res.drift_ratio)
    if v > DRIFT_TOL:
        return "drifting"
    return "creep" if v > STICK_TOL else "stick"


def _summary(res: sd.Result) -> dict:
    return {"drift_ratio": res.drift_ratio, "periods": res.periods,
            "measure_periods": res.measure_periods, "steps_per_period": res.steps_per_period,
            "regime": res.regime, "wall_s": res.wall_time_s}


def compute_cell(model: str, m_star: float, amplitude: float, mu: float,
                 max_doublings: int = 3) -> dict:
    """Run one cell with both convergence checks; returns its JSON record."""
    t0 = time.perf_counter()
    n = base_periods(m_star, mu)
    half = brute(model, m_star, amplitude, mu, n // 2)
    main = brute(model, m_star, amplitude, mu, n)
    doublings = 0
    history = [_summary(half), _summary(main)]
    while not agree(half.drift_ratio, main.drift_ratio) and doublings < max_doublings:
        doublings += 1
        n *= 2
        half, main = main, brute(model, m_star, amplitude, mu, n)
        history.append(_summary(main))
    fine = brute(model, m_star, amplitude, mu, n, steps_per_period=2 * main.steps_per_period)
    v = main.drift_ratio
    rec = {
        "key": cell_key(model, m_star, amplitude, mu),
        "model": model, "m_star": m_star, "amplitude": amplitude, "mu": mu,
        "kind": kind_of(main),
        "drift_ratio": v,
        "regime": main.regime,
        "gross_slip_fraction": main.gross_slip_fraction,
        "contact_lost": bool(main.contact_lost),
        "hop_period": int(main.hop_period),
        "periods": int(n),
        "measure_periods": int(main.measure_periods),
        "steps_per_period": int(main.steps_per_period),
        "vertical_period": 2.0 * math.pi * math.sqrt(m_star / 1.5),
        "doublings": doublings,
        "half": {"periods": int(half.periods), "measure_periods": int(half.measure_periods),
                 "drift_ratio": half.drift_ratio, "regime": half.regime,
                 "abs_diff": abs(half.drift_ratio - v), "rel_diff": rel_diff(half.drift_ratio, v),
                 "agrees": agree(half.drift_ratio, v)},
        "fine": {"steps_per_period": int(fine.steps_per_period), "drift_ratio": fine.drift_ratio,
                 "regime": fine.regime, "abs_diff": abs(fine.drift_ratio - v),
                 "rel_diff": rel_diff(fine.drift_ratio, v), "agrees": agree(fine.drift_ratio, v)},
        "wall_s": {"main": main.wall_time_s, "half": half.wall_time_s, "fine": fine.wall_time_s,
                   "cell_total": time.perf_counter() - t0},
        "runs": history,
    }
    return rec


def _git(*args: str) -> str:
    try:
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def header() -> dict:
    """How the data was made: command, date, machine, package version and commit."""
    import numba
    import numpy

    cpu = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {
        "what": "steady drift ratio of heavy particles by brute force at full inertia "
                "(numerics.settle = false), for the validation case "
                "validation/g9c_steady_vs_full_inertia.py",
        "method": {
            "periods": "N = ceil(40 m*/mu) + 2000, doubled while the run of N/2 disagrees",
            "window": "W = max(ceil(0.3 N), ceil(3 * 2 pi sqrt(m*/1.5))) periods at the end",
            "check_half": "a run of N/2 periods, window by the same rule",
            "check_fine": "the run of N with twice the steps per period",
            "agreement": f"within {REL:g} relative or {ABS:g} absolute in drift ratio",
            "kind": f"hopping: contact lost in the window; drifting: |V| > {DRIFT_TOL:g}; "
                    f"creep: {STICK_TOL:g} < |V| <= {DRIFT_TOL:g} without contact loss",
        },
        "command": "PYTHONPATH=src:plugins python3 " + " ".join(
            [str(Path(sys.argv[0]).resolve().relative_to(ROOT))
             if Path(sys.argv[0]).resolve().is_relative_to(ROOT) else sys.argv[0], *sys.argv[1:]]),
        "machine": {"cores": os.cpu_count(), "cpu": cpu, "platform": platform.platform(),
                    "note": "2 cores shared with two other workers; one run at a time"},
        "versions": {"sawdrift": sd.__version__ if hasattr(sd, "__version__") else "unknown",
                     "python": platform.python_version(), "numpy": numpy.__version__,
                     "numba": numba.__version__},
        "commit": _git("rev-parse", "HEAD"),
        "branch": _git("rev-parse", "--abbrev-ref", "HEAD"),
    }


def load(path: Path) -> dict:
    """The existing file, or an empty one."""
    if path.exists():
        return json.loads(path.read_text())
    return {"header": {}, "cells": []}


def save(path: Path, data: dict) -> None:
    """Write atomically (a crash mid-write keeps the previous file)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(data, indent=1, allow_nan=True) + "\n")
    tmp.replace(path)


def main() -> int:
    """Compute the cells that are not yet in the file; print one line per cell."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=OUT)
    parser.add_argument("--only", default=None, help="only the cells of this model")
    parser.add_argument("--max-doublings", type=int, default=3)
    parser.add_argument("--dry-run", action="store_true", help="list the cells and their N")
    args = parser.parse_args()
    data = load(args.out)
    done = {c["key"] for c in data["cells"]}
    todo = [c for c in CELLS if cell_key(*c) not in done and (args.only in (None, c[0]))]
    if args.dry_run:
        for c in todo:
            n = base_periods(c[1], c[3])
            print(f"{cell_key(*c):40s} N = {n:8d}  W = {window(n, c[1]):7d}")
        print(f"{len(todo)} cells to run, {sum(base_periods(c[1], c[3]) for c in todo)} periods at N")
        return 0
    # compile and load caches outside the measured runs (200 periods: the window spans three
    # free vertical periods, 85 at m* = 30, and 10 periods were refused as shorter than it)
    brute("mmd", 30.0, 0.5, 0.3, 200)
    for model in {c[0] for c in todo}:
        brute(model, 30.0, 0.5, 0.3, 200)
    t_all = time.perf_counter()
    for cell in todo:
        rec = compute_cell(*cell, max_doublings=args.max_doublings)
        data = load(args.out)  # re-read: another invocation may have added cells
        data["cells"] = [c for c in data["cells"] if c["key"] != rec["key"]] + [rec]
        hdr = header()
        hdr["date"] = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
        hdr["total_wall_s"] = sum(c["wall_s"]["cell_total"] for c in data["cells"])
        data["header"] = hdr
        save(args.out, data)
        print(f"{rec['key']:40s} {rec['kind']:8s} V = {rec['drift_ratio']:+.6e} {rec['regime']:17s} "
              f"N = {rec['periods']:7d} (x2^{rec['doublings']}) half {rec['half']['rel_diff']:.1e} "
              f"fine {rec['fine']['rel_diff']:.1e} ok {rec['half']['agrees'] and rec['fine']['agrees']} "
              f"{rec['wall_s']['cell_total']:6.1f} s", flush=True)
    print(f"{len(todo)} cells in {time.perf_counter() - t_all:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
