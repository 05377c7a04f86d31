"""Where the default sweep's time goes: every cell run by default and fixed, back to back.

The 41 x 41 mmd sweep of `sawdrift bench speed` (m* 1e-3..1e2, A* 1e-2..10), serially in this one
process: each cell is run with default numerics and as a fixed 60-period run (``settle = false``)
one right after the other, in alternating order, so that both see the same state of a shared
machine. Prints the run time of each route the default takes (``settle_method``, and whether it
reported a long-time mean), the same cells' fixed runs, and the totals; writes one row per cell.

Each run's time is also split: the time spent in ``Stepper.advance`` (the compiled wave loop and
its call, ``*_advance_s``) and the rest (the solves of a heavy particle, the Lyapunov
stretchings, the windows' evidence, the Result: compiled and Python code outside the main
integration). The totals line says what the ratio would be if the default's rest cost no more
than the fixed runs' (its integration alone against theirs): a floor no overhead cut can pass.

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
from sawdrift.dynamics import stepper as _stepper

OUT = Path(__file__).parent / "results" / "sweep_routes.csv"


#: seconds spent in Stepper.advance since the last reset (see :func:`_timed_advance`)
ADVANCE = [0.0]


def _timed_advance() -> None:
    """Wrap ``Stepper.advance`` so that the time in it adds up in :data:`ADVANCE`."""
    advance = _stepper.Stepper.advance

    def timed(self, *args, **kwargs):
        t0 = time.perf_counter()
        try:
            return advance(self, *args, **kwargs)
        finally:
            ADVANCE[0] += time.perf_counter() - t0

    _stepper.Stepper.advance = timed


def cell(m: float, a: float, settle: bool | None) -> tuple[float, float, sd.Result]:
    """(seconds, seconds in Stepper.advance, result) of one run of the sweep's cell."""
    scene = sd.Scene(model="mmd", particle={"m_star": m}, drive={"amplitude": a},
                     numerics={"settle": settle})
    ADVANCE[0] = 0.0
    t0 = time.perf_counter()
    result = sd.run(scene)
    return time.perf_counter() - t0, ADVANCE[0], result


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--grid", type=int, default=41)
    ap.add_argument("--out", type=Path, default=OUT)
    args = ap.parse_args()
    _timed_advance()
    cell(1.0, 1.0, None)  # compiled code loaded before the clock runs
    cell(50.0, 1.0, None)
    rows = []
    order = ((None, False), (False, None))
    for i, (m, a) in enumerate((float(m), float(a)) for m in np.logspace(-3, 2, args.grid)
                               for a in np.logspace(-2, 1, args.grid)):
        got = {settle: cell(m, a, settle) for settle in order[i % 2]}
        wall, adv, r = got[None]
        rows.append({"m_star": m, "amplitude": a, "route": r.settle_method,
                     "long_mean": r.drift_ratio_se is not None and math.isfinite(r.drift_ratio_se),
                     "regime": r.regime, "settled": r.settled, "default_s": wall,
                     "default_advance_s": adv, "fixed_s": got[False][0],
                     "fixed_advance_s": got[False][1]})
    table = pd.DataFrame(rows)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    table.to_csv(args.out, index=False, float_format="%.6g")
    table["extra_s"] = table["default_s"] - table["fixed_s"]
    by = table.groupby(["long_mean", "route"]).agg(
        cells=("default_s", "size"), default_s=("default_s", "sum"),
        default_advance_s=("default_advance_s", "sum"), fixed_s=("fixed_s", "sum"),
        fixed_advance_s=("fixed_advance_s", "sum"), extra_s=("extra_s", "sum"))
    print(by.round(3).to_string())
    d, f = table["default_s"].sum(), table["fixed_s"].sum()
    da, fa = table["default_advance_s"].sum(), table["fixed_advance_s"].sum()
    print(f"total: default {d:.2f} s ({da:.2f} s in Stepper.advance), fixed {f:.2f} s "
          f"({fa:.2f} s in Stepper.advance), ratio {d / f:.3f}; with the default's rest cut to "
          f"the fixed runs' rest: {(da + f - fa) / f:.3f}; wrote {args.out}")


if __name__ == "__main__":
    main()
