"""Observed orders, the markdown summary and the recommended defaults of the work-precision study."""

from __future__ import annotations

import math
import os
import platform
from typing import Any

import numpy as np
import pandas as pd

from ..dynamics.assembly import steps_per_period
from ..report.texts import text
from ..report.work_precision_plot import _order_or_none, _orders
from ..scene.schema import Numerics
from .core import (
    WAVE_AMPLITUDE,
    WAVE_M_STAR,
    StudyConfig,
    _is_rigid,
    _wave_scene,
    fit_order,
)
from .study_rows import converged_cells

# -- observed orders and the summary ---------------------------------------------------------------


def observed_orders(frame: pd.DataFrame) -> pd.DataFrame:
    """Observed orders of every ladder: wave (per model and order), mdr strips (both settings).

    The error floor of a wave ladder is ten times its reference uncertainty; the fit uses the
    four finest usable points.
    """
    out = []
    wave = frame[(frame["setting"] == "wave") & (frame["ladder"] == "steps")]
    for (model, order), g in wave.groupby(["model", _orders(wave["order"]).fillna(0)],
                                          sort=False):
        order = order or None  # 0 stands for "no order" (rigid event scheme)
        unc = float(np.nanmax(g["reference_uncertainty"].astype(float)))
        floor = 10.0 * unc if np.isfinite(unc) else 0.0
        out.append(dict(setting="wave", model=model, ladder="steps", order=order,
                        observed_order=fit_order(g["steps_per_period"], g["error"], floor),
                        error_floor=floor))
    for setting in ("prescribed", "wave"):
        g = frame[(frame["setting"] == setting) & (frame["ladder"] == "strips")]
        if len(g) >= 2:
            out.append(dict(setting=setting, model="mdr", ladder="strips", order=None,
                            observed_order=fit_order(g["strips"], g["error"], 1e-14,
                                                     finest=len(g)),
                            error_floor=1e-14))
    return pd.DataFrame(out, columns=["setting", "model", "ladder", "order", "observed_order",
                                      "error_floor"])


def _fmt(x: Any, spec: str = ".2e") -> str:
    try:
        xf = float(x)
    except (TypeError, ValueError):
        return str(x)
    if not math.isfinite(xf):
        return "n/a"
    return format(xf, spec)


def cheapest(frame: pd.DataFrame, model: str, tol: float) -> pd.Series | None:
    """The fastest wave run of ``model`` (any order, any step) with error <= ``tol``."""
    g = frame[(frame["setting"] == "wave") & (frame["model"] == model) & (frame["ladder"] == "steps")]
    g = g[g["error"].astype(float) <= tol]
    if g.empty:
        return None
    return g.loc[g["wall_s"].astype(float).idxmin()]


def summary_markdown(frame: pd.DataFrame, orders: pd.DataFrame, cfg: StudyConfig,
                     quick: bool = False) -> str:
    """The markdown summary of a work-precision study, with data-driven recommendations.

    The prose comes from ``report/text/work_precision.toml``; this function fills it in.
    """
    T = text("work_precision")
    h = T["head"]
    lines = [
        h["title"].format(quick=" (quick)" if quick else ""), "",
        h["machine"].format(cores=os.cpu_count(), cpu=platform.processor() or platform.machine(),
                            python=platform.python_version(), repeats=cfg.repeats), "",
        h["defaults"].format(order=Numerics().order), "",
    ]
    pre = frame[frame["setting"] == "prescribed"]
    if not pre.empty:
        t = T["prescribed"]
        lines += [t["heading"], "", t["intro"].format(segments=cfg.cycles * 10,
                                                      samples=int(pre["steps"].max())), "",
                  t["table"]]
        for _, r in pre.iterrows():
            lines.append(t["row"].format(
                model=r["model"], ladder=r["ladder"], samples=int(r["samples_per_segment"]),
                strips="" if pd.isna(r["strips"]) else int(r["strips"]), error=_fmt(r["error"]),
                rms=_fmt(r["error_rms"]), ns=_fmt(r["ns_per_step"], ".0f")))
        lines += ["", t["outro"], ""]
    wave = frame[frame["setting"] == "wave"]
    if not wave.empty:
        lines += _wave_section(T["wave"], frame, wave, orders, cfg)
    grid = frame[frame["setting"] == "defaults"]
    if not grid.empty:
        t = T["plane"]
        lines += [t["heading"], "", t["intro"].format(n=cfg.grid, periods=cfg.periods,
                                                      fine=cfg.grid_refine[1],
                                                      coarse=cfg.grid_refine[0]), "", t["table"]]
        for model, g in grid.groupby("model", sort=False):
            ok = converged_cells(g) & np.isfinite(g["error"].astype(float))
            good = g[ok]
            if not good.empty:
                w = good.loc[good["error"].astype(float).idxmax()]
                worst = f"{w['m_star']:.3g}, {w['amplitude']:.3g}, {_fmt(w['rel_error'])}"
            else:
                worst = "n/a"
            lines.append(t["row"].format(
                model=model, cells=len(g), resolved=int(ok.sum()), max_error=_fmt(good["error"].max()),
                worst=worst, median=_fmt(good["error"].median()),
                half=_fmt(good["error_half_default"].max()),
                double=_fmt(good["error_double_default"].max()), all_max=_fmt(g["error"].max()),
                changes=int((g["regime"] != g["reference_regime"]).sum())))
        lines += ["", t["chaotic_intro"], ""]
        for model, g in grid.groupby("model", sort=False):
            bad = g[~converged_cells(g)]
            cells = ", ".join(f"({float(r['m_star']):.3g}, {float(r['amplitude']):.3g})"
                              for _, r in bad.iterrows())
            lines.append(t["chaotic_row"].format(model=model, cells=cells or "none"))
        lines.append("")
    long = frame[frame["setting"] == "long"]
    if not long.empty:
        t = T["long"]
        lines += [t["heading"].format(periods=float(long["periods"].iloc[0])), "", t["intro"], "",
                  t["table"]]
        for _, r in long.iterrows():
            lines.append(t["row"].format(
                model=r["model"], case=r["note"], order=int(r["order"]),
                steps=int(r["steps_per_period"]), value=float(r["value"]),
                reference=float(r["reference"]), error=_fmt(r["error"])))
        lines.append("")
    lines += recommendations(frame, orders)
    return "\n".join(lines) + "\n"


def _wave_section(t: dict[str, str], frame: pd.DataFrame, wave: pd.DataFrame, orders: pd.DataFrame,
                  cfg: StudyConfig) -> list[str]:
    """Section (b) of the summary: the wave scene's references, orders and defaults."""
    lines = [t["heading"], "", t["intro"].format(m_star=WAVE_M_STAR, amplitude=WAVE_AMPLITUDE,
                                                 periods=cfg.periods, fine=cfg.reference_steps[1],
                                                 coarse=cfg.reference_steps[0]), "", t["table"]]
    for model, g in wave[wave["ladder"] == "steps"].groupby("model", sort=False):
        r = g.iloc[0]
        lines.append(t["row"].format(model=model, reference=_fmt(r["reference"], ".8f"),
                                     uncertainty=_fmt(r["reference_uncertainty"]),
                                     regime=r["reference_regime"],
                                     vs_mmd=_fmt(r["model_error_vs_mmd"])))
    lines += ["", t["orders_intro"], "", t["orders_table"]]
    for _, o in orders[(orders["setting"] == "wave") & (orders["ladder"] == "steps")].iterrows():
        g = wave[(wave["model"] == o["model"]) & (wave["ladder"] == "steps")]
        want = _order_or_none(o["order"])
        g = g[_orders(g["order"]).map(lambda v, want=want: v == want)]

        def at(spp: int, col: str, g: pd.DataFrame = g) -> Any:
            hit = g[g["steps_per_period"] == spp]
            return hit[col].iloc[0] if not hit.empty else math.nan

        observed = _fmt(o["observed_order"], ".2f")
        if observed == "n/a" and float(g["error"].max()) <= 1e-9:
            observed = t["round_off"]
        lines.append(t["orders_row"].format(
            model=o["model"], order=t["event_scheme"] if pd.isna(o["order"]) else str(int(o["order"])),
            observed=observed, e128=_fmt(at(128, "error")), e512=_fmt(at(512, "error")),
            wall=_fmt(1e3 * float(at(128, "wall_s")), ".2f")))
    dflt = wave[wave["is_default"].astype(bool) & (wave["ladder"] == "steps")]
    if not dflt.empty:
        lines += ["", t["defaults_intro"], ""]
        for _, r in dflt.iterrows():
            lines.append(t["defaults_row"].format(
                model=r["model"], steps=int(r["steps_per_period"]), value=_fmt(r["value"], ".6f"),
                error=_fmt(r["error"]), rel=_fmt(r["rel_error"]),
                ms=_fmt(1e3 * float(r["wall_s"]), ".2f"), ns=_fmt(r["ns_per_step"], ".0f")))
    strips = wave[wave["ladder"] == "strips"]
    if not strips.empty:
        lines += ["", t["strips_intro"], "", t["strips_table"]]
        for _, r in strips.sort_values("strips").iterrows():
            lines.append(t["strips_row"].format(strips=int(r["strips"]), value=_fmt(r["value"], ".8f"),
                                                error=_fmt(r["error"]),
                                                ns=_fmt(r["ns_per_step"], ".0f")))
    for tol in (1e-4, 1e-6):
        best = cheapest(frame, "mmd", tol)
        if best is not None:
            lines += ["", t["cheapest"].format(tol=tol, order=int(best["order"]),
                                               steps=int(best["steps_per_period"]),
                                               ms=_fmt(1e3 * float(best["wall_s"]), ".2f"),
                                               error=_fmt(best["error"]))]
    lines.append("")
    return lines


def recommendations(frame: pd.DataFrame, orders: pd.DataFrame) -> list[str]:
    """Data-driven recommendation lines (markdown) on the default order and step count."""
    t = text("work_precision")["recommend"]
    out = [t["heading"], ""]
    wave = frame[(frame["setting"] == "wave") & (frame["ladder"] == "steps")]
    mmd = wave[wave["model"] == "mmd"]
    if mmd.empty:
        out.append(t["no_mmd"])
        return out
    default_order = Numerics().order
    dflt = mmd[mmd["is_default"].astype(bool)]
    by_order = {}
    for order in sorted({_order_or_none(o) for o in mmd["order"]} - {None}):
        g = mmd[(mmd["order"] == order) & (mmd["steps_per_period"] == 128)]
        if not g.empty:
            by_order[order] = float(g["error"].iloc[0])
    if by_order:
        out.append(t["by_order"].format(orders=", ".join(f"AB{k} {_fmt(v)}" for k, v in by_order.items())))
    if not dflt.empty:
        e = float(dflt["error"].iloc[0])
        out.append(t["default_ok"].format(error=_fmt(e), far="far " if e < 1e-4 else "")
                   if e < 1e-3 else t["default_bad"].format(error=_fmt(e)))
    grid = frame[(frame["setting"] == "defaults") & (frame["model"] == "mmd")]
    if not grid.empty:
        ok = converged_cells(grid) & np.isfinite(grid["error"].astype(float))
        good = grid[ok]
        if not good.empty:
            w = good.loc[good["error"].astype(float).idxmax()]
            changes = int((grid["regime"] != grid["reference_regime"]).sum())
            out.append(t["plane"].format(
                median=_fmt(good["error"].median()), worst=_fmt(w["error"]), rel=_fmt(w["rel_error"]),
                m_star=w["m_star"], amplitude=w["amplitude"], steps=int(w["steps_per_period"]),
                regime=w["regime"], changes=changes, cells=len(grid), chaotic=int((~ok).sum()),
                double=_fmt(float(good["error_double_default"].max()))))
            verdict = float(w["rel_error"]) if math.isfinite(float(w["rel_error"])) else math.inf
            if verdict <= 1e-2 and changes == 0:
                out.append(t["step_ok"].format(percent=_fmt(100 * verdict, ".2g")))
            else:
                out.append(t["step_bad"].format(rel=_fmt(verdict)))
    rows = orders[(orders["setting"] == "wave") & (orders["model"] == "mmd")]
    hi = rows[rows["order"].map(lambda o: o is not None and not pd.isna(o) and int(o) >= 3)]
    if not hi.empty:
        out.append(t["high_orders"].format(orders=", ".join(
            f"AB{int(r['order'])} {_fmt(r['observed_order'], '.2f')}" for _, r in hi.iterrows())))
    long = frame[frame["setting"] == "long"]
    if not long.empty:
        err = long.groupby("order")["error"].max()
        e3, e4 = float(err.get(3, math.nan)), float(err.get(4, math.nan))
        best = 4 if e4 <= e3 else 3
        which = (t["long_is_default"] if best == default_order
                 else t["long_not_default"].format(order=default_order))
        out.append(t["long"].format(periods=float(long["periods"].iloc[0]), e3=_fmt(e3), e4=_fmt(e4),
                                    best=best, which=which))
    ab3 = by_order.get(3, math.nan)
    ab2 = by_order.get(2, math.nan)
    if math.isfinite(ab3) and math.isfinite(ab2):
        out.append(t["low_orders"].format(ab3=_fmt(ab3), ab2=_fmt(ab2)))
    strips = frame[(frame["setting"] == "wave") & (frame["ladder"] == "strips")]
    dflt_strips = strips[strips["is_default"].astype(bool)]
    if not dflt_strips.empty and not dflt.empty:
        e_s = float(dflt_strips["error"].iloc[0])
        e_t = float(dflt["error"].iloc[0])
        below = e_s < e_t
        out.append(t["strips"].format(
            strips=int(dflt_strips["strips"].iloc[0]), e_s=_fmt(e_s), e_t=_fmt(e_t),
            relation=t["strips_below"] if below else t["strips_above"],
            verdict=t["strips_ok"] if below else t["strips_raise"]))
    for model in frame.loc[frame["setting"] == "wave", "model"].unique():
        if not _is_rigid(str(model)):
            continue
        g = frame[(frame["model"] == model) & (frame["setting"].isin(["wave", "defaults"]))]
        w = g[g["setting"] == "wave"]
        out.append(t["rigid"].format(
            model=model, lo=int(w["steps_per_period"].min()), hi=int(w["steps_per_period"].max()),
            wave_max=_fmt(w["error"].max()),
            plane_max=_fmt(g.loc[g["setting"] == "defaults", "error"].max()),
            steps=int(steps_per_period(_wave_scene(str(model))))))
    return out
