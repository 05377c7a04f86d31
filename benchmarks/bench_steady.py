"""Steady drift of heavy particles: ``numerics.settle`` against brute-force runs.

The cells are mmd at every corner of m* in {30, 300, 3000}, A* in {0.25, 0.7}, mu in {0.1, 0.3},
plus three inner cells. For each, a brute-force run of 40 m*/mu + 2000 periods (full inertia, no
settle criterion; the horizontal velocity approaches its steady value over a few m*/mu periods)
gives the reference drift ratio, the mean over its last 30 %. A second brute-force run half as
long checks the reference itself: the two must agree within 0.2 % (or both stay below the drift
tolerance 1e-3), so the reference is not a transient. The settled run (reduced horizontal
inertia, see sawdrift.dynamics.steady) must agree with the reference within 1 % (or both stay
below 1e-3: a cell without steady drift) with settled = true, in at most 1.5 s of reported run
time. A light particle (m* = 0.1) is checked against a plain 60-period run. Writes
benchmarks/results/steady.json and prints a table.

    python benchmarks/bench_steady.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import sawdrift as sd

CORNERS = [(m, a, mu) for m in (30.0, 300.0, 3000.0) for a in (0.25, 0.7) for mu in (0.1, 0.3)]
CELLS = [(30.0, 0.5, 0.2), (300.0, 0.4, 0.1), (3000.0, 0.6, 0.3), *CORNERS]
DRIFT_TOL = 1e-3


def brute(m: float, a: float, mu: float, factor: float = 40.0) -> tuple[float, float, int]:
    """Reference drift ratio of a run of ``factor`` m*/mu + 2000 periods, its wall time, periods."""
    periods = int(factor * m / mu) + 2000
    window = int(0.3 * periods)
    scene = sd.Scene(model="mmd", particle={"m_star": m}, material={"mu": mu},
                     drive={"amplitude": a},
                     numerics={"periods": periods, "measure_periods": window, "max_periods": periods})
    res = sd.run(scene)
    return res.drift_ratio, res.wall_time_s, periods


def settled(m: float, a: float, mu: float) -> sd.Result:
    """The settled run."""
    return sd.run(sd.Scene(model="mmd", particle={"m_star": m}, material={"mu": mu},
                           drive={"amplitude": a},
                           numerics={"settle": True, "max_periods": 1e6}))


def main() -> None:
    """Run every cell; print and store the comparison."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="the first two cells only")
    args = parser.parse_args()
    settled(1.0, 0.3, 0.1)  # compile first: compilation is not part of the measured times
    rows = []
    for m, a, mu in CELLS[:2] if args.quick else CELLS:
        ref, t_ref, periods = brute(m, a, mu)
        half, _, _ = brute(m, a, mu, factor=20.0)
        res = settled(m, a, mu)
        rel = abs(res.drift_ratio - ref) / max(abs(ref), 1e-12)
        ref_rel = abs(half - ref) / max(abs(ref), 1e-12)
        # a cell without steady drift (|V| below the drift tolerance) has no relative error
        close = rel <= 0.01 or max(abs(ref), abs(res.drift_ratio)) <= DRIFT_TOL
        converged = ref_rel <= 0.002 or max(abs(ref), abs(half)) <= DRIFT_TOL
        ok = close and converged and res.settled and res.wall_time_s <= 1.5
        rows.append(dict(m_star=m, amplitude=a, mu=mu, brute_periods=periods, brute=ref,
                         brute_half=half, reference_rel_change=ref_rel,
                         brute_wall_s=t_ref, settled=res.drift_ratio,
                         settled_flag=res.settled, settle_periods=res.settle_periods,
                         settle_wall_s=res.wall_time_s, rel_error=rel, passed=bool(ok)))
        print(f"m* = {m:6g}  A* = {a:4g}  mu = {mu:3g}: brute ({periods} periods, {t_ref:6.2f} s) "
              f"{ref:+.5f} (half as long: {ref_rel:.1e}); settled {res.drift_ratio:+.5f} "
              f"({res.settle_periods:.0f} periods, "
              f"{res.wall_time_s:.3f} s, settled = {res.settled}): "
              f"rel. error {rel:.2e} {'PASS' if ok else 'FAIL'}", flush=True)
    light = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.316},
                            numerics={"settle": True}))
    plain = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.316}))
    print(f"light m* = 0.1: settled {light.drift_ratio:.6f} ({light.settle_method}), "
          f"plain 60 periods {plain.drift_ratio:.6f}")
    out = Path(__file__).parent / "results"
    out.mkdir(exist_ok=True)
    (out / "steady.json").write_text(json.dumps(
        {"cells": rows, "light": {"settled": light.drift_ratio, "plain": plain.drift_ratio},
         "when": time.strftime("%Y-%m-%d %H:%M")}, indent=2) + "\n")
    if not all(r["passed"] for r in rows):
        raise SystemExit(1)


if __name__ == "__main__":
    main()
