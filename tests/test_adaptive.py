"""Adaptive phase diagrams: refinement follows the regime boundaries; resumable."""

from __future__ import annotations

import numpy as np

import sawdrift as sd
from sawdrift.study.adaptive import adaptive_sweep, misclassified_area

BASE = sd.Scene(numerics={"periods": 30})


def test_adaptive_point_diagram_matches_the_uniform_one_with_fewer_cells(tmp_path):
    # material point, 9 x 9 base grid refined twice (the 33 x 33 grid's nodes)
    pts = adaptive_sweep("material_point", (1e-3, 1e2), (1e-2, 10.0), budget=450, base=9,
                         levels=2, scene=BASE, workers=1, table=tmp_path / "a.parquet")
    uniform = sd.sweep(["material_point"], "1e-3:1e2:33", "1e-2:10:33", base=BASE, workers=1,
                       progress=False)
    assert int((~pts["inferred"]).sum()) <= 0.45 * len(uniform)
    assert misclassified_area(pts, uniform) < 0.05
    # the refined points crowd the contact-loss boundary Gz = 4 pi^2 m* A* = 1 (closed form):
    # far more of them lie within a quarter decade of it than on the uniform grid
    def near(frame):
        gz = 4 * np.pi**2 * frame["m_star"] * frame["amplitude"]
        return float(np.mean(np.abs(np.log10(gz)) < 0.25))

    assert near(pts[~pts["inferred"]]) > 1.3 * near(uniform)


def test_adaptive_sweep_resumes_without_recomputing(tmp_path):
    table = tmp_path / "a.parquet"
    kw = dict(budget=150, base=5, levels=2, scene=BASE, workers=1, table=table)
    first = adaptive_sweep("material_point", (1e-3, 1e2), (1e-2, 10.0), **kw)
    computed = []
    again = adaptive_sweep("material_point", (1e-3, 1e2), (1e-2, 10.0), on_row=computed.append, **kw)
    assert computed == [] and len(again) == len(first)
    assert again["regime"].tolist() == first["regime"].tolist()
