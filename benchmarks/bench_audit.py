"""The steady drift out of sample: default runs against brute force from rest on a fresh grid.

The default run of each cell of an n x n grid (m* log-spaced over [m0, m1], A* log-spaced over
[0.013, 8.7]: values no tuning of the settle rules used) is compared with brute force from rest
at full inertia: a fixed run of N = max(4000, 40 m*/mu + 2000) periods measured over its last
N/2, and one of 2N measured over its last N. The brute force counts as converged where the two
agree within 1e-3 relative or 2e-5 absolute. A cell is

* a **bad settled** cell where the default run says ``settled`` but is outside that bound of the
  2N run, and brute force converged;
* a **bad mean** where the default run reports a long-time mean with a standard error and is more
  than 3 errors (plus the two brute-force runs' difference) from the 2N run.

A failure that carries no warning in the Result is the worst kind (``warn`` = 0). Prints the
counts and the failures; writes one row per cell to ``--out``.

    python benchmarks/bench_audit.py mmd --grid 13 --m-star 0.0013 0.9 [--scene '{"drive":
        {"backward": 0.5}}'] [--out results/audit.csv]

With ``--stored``, the default runs are judged against the brute force stored in
``results/audit_brute.csv`` (2076 cells of 20 grids: the seven grids below and the backward wave,
and twelve variants: mmd with normal damping, rotation, rolling resistance, a retrograde orbit,
air drag, a cone and DMT adhesion; jaeger with mu = 0.5; the material point with restitution
0.5; hertz_mindlin_dem with JKR adhesion; light jaeger and hertz_mindlin_dem): brute force does
not depend on the settle rules, so a change to them is audited in about a minute. The names
after ``--stored`` pick grids (all by default); ``--out`` gets one row per cell.

    python benchmarks/bench_audit.py --stored [point_heavy mmd_rolling_resistance ...]

On 2026-11-28 (tenth session, 2 cores) the 1024 cells of seven grids (13 x 13 light cells of
mmd and material_point; 11 x 11 heavy cells, m* 1.3 to 90, of mmd, jaeger, hertz_mindlin_dem,
material_point and hertz_tsuji; 9 x 9 of mmd with a backward wave of half the amplitude) gave,
on the code at the session's start, 18 of 851 settled drifts outside the bound, 26 of 170 means
more than 3 errors off, 38 failures without a warning; on its final code 1 of 866, 10 of 155
and 2. About 1 min per 121 heavy cells. In the eleventh session, ``--stored`` on its final code:
the first 1024 cells 1 of 866 settled drifts off, 6 of 157 means, 2 without a warning; the
other 1052, 2 of 826, 9 of 221 and 3. In the twelfth session the stored brute force of the 807
bouncing and hopping cells was recomputed with the orbit search up to the window's length (87
changed: long orbits measured over whole orbits); on its final code, all 2076 cells: 2 of 1707
settled drifts off, 15 of 363 means, 4 without a warning. In the nineteenth session the
rolling-resistance grid's brute force was recomputed after the rolling torque was held to its
cap as a whole (34 of its 81 cells moved, by up to 0.38 in drift ratio; no regime changed).
In the twenty-fourth session, on its final code: 2 of 1708 settled drifts off, 14 of 357 means,
5 without a warning (at its start 2 of 1711, 13 of 352 and 4: the new bad mean, mmd with normal
damping 0.5 at m* 22.3, A* 8.7, is 0.92455 +- 0.00012 against 0.92439 from 1.28e5 periods; its
stored brute force, 0.21 and 0.36, had not converged). In the twenty-fifth session, on its final
code: 2 of 1707 settled drifts off, 14 of 358 means, 5 without a warning (the windows of a few
long flights no longer jump the speed: 44 drifts moved, the same bad counts, the median distance
from brute force in errors 0.27 -> 0.26).
"""

from __future__ import annotations

import argparse
import json
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

import sawdrift as sd

OUT = Path(__file__).parent / "results" / "audit.csv"

#: agreement: within REL relative or ABS absolute in drift ratio
REL, ABS = 1e-3, 2e-5


def scene_dict(model: str, m: float, a: float, extra: dict) -> dict:
    """The cell's scene fields: the model, m*, A*, and ``extra`` merged in (one level deep)."""
    sc: dict = {"model": model, "particle": {"m_star": m}, "drive": {"amplitude": a}}
    for key, value in extra.items():
        sc[key] = {**sc.get(key, {}), **value} if isinstance(value, dict) else value
    return sc


STORED = Path(__file__).parent / "results" / "audit_brute.csv"


def default_row(args: tuple[str, float, float, dict]) -> dict:
    """The default run of one cell."""
    model, m, a, extra = args
    res = sd.run(sd.Scene(**scene_dict(model, m, a, extra)))
    return {"m_star": m, "amplitude": a, "drift_ratio": res.drift_ratio,
            "drift_ratio_se": res.drift_ratio_se, "settled": bool(res.settled),
            "regime": res.regime, "settle_method": res.settle_method,
            "warnings": len(res.warnings)}


def cell(args: tuple[str, float, float, dict]) -> dict:
    """The default run of one cell and its two brute-force runs from rest."""
    model, m, a, extra = args
    sc = scene_dict(model, m, a, extra)
    mu = sd.Scene(**sc).material.mu
    n = max(4000, int(40 * m / mu) + 2000)
    runs = [sd.run(sd.Scene(**sc, numerics={"settle": False, "periods": p, "measure_periods": p // 2,
                                            "max_periods": p})) for p in (n, 2 * n)]
    return {**default_row(args), "brute_n": runs[0].drift_ratio,
            "brute_2n": runs[1].drift_ratio, "brute_regime": runs[1].regime}


def judge(rows: pd.DataFrame) -> pd.DataFrame:
    """The verdict columns of :func:`cell`'s rows (module docstring)."""
    x = rows.copy()
    x["bound"] = np.maximum(REL * x.brute_2n.abs(), ABS)
    x["converged"] = (x.brute_n - x.brute_2n).abs() <= x.bound
    x["error"] = (x.drift_ratio - x.brute_2n).abs()
    x["bad_settled"] = x.settled & (x.error > x.bound) & x.converged
    spread = (x.brute_n - x.brute_2n).abs()
    x["bad_mean"] = np.isfinite(x.drift_ratio_se) & (x.error > 3.0 * x.drift_ratio_se + spread)
    return x


def summary(name: str, rows: pd.DataFrame) -> str:
    """One line of counts for a judged grid (module docstring)."""
    failed = rows[rows.bad_settled | rows.bad_mean]
    return (f"{name}: {len(rows)} cells; settled {int(rows.settled.sum())}, "
            f"{int(rows.bad_settled.sum())} outside the bound; means "
            f"{int(np.isfinite(rows.drift_ratio_se).sum())}, {int(rows.bad_mean.sum())} more than "
            f"3 errors off; {int((failed.warnings == 0).sum())} failures without a warning; brute "
            f"force not converged on {int((~rows.converged).sum())}")


def print_failures(rows: pd.DataFrame) -> None:
    """The judged rows that failed, if any."""
    failed = rows[rows.bad_settled | rows.bad_mean]
    if len(failed):
        with pd.option_context("display.width", 200):
            print(failed[["m_star", "amplitude", "drift_ratio", "drift_ratio_se", "settled",
                          "settle_method", "brute_n", "brute_2n", "warnings"]].to_string())


def stored_grids(names: list[str]) -> tuple[pd.DataFrame, str | None]:
    """The stored brute force of the grids ``names`` (all where empty), or an error line naming
    the unknown ones and the grids there are."""
    brute = pd.read_csv(STORED)
    unknown = sorted(set(names) - set(brute.grid))
    if unknown:
        return brute, (f"--stored: no grid {', '.join(unknown)}; the grids are "
                       f"{', '.join(dict.fromkeys(brute.grid))}")
    return (brute[brute.grid.isin(names)] if names else brute), None


def stored(brute: pd.DataFrame, workers: int, out: Path) -> None:
    """Default runs judged against the stored brute force (``--stored``), grid by grid."""
    judged = []
    with ProcessPoolExecutor(workers) as ex:
        for name, grid in brute.groupby("grid", sort=False):
            todo = [(m, float(ms), float(a), json.loads(sc)) for m, ms, a, sc
                    in zip(grid.model, grid.m_star, grid.amplitude, grid.scene, strict=True)]
            rows = pd.DataFrame(list(ex.map(default_row, todo, chunksize=2)))
            for col in ("brute_n", "brute_2n", "brute_regime", "grid"):
                rows[col] = grid[col].to_numpy()
            rows = judge(rows)
            print(summary(str(name), rows), flush=True)
            print_failures(rows)
            judged.append(rows)
    rows = pd.concat(judged, ignore_index=True)
    print(summary("all", rows))
    out.parent.mkdir(parents=True, exist_ok=True)
    rows.to_csv(out, index=False)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("model", nargs="?", help="the model of a new grid (not with --stored)")
    ap.add_argument("--stored", nargs="*", default=None, metavar="GRID",
                    help="judge default runs against the stored brute force (all grids, or these)")
    ap.add_argument("--grid", type=int, default=13)
    ap.add_argument("--m-star", type=float, nargs=2, default=(0.0013, 0.9))
    ap.add_argument("--scene", default="{}", help="scene fields merged into every cell (JSON)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", type=Path, default=OUT)
    args = ap.parse_args()
    if args.stored is not None:
        brute, error = stored_grids(args.stored)
        if error:
            ap.error(error)  # one line, exit status 2
        stored(brute, args.workers, args.out)
        return
    if args.model is None:
        ap.error("a model, or --stored")
    extra = json.loads(args.scene)
    ms = np.logspace(*np.log10(args.m_star), args.grid)
    amps = np.logspace(np.log10(0.013), np.log10(8.7), args.grid)
    todo = [(args.model, float(m), float(a), extra) for m in ms for a in amps]
    with ProcessPoolExecutor(args.workers) as ex:
        rows = judge(pd.DataFrame(list(ex.map(cell, todo, chunksize=2))))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    rows.to_csv(args.out, index=False)
    print(summary(f"{args.model} {extra or ''}", rows))
    print_failures(rows)


if __name__ == "__main__":
    main()
