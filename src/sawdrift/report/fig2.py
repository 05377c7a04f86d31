"""The paper's Fig. 2: trajectories x*(t*) of the regimes, with insets at one wave period.

Four runs of the memory-diagram sphere (mmd, mu = 0.1, nu = 0.3, prograde orbit), one per regime
of the paper: weak oscillation without drift (stick), drift with the wave, drift against it, and
contact loss (bouncing). Each panel shows x*(t*) over the run and, inset, the last wave period
with the substrate's u_x(t*) for scale. The regime printed is the one sawdrift finds.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..result.runner import run  # noqa: E402
from ..scene.schema import Scene  # noqa: E402
from .plots import unsettled_mark  # noqa: E402

#: (label, m*, A*) of the four panels
CELLS = (
    ("weak oscillation, no drift", 1.0, 0.01),
    ("drift with the wave", 0.1, 0.316),
    ("drift against the wave", 0.01, 0.562),
    ("contact loss, bouncing", 0.01, 5.0),
)


def plot_fig2(path: str | Path, periods: float = 60.0) -> Path:
    """Draw the four regimes' trajectories to ``path`` (PNG) and return it."""
    fig, axes = plt.subplots(2, 2, figsize=(10.0, 7.0), layout="constrained")
    for ax, (label, m, a) in zip(axes.flat, CELLS, strict=True):
        scene = Scene(model="mmd", particle={"m_star": m}, drive={"amplitude": a},
                      numerics={"periods": periods})
        res = run(scene, trajectory=True)
        tr = res.trajectory
        ax.plot(tr["t"], tr["x"], color="#3182bd", lw=1.0)
        ax.set_title(f"{label}\nsawdrift: {res.regime}, V = {res.drift_ratio:+.3f}"
                     f"{unsettled_mark(res)}", fontsize=9)
        ax.set_xlabel("t* (wave periods)")
        ax.set_ylabel("x*")
        ax.plot([], [], " ", label=f"m* = {m:g}, A* = {a:g}")
        ax.legend(loc="upper left", fontsize=8, frameon=False)
        last = tr[tr["t"] >= tr["t"].iloc[-1] - 1.0]
        ins = ax.inset_axes([0.58, 0.08, 0.38, 0.34])
        t = last["t"].to_numpy()
        ins.plot(t, last["x"] - last["x"].iloc[0], color="#3182bd", lw=1.0, label="x*")
        ux = -a * scene.horizontal_ratio * np.sin(2 * np.pi * t)
        ins.plot(t, ux - ux[0], color="0.6", lw=0.8, ls="--", label="u_x")
        ins.set_title("last period", fontsize=7)
        ins.tick_params(labelsize=6)
        ins.legend(fontsize=6, frameon=False, loc="upper right")
    fig.suptitle("Four motion regimes of a deformable sphere (mmd, mu = 0.1, nu = 0.3)", fontsize=11)
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
