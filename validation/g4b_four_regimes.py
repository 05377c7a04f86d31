"""The deformable sphere shows four regimes (paper section 5, Fig. 3): weak oscillation without
drift, contact loss, drift with the wave, drift against the wave."""

from __future__ import annotations

from sawdrift.report.validation import Case, CaseResult, regime_class, regime_table

FOUR = ("stick", "lost", "drift_with", "drift_against")

CASE = Case(
    name="four_regimes",
    group="diagrams",
    title="The Mindlin sphere's diagram holds all four regimes: stick, contact loss (hopping or "
    "bouncing), drift with and drift against the wave; value: how many of the four appear",
    tolerance=4,
    compare=">=",
    models=("mmd", "mdr"),
    quick=True,
)


def run(model: str) -> CaseResult:
    """Count the regime classes found on the shared diagram grid."""
    table = regime_table(model)
    classes = [regime_class(g) for g in table["regime"]]
    found = [c for c in FOUR if c in classes]
    return CASE.result(
        len(found),
        model=model,
        message=", ".join(f"{c}: {classes.count(c)} cells" for c in FOUR),
    )
