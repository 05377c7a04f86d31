"""Steady drift of heavy particles: the default run against full-inertia brute force.

The reference is ``validation/data/steady_reference.json``, made by
``benchmarks/steady_reference.py``: for heavy cells (mmd, hertz_mindlin_dem, jaeger, and the
damped hertz_tsuji plugin; m* = 30 to 1e4) a plain run at full inertia of at least
40 m*/mu + 2000 periods, measured over its last 30 % (and at least three periods of the free
vertical oscillation, 2 pi sqrt(m*/1.5)), checked
against a run half as long and one with twice the steps per period. The cells are labelled
``creep`` (a partly stuck contact creeping at the stick boundary, drift ratio below 1e-3),
``drifting`` (steady sliding drift) and ``hopping`` (contact lost, synchronous).

For each cell the DEFAULT :func:`sawdrift.run` of the scene (no numerics set: a heavy particle
settles its drift by itself) must agree with the reference within 1e-3 relative or 2e-5
absolute in drift ratio, and report the same regime. Value: the worst relative error among the
cells outside the absolute bound (0 if every cell is within it); the message also names the
worst relative error over all cells. The quick subset runs the cheapest cell of each kind.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

import sawdrift as sd
from sawdrift.validation import Case, CaseResult

#: the stored reference (benchmarks/steady_reference.py writes it)
DATA = Path(__file__).parent / "data" / "steady_reference.json"
#: agreement: within REL relative or ABS absolute in drift ratio
REL, ABS = 1e-3, 2e-5
KIND_COLOURS = {"creep": "#3182bd", "drifting": "#31a354", "hopping": "#e6550d", "stick": "0.5"}

CASE = Case(
    name="steady_vs_full_inertia",
    group="steady",
    title="Default run of heavy cells (mmd, hertz_mindlin_dem, jaeger, damped hertz_tsuji; m* 30 "
    "to 1e4; creep, drifting, hopping) against stored full-inertia brute force: within 1e-3 "
    "relative or 2e-5 absolute (the resolution of a default run: a creep below it, jaeger's "
    "1e-6 to 1e-5 at A* 0.45, is judged to it and by its sign only), same regime, every creep "
    "of the same sign; value: worst relative error outside the absolute bound",
    tolerance=REL,
    quick=True,
)


def load_reference(path: Path = DATA) -> list[dict]:
    """The reference cells of ``path``, in file order.

    Parameters
    ----------
    path
        The JSON file written by ``benchmarks/steady_reference.py``.

    Returns
    -------
    list of dict
        One record per cell (model, m_star, amplitude, mu, drift_ratio, regime, kind, ...).
    """
    return json.loads(Path(path).read_text())["cells"]


def quick_cells(cells: list[dict]) -> list[dict]:
    """The cheapest cell (fewest reference periods) of each kind."""
    chosen: dict[str, dict] = {}
    for cell in sorted(cells, key=lambda c: (c["periods"], c["m_star"])):
        chosen.setdefault(cell["kind"], cell)
    return list(chosen.values())


def default_run(cell: dict) -> sd.Result:
    """The default run of a cell's scene: no numerics set."""
    return sd.run(sd.Scene(model=cell["model"], particle={"m_star": cell["m_star"]},
                           drive={"amplitude": cell["amplitude"]}, material={"mu": cell["mu"]}))


def run(quick: bool = False) -> CaseResult:
    """Run every reference cell (or the quick subset) with the default numerics."""
    if not DATA.exists():
        return CASE.skip(f"no reference data at {DATA.name}: run benchmarks/steady_reference.py")
    cells = load_reference()
    if quick:
        cells = quick_cells(cells)
    rows = []
    for cell in cells:
        res = default_run(cell)
        ref, got = cell["drift_ratio"], res.drift_ratio
        err = abs(got - ref)
        rel = err / abs(ref) if ref != 0.0 else math.inf
        rows.append({"key": cell["key"], "kind": cell["kind"], "reference": ref, "default": got,
                     "abs_error": err, "rel_error": rel, "within": err <= max(REL * abs(ref), ABS),
                     "regime_ref": cell["regime"], "regime": res.regime,
                     # a creep below the resolution still has its direction: 0 or the wrong sign
                     # passed the absolute bound
                     "same_sign": cell["kind"] != "creep" or got * ref > 0.0,
                     "same_regime": res.regime == cell["regime"], "settled": res.settled,
                     "settle_method": res.settle_method, "settle_periods": res.settle_periods,
                     "wall_s": res.wall_time_s})
    outside = [r["rel_error"] for r in rows if r["abs_error"] > ABS]
    value = max(outside, default=0.0)
    missed = [r for r in rows if not r["within"]]
    regimes = [r for r in rows if not r["same_regime"]]
    signs = [r for r in rows if not r["same_sign"]]
    msg = judged_message(rows)
    below = [r for r in rows if r["kind"] == "creep" and abs(r["reference"]) < ABS]
    msg += (f"; {len(below)} creep cells below the 2e-5 resolution, judged to it and by their "
            f"sign ({len(signs)} of another sign)")
    if below:
        msg += ": " + ", ".join(f"{r['key']} {r['default']:.3g} vs {r['reference']:.3g}"
                                for r in below)
    return CASE.result(value, require=not missed and not regimes and not signs, message=msg,
                       figure=_figure(rows), details={"cells": rows})


def _cell(row: dict) -> str:
    return (f"{row['rel_error']:.2e} at {row['key']} ({row['kind']}: default {row['default']:.6g}, "
            f"reference {row['reference']:.6g})")


def judged_message(rows: list[dict]) -> str:
    """The case's message: the judged quantity first, then the worst cell over all cells.

    Parameters
    ----------
    rows
        One record per cell, with ``key``, ``kind``, ``default``, ``reference``, ``abs_error``,
        ``rel_error``, ``within``, ``same_regime``, ``regime`` and ``regime_ref``.

    Returns
    -------
    str
        The judged value (the worst relative error among the cells outside the absolute bound,
        or that there is none), the counts of missed cells and regimes, and the worst relative
        error over all cells, marked as within the absolute bound when it is.
    """
    outside = [r for r in rows if r["abs_error"] > ABS]
    missed = [r for r in rows if not r["within"]]
    regimes = [r for r in rows if not r["same_regime"]]
    if outside:
        judged = ("worst relative error among the cells outside the 2e-5 absolute bound "
                  + _cell(max(outside, key=lambda r: r["rel_error"])))
    else:
        judged = "every cell within the 2e-5 absolute bound (judged relative error 0)"
    msg = (f"{judged}; {len(rows)} cells: {len(missed)} outside 1e-3 rel / 2e-5 abs, "
           f"{len(regimes)} with another regime")
    worst = max(rows, key=lambda r: r["rel_error"])
    if worst["abs_error"] <= ABS:
        msg += f"; over all cells (not judged: within the absolute bound) {_cell(worst)}"
    if regimes:
        msg += "; regimes: " + ", ".join(f"{r['key']} {r['regime']} vs {r['regime_ref']}"
                                         for r in regimes[:3])
    return msg


def _figure(rows: list[dict]):
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10.0, 4.0), layout="constrained")
    ref = np.array([r["reference"] for r in rows])
    got = np.array([r["default"] for r in rows])
    colours = [KIND_COLOURS.get(r["kind"], "k") for r in rows]
    lim = 1.5 * max(np.abs(ref).max(), np.abs(got).max())
    ax1.plot([-lim, lim], [-lim, lim], color="0.6", lw=0.8)
    ax1.scatter(ref, got, c=colours, s=28, zorder=3)
    ax1.set_xscale("symlog", linthresh=1e-5)
    ax1.set_yscale("symlog", linthresh=1e-5)
    ax1.tick_params(labelsize=7)
    ax1.set_xlabel("reference drift ratio (full-inertia brute force)")
    ax1.set_ylabel("default run drift ratio")
    ax1.set_title("default vs reference", fontsize=9)
    # error in units of the allowed error max(1e-3 |V|, 2e-5): above 1 fails
    score = np.array([r["abs_error"] / max(REL * abs(r["reference"]), ABS) for r in rows])
    x = np.arange(len(rows))
    ax2.axhspan(1e-4, 1.0, color="0.92")
    ax2.axhline(1.0, color="k", lw=0.8)
    ax2.scatter(x, np.maximum(score, 1e-4), c=colours, s=28, zorder=3)
    for xi, r in zip(x, rows, strict=True):
        if not r["same_regime"]:
            ax2.annotate("regime", (xi, max(score[xi], 1e-4)), textcoords="offset points",
                         xytext=(0, 6), ha="center", fontsize=6)
    ax2.set_yscale("log")
    ax2.set_xticks(x, [r["key"].replace("hertz_mindlin_dem", "hmd") for r in rows], rotation=90,
                   fontsize=6)
    ax2.set_ylabel("|error| / max(1e-3 |ref|, 2e-5)")
    ax2.set_title("error per cell (grey: within the bound)", fontsize=9)
    for kind, colour in KIND_COLOURS.items():
        if any(r["kind"] == kind for r in rows):
            ax1.scatter([], [], c=colour, s=28, label=kind)
    ax1.legend(fontsize=8, loc="upper left")
    return fig
