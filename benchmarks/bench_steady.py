"""Steady drift of heavy particles: ``numerics.settle`` against brute-force runs.

For each cell (mmd, m* = 30, 300, 3000; mu 0.1 to 0.3; A* 0.25 to 0.7) a brute-force run of
40 m*/mu + 2000 periods (full inertia, no settle criterion; the approach time measured on these
cells is 1.4 to 2.1 m*/mu, so this is 19 to 29 approach times) gives the reference drift ratio,
the mean over its last 30 %; the settled
run (reduced horizontal inertia, see sawdrift.dynamics.steady) must agree within 1 % (or both
stay below the drift tolerance 1e-3, a cell without steady drift) with
settled = true, in at most 1.5 s of reported run time. A light particle (m* = 0.1) is checked
against a plain 60-period run. Writes benchmarks/results/steady.json and prints a table.

    python benchmarks/bench_steady.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import sawdrift as sd

CELLS = [(30.0, 0.5, 0.2), (300.0, 0.4, 0.1), (300.0, 0.25, 0.3), (3000.0, 0.6, 0.3),
         (3000.0, 0.7, 0.1)]


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
        res = settled(m, a, mu)
        rel = abs(res.drift_ratio - ref) / max(abs(ref), 1e-12)
        # a cell without steady drift (|V| below the drift tolerance) has no relative error
        close = rel <= 0.01 or max(abs(ref), abs(res.drift_ratio)) <= 1e-3
        ok = close and res.extra["settled"] and res.wall_time_s <= 1.5
        rows.append(dict(m_star=m, amplitude=a, mu=mu, brute_periods=periods, brute=ref,
                         brute_wall_s=t_ref, settled=res.drift_ratio,
                         settled_flag=res.extra["settled"], settle_periods=res.extra["settle_periods"],
                         settle_wall_s=res.wall_time_s, rel_error=rel, passed=bool(ok)))
        print(f"m* = {m:6g}  A* = {a:4g}  mu = {mu:3g}: brute ({periods} periods, {t_ref:6.2f} s) "
              f"{ref:+.5f}; settled {res.drift_ratio:+.5f} ({res.extra['settle_periods']:.0f} periods, "
              f"{res.wall_time_s:.3f} s, settled = {res.extra['settled']}): "
              f"rel. error {rel:.2e} {'PASS' if ok else 'FAIL'}", flush=True)
    light = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.316},
                            numerics={"settle": True}))
    plain = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.316}))
    print(f"light m* = 0.1: settled {light.drift_ratio:.6f} ({light.extra['settle_method']}), "
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
