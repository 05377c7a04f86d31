"""Proportional loading from zero, b* = lambda a* with |lambda| <= 1, never slips: T* = lambda N*(a*).

This is the Mindlin-Deresiewicz load-path result under a *varying* a*: strips enter contact
with zero displacement. The ``jaeger`` model keeps its profile attached to the moving contact
edge and gives N*(a*) - N*((1 - lambda) a*) instead (by design, see its module docstring).
"""

from __future__ import annotations

import numpy as np

from sawdrift.validation import COMPLIANT_MODELS, DEVIATION_TOL, Case, CaseResult, prescribed

CASE = Case(
    name="cm_proportional",
    group="mindlin",
    title="Oblique loading from zero along b* = lambda a* (lambda = -0.5, 0.3, 0.7, 1; a* up to 1.5) "
    "against T* = lambda N*(a*); value: max |T* - lambda N*| / N*(a*_max)",
    tolerance=1e-9,
    model_tolerance={"mdr": 1e-3},
    expected_deviation=("jaeger",),
    deviation_reason={
        "jaeger": (
            "jaeger keeps its profile attached to the moving contact edge, so oblique "
            "loading from zero gives N*(a*) - N*((1 - lambda) a*), not lambda N*(a*): it is exact "
            "only at constant a*"
        ),
    },
    models=COMPLIANT_MODELS,
    quick=True,
)


def run(model: str) -> CaseResult:
    """Drive four proportional paths and compare T* with lambda N*."""
    worst, own, parts = 0.0, 0.0, []
    for lam in (-0.5, 0.3, 0.7, 1.0):
        tr = prescribed(model, {"waveform": "proportional", "a_max": 1.5, "slope": lam,
                                "samples_per_segment": 1000})
        t, a = tr["T_star"].to_numpy(), tr["a"].to_numpy()
        err = np.abs(t - lam * tr["N_star"].to_numpy()) / 1.5**1.5
        worst = max(worst, float(err.max()))
        # jaeger's own: its profile attached to the contact edge, sgn(lambda) [N*(a*) -
        # N*((1 - |lambda|) a*)] with N* = a*^(3/2)
        edge = np.sign(lam) * (np.clip(a, 0.0, None) ** 1.5
                               - np.clip((1.0 - abs(lam)) * a, 0.0, None) ** 1.5)
        own = max(own, float(np.abs(t - edge).max()) / 1.5**1.5)
        parts.append(f"lambda = {lam}: {err.max():.2e}")
    message = "max error " + "; ".join(parts)
    matches = None
    if CASE.deviation_expected(model):
        matches = own <= DEVIATION_TOL
        message += f"; against N*(a*) - N*((1 - lambda) a*): {own:.2e}"
    return CASE.result(worst, model=model, message=message, deviation_matches=matches)
