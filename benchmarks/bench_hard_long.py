"""Long versions of the hard cases in tests/hard (CI runs the short ones).

Every case of ``tests/hard/test_hard_cases.py`` runs for 1e4 periods at the default step and at
twice the default step, with both engines compared over 20 periods. The script prints, per case:
finite or not, the drift ratio at both steps and their difference, the energy residual relative
to the total work, the largest python/compiled difference, and the wall time. It exits 1 if a
value is not finite or the engines disagree.

    python benchmarks/bench_hard_long.py [--periods 10000]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

from sawdrift.dynamics.assembly import steps_per_period

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import sawdrift as sd  # noqa: E402
from sawdrift.dynamics.energy import energy_residual  # noqa: E402
from tests.hard.test_hard_cases import CASES, _scene  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--periods", type=float, default=10_000.0)
    args = parser.parse_args()
    bad = 0
    print(f"{'case':24} {'finite':>6} {'V(K)':>12} {'V(2K)':>12} {'|dV|':>9} {'energy':>9} "
          f"{'engines':>9} {'wall s':>7}")
    for name in sorted(CASES):
        t0 = time.perf_counter()
        base = _scene(CASES[name], periods=args.periods)
        k = steps_per_period(base)
        coarse = sd.run(base)
        fine = sd.run(_scene(CASES[name], periods=args.periods, steps=2 * k))
        finite = all(math.isfinite(r.drift_ratio) for r in (coarse, fine))
        short = _scene(CASES[name], periods=20.0)
        traj = sd.run(short, trajectory=True, record_every=1)
        resid, scale = energy_residual(traj.trajectory, traj.m_star, traj.mu)
        slow = sd.run(short, trajectory=True, record_every=1, engine="python")
        cols = ["x", "vx", "y", "vy", "N_star", "T_star"]
        diff = float(np.max(np.abs(traj.trajectory[cols].to_numpy() - slow.trajectory[cols].to_numpy())))
        ok = finite and diff < 1e-6 * max(1.0, float(np.abs(traj.trajectory[cols].to_numpy()).max()))
        bad += not ok
        print(f"{name:24} {str(finite):>6} {coarse.drift_ratio:12.6g} {fine.drift_ratio:12.6g} "
              f"{abs(coarse.drift_ratio - fine.drift_ratio):9.2e} {resid / max(scale, 1e-300):9.2e} "
              f"{diff:9.2e} {time.perf_counter() - t0:7.1f}")
    print(f"{len(CASES) - bad} of {len(CASES)} cases finite with agreeing engines")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
