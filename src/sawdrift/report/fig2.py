"""The paper's Fig. 2: trajectories x*(t*) of the regimes, each beside its last wave period.

Four runs of the memory-diagram sphere (mmd, mu = 0.1, nu = 0.3, prograde orbit), one per regime
of the paper: weak oscillation without drift (stick), drift with the wave, drift against it, and
contact loss (bouncing). Each run goes until its drift has settled (``numerics.settle``, at least
60 periods), as the demo's phase diagrams do; each panel shows x*(t*) over the run and, beside it
(not over it: the run's last periods stay visible), the last wave period with the substrate's
u_x(t*) for scale. The regime printed is the one sawdrift finds, with how its drift was settled.

The cell of drift against the wave settles in 141 periods; the earlier choice, m* = 0.01,
A* = 0.56, settles only after 357 (-0.3468), its free vertical oscillation, which nothing damps,
beating against the wave for that long.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..result.result import Result  # noqa: E402
from ..result.runner import run  # noqa: E402
from ..scene.schema import Scene  # noqa: E402
from .plots import unsettled_mark  # noqa: E402

#: (label, m*, A*) of the four panels
CELLS = (
    ("weak oscillation, no drift", 1.0, 0.01),
    ("drift with the wave", 0.1, 0.316),
    ("drift against the wave", 0.0056, 1.26),
    ("contact loss, bouncing", 0.01, 5.0),
)

#: most points of a trajectory drawn (a long settle run is thinned evenly)
MAX_POINTS = 20000


def fig2_scene(m_star: float, amplitude: float, periods: float = 60.0) -> Scene:
    """The scene of one panel: mmd at (m*, A*), run until its drift settles."""
    return Scene(model="mmd", particle={"m_star": m_star}, drive={"amplitude": amplitude},
                 numerics={"periods": periods, "settle": True})


def verdict(res: Result) -> str:
    """How the panel's drift was reached: settled after n periods, or why it is not steady."""
    if res.settled:
        return f", settled after {res.settle_periods:.0f} periods"
    if res.drift_ratio_se == res.drift_ratio_se:  # a long-time mean with its error (not NaN)
        return f"{unsettled_mark(res)}: irregular, long-time mean +- {res.drift_ratio_se:.3f}"
    if res.regime in ("bouncing", "hopping"):
        return f"{unsettled_mark(res)}: irregular, the mean of its last window"
    return unsettled_mark(res)


def signed(v: float) -> str:
    """A drift ratio for a title: three decimals, or two significant digits below 5e-4 (a
    sticking particle's -3e-7 read "-0.000")."""
    return f"{v:+.3f}" if abs(v) >= 5e-4 or v != v else f"{v:+.1e}"


def _panel(sub, label: str, m: float, a: float, periods: float) -> None:
    """One regime: x*(t*) over the run (left) and its last period beside u_x (right)."""
    scene = fig2_scene(m, a, periods)
    res = run(scene, trajectory=True)
    tr = res.trajectory
    step = max(1, len(tr) // MAX_POINTS)
    ax, last_ax = sub.subplots(1, 2, width_ratios=(2.4, 1.0))
    ax.plot(tr["t"].to_numpy()[::step], tr["x"].to_numpy()[::step], color="#3182bd", lw=1.0)
    ax.set_xlabel("t* (wave periods)")
    ax.set_ylabel("x*")
    ax.grid(alpha=0.3)
    last = tr[tr["t"] >= tr["t"].iloc[-1] - 1.0]
    t = last["t"].to_numpy()
    last_ax.plot(t, last["x"] - last["x"].iloc[0], color="#3182bd", lw=1.0, label="x*")
    ux = -a * scene.horizontal_ratio * np.sin(2 * np.pi * t)
    last_ax.plot(t, ux - ux[0], color="0.5", lw=0.9, ls="--", label="u_x")
    last_ax.set_title("last period", fontsize=8)
    last_ax.set_xlabel("t*", fontsize=8)
    last_ax.tick_params(labelsize=7)
    last_ax.grid(alpha=0.3)
    last_ax.legend(fontsize=7, frameon=False, loc="best")
    sub.suptitle(f"{label}: m* = {m:g}, A* = {a:g}\nsawdrift: {res.regime}, "
                 f"V = {signed(res.drift_ratio)}{verdict(res)}", fontsize=9)


def plot_fig2(path: str | Path, periods: float = 60.0,
              cells: tuple[tuple[str, float, float], ...] = CELLS) -> Path:
    """Draw the regimes' trajectories (default: the four :data:`CELLS`) to ``path`` (PNG)."""
    rows = -(-len(cells) // 2)
    fig = plt.figure(figsize=(11.0, 3.7 * rows + 0.4), layout="constrained")
    subs = np.atleast_1d(fig.subfigures(rows, 2, wspace=0.04, hspace=0.04)).ravel()
    for sub, (label, m, a) in zip(subs, cells, strict=False):
        _panel(sub, label, m, a, periods)
    fig.suptitle("Motion regimes of a deformable sphere (mmd, mu = 0.1, nu = 0.3); "
                 "V = <x*'> / (2 pi r A*), the drift over the horizontal surface speed",
                 fontsize=11)
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
