"""Each compliant model's numba kernel reproduces its own pure-Python reference.

The runner uses the compiled kernel; the reference is the readable statement of the law. They
are driven through the same random two-axis history with contact loss.
"""

from __future__ import annotations

import numpy as np

from sawdrift.validation import COMPLIANT_MODELS, Case, CaseResult, prescribed

DRIVE = {"waveform": "random", "a_max": 1.0, "cycles": 3, "samples_per_segment": 100, "seed": 3}

CASE = Case(
    name="kernel_vs_reference",
    group="convergence",
    title="Compiled kernel against the model's own pure-Python reference on a random (a*, b*) "
    "history; value: max |difference in N*, T*| / max N*",
    tolerance=1e-10,
    models=COMPLIANT_MODELS,
)


def run(model: str) -> CaseResult:
    """Drive both engines through the same history."""
    fast = prescribed(model, DRIVE, engine="compiled")
    slow = prescribed(model, DRIVE, engine="python")
    scale = float(slow["N_star"].max())
    diff = max(float(np.abs(fast[c].to_numpy() - slow[c].to_numpy()).max())
               for c in ("N_star", "T_star")) / scale
    return CASE.result(diff, model=model, message=f"{len(fast)} samples; max difference {diff:.2e}")
