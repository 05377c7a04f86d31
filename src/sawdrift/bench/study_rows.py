"""The rows of the work-precision study: the prescribed history, the wave scene, the defaults."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from typing import Any

import numpy as np
import pandas as pd

from ..contact.registry import get_model
from ..dynamics.assembly import steps_per_period
from ..errors import NonFiniteStateError
from ..result.runner import run
from ..scene.schema import Numerics, Scene
from .core import (
    WAVE_AMPLITUDE,
    WAVE_M_STAR,
    StudyConfig,
    _history,
    _is_rigid,
    _progress,
    _row,
    _wave_scene,
    best_time,
    drive_timed,
    random_history,
)

# -- (a) the contact law alone along a prescribed random history --------------------------------


def _prescribed_rows(models: Sequence[str], cfg: StudyConfig, progress: bool) -> list[dict[str, Any]]:
    compliant = [m for m in models if not _is_rigid(m)]
    if not compliant:
        return []
    rows: list[dict[str, Any]] = []
    n_runs = len(compliant) * len(cfg.samples) + (len(cfg.strips) if "mdr" in compliant else 0)
    bar = _progress(n_runs, "prescribed", progress)
    exact: dict[int, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = {}

    def reference(samples: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        if samples not in exact:
            a, b = random_history(cfg.cycles, samples, cfg.seed)
            hist = _history("mmd", None, "python")
            n_ref, t_ref = hist.drive(a, b)
            exact[samples] = (a, b, n_ref, t_ref)
        return exact[samples]

    def measure(model: str, samples: int, params: dict[str, Any] | None, ladder: str,
                strips: int | None, note: str) -> None:
        a, b, _n_ref, t_ref = reference(samples)
        wall, _n, t_f = drive_timed(model, a, b, params=params, repeats=cfg.repeats)
        # compared at the vertices of the path (every samples-th point): the same points for
        # every sampling, so a law that is exact along straight segments shows a flat error
        diff = (t_f - t_ref)[::samples]
        t_v = t_ref[::samples]
        rows.append(_row(
            setting="prescribed", model=model, ladder=ladder, strips=strips,
            samples_per_segment=samples, steps=int(a.size), wall_s=wall,
            ns_per_step=1e9 * wall / a.size, value=float(np.max(np.abs(t_f))),
            reference=float(np.max(np.abs(t_v))), error=float(np.max(np.abs(diff))),
            error_rms=float(np.sqrt(np.mean(diff**2))),
            rel_error=float(np.max(np.abs(diff)) / max(np.max(np.abs(t_v)), 1e-300)),
            is_default=False, note=note,
        ))
        bar.update(1)

    for model in compliant:
        if model == "mmd":
            note = "compiled kernel vs the pure-Python reference (exact law): round-off"
        elif model == "mdr":
            note = f"discretization error at the default {_default_strips()} strips"
        else:
            note = "model error: a different contact law than the exact mmd"
        for samples in cfg.samples:
            measure(model, samples, None, "samples", _default_strips() if model == "mdr" else None,
                    note)
    if "mdr" in compliant:
        for strips in cfg.strips:
            measure("mdr", cfg.strip_samples, {"strips": strips}, "strips", strips,
                    "strip ladder: discretization error vs the exact mmd")
    bar.close()
    return rows


def _default_strips() -> int:
    return int(get_model("mdr").Params().strips)


# -- (b) the wave scene ---------------------------------------------------------------------------


def _drift(scene: Scene, repeats: int) -> tuple[float, Any]:
    wall, result = best_time(lambda: run(scene), repeats)
    return wall, result


class _Ladders:
    """The step-size ladders of the wave setting: each model's reference drift (fixed runs at
    the two reference steps) and one row per (order, steps per period) against it."""

    def __init__(self, cfg: StudyConfig, bar: Any):
        self.cfg, self.bar = cfg, bar
        self.rows: list[dict[str, Any]] = []
        self.mmd_ref = math.nan

    def reference(self, model: str, params: dict[str, Any] | None = None
                  ) -> tuple[float, float, str]:
        """(drift ratio at the fine reference step, its change from the coarse one, regime)."""
        cfg = self.cfg
        coarse, fine = cfg.reference_steps
        # runs of fixed length throughout the ladders: each step size sees the same window (a
        # default run could go on settling for a different number of periods at each)
        r1 = run(_wave_scene(model, order=4, steps_per_period=coarse, periods=cfg.periods,
                             model_params=params, settle=False))
        self.bar.update(1)
        r2 = run(_wave_scene(model, order=4, steps_per_period=fine, periods=cfg.periods,
                             model_params=params, settle=False))
        self.bar.update(1)
        return r2.drift_ratio, abs(r2.drift_ratio - r1.drift_ratio), r2.regime

    def row(self, model: str, order: int | None, spp: int, ref: float, unc: float,
            ref_regime: str, default_spp: int, params: dict[str, Any] | None = None,
            ladder: str = "steps", strips: int | None = None, note: str = "") -> None:
        """One rung: a fixed run at ``spp`` steps per period (and ``order``) against ``ref``."""
        cfg = self.cfg
        scene = _wave_scene(model, order=order, steps_per_period=spp, periods=cfg.periods,
                            model_params=params, settle=False)
        try:
            wall, res = _drift(scene, cfg.repeats)
            value, steps, regime = res.drift_ratio, res.steps, res.regime
            err = abs(value - ref)
        except NonFiniteStateError:
            wall, value, steps, regime, err = math.nan, math.nan, None, "non-finite", math.nan
            note = (note + "; " if note else "") + "state became non-finite (unstable)"
        is_default = spp == default_spp and (order is None or order == Numerics().order)
        if ladder == "strips":
            is_default = is_default and strips == _default_strips()
        self.rows.append(_row(
            setting="wave", model=model, ladder=ladder, order=order, steps_per_period=spp,
            strips=strips, m_star=WAVE_M_STAR, amplitude=WAVE_AMPLITUDE, periods=cfg.periods,
            steps=steps, wall_s=wall,
            ns_per_step=1e9 * wall / steps if steps else math.nan, value=value, reference=ref,
            error=err, rel_error=err / abs(ref) if ref else math.nan, reference_uncertainty=unc,
            model_error_vs_mmd=(abs(ref - self.mmd_ref) if ladder == "steps"
                                and not _is_rigid(model) else math.nan),
            regime=regime, reference_regime=ref_regime, is_default=is_default, note=note,
        ))
        self.bar.update(1)


def _wave_rows(models: Sequence[str], cfg: StudyConfig, progress: bool) -> list[dict[str, Any]]:
    default_order = Numerics().order
    compliant = [m for m in models if not _is_rigid(m)]
    rigid = [m for m in models if _is_rigid(m)]
    n_runs = (
        len(compliant) * (2 + len(cfg.orders) * len(cfg.steps))
        + len(rigid) * (2 + len(cfg.rigid_steps))
        + (1 + len(cfg.wave_strips) if "mdr" in compliant else 0)
    )
    periods = cfg.periods
    ladders = _Ladders(cfg, _progress(n_runs, "wave", progress))
    mmd_unc, mmd_regime = math.nan, ""
    if compliant:
        ladders.mmd_ref, mmd_unc, mmd_regime = ladders.reference("mmd")
    for model in compliant:
        if model == "mmd":
            ref, unc, ref_regime = ladders.mmd_ref, mmd_unc, mmd_regime
        else:
            ref, unc, ref_regime = ladders.reference(model)
        default_spp = steps_per_period(_wave_scene(model, periods=periods))
        strips = _default_strips() if model == "mdr" else None
        for order in cfg.orders:
            for spp in cfg.steps:
                ladders.row(model, order, spp, ref, unc, ref_regime, default_spp, strips=strips)
    if "mdr" in compliant:
        # strip ladder at the default numerics, against mmd run with identical numerics
        base = _wave_scene("mmd", periods=periods, settle=False)
        default_spp = steps_per_period(base)
        mmd_same = run(base)
        ladders.bar.update(1)
        for strips in cfg.wave_strips:
            ladders.row("mdr", default_order, default_spp, mmd_same.drift_ratio, math.nan,
                        mmd_same.regime, default_spp, params={"strips": strips},
                        ladder="strips", strips=strips,
                        note="vs mmd with identical numerics (strip error only)")
    for model in rigid:
        ref, unc, ref_regime = ladders.reference(model)
        default_spp = steps_per_period(_wave_scene(model, periods=periods))
        for spp in cfg.rigid_steps:
            ladders.row(model, None, spp, ref, unc, ref_regime, default_spp,
                        note="event-locating scheme (no Adams-Bashforth order)")
    ladders.bar.close()
    return ladders.rows


# -- (c) the defaults over the (m*, A*) plane ------------------------------------------------------


def _defaults_rows(models: Sequence[str], cfg: StudyConfig, progress: bool) -> list[dict[str, Any]]:
    """(c) The default numerics against order 4 at finer steps over the (m*, A*) plane.

    Every run has ``cfg.periods`` periods (settling off), so that a cell's error compares like
    with like across the step ladder.
    """
    if cfg.grid <= 0:
        return []
    m_axis = np.geomspace(1e-3, 1e2, cfg.grid)
    a_axis = np.geomspace(1e-2, 10.0, cfg.grid)
    rows: list[dict[str, Any]] = []
    bar = _progress(len(models) * m_axis.size * a_axis.size, "defaults", progress)
    k1, k2 = cfg.grid_refine
    for model in models:
        for m in m_axis:
            for amp in a_axis:
                # fixed-length runs: a settled run of a heavy cell (material_point, m* = 100,
                # A* = 10) is a chaotic long-time mean over ~6e4 periods, whose change with the
                # step measures sensitivity, not the integrator, and took most of the study
                scene = _wave_scene(model, periods=cfg.periods, m_star=float(m),
                                    amplitude=float(amp), settle=False)
                spp = steps_per_period(scene)
                note = ""
                try:
                    t0 = time.perf_counter()
                    res = run(scene)
                    wall = time.perf_counter() - t0
                    half = run(scene.with_updates(**{"numerics.steps_per_period": max(8, spp // 2)}))
                    double = run(scene.with_updates(**{"numerics.steps_per_period": 2 * spp}))
                    r1 = run(scene.with_updates(**{"numerics.steps_per_period": k1 * spp,
                                                   "numerics.order": 4}))
                    r2 = run(scene.with_updates(**{"numerics.steps_per_period": k2 * spp,
                                                   "numerics.order": 4}))
                    err = abs(res.drift_ratio - r2.drift_ratio)
                    row = dict(
                        value=res.drift_ratio, reference=r2.drift_ratio, error=err,
                        rel_error=err / abs(r2.drift_ratio) if r2.drift_ratio else math.nan,
                        reference_uncertainty=abs(r2.drift_ratio - r1.drift_ratio),
                        error_half_default=abs(half.drift_ratio - r2.drift_ratio),
                        error_double_default=abs(double.drift_ratio - r2.drift_ratio),
                        regime=res.regime, reference_regime=r2.regime, steps=res.steps,
                        wall_s=wall, ns_per_step=1e9 * wall / res.steps,
                    )
                except NonFiniteStateError as exc:
                    row = dict(regime="non-finite", error=math.nan)
                    note = str(exc).splitlines()[0]
                rows.append(_row(
                    setting="defaults", model=model, ladder="grid", order=scene.numerics.order,
                    steps_per_period=spp, m_star=float(m), amplitude=float(amp),
                    periods=cfg.periods, is_default=True, note=note, **row,
                ))
                bar.update(1)
    bar.close()
    return rows


def _long_rows(models: Sequence[str], quick: bool, progress: bool) -> list[dict[str, Any]]:
    """(d) Long runs: the drift after many periods, each order at the default step.

    The normal oscillation has no damping, so the free oscillation started by the ramp (a short
    one here, 1 period, to excite it) persists, and the drift depends on its amplitude. An
    integrator that damps it numerically (AB3: |zeta| = 1 - (3/8)(h omega)^4 per step) shifts the
    long-run drift; AB4's amplitude error is O((h omega)^6). Reference: order 4 at 8x the steps.
    """
    periods = 300.0 if quick else 2000.0
    rows: list[dict[str, Any]] = []
    compliant = [m for m in models if not _is_rigid(m)]
    cases = [("mmd", {"nu": 0.499}), ("mmd", {"nu": 0.3})] if "mmd" in compliant else []
    with _progress(len(cases) * 3, "long runs", progress) as bar:
        for model, material in cases:
            def scene(order: int, factor: int, model=model, material=material) -> Scene:
                base = Scene(model=model, material=material, particle={"m_star": WAVE_M_STAR},
                             drive={"amplitude": 0.3, "ramp_periods": 1.0},
                             numerics={"periods": periods, "order": order})
                k = steps_per_period(base)
                return base.with_updates(**{"numerics.steps_per_period": k * factor})

            ref = run(scene(4, 8))
            bar.update(1)
            for order in (3, 4):
                t0 = time.perf_counter()
                res = run(scene(order, 1))
                wall = time.perf_counter() - t0
                bar.update(1)
                rows.append(_row(
                    setting="long", model=model, ladder="steps", order=order,
                    steps_per_period=res.steps_per_period, m_star=WAVE_M_STAR, amplitude=0.3,
                    periods=periods, steps=res.steps, wall_s=wall, ns_per_step=1e9 * wall / res.steps,
                    value=res.drift_ratio, reference=ref.drift_ratio,
                    error=abs(res.drift_ratio - ref.drift_ratio), regime=res.regime,
                    reference_regime=ref.regime, is_default=order == Numerics().order,
                    note=f"nu = {material['nu']}, ramp 1 period",
                ))
    return rows


def converged_cells(frame: pd.DataFrame) -> pd.Series:
    """Defaults-check cells where the default's error is a discretization error.

    A cell is *chaotic* (irregular bouncing, where the 60-period drift ratio changes by O(1)
    with any change of step, so that its "error" measures sensitivity, not the integrator) when
    its two references disagree by more than max(1e-6, error / 10), or when its error exceeds
    1e-4 and does not converge (halving the steps does not make it 1.5x larger). All other
    cells are resolved.
    """
    unc = frame["reference_uncertainty"].astype(float)
    err = frame["error"].astype(float)
    half = frame["error_half_default"].astype(float)
    chaotic = (unc > np.maximum(1e-6, 0.1 * err)) | ((err > 1e-4) & (half < 1.5 * err))
    return ~chaotic
