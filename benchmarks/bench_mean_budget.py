"""Long-time means of irregular cells: is the batch-means error honest at a given budget?

The cells are those of the default 41 x 41 mmd sweep (m* 1e-3..1e2, A* 1e-2..10, mu 0.1)
whose drift is a long-time mean (chaotic light bouncers, quasi-periodic and wandering motions,
irregular heavy bouncers), a random sample of them. Each is run by default with
``numerics.mean_periods`` = B for each budget B asked for, and once more as the reference: a
run of ``--reference`` periods of long-time mean started on another trajectory (the drive's
start-up ramp two periods longer: a chaotic motion forgets where it began), so the reference
is an independent sample. A mean is a defect when it is more than 3 combined standard errors
from the reference's, z = |m_B - m_ref| / sqrt(se_B^2 + se_ref^2) > 3, unless it agrees with a
run of as many periods from its own start (``z_same_start``): then the two starts reached
coexisting motions (a bistable cell), which no error bar of one run can show. A reference
that is no long-time mean (its run says it is still moving or heating up: no error) gives no
z; such cells are counted apart (``unsteady_references``), with whether the budget's own run
warned of it (``flagged``). Writes benchmarks/results/mean_budget.json and prints the counts.

    python benchmarks/bench_mean_budget.py [--cells 40] [--budgets 500 1000 2000]
        [--reference 16000]
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

import sawdrift as sd
from sawdrift._texts import says_heating, says_still_moving

OUT = Path(__file__).parent / "results" / "mean_budget.json"


def irregular_cells(n_grid: int = 41) -> list[tuple[float, float]]:
    """(m*, A*) of the sweep's cells whose default run reports a long-time mean."""
    table = sd.sweep("mmd", f"1e-3:1e2:{n_grid}", f"1e-2:10:{n_grid}", progress=True)
    rows = table[table["resolved_as"].isin(["chaotic_mean", "long_time_mean"])]
    return [(float(m), float(a)) for m, a in zip(rows["m_star"], rows["amplitude"], strict=True)]


def mean_of(m: float, a: float, budget: int, ramp_extra: float = 0.0,
            reference: bool = False) -> tuple[float, float, float, bool]:
    """(drift ratio, its standard error, wall time, whether its warnings say the mean is still
    moving or heating up) of the default run at ``budget``."""
    scene = sd.Scene(model="mmd", particle={"m_star": m},
                     drive={"amplitude": a, "ramp_periods": 5.0 + ramp_extra},
                     numerics={"mean_periods": budget,
                               # a reference runs its whole budget (no early stop)
                               "settle_tolerance": 1e-9 if reference else 1e-3})
    t0 = time.perf_counter()
    r = sd.run(scene)
    wall = time.perf_counter() - t0
    flagged = says_heating(r.warnings) or says_still_moving(r.warnings)
    return r.drift_ratio, r.drift_ratio_se, wall, flagged


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cells", type=int, default=40)
    ap.add_argument("--budgets", type=int, nargs="+", default=[500, 1000, 2000])
    ap.add_argument("--reference", type=int, default=16000)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    cells = irregular_cells()
    rng = np.random.default_rng(args.seed)
    pick = rng.choice(len(cells), size=min(args.cells, len(cells)), replace=False)
    rows = []
    for i in sorted(pick):
        m, a = cells[i]
        ref, ref_se, ref_wall, _ = mean_of(m, a, args.reference, ramp_extra=2.0, reference=True)
        same, same_se, _, _ = mean_of(m, a, args.reference, reference=True)
        row = {"m_star": m, "amplitude": a, "reference": ref, "reference_se": ref_se,
               "reference_wall_s": ref_wall, "same_start": same, "same_start_se": same_se}
        for b in args.budgets:
            got, se, wall, flagged = mean_of(m, a, b)
            z = abs(got - ref) / math.hypot(se, ref_se) if math.isfinite(se) else math.nan
            z_same = (abs(got - same) / math.hypot(se, same_se) if math.isfinite(se)
                      else math.nan)
            row[str(b)] = {"drift_ratio": got, "se": se, "z": z, "z_same_start": z_same,
                           "wall_s": wall, "flagged": flagged}
        rows.append(row)
        print(f"m* {m:9.4g} A* {a:6.3g} ref {ref:+.4f} +- {ref_se:.4f} same start {same:+.4f} "
              f"+- {same_se:.4f}  " + "  ".join(
                  f"B{b}: {row[str(b)]['drift_ratio']:+.4f} +- {row[str(b)]['se']:.4f} "
                  f"z {row[str(b)]['z']:.2f} ({row[str(b)]['z_same_start']:.2f})"
                  for b in args.budgets), flush=True)
    summary = {}
    for b in args.budgets:
        z = np.array([r[str(b)]["z"] for r in rows], dtype=float)
        z_same = np.array([r[str(b)]["z_same_start"] for r in rows], dtype=float)
        se = np.array([r[str(b)]["se"] for r in rows], dtype=float)
        wall = np.array([r[str(b)]["wall_s"] for r in rows], dtype=float)
        unsteady = [r for r in rows if not math.isfinite(r["reference_se"])]
        summary[str(b)] = {"cells": len(rows), "z_above_3": int(np.sum(z > 3.0)),
                           "unsteady_references": [
                               {"m_star": r["m_star"], "amplitude": r["amplitude"],
                                "reference": r["reference"],
                                "drift_ratio": r[str(b)]["drift_ratio"],
                                "se": r[str(b)]["se"], "flagged": r[str(b)]["flagged"]}
                               for r in unsteady],
                           "z_above_2": int(np.sum(z > 2.0)), "z_finite": int(np.isfinite(z).sum()),
                           "z_same_start_above_3": int(np.sum(z_same > 3.0)),
                           "median_se": float(np.nanmedian(se)), "wall_s": float(wall.sum())}
        print(f"budget {b}: {summary[str(b)]}")
    OUT.parent.mkdir(exist_ok=True)
    OUT.write_text(json.dumps({"reference_periods": args.reference, "summary": summary,
                               "cells": rows}, indent=1))


if __name__ == "__main__":
    main()
