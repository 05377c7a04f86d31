"""The ``settled`` flag of fixed-length runs is never wrong in the unsafe direction.

Every run of fixed length reports whether its drift is the steady one. Over a grid of cells
(mmd and the material point; m* = 0.1 to 1000, A* = 0.1 to 4, mu = 0.1, the default 60
periods) the reference is a settled run of the same cell. Value: runs flagged settled whose
drift differs from the reference by more than 2e-3 (must be 0). The runs flagged unsettled
although within 2e-3 are reported (the flag is conservative by design).
"""

from __future__ import annotations

import itertools

import sawdrift as sd
from sawdrift.validation import Case, CaseResult

CASE = Case(
    name="settled_flag",
    group="steady",
    title="Fixed 60-period runs over m* 0.1..1000, A* 0.1..4 (mmd, material_point): flagged "
    "settled but more than 2e-3 from the settled drift; value: such runs",
    tolerance=0,
    quick=False,
)


def run(quick: bool = False) -> CaseResult:  # noqa: ARG001 - the case is not in the quick subset
    """Run every cell plain and settled."""
    wrong, missed, flagged, n = [], 0, 0, 0
    for model, m, a in itertools.product(("mmd", "material_point"), (0.1, 1.0, 10.0, 100.0, 1000.0),
                                         (0.1, 0.3, 1.5, 4.0)):
        scene = sd.Scene(model=model, particle={"m_star": m}, drive={"amplitude": a},
                         numerics={"settle": False})  # fixed runs (heavy ones settle by default)
        plain = sd.run(scene)
        ref = sd.run(scene.with_updates(**{"numerics.settle": True, "numerics.max_periods": 1e5}))
        close = abs(plain.drift_ratio - ref.drift_ratio) <= 2e-3
        n += 1
        flagged += bool(plain.settled)
        if plain.settled and not close:
            wrong.append(f"{model} m* {m:g} A* {a:g}")
        missed += (not plain.settled) and close
    # the flag must be set on some runs and not on all (a flag never set would pass vacuously):
    # at least an eighth of them. 7 of the 40 are settled; the held contacts of m* 10, 100 and
    # 1000 at A* 0.1 are not (their 27-period windows are shorter than the vertical period, and
    # their box means 4e-5 to 2e-4 from the steady 1e-6: the tapered mean is not at the floor),
    # nor, since a window's thirds are judged relative to its drift, mmd m* 0.1, A* 0.3 (its
    # thirds beat by 6.8e-4 around 0.3493) and the material point at m* 0.1, A* 4
    return CASE.result(
        len(wrong),
        require=flagged >= n // 8 and flagged < n,
        message=f"{n} runs, {flagged} flagged settled; wrongly settled: {', '.join(wrong) or 'none'}; "
        f"within 2e-3 but flagged unsettled: {missed}",
    )
