"""Where the default sweep's time goes: every cell run by default and fixed, back to back.

The 41 x 41 mmd sweep of `sawdrift bench speed` (m* 1e-3..1e2, A* 1e-2..10), serially in this one
process: each cell is run with default numerics and as a fixed 60-period run (``settle = false``)
one right after the other, in alternating order, so that both see the same state of a shared
machine. Prints the run time of each route the default takes (``settle_method``, and whether it
reported a long-time mean), the same cells' fixed runs, and the totals; writes one row per cell.

    python benchmarks/bench_sweep_routes.py [--grid 41] [--out results/sweep_routes.csv]
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np
import pandas as pd

import sawdrift as sd

OUT = Path(__file__).parent / "results" / "sweep_routes.csv"


def cell(m: float, a: float, settle: bool | None) -> tuple[float, sd.Result]:
    """(seconds, result) of one run of the sweep's cell."""
    scene = sd.Scene(model="mmd", particle={"m_star": m}, drive={"amplitude": a},
                     numerics={"settle": settle})
    t0 = time.perf_counter()
    result = sd.run(scene)
    return time.perf_counter() - t0, result


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--grid", type=int, default=41)
    ap.add_argument("--out", type=Path, default=OUT)
    args = ap.parse_args()
    cell(1.0, 1.0, None)  # compiled code loaded before the clock runs
    cell(50.0, 1.0, None)
    rows = []
    order = ((None, False), (False, None))
    for i, (m, a) in enumerate((float(m), float(a)) for m in np.logspace(-3, 2, args.grid)
                               for a in np.logspace(-2, 1, args.grid)):
        got = {settle: cell(m, a, settle) for settle in order[i % 2]}
        wall, r = got[None]
        rows.append({"m_star": m, "amplitude": a, "route": r.settle_method,
                     "long_mean": r.drift_ratio_se is not None and math.isfinite(r.drift_ratio_se),
                     "regime": r.regime, "settled": r.settled, "default_s": wall,
                     "fixed_s": got[False][0]})
    table = pd.DataFrame(rows)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    table.to_csv(args.out, index=False, float_format="%.6g")
    table["extra_s"] = table["default_s"] - table["fixed_s"]
    by = table.groupby(["long_mean", "route"]).agg(
        cells=("default_s", "size"), default_s=("default_s", "sum"), fixed_s=("fixed_s", "sum"),
        extra_s=("extra_s", "sum"))
    print(by.round(3).to_string())
    d, f = table["default_s"].sum(), table["fixed_s"].sum()
    print(f"total: default {d:.2f} s, fixed {f:.2f} s, ratio {d / f:.3f}, wrote {args.out}")


if __name__ == "__main__":
    main()
