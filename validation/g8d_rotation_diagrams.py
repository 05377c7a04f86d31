"""Rotation: regime diagrams of the material point and the memory-diagram sphere, rotation off
and on, side by side (docs/regimes.md, "What rolling changes").

The fact checked: rotation changes only the tangential motion. The normal equation does not
depend on x* or on the rotation, so the cells that lose contact (hopping or bouncing) must be
the same with and without rotation, for both models. 9 x 9 cells, m* in [1e-3, 1e2], A* in
[1e-2, 10], 40 periods, kappa = 2/5.
"""

from __future__ import annotations

import sawdrift as sd
from sawdrift.validation import Case, CaseResult, regime_class

CASE = Case(
    name="rotation_diagrams",
    group="rotation",
    title="Rotation off and on (kappa = 2/5), material point and mmd, 9 x 9 cells: the "
    "contact-loss cells coincide; value: number of cells whose contact loss differs",
    tolerance=0,
    quick=True,
)


def run() -> CaseResult:
    """Sweep both models with rotation off and on; compare contact loss; draw them."""
    import tempfile
    from pathlib import Path

    from sawdrift.report.compare_plot import plot_compare

    table = sd.sweep(["material_point", "mmd"], "1e-3:1e2:9", "1e-2:10:9",
                     axes={"effects.rotation": "false,true"}, base=sd.Scene(numerics={"periods": 40}),
                     progress=False)
    lost = table.assign(lost=[regime_class(r) == "lost" for r in table["regime"]])
    pivot = lost.pivot_table(index=["model", "m_star", "amplitude"], columns="effects.rotation",
                             values="lost", aggfunc="first")
    differ = int((pivot[False] != pivot[True]).sum())
    # not vacuous: each model loses contact in a good part of the plane (a regime_class that
    # never said "lost" compared 0 with 0)
    losing = {m: int(pivot.loc[m][False].sum()) for m in ("material_point", "mmd")}
    counts = {(m, rot): int(((table["model"] == m) & (table["effects.rotation"] == rot)
                             & (table["regime"] == reg)).sum())
              for m in ("material_point", "mmd") for rot in (False, True)
              for reg in ("drift_against",)}
    with tempfile.TemporaryDirectory() as tmp:
        path, _ = plot_compare(table, ["material_point", "mmd"], Path(tmp) / "rot.png",
                               by="effects.rotation")
        png = path.read_bytes()
    return CASE.result(
        differ,
        require=min(losing.values()) >= 10,
        message=f"contact-loss cells differing: {differ} (cells losing contact without rotation: "
        f"material point {losing['material_point']}, mmd {losing['mmd']}, at least 10 each); "
        "drift against the wave, rotation off -> on: "
        f"material point {counts[('material_point', False)]} -> {counts[('material_point', True)]}, "
        f"mmd {counts[('mmd', False)]} -> {counts[('mmd', True)]} cells",
        figure=png,
    )
