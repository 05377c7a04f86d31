"""Conformance of every installed model (sawdrift check-model), with its loop work per cycle.

Every registered model runs the conformance suite (:mod:`sawdrift.contact.conformance`) on every
profile it declares: N*(1) = 1, passivity (loop work of N* da* + T* db* on closed (a*, b*)
cycles in both orientations, at the cycles' velocities), the Coulomb bound, compiled kernel
against the pure-Python reference (velocities included, up to a* = 20), velocity independence
for models that declare it, split invariance, contact-loss reset and replay. A check a model
fails but declares (with its reason) is an expected deviation of that model, shown with its
value; an undeclared failure fails the case. The figure shows the loop work of each cycle shape
and orientation for every model on the sphere: a passive contact has all its bars >= 0.
"""

from __future__ import annotations

import numpy as np

from sawdrift.contact.conformance import check_model, cycles, loop_works
from sawdrift.contact.registry import registry
from sawdrift.validation import Case, CaseResult

PLAIN_DEM = "hertz_mindlin_dem[rescale=false]"

CASE = Case(
    name="conformance",
    group="conformance",
    title="Every installed model passes the conformance suite on every profile it declares "
    "(normalization, passivity with the normal work, Coulomb bound, kernel vs reference, velocity "
    "independence, split invariance, contact-loss reset, replay) or declares the check it misses; "
    "value: number of undeclared failures",
    tolerance=0,
    quick=True,
)


def run() -> CaseResult:
    """Check every model; draw the loop work per cycle of the compliant ones."""
    results = {name: check_model(name) for name in registry.names()}
    if "hertz_mindlin_dem" in results:
        # LAMMPS mindlin/force (no rescaling): its declared energy creation is shown, not hidden
        results[PLAIN_DEM] = check_model("hertz_mindlin_dem", rescale=False)
    failures = [f"{m}/{c.profile}/{c.name}" for m, r in results.items() for c in r.failures]
    declared = []
    for m, r in results.items():
        for name in dict.fromkeys(c.name for c in r.checks if c.status == "declared"):
            rows = [c for c in r.checks if c.name == name and c.status == "declared"]
            declared.append(f"{m}: {name} ({', '.join(f'{c.profile} {c.value:.3g}' for c in rows)})")
    notes = [f"{len(results)} models; undeclared failures: " + (", ".join(failures) or "none")]
    if declared:
        notes.append("declared deviations: " + "; ".join(declared))
    return CASE.result(len(failures), message=". ".join(notes), figure=_figure(results),
                       details={m: r.to_json() for m, r in results.items()})


def _figure(results):
    import matplotlib.pyplot as plt

    from sawdrift.contact.registry import get_model

    def build(label):
        if label == PLAIN_DEM:
            cls = get_model("hertz_mindlin_dem")
            return cls(cls.Params(rescale=False))
        return get_model(label)()

    names = [m for m in results if not build(m).capabilities.rigid]
    shapes = list(cycles())
    labels = [f"{s} {o}" for s in shapes for o in ("fwd", "rev")]
    fig, ax = plt.subplots(figsize=(9.0, 4.2), layout="constrained")
    width = 0.8 / max(len(names), 1)
    x = np.arange(len(labels))
    for i, name in enumerate(names):
        model = build(name)
        per_cycle = []
        for verts in cycles().values():
            for vv in (verts, verts[::-1]):
                works, _ = loop_works(model, vv, laps=3)
                per_cycle.append(works[-1])
        ax.bar(x + (i - (len(names) - 1) / 2) * width, per_cycle, width, label=name)
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_yscale("symlog", linthresh=1e-3)
    ax.set_xticks(x, labels, rotation=30, ha="right", fontsize=8)
    ax.set_ylabel("loop work per cycle, closed integral of N* da* + T* db*")
    ax.set_title("Passivity: loop work >= 0 on every closed (a*, b*) cycle", fontsize=10)
    ax.legend(fontsize=8, ncol=3)
    return fig
