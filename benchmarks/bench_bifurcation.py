"""Bifurcation diagrams: how long a whole diagram takes (issue 24's targets).

1. The material point (restitution 0, r = 0: the completely inelastic bouncing ball), 200 values
   of A* = Gamma / (4 pi^2 m*) for Gamma in [0.5, 4.5], 64 Poincare samples each, swept upwards,
   table, summary and figure written. Target: at most 30 s. The same diagram with ``locate=True``
   is timed too (its located thresholds printed against 1, sqrt(1 + pi^2), sqrt(4 + pi^2)).
2. mmd (m* = 0.1, normal damping 0.3, mu = 0.1, the Rayleigh ratio of nu = 0.3), 100 values of
   A* in [0.1, 1.5], 64 samples, swept up and down in two processes (``workers=2``), files
   written. Target: at most 60 s on 2 cores.

Each timed call is preceded by a two-value warm-up of the same scene (compilation, cache
loading), which is discarded. Writes benchmarks/results/bifurcation.json.

    python benchmarks/bench_bifurcation.py
"""

from __future__ import annotations

import json
import math
import tempfile
import time
from pathlib import Path

import sawdrift as sd
from sawdrift.report.bifurcation_plot import plot_bifurcation
from sawdrift.study.bifurcation import FIGURE, bifurcation

HERE = Path(__file__).parent
M_POINT = 0.1
EXACT = {"lift_off": 1.0, "sticking_lost": math.sqrt(1 + math.pi**2),
         "period_doubling": math.sqrt(4 + math.pi**2)}


def _timed(scene: sd.Scene, values: str, out: Path, **kwargs) -> tuple[float, object]:
    bifurcation(scene, "drive.amplitude", values.rsplit(":", 1)[0] + ":2", samples=4,
                progress=False, workers=kwargs.get("workers", 1))  # warm-up
    t0 = time.perf_counter()
    res = bifurcation(scene, "drive.amplitude", values, samples=64, out=out, progress=False,
                      **kwargs)
    plot_bifurcation(res, out / FIGURE)
    return time.perf_counter() - t0, res


def main() -> None:
    """Run both diagrams, print PASS/FAIL lines, store the numbers."""
    k = 4 * math.pi**2 * M_POINT
    point = sd.Scene(model="material_point", particle={"m_star": M_POINT},
                     drive={"horizontal_ratio": 0.0})
    mmd = sd.Scene(model="mmd", particle={"m_star": 0.1}, effects={"normal_damping": 0.3})
    numbers: dict[str, object] = {}
    with tempfile.TemporaryDirectory() as tmp:
        axis = f"lin:{0.5 / k}:{4.5 / k}:200"
        t_point, res = _timed(point, axis, Path(tmp) / "point", workers=1)
        failed = sum(p["error"] is not None for p in res.summary["points"]["material_point"]["up"])
        ok = t_point <= 30.0
        print(f"material point, 200 values x 64 samples (up, 1 process): {t_point:.1f} s "
              f"(target <= 30 s), {failed} values failed: {'PASS' if ok else 'FAIL'}")
        t_loc, res_loc = _timed(point, axis, Path(tmp) / "point_locate", workers=2, locate=True)
        found = {b["kind"]: b["value"] * k for b in res_loc.bifurcations
                 if b["kind"] in EXACT and b["located"]}
        errors = {kind: abs(found[kind] - v) if kind in found else math.inf
                  for kind, v in EXACT.items()}
        print(f"  with --locate (2 processes): {t_loc:.1f} s; "
              + ", ".join(f"{kind} {found.get(kind, math.nan):.5f} (exact {v:.5f})"
                          for kind, v in EXACT.items()))
        t_mmd, res_mmd = _timed(mmd, "lin:0.1:1.5:100", Path(tmp) / "mmd", workers=2,
                                direction="both")
        ok_mmd = t_mmd <= 60.0
        n_hyst = len(res_mmd.hysteresis)
        print(f"mmd, 100 values x 64 samples, up and down (2 processes): {t_mmd:.1f} s "
              f"(target <= 60 s), {n_hyst} hysteresis intervals: {'PASS' if ok_mmd else 'FAIL'}")
    numbers.update(point_s=t_point, point_failed_values=failed, point_locate_s=t_loc,
                   point_located=found, point_errors=errors, mmd_both_s=t_mmd,
                   mmd_hysteresis=res_mmd.hysteresis, passed=ok and ok_mmd)
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    (out / "bifurcation.json").write_text(json.dumps(numbers, indent=2, default=str) + "\n")
    if not (ok and ok_mmd):
        raise SystemExit(1)


if __name__ == "__main__":
    import argparse

    # no options: --help prints what the script does and where it writes, and runs nothing
    argparse.ArgumentParser(description=__doc__,
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    main()
