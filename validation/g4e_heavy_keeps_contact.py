"""A heavy deformable particle keeps contact where the material point detaches (paper section 5).

For m* >> 1 and A* well below 1 (here m* >= 10, A* <= 0.3, where Gz = 4 pi^2 m* A* >> 1) the
point loses contact, while the compliant sphere, whose static compression a* = 1 exceeds the
wave amplitude, follows the substrate. The normal equation does not involve the tangential law,
so every compliant model must agree.
"""

from __future__ import annotations

from sawdrift.validation import COMPLIANT_MODELS, Case, CaseResult, regime_class, regime_table

CASE = Case(
    name="heavy_keeps_contact",
    group="diagrams",
    title="In the cells m* >= 10, A* <= 0.3 where the material point loses contact, the deformable "
    "particle keeps it; value: cells where the model loses contact too",
    tolerance=0,
    models=COMPLIANT_MODELS,
    quick=True,
)


def run(model: str) -> CaseResult:
    """Compare contact loss cell by cell with the material point's diagram."""
    point = regime_table("material_point")
    mine = regime_table(model)
    merged = point.merge(mine, on=["m_star", "amplitude"], suffixes=("_point", "_model"))
    zone = merged[(merged["m_star"] >= 10.0) & (merged["amplitude"] <= 0.3)]
    detached = zone[[regime_class(g) == "lost" for g in zone["regime_point"]]]
    both = int(sum(regime_class(g) == "lost" for g in detached["regime_model"]))
    return CASE.result(
        both,
        model=model,
        require=len(detached) >= 10,
        message=f"{len(zone)} cells in the zone, the point detaches in {len(detached)}; "
        f"{model} loses contact in {both} of them (its regimes there: "
        + ", ".join(f"{k} {v}" for k, v in detached["regime_model"].value_counts().items()) + ")",
    )
