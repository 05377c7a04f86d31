"""The default run of a scene beside brute force from rest at full inertia, for tests that hold
the steady drift to the acceptance bound (1e-3 relative or 2e-5 absolute)."""

from __future__ import annotations

from typing import Any

import sawdrift as sd


def default_and_brute(periods: int | None = None, **scene: Any) -> tuple[sd.Result, sd.Result]:
    """(the default run, brute force) of ``Scene(**scene)``: a fixed run of ``periods`` periods
    (default N = 40 m*/mu + 2000) measured over its last quarter."""
    res = sd.run(sd.Scene(**scene))
    m, mu = res.m_star, res.mu
    n = periods if periods is not None else round(40.0 * m / mu + 2000.0)
    brute = sd.run(sd.Scene(**scene, numerics={"settle": False, "periods": n,
                                               "measure_periods": n // 4}))
    return res, brute
