"""Adaptive phase diagram against a uniform 161 x 161 grid (mmd, the whole plane).

The uniform reference: mmd over m* in [1e-3, 1e4] and A* in [1e-2, 10], 161 x 161 log-spaced
cells, default numerics (computed once into benchmarks/data/uniform_161.parquet, resumable; about
a minute on 2 cores; computed again when the stored one is from other code). The adaptive
diagram: a 21 x 21 base grid, every cell probed at its centre and its edges and refined three
times where they disagree in regime (sawdrift.study.adaptive), with a budget of 15 % of the
uniform grid's cells. Target: misclassified area (the fraction of the uniform grid's cells whose
regime the adaptive map gets wrong) below 1 %. Writes benchmarks/results/adaptive.json.

    python benchmarks/bench_adaptive.py
"""

from __future__ import annotations

import json
import time
from pathlib import Path

import pandas as pd

import sawdrift as sd
from sawdrift.study.adaptive import adaptive_sweep, misclassified_area

HERE = Path(__file__).parent
M_RANGE, A_RANGE, N = (1e-3, 1e4), (1e-2, 10.0), 161
BUDGET = int(0.15 * N * N)


def uniform() -> tuple[pd.DataFrame, float]:
    """The 161 x 161 reference table (computed or resumed) and the seconds it took now.

    A stored reference computed by other code is not reused: it is computed again.
    """
    from sawdrift.study.provenance import TableProvenanceError
    from sawdrift.study.sweep import journal_path

    path = HERE / "data" / "uniform_161.parquet"
    path.parent.mkdir(exist_ok=True)
    t0 = time.perf_counter()
    axes = (f"{M_RANGE[0]}:{M_RANGE[1]}:{N}", f"{A_RANGE[0]}:{A_RANGE[1]}:{N}")
    try:
        frame = sd.sweep(["mmd"], *axes, table=path, progress=True)
    except TableProvenanceError as exc:
        print(f"recomputing the reference: {exc}")
        path.unlink(missing_ok=True)
        journal_path(path).unlink(missing_ok=True)
        frame = sd.sweep(["mmd"], *axes, table=path, progress=True)
    return frame, time.perf_counter() - t0


def main() -> None:
    """Compare and store."""
    ref, t_ref = uniform()
    t0 = time.perf_counter()
    points = adaptive_sweep("mmd", M_RANGE, A_RANGE, budget=BUDGET, base=21, levels=3)
    t_ad = time.perf_counter() - t0
    err = misclassified_area(points, ref)
    n_run, n_inferred = points.attrs["computed"], points.attrs["inferred"]
    share = n_run / (N * N)
    ok = err < 0.01 and share <= 0.15
    print(f"uniform {N} x {N}: {len(ref)} cells ({t_ref:.1f} s this run); adaptive: {n_run} "
          f"cells computed = {share:.1%} of the grid, {n_inferred} inferred "
          f"({points.attrs['wrong_guesses']} sampled guesses proved wrong and were refined), "
          f"{t_ad:.1f} s; "
          f"misclassified area {err:.2%}: "
          f"{'PASS' if ok else 'FAIL'}")
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    (out / "adaptive.json").write_text(json.dumps(
        {"uniform_cells": len(ref), "adaptive_cells": n_run, "inferred_cells": n_inferred,
         "wrong_guesses": points.attrs["wrong_guesses"], "share": share,
         "misclassified_area": err, "adaptive_s": t_ad, "passed": ok}, indent=2) + "\n")
    if not ok:
        raise SystemExit(1)


if __name__ == "__main__":
    import argparse

    # no options: --help prints what the script does and where it writes, and runs nothing
    argparse.ArgumentParser(description=__doc__,
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    main()
