"""A material point never drifts with the wave (paper section 5; docs/physics.md)."""

from __future__ import annotations

from sawdrift.validation import Case, CaseResult, regime_class, regime_table

#: |drift ratio| at or below this is "no steady drift" (the default Numerics.drift_tolerance).
DRIFT_TOL = 1e-3

CASE = Case(
    name="point_never_drifts_with",
    group="diagrams",
    title="On the material point's diagram no cell drifts with the wave while in contact "
    "(no drift_with cell); value: largest drift ratio among cells that keep contact",
    tolerance=DRIFT_TOL,
    quick=True,
)


def run() -> CaseResult:
    """Read the drift ratios of the point's cells in contact."""
    table = regime_table("material_point")
    kept = table[[regime_class(g) != "lost" for g in table["regime"]]]
    lost = table[[regime_class(g) == "lost" for g in table["regime"]]]
    n_with = int((table["regime"] == "drift_with").sum())
    n_lost_pos = int((lost["drift_ratio"] > DRIFT_TOL).sum())
    return CASE.result(
        float(kept["drift_ratio"].max()),
        require=n_with == 0,
        message=f"{len(kept)} cells keep contact, {n_with} drift with the wave; "
        f"(not covered by the statement: {n_lost_pos} of {len(lost)} hopping/bouncing cells have a "
        "net displacement with the wave)",
    )
