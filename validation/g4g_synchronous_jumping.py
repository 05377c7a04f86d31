"""The later full paper on this model (Terzi, Aleshin, Ghesquiere, Tournat, 2025) adds a jumping
regime with drift: the particle rebounds once per period at a fixed phase. In sawdrift that is
``hopping`` with hop period k = 1: exactly one lift-off in every period of the measurement window,
at a wave phase whose circular spread is small.

The case runs the three cells where the memory-diagram sphere jumps, (m*, A*) = (0.3, 1.5),
(10, 1.2) and (3, 1), for 200 periods, and draws where the mmd diagram of the shared 15 x 15 grid
is hopping.
"""

from __future__ import annotations

import sawdrift as sd
from sawdrift.validation import DIAGRAM_GRID, Case, CaseResult, regime_table

CELLS = ((0.3, 1.5), (10.0, 1.2), (3.0, 1.0))

CASE = Case(
    name="synchronous_jumping",
    group="diagrams",
    title="Later paper: jumping with drift, one rebound per period at a fixed phase. mmd at "
    "(m*, A*) = (0.3, 1.5), (10, 1.2), (3, 1): hopping with k = 1, one lift-off per period, phase "
    "spread below 0.05 period, non-zero drift; value: largest phase spread (periods)",
    tolerance=0.05,
    quick=True,
)


def run() -> CaseResult:
    """Run the three cells and draw the hopping region of the mmd diagram."""
    results = [sd.run(sd.Scene(model="mmd", particle={"m_star": m}, drive={"amplitude": a},
                               numerics={"periods": 200})) for m, a in CELLS]
    ok = all(r.regime == "hopping" and r.hop_period == 1 and abs(r.liftoffs_per_period - 1) < 1e-12
             and abs(r.drift_ratio) > 1e-3 for r in results)
    spread = max(r.liftoff_phase_spread for r in results)
    return CASE.result(
        spread,
        require=ok,
        message="; ".join(
            f"({m:g}, {a:g}): {r.regime}, k = {r.hop_period}, {r.liftoffs_per_period:g} lift-offs/"
            f"period at phase {r.liftoff_phase:.3f} +- {r.liftoff_phase_spread:.3f}, drift ratio "
            f"{r.drift_ratio:.3f}" for (m, a), r in zip(CELLS, results, strict=True)),
        figure=_figure(results),
    )


def _figure(results):
    import matplotlib.pyplot as plt

    table = regime_table("mmd")
    fig, ax = plt.subplots(figsize=(5.4, 4.2), layout="constrained")
    hop = table["regime"] == "hopping"
    bounce = table["regime"] == "bouncing"
    ax.scatter(table["amplitude"], table["m_star"], s=12, c="#dddddd", label="other regimes")
    ax.scatter(table.loc[bounce, "amplitude"], table.loc[bounce, "m_star"], s=22, c="#bcbddc",
               label="bouncing")
    ax.scatter(table.loc[hop, "amplitude"], table.loc[hop, "m_star"], s=30, c="#756bb1",
               label="hopping (synchronous jumping)")
    for (m, a), r in zip(CELLS, results, strict=True):
        ax.plot(a, m, "k*", ms=11)
        ax.annotate(f"V = {r.drift_ratio:.2f}", (a, m), textcoords="offset points", xytext=(6, 4),
                    fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("A*")
    ax.set_ylabel("m*")
    ax.set_title(f"mmd: where the sphere jumps ({DIAGRAM_GRID['periods']:g} periods; stars: "
                 "200-period runs)", fontsize=9)
    ax.legend(fontsize=8, loc="lower left")
    return fig
