"""Performance study: work-precision diagrams and speed targets (issue 7).

Two entry points, wrapped by ``sawdrift bench``:

* :func:`work_precision` measures error against a tight reference and wall time for every model,
  Adams-Bashforth order and resolution, in two settings, and writes a CSV, two figures and a
  markdown summary that recommends defaults:

  (a) *prescribed*: the contact law alone along a seeded random (a*, b*) history. The error is the
      largest |T* - T*_mmd| against the pure-Python memory-diagram reference (the exact law for a
      piecewise-linear path). The ladder is the sampling of the path (samples per straight
      segment) and, for ``mdr``, the strip count. For ``jaeger`` and ``hertz_mindlin_dem`` the
      error is a *model* error (a different contact law), reported as such.
  (b) *wave*: the drift ratio of the wave scene (m* = 0.1, A* = 0.316 by default, a clear drift
      with the wave for the compliant models) against a reference run of the same model at order
      4 and a very fine step; for ``mdr`` also a strip ladder against ``mdr``'s limit ``mmd``
      run with identical numerics. Rigid models (``material_point``) use their own event scheme:
      a step ladder, no order.

  A third table checks the current defaults over the (m*, A*) plane of a sweep: drift ratio at
  the default numerics (and at half the default steps) against order 4 at 16x and 32x the
  default steps.

* :func:`speed` measures the speed targets of issue 7 and prints a PASS/FAIL report.

Timing rules: every timed call is preceded by an identical warm-up call that is discarded (it
absorbs numba compilation and cache loading), and the best of a few repeats is kept.
"""

from __future__ import annotations

import json
import math
import os
import platform
import tempfile
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import Any, TypeVar

import numpy as np
import pandas as pd

from ..contact.base import ContactHistory
from ..contact.registry import get_model
from ..dynamics.runner import prescribed_history, run
from ..errors import NonFiniteStateError, SceneError
from ..scene.schema import Numerics, Prescribed, Scene
from ..study.sweep import sweep

T = TypeVar("T")

#: Models studied when none are named.
DEFAULT_MODELS: tuple[str, ...] = ("mmd", "mdr", "jaeger", "hertz_mindlin_dem", "material_point")

#: The wave scene of the study: a clear drift with the wave for the compliant models.
WAVE_M_STAR = 0.1
WAVE_AMPLITUDE = 0.316

#: Columns of the work-precision table, in order.
COLUMNS: tuple[str, ...] = (
    "setting",
    "model",
    "ladder",
    "order",
    "steps_per_period",
    "strips",
    "samples_per_segment",
    "m_star",
    "amplitude",
    "periods",
    "steps",
    "wall_s",
    "ns_per_step",
    "value",
    "reference",
    "error",
    "error_rms",
    "rel_error",
    "reference_uncertainty",
    "model_error_vs_mmd",
    "error_half_default",
    "error_double_default",
    "regime",
    "reference_regime",
    "is_default",
    "note",
)


@dataclass(frozen=True)
class StudyConfig:
    """Ladders, references and repeats of :func:`work_precision`.

    Attributes
    ----------
    periods
        Simulated periods of each wave run (ramp included).
    orders
        Adams-Bashforth orders.
    steps
        Steps-per-period ladder of the compliant models in the wave scene.
    rigid_steps
        Steps-per-period ladder of rigid models.
    reference_steps
        (coarse, fine) steps per period of the order-4 reference; their difference is reported as
        the reference uncertainty.
    wave_strips
        ``mdr`` strip ladder in the wave scene (default numerics, compared with ``mmd``).
    cycles
        Size of the prescribed random history (10 straight segments per cycle).
    samples
        Samples-per-segment ladder of the prescribed history.
    strips
        ``mdr`` strip ladder on the prescribed history.
    strip_samples
        Samples per segment used for the strip ladder.
    grid
        Points per axis of the defaults check over m* in [1e-3, 1e2], A* in [1e-2, 10] (0: off).
    grid_refine
        (coarse, fine) multiples of the default steps for the defaults check's reference.
    repeats
        Timed repeats (best kept) after one discarded warm-up call.
    seed
        Seed of the prescribed random history.
    """

    periods: float = 60.0
    orders: tuple[int, ...] = (1, 2, 3, 4)
    steps: tuple[int, ...] = (32, 48, 64, 96, 128, 192, 256, 384, 512, 768, 1024, 1536, 2048, 4096)
    rigid_steps: tuple[int, ...] = (16, 32, 64, 128, 256, 512, 1024, 2048, 4096)
    reference_steps: tuple[int, int] = (32768, 65536)
    wave_strips: tuple[int, ...] = (16, 32, 64, 128, 256, 512, 1024, 2048)
    cycles: int = 20
    samples: tuple[int, ...] = (1, 4, 16, 64)
    strips: tuple[int, ...] = (16, 32, 64, 128, 256, 512, 1024, 2048, 4096, 8192)
    strip_samples: int = 16
    grid: int = 7
    grid_refine: tuple[int, int] = (16, 32)
    repeats: int = 3
    seed: int = 7


FULL = StudyConfig()
QUICK = StudyConfig(
    periods=20.0,
    steps=(64, 128, 256),
    rigid_steps=(64, 256),
    reference_steps=(2048, 4096),
    wave_strips=(64, 256),
    cycles=4,
    samples=(1, 8),
    strips=(64, 256, 1024),
    strip_samples=8,
    grid=2,
    grid_refine=(8, 16),
    repeats=1,
)


# -- small helpers ----------------------------------------------------------------------------


def best_time(fn: Callable[[], T], repeats: int = 3, warmup: bool = True) -> tuple[float, T]:
    """Best wall time of ``repeats`` calls of ``fn`` (after one discarded warm-up call).

    Returns
    -------
    (seconds, result of the last call)
    """
    if warmup:
        fn()
    best = math.inf
    out: Any = None
    for _ in range(max(1, repeats)):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def fit_order(x: Iterable[float], err: Iterable[float], floor: float = 0.0,
              finest: int = 4) -> float:
    """Observed order of convergence: minus the slope of log(err) against log(x).

    Fitted by least squares over the ``finest`` largest ``x`` whose error is finite and above
    ``floor`` (points at or below the floor, e.g. under the reference uncertainty, are dropped).
    Returns NaN with fewer than two usable points.
    """
    xs = np.asarray(list(x), dtype=float)
    es = np.asarray(list(err), dtype=float)
    ok = np.isfinite(xs) & np.isfinite(es) & (es > floor) & (xs > 0)
    xs, es = xs[ok], es[ok]
    if xs.size < 2:
        return math.nan
    keep = np.argsort(xs)[-finest:]
    if np.unique(xs[keep]).size < 2:
        return math.nan
    slope = np.polyfit(np.log(xs[keep]), np.log(es[keep]), 1)[0]
    return float(-slope)


def _progress(total: int, desc: str, enabled: bool):
    from tqdm import tqdm

    return tqdm(total=total, desc=desc, unit="run", dynamic_ncols=True, disable=not enabled,
                leave=False)


def _wave_scene(model: str, *, order: int | None = None, steps_per_period: int | None = None,
                periods: float = 60.0, m_star: float = WAVE_M_STAR,
                amplitude: float = WAVE_AMPLITUDE,
                model_params: dict[str, Any] | None = None) -> Scene:
    numerics: dict[str, Any] = {"periods": periods}
    if order is not None:
        numerics["order"] = order
    if steps_per_period is not None:
        numerics["steps_per_period"] = steps_per_period
    return Scene(model=model, model_params=model_params or {}, particle={"m_star": m_star},
                 drive={"amplitude": amplitude}, numerics=numerics)


def _is_rigid(model: str) -> bool:
    return bool(get_model(model).capabilities.rigid)


def _history(model: str, params: dict[str, Any] | None, engine: str = "compiled") -> ContactHistory:
    scene = Scene(model=model, model_params=params or {}, drive={"kind": "prescribed"})
    inst = scene.model_instance()
    if engine == "compiled" and not inst.capabilities.compiled:
        engine = "python"
    return ContactHistory(inst, engine)


def drive_timed(model: str, a: np.ndarray, b: np.ndarray, *, params: dict[str, Any] | None = None,
                engine: str = "compiled", repeats: int = 3) -> tuple[float, np.ndarray, np.ndarray]:
    """Drive a fresh history of ``model`` through (a*, b*) samples; best wall time and (N*, T*).

    The history is created outside the timed region; the warm-up drive (discarded) compiles the
    model's drive loop.
    """
    _history(model, params, engine).drive(a[: min(a.size, 200)], b[: min(b.size, 200)])
    best = math.inf
    n_f = t_f = np.empty(0)
    for _ in range(max(1, repeats)):
        hist = _history(model, params, engine)
        t0 = time.perf_counter()
        n_f, t_f = hist.drive(a, b)
        best = min(best, time.perf_counter() - t0)
    return best, n_f, t_f


def random_history(cycles: int, samples_per_segment: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """The seeded random (a*, b*) history of :class:`~sawdrift.scene.Prescribed` (a* crosses 0)."""
    drive = Prescribed(waveform="random", cycles=cycles, samples_per_segment=samples_per_segment,
                       seed=seed)
    return prescribed_history(drive)


def drifting_history(n: int, seed: int = 0, drift: float = 0.01) -> tuple[np.ndarray, np.ndarray]:
    """A long drifting history: a* mean-reverting around 1, b* a random walk with a mean drift.

    a*: AR(1) a_k = a_{k-1} + 0.02 (1 - a_{k-1}) + N(0, 0.03); b*: cumulative sum of
    N(``drift``, 0.05), so |b*| grows like ``drift`` n (the kernel must re-base its offsets).
    """
    from scipy.signal import lfilter

    rng = np.random.default_rng(seed)
    forcing = 0.02 + rng.normal(0.0, 0.03, n)
    a = lfilter([1.0], [1.0, -0.98], forcing, zi=[0.98])[0]
    b = np.cumsum(rng.normal(drift, 0.05, n))
    return a, b


def _row(**kw: Any) -> dict[str, Any]:
    row: dict[str, Any] = dict.fromkeys(COLUMNS)
    row.update(kw)
    return row


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


def _wave_rows(models: Sequence[str], cfg: StudyConfig, progress: bool) -> list[dict[str, Any]]:
    rows: list[dict[str, Any]] = []
    default_order = Numerics().order
    compliant = [m for m in models if not _is_rigid(m)]
    rigid = [m for m in models if _is_rigid(m)]
    n_runs = (
        len(compliant) * (2 + len(cfg.orders) * len(cfg.steps))
        + len(rigid) * (2 + len(cfg.rigid_steps))
        + (1 + len(cfg.wave_strips) if "mdr" in compliant else 0)
    )
    bar = _progress(n_runs, "wave", progress)
    periods = cfg.periods

    def reference(model: str, params: dict[str, Any] | None = None) -> tuple[float, float, str]:
        coarse, fine = cfg.reference_steps
        r1 = run(_wave_scene(model, order=4, steps_per_period=coarse, periods=periods,
                             model_params=params))
        bar.update(1)
        r2 = run(_wave_scene(model, order=4, steps_per_period=fine, periods=periods,
                             model_params=params))
        bar.update(1)
        return r2.drift_ratio, abs(r2.drift_ratio - r1.drift_ratio), r2.regime

    mmd_ref, mmd_unc, mmd_regime = math.nan, math.nan, ""
    if compliant:
        mmd_ref, mmd_unc, mmd_regime = reference("mmd")

    def ladder_row(model: str, order: int | None, spp: int, ref: float, unc: float, ref_regime: str,
                   default_spp: int, params: dict[str, Any] | None = None, ladder: str = "steps",
                   strips: int | None = None, note: str = "") -> None:
        scene = _wave_scene(model, order=order, steps_per_period=spp, periods=periods,
                            model_params=params)
        try:
            wall, res = _drift(scene, cfg.repeats)
            value, steps, regime = res.drift_ratio, res.steps, res.regime
            err = abs(value - ref)
        except NonFiniteStateError:
            wall, value, steps, regime, err = math.nan, math.nan, None, "non-finite", math.nan
            note = (note + "; " if note else "") + "state became non-finite (unstable)"
        is_default = spp == default_spp and (order is None or order == default_order)
        if ladder == "strips":
            is_default = is_default and strips == _default_strips()
        rows.append(_row(
            setting="wave", model=model, ladder=ladder, order=order, steps_per_period=spp,
            strips=strips, m_star=WAVE_M_STAR, amplitude=WAVE_AMPLITUDE, periods=periods,
            steps=steps, wall_s=wall,
            ns_per_step=1e9 * wall / steps if steps else math.nan, value=value, reference=ref,
            error=err, rel_error=err / abs(ref) if ref else math.nan, reference_uncertainty=unc,
            model_error_vs_mmd=(abs(ref - mmd_ref) if ladder == "steps" and not _is_rigid(model)
                                else math.nan),
            regime=regime, reference_regime=ref_regime, is_default=is_default, note=note,
        ))
        bar.update(1)

    for model in compliant:
        if model == "mmd":
            ref, unc, ref_regime = mmd_ref, mmd_unc, mmd_regime
        else:
            ref, unc, ref_regime = reference(model)
        default_spp = _wave_scene(model, periods=periods).steps_per_period()
        strips = _default_strips() if model == "mdr" else None
        for order in cfg.orders:
            for spp in cfg.steps:
                ladder_row(model, order, spp, ref, unc, ref_regime, default_spp, strips=strips)
    if "mdr" in compliant:
        # strip ladder at the default numerics, against mmd run with identical numerics
        base = _wave_scene("mmd", periods=periods)
        default_spp = base.steps_per_period()
        mmd_same = run(base)
        bar.update(1)
        for strips in cfg.wave_strips:
            ladder_row("mdr", default_order, default_spp, mmd_same.drift_ratio, math.nan,
                       mmd_same.regime, default_spp, params={"strips": strips}, ladder="strips",
                       strips=strips, note="vs mmd with identical numerics (strip error only)")
    for model in rigid:
        ref, unc, ref_regime = reference(model)
        default_spp = _wave_scene(model, periods=periods).steps_per_period()
        for spp in cfg.rigid_steps:
            ladder_row(model, None, spp, ref, unc, ref_regime, default_spp,
                       note="event-locating scheme (no Adams-Bashforth order)")
    bar.close()
    return rows


# -- (c) the defaults over the (m*, A*) plane ------------------------------------------------------


def _defaults_rows(models: Sequence[str], cfg: StudyConfig, progress: bool) -> list[dict[str, Any]]:
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
                scene = _wave_scene(model, periods=cfg.periods, m_star=float(m), amplitude=float(amp))
                spp = scene.steps_per_period()
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
                k = base.steps_per_period()
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


# -- figures -----------------------------------------------------------------------------------------

_MODEL_COLORS = {
    "mmd": "tab:blue",
    "mdr": "tab:orange",
    "jaeger": "tab:green",
    "hertz_mindlin_dem": "tab:red",
    "material_point": "tab:purple",
}
_ORDER_STYLE = {1: (":", "v"), 2: ("-.", "s"), 3: ("-", "o"), 4: ("--", "D"), None: ("-", "P")}
ERROR_FLOOR = 1e-16


def _color(model: str, i: int) -> str:
    import matplotlib.pyplot as plt

    return _MODEL_COLORS.get(model, plt.rcParams["axes.prop_cycle"].by_key()["color"][i % 10])


def _order_or_none(value: Any) -> int | None:
    return None if value is None or pd.isna(value) else int(value)


def _orders(column: pd.Series) -> pd.Series:
    """An order column as plain Python ints and None (object dtype: None stays None)."""
    return pd.Series([_order_or_none(v) for v in column], index=column.index, dtype=object)


def plot_prescribed(frame: pd.DataFrame, path: Path) -> Path:
    """Work-precision (error vs wall time) and the mdr strip convergence, prescribed setting."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sub = frame[frame["setting"] == "prescribed"]
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 5.2))
    for i, ((model, ladder), g) in enumerate(sub.groupby(["model", "ladder"], sort=False)):
        g = g.sort_values("wall_s")
        label = f"{model} (strips {int(g['strips'].min())}-{int(g['strips'].max())})" if (
            ladder == "strips") else f"{model}, samples/segment {int(g['samples_per_segment'].min())}-" \
            f"{int(g['samples_per_segment'].max())}"
        ax.loglog(np.maximum(g["error"].astype(float), ERROR_FLOOR), g["wall_s"].astype(float),
                  "-o" if ladder == "strips" else "--s", color=_color(model, i), label=label, ms=4)
    ax.set_xlabel("max |T* - T*_mmd| at the vertices of the random history")
    ax.set_ylabel("wall time of the history (s)")
    ax.set_title("(a) contact law alone: work-precision")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    strips = sub[sub["ladder"] == "strips"].sort_values("strips")
    if not strips.empty:
        s = strips["strips"].astype(float)
        ax2.loglog(s, strips["error"].astype(float), "-o", color=_color("mdr", 1), label="max error")
        ax2.loglog(s, strips["error_rms"].astype(float), "--o", color=_color("mdr", 1), alpha=0.6,
                   label="rms error")
        p_max = fit_order(s, strips["error"], finest=len(s))
        p_rms = fit_order(s, strips["error_rms"], finest=len(s))
        ax2.set_title(f"mdr vs strips: observed order {p_max:.2f} (max), {p_rms:.2f} (rms)")
        ax3 = ax2.twinx()
        ax3.loglog(s, strips["ns_per_step"].astype(float), ":^", color="gray", label="ns/step")
        ax3.set_ylabel("ns per sample (gray)")
        mmd = sub[(sub["model"] == "mmd")]
        if not mmd.empty:
            longest = mmd.loc[mmd["steps"].astype(float).idxmax()]
            ax3.axhline(float(longest["ns_per_step"]), color=_color("mmd", 0), ls=":",
                        label="mmd ns/step")
            ax3.legend(loc="upper center", fontsize=8)
        ax2.legend(loc="lower left", fontsize=8)
    ax2.set_xlabel("strips")
    ax2.set_ylabel("|T* - T*_mmd|")
    ax2.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def plot_wave(frame: pd.DataFrame, path: Path) -> Path:
    """Work-precision (error vs wall time) and error vs steps per period, wave setting."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sub = frame[frame["setting"] == "wave"]
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(16, 6.4))
    models = list(dict.fromkeys(sub["model"]))
    for i, model in enumerate(models):
        g_model = sub[sub["model"] == model]
        for ladder, g_l in g_model.groupby("ladder", sort=False):
            orders = _orders(g_l["order"]) if ladder == "steps" else pd.Series(
                [None] * len(g_l), index=g_l.index, dtype=object)
            for order in dict.fromkeys(orders):
                g = g_l[orders.map(lambda o, order=order: o == order)]
                g = g[np.isfinite(g["error"].astype(float))].sort_values("wall_s")
                if g.empty:
                    continue
                ls, mk = _order_style(order, ladder)
                if ladder == "strips":
                    label = f"{model} strips {int(g['strips'].min())}-{int(g['strips'].max())}"
                elif order is None:
                    label = f"{model} (event scheme)"
                else:
                    label = f"{model} AB{order}"
                err = np.maximum(g["error"].astype(float), ERROR_FLOOR)
                # mmd on top: mdr (256 strips) lies almost exactly under it
                style = dict(ls=ls, marker=mk, color=_color(model, i), label=label, ms=4,
                             lw=1.8 if model == "mmd" else 1.1, zorder=3 if model == "mmd" else 2)
                ax.loglog(err, g["wall_s"].astype(float), **style)
                if ladder == "steps":
                    ax2.loglog(g["steps_per_period"].astype(float), err, **style)
        dflt = g_model[g_model["is_default"].astype(bool) & (g_model["ladder"] == "steps")]
        for _, r in dflt.iterrows():
            ax.loglog(max(float(r["error"]), ERROR_FLOOR), float(r["wall_s"]), "*", ms=16,
                      mfc="none", mec="k")
            ax2.loglog(float(r["steps_per_period"]), max(float(r["error"]), ERROR_FLOOR), "*",
                       ms=16, mfc="none", mec="k")
    ax.set_xlabel("|drift ratio - reference|")
    ax.set_ylabel("wall time of the run (s)")
    ax.set_title(f"(b) wave scene m* = {WAVE_M_STAR:g}, A* = {WAVE_AMPLITUDE:g}: work-precision "
                 "(star: current default)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    handles, labels = ax.get_legend_handles_labels()
    fig.legend(handles, labels, loc="center right", fontsize=8, frameon=False)
    for slope in (1, 2, 3):
        xs = np.array([40.0, 320.0])
        ax2.loglog(xs, 1e-6 * (xs / 40.0) ** (-slope), color="0.55", lw=0.9)
        ax2.text(xs[-1] * 1.05, 1e-6 * 8.0 ** (-slope), f"order {slope}", fontsize=7, color="0.35",
                 va="center")
    ax2.set_xlabel("steps per period")
    ax2.set_ylabel("|drift ratio - reference|")
    ax2.set_title("convergence (gray: slopes of order 1, 2, 3; mdr lies under mmd)", fontsize=10)
    ax2.grid(True, which="both", alpha=0.3)
    fig.tight_layout(rect=(0.0, 0.0, 0.86, 1.0))
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def _order_style(order: int | None, ladder: str) -> tuple[str, str]:
    if ladder == "strips":
        return "-", "x"
    return _ORDER_STYLE.get(order, ("-", "o"))


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
    """The markdown summary of a work-precision study, with data-driven recommendations."""
    default_order = Numerics().order
    lines = [
        "# sawdrift work-precision study" + (" (quick)" if quick else ""),
        "",
        f"Machine: {os.cpu_count()} cores, {platform.processor() or platform.machine()}, "
        f"Python {platform.python_version()}. Timings: best of {cfg.repeats} after one discarded "
        "warm-up call (numba compilation excluded).",
        "",
        f"Current default: Adams-Bashforth order {default_order}, steps per period "
        "max(128, ceil(omega / 0.06)), omega = sqrt(k / m*).",
        "",
    ]
    pre = frame[frame["setting"] == "prescribed"]
    if not pre.empty:
        n_samples = int(pre["steps"].max())
        lines += [
            "## (a) Contact law alone: prescribed random history",
            "",
            f"Seeded random (a*, b*) walk, {cfg.cycles * 10} straight segments, a* crossing zero; "
            "error = max |T* - T*_mmd| at the path's vertices (the same points for every "
            "sampling) against the pure-Python memory-diagram reference (the exact law). Longest "
            f"sampling: {n_samples} samples.",
            "",
            "| model | ladder | samples/segment | strips | max error | rms error | ns/sample |",
            "|---|---|---|---|---|---|---|",
        ]
        for _, r in pre.iterrows():
            lines.append(
                f"| {r['model']} | {r['ladder']} | {int(r['samples_per_segment'])} | "
                f"{'' if pd.isna(r['strips']) else int(r['strips'])} | {_fmt(r['error'])} | "
                f"{_fmt(r['error_rms'])} | {_fmt(r['ns_per_step'], '.0f')} |"
            )
        lines += [
            "",
            "All laws are exact along each straight segment, so the sampling of the path changes "
            "the cost but not the error: the error of mmd is round-off, that of jaeger and "
            "hertz_mindlin_dem is their model error (a different law), that of mdr its strip "
            "discretization.",
            "",
        ]
    wave = frame[frame["setting"] == "wave"]
    if not wave.empty:
        lines += [
            "## (b) Wave scene",
            "",
            f"m* = {WAVE_M_STAR:g}, A* = {WAVE_AMPLITUDE:g}, {cfg.periods:g} periods (5-period ramp). "
            f"Reference: order 4 at {cfg.reference_steps[1]} steps per period; its uncertainty is "
            f"the change from {cfg.reference_steps[0]}.",
            "",
            "| model | reference drift ratio | reference uncertainty | regime | model error vs mmd |",
            "|---|---|---|---|---|",
        ]
        for model, g in wave[wave["ladder"] == "steps"].groupby("model", sort=False):
            r = g.iloc[0]
            lines.append(f"| {model} | {_fmt(r['reference'], '.8f')} | "
                         f"{_fmt(r['reference_uncertainty'])} | {r['reference_regime']} | "
                         f"{_fmt(r['model_error_vs_mmd'])} |")
        lines += [
            "",
            "Observed order (fit of log error vs log steps per period, four finest points above "
            "10x the reference uncertainty), and the error at 128 and 512 steps per period:",
            "",
            "| model | order | observed order | error @128 | error @512 | wall @128 (ms) |",
            "|---|---|---|---|---|---|",
        ]
        for _, o in orders[(orders["setting"] == "wave") & (orders["ladder"] == "steps")].iterrows():
            g = wave[(wave["model"] == o["model"]) & (wave["ladder"] == "steps")]
            want = _order_or_none(o["order"])
            g = g[_orders(g["order"]).map(lambda v, want=want: v == want)]

            def at(spp: int, col: str, g: pd.DataFrame = g) -> Any:
                hit = g[g["steps_per_period"] == spp]
                return hit[col].iloc[0] if not hit.empty else math.nan

            order_txt = "event scheme" if pd.isna(o["order"]) else str(int(o["order"]))
            observed = _fmt(o["observed_order"], ".2f")
            if observed == "n/a" and float(g["error"].max()) <= 1e-9:
                observed = "none (round-off at every step)"
            lines.append(f"| {o['model']} | {order_txt} | {observed} | "
                         f"{_fmt(at(128, 'error'))} | {_fmt(at(512, 'error'))} | "
                         f"{_fmt(1e3 * float(at(128, 'wall_s')), '.2f')} |")
        dflt = wave[wave["is_default"].astype(bool) & (wave["ladder"] == "steps")]
        if not dflt.empty:
            lines += ["", "At the current defaults:", ""]
            for _, r in dflt.iterrows():
                lines.append(
                    f"- {r['model']}: {int(r['steps_per_period'])} steps per period, drift ratio "
                    f"{_fmt(r['value'], '.6f')}, error {_fmt(r['error'])} "
                    f"(relative {_fmt(r['rel_error'])}), {_fmt(1e3 * float(r['wall_s']), '.2f')} ms, "
                    f"{_fmt(r['ns_per_step'], '.0f')} ns/step"
                )
        strips = wave[wave["ladder"] == "strips"]
        if not strips.empty:
            lines += [
                "",
                "mdr strip count at the default numerics (error vs mmd with identical numerics):",
                "",
                "| strips | drift ratio | error vs mmd | ns/step |",
                "|---|---|---|---|",
            ]
            for _, r in strips.sort_values("strips").iterrows():
                lines.append(f"| {int(r['strips'])} | {_fmt(r['value'], '.8f')} | {_fmt(r['error'])} | "
                             f"{_fmt(r['ns_per_step'], '.0f')} |")
        for tol in (1e-4, 1e-6):
            best = cheapest(frame, "mmd", tol)
            if best is not None:
                lines.append("")
                lines.append(
                    f"Cheapest mmd run with error <= {tol:g}: order {int(best['order'])}, "
                    f"{int(best['steps_per_period'])} steps per period, "
                    f"{_fmt(1e3 * float(best['wall_s']), '.2f')} ms (error {_fmt(best['error'])})."
                )
        lines.append("")
    grid = frame[frame["setting"] == "defaults"]
    if not grid.empty:
        lines += [
            "## (c) Current defaults over the (m*, A*) plane",
            "",
            f"{cfg.grid} x {cfg.grid} log grid, m* in [1e-3, 1e2], A* in [1e-2, 10], "
            f"{cfg.periods:g} periods, drift ratio at the default numerics, at half and at twice "
            f"the default steps, against order 4 at {cfg.grid_refine[1]}x the default steps "
            f"(reference uncertainty: the change from {cfg.grid_refine[0]}x). A cell is "
            "*chaotic* when its references differ by more than max(1e-6, error / 10), or when "
            "its error exceeds 1e-4 without converging (half the steps does not give 1.5x the "
            "error): irregular bouncing, where any change of step changes the 60-period drift "
            "ratio by O(1). All other cells are *resolved*.",
            "",
            "| model | cells | resolved | max error (resolved) | worst resolved cell (m*, A*, "
            "rel. error) | median error | max error, half steps | max error, 2x steps | "
            "max error (all cells) | regime changes (all cells) |",
            "|---|---|---|---|---|---|---|---|---|---|",
        ]
        for model, g in grid.groupby("model", sort=False):
            ok = converged_cells(g) & np.isfinite(g["error"].astype(float))
            good = g[ok]
            changes = int((g["regime"] != g["reference_regime"]).sum())
            if not good.empty:
                w = good.loc[good["error"].astype(float).idxmax()]
                worst = f"{w['m_star']:.3g}, {w['amplitude']:.3g}, {_fmt(w['rel_error'])}"
            else:
                worst = "n/a"
            lines.append(
                f"| {model} | {len(g)} | {int(ok.sum())} | {_fmt(good['error'].max())} | {worst} | "
                f"{_fmt(good['error'].median())} | {_fmt(good['error_half_default'].max())} | "
                f"{_fmt(good['error_double_default'].max())} | {_fmt(g['error'].max())} | "
                f"{changes} |"
            )
        lines += ["", "Chaotic cells (m*, A*):", ""]
        for model, g in grid.groupby("model", sort=False):
            bad = g[~converged_cells(g)]
            cells = ", ".join(f"({float(r['m_star']):.3g}, {float(r['amplitude']):.3g})"
                              for _, r in bad.iterrows())
            lines.append(f"- {model}: {cells or 'none'}")
        lines.append("")
    long = frame[frame["setting"] == "long"]
    if not long.empty:
        lines += [
            f"## (d) Long runs: {float(long['periods'].iloc[0]):g} periods at the default step",
            "",
            "Ramp of 1 period (a large free normal oscillation), m* = 0.1, A* = 0.3; reference: "
            "order 4 at 8x the default steps.",
            "",
            "| model | case | order | steps/period | drift ratio | reference | error |",
            "|---|---|---|---|---|---|---|",
        ]
        for _, r in long.iterrows():
            lines.append(
                f"| {r['model']} | {r['note']} | {int(r['order'])} | {int(r['steps_per_period'])} | "
                f"{float(r['value']):.6f} | {float(r['reference']):.6f} | {_fmt(r['error'])} |"
            )
        lines.append("")
    lines += recommendations(frame, orders)
    return "\n".join(lines) + "\n"


def recommendations(frame: pd.DataFrame, orders: pd.DataFrame) -> list[str]:
    """Data-driven recommendation lines (markdown) on the default order and step count."""
    out = ["## Recommendation", ""]
    wave = frame[(frame["setting"] == "wave") & (frame["ladder"] == "steps")]
    mmd = wave[wave["model"] == "mmd"]
    if mmd.empty:
        out.append("- (mmd not in this study: no recommendation on the integrator defaults.)")
        return out
    default_order = Numerics().order
    dflt = mmd[mmd["is_default"].astype(bool)]
    by_order = {}
    for order in sorted({_order_or_none(o) for o in mmd["order"]} - {None}):
        g = mmd[(mmd["order"] == order) & (mmd["steps_per_period"] == 128)]
        if not g.empty:
            by_order[order] = float(g["error"].iloc[0])
    if by_order:
        txt = ", ".join(f"AB{k} {_fmt(v)}" for k, v in by_order.items())
        out.append(f"- mmd drift-ratio error at 128 steps per period, by order: {txt}.")
    if not dflt.empty:
        e = float(dflt["error"].iloc[0])
        out.append(
            f"- At the defaults the wave-scene error is {_fmt(e)} in drift ratio, "
            f"{'far ' if e < 1e-4 else ''}below the 1e-3 stick tolerance of the regime classifier."
            if e < 1e-3 else
            f"- At the defaults the wave-scene error is {_fmt(e)} in drift ratio, ABOVE the 1e-3 "
            "stick tolerance: increase the default steps per period."
        )
    grid = frame[(frame["setting"] == "defaults") & (frame["model"] == "mmd")]
    if not grid.empty:
        ok = converged_cells(grid) & np.isfinite(grid["error"].astype(float))
        good = grid[ok]
        if not good.empty:
            w = good.loc[good["error"].astype(float).idxmax()]
            changes = int((grid["regime"] != grid["reference_regime"]).sum())
            dbl = float(good["error_double_default"].max())
            out.append(
                f"- Over the (m*, A*) plane, mmd at the defaults: median error "
                f"{_fmt(good['error'].median())}, worst resolved cell {_fmt(w['error'])} "
                f"(relative {_fmt(w['rel_error'])}) at m* = {w['m_star']:.3g}, "
                f"A* = {w['amplitude']:.3g} ({int(w['steps_per_period'])} steps per period, regime "
                f"{w['regime']}); {changes} regime changes in {len(grid)} cells; "
                f"{int((~ok).sum())} chaotic cells. Twice the default steps would bring the worst "
                f"resolved error to {_fmt(dbl)} at twice the cost."
            )
            verdict = float(w["rel_error"]) if math.isfinite(float(w["rel_error"])) else math.inf
            if verdict <= 1e-2 and changes == 0:
                out.append(
                    "- The step default is adequate: every resolved cell is within "
                    f"{_fmt(100 * verdict, '.2g')} % of its converged drift ratio and no regime "
                    "changes; keep max(128, ceil(omega / 0.06))."
                )
            else:
                out.append(
                    "- The step default is too coarse somewhere in the plane (relative error "
                    f"{_fmt(verdict)} or regime changes): tighten it (e.g. h omega <= 0.03 or a "
                    "floor of 256 steps per period)."
                )
    rows = orders[(orders["setting"] == "wave") & (orders["model"] == "mmd")]
    hi = rows[rows["order"].map(lambda o: o is not None and not pd.isna(o) and int(o) >= 3)]
    if not hi.empty:
        obs = ", ".join(f"AB{int(r['order'])} {_fmt(r['observed_order'], '.2f')}"
                        for _, r in hi.iterrows())
        out.append(
            f"- Observed orders of AB3/AB4 on mmd: {obs}. The contact law is not smooth in time "
            "(stick-slip transitions, turning points, contact loss), which caps the observed "
            "order at about 2 for every model (table above)."
        )
    long = frame[frame["setting"] == "long"]
    if not long.empty:
        err = long.groupby("order")["error"].max()
        e3, e4 = float(err.get(3, math.nan)), float(err.get(4, math.nan))
        periods = float(long["periods"].iloc[0])
        best = 4 if e4 <= e3 else 3
        out.append(
            f"- Long runs ({periods:g} periods, table (d)): largest drift-ratio error at the default "
            f"step AB3 {_fmt(e3)}, AB4 {_fmt(e4)}. The normal oscillation is undamped and AB3 "
            "damps it numerically ((3/8)(h omega)^4 per step), AB4 only at O((h omega)^6): "
            f"order {best} is the better default"
            + (" (it is the default)." if best == default_order else f" (the default is {default_order}).")
        )
    ab3 = by_order.get(3, math.nan)
    ab2 = by_order.get(2, math.nan)
    if math.isfinite(ab3) and math.isfinite(ab2):
        out.append(f"- At 60 periods: AB3 error {_fmt(ab3)} vs AB2 {_fmt(ab2)} at equal cost; "
                   "never use AB1 or AB2.")
    strips = frame[(frame["setting"] == "wave") & (frame["ladder"] == "strips")]
    dflt_strips = strips[strips["is_default"].astype(bool)]
    if not dflt_strips.empty and not dflt.empty:
        e_s = float(dflt_strips["error"].iloc[0])
        e_t = float(dflt["error"].iloc[0])
        out.append(
            f"- mdr: at its default {int(dflt_strips['strips'].iloc[0])} strips the strip error in "
            f"drift ratio is {_fmt(e_s)}, {'below' if e_s < e_t else 'ABOVE'} the time-step error "
            f"{_fmt(e_t)} at the default step: "
            + ("the strip default is adequate." if e_s < e_t else "raise the strip default.")
        )
    for model in frame.loc[frame["setting"] == "wave", "model"].unique():
        if not _is_rigid(str(model)):
            continue
        g = frame[(frame["model"] == model) & (frame["setting"].isin(["wave", "defaults"]))]
        w = g[g["setting"] == "wave"]
        out.append(
            f"- {model}: the event scheme's error does not depend on the step (wave ladder "
            f"{int(w['steps_per_period'].min())}-{int(w['steps_per_period'].max())} steps per "
            f"period: max error {_fmt(w['error'].max())}; over the plane: max "
            f"{_fmt(g.loc[g['setting'] == 'defaults', 'error'].max())}), so its default of "
            f"{int(_wave_scene(str(model)).steps_per_period())} steps per period only bounds the "
            "length of events missed inside one step; keep it (its cost is negligible)."
        )
    return out


# -- work_precision -------------------------------------------------------------------------------


def _models_list(models: str | Sequence[str] | None) -> list[str]:
    if models is None:
        names = list(DEFAULT_MODELS)
    elif isinstance(models, str):
        names = [m.strip() for m in models.split(",") if m.strip()]
    else:
        names = [str(m) for m in models]
    if not names:
        raise SceneError(f"models = {models!r} must name at least one model")
    for name in names:
        get_model(name)  # a one-line ModelNotFoundError for an unknown name
    return names


def work_precision(models: str | Sequence[str] | None, out_dir: str | Path, quick: bool = False, *,
                   progress: bool = True, config: StudyConfig | None = None,
                   defaults_check: bool = True) -> pd.DataFrame:
    """Work-precision study of ``models``: error against a tight reference versus wall time.

    Parameters
    ----------
    models
        Model names (a sequence or a comma-separated string); None: :data:`DEFAULT_MODELS`.
    out_dir
        Directory for ``work_precision.csv``, ``orders.csv``, ``work_precision_prescribed.png``,
        ``work_precision_wave.png`` and ``summary.md`` (created if needed).
    quick
        Short ladders and runs (seconds, for CI) instead of the full study (minutes).
    progress
        tqdm progress bars on stderr.
    config
        Explicit ladders (overrides ``quick``).
    defaults_check
        Also check the current defaults over a (m*, A*) grid (setting ``"defaults"``).

    Returns
    -------
    pandas.DataFrame
        One row per measured run, columns :data:`COLUMNS`; ``setting`` is ``"prescribed"``,
        ``"wave"`` or ``"defaults"``.
    """
    cfg = config if config is not None else (QUICK if quick else FULL)
    if not defaults_check:
        cfg = replace(cfg, grid=0)
    names = _models_list(models)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    rows = _prescribed_rows(names, cfg, progress)
    rows += _wave_rows(names, cfg, progress)
    rows += _defaults_rows(names, cfg, progress)
    rows += _long_rows(names, quick, progress)
    frame = pd.DataFrame(rows, columns=list(COLUMNS))
    frame["order"] = frame["order"].astype("Int64")
    for col in ("steps_per_period", "strips", "samples_per_segment", "steps"):
        frame[col] = pd.to_numeric(frame[col]).astype("Int64")
    frame["is_default"] = frame["is_default"].fillna(False).astype(bool)
    frame.to_csv(out / "work_precision.csv", index=False)
    orders = observed_orders(frame)
    orders.to_csv(out / "orders.csv", index=False)
    if (frame["setting"] == "prescribed").any():
        plot_prescribed(frame, out / "work_precision_prescribed.png")
    if (frame["setting"] == "wave").any():
        plot_wave(frame, out / "work_precision_wave.png")
    (out / "summary.md").write_text(summary_markdown(frame, orders, cfg, quick))
    return frame


# -- speed -----------------------------------------------------------------------------------------


@dataclass
class Target:
    """One speed target: what was measured, the limit and the verdict."""

    name: str
    description: str
    measured: float
    unit: str
    limit: float
    comparison: str  # "<=", "<" or ">="
    passed: bool
    details: dict[str, Any]

    def line(self) -> str:
        """One report line: verdict, measured value and target."""
        verdict = "PASS" if self.passed else "FAIL"
        return (f"[{verdict}] {self.description}: {self.measured:.4g} {self.unit} "
                f"(target {self.comparison} {self.limit:g} {self.unit})")


def _target(name: str, description: str, measured: float, unit: str, limit: float,
            comparison: str, details: dict[str, Any], extra_ok: bool = True) -> Target:
    ok = {"<=": measured <= limit, "<": measured < limit, ">=": measured >= limit}[comparison]
    return Target(name, description, float(measured), unit, float(limit), comparison,
                  bool(ok and extra_ok and math.isfinite(measured)), details)


def speed_sweep(quick: bool = False, progress: bool = True) -> Target:
    """The 41 x 41 mmd sweep (9 x 9 with ``quick``), 60 periods, default accuracy and executor."""
    n = 9 if quick else 41
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        table = sweep("mmd", f"1e-3:1e2:{n}", f"1e-2:10:{n}", table=Path(tmp) / "sweep.parquet",
                      progress=progress)
        wall = time.perf_counter() - t0
    errors = int(table["error"].notna().sum())
    details = {
        "cells": int(len(table)), "errors": errors, "workers": os.cpu_count(),
        "steps_total": int(table["steps"].sum()),
        "cpu_s_in_runs": float(table["wall_time_s"].sum()),
        "regimes": {str(k): int(v) for k, v in table["regime"].value_counts().items()},
    }
    return _target(
        "sweep", f"{n}x{n} mmd sweep, m* 1e-3..1e2, A* 1e-2..10, 60 periods, default accuracy, "
        f"{os.cpu_count()} workers ({len(table)} cells, {errors} errors, "
        f"{details['steps_total']:.3g} steps)",
        wall, "s", 60.0, "<=", details, extra_ok=errors == 0,
    )


def speed_engines(quick: bool = False, repeats: int = 3) -> Target:
    """Compiled vs python engine for mmd on the same short wave run (ratio in one process)."""
    periods = 10.0 if quick else 20.0
    scene = _wave_scene("mmd", periods=periods)
    t_c, r_c = best_time(lambda: run(scene, engine="compiled"), repeats=5 * repeats)
    t_p, r_p = best_time(lambda: run(scene, engine="python"), repeats=repeats)
    ratio = t_p / t_c
    details = {"periods": periods, "steps": r_c.steps, "compiled_s": t_c, "python_s": t_p,
               "drift_ratio_compiled": r_c.drift_ratio, "drift_ratio_python": r_p.drift_ratio,
               "engines_agree_to": abs(r_c.drift_ratio - r_p.drift_ratio)}
    return _target(
        "engines", f"compiled vs python engine, mmd, m* = {WAVE_M_STAR:g}, A* = {WAVE_AMPLITUDE:g}, "
        f"{periods:g} periods ({r_c.steps} steps; compiled {1e3 * t_c:.2f} ms, python "
        f"{1e3 * t_p:.1f} ms)", ratio, "x", 50.0, ">=", details,
    )


def speed_vs_material_point(quick: bool = False, repeats: int = 5) -> Target:
    """Cost per step of mmd against material_point on the wave scene (default numerics)."""
    periods = 40.0 if quick else 200.0
    per: dict[str, dict[str, float]] = {}
    for model in ("mmd", "material_point"):
        scene = _wave_scene(model, periods=periods)
        wall, res = best_time(lambda scene=scene: run(scene), repeats=repeats)
        per[model] = {"wall_s": wall, "steps": res.steps, "ns_per_step": 1e9 * wall / res.steps,
                      "steps_per_period": res.steps_per_period}
    ratio = per["mmd"]["ns_per_step"] / per["material_point"]["ns_per_step"]
    return _target(
        "vs_material_point", f"mmd cost per step / material_point's, wave scene, {periods:g} periods "
        f"(mmd {per['mmd']['ns_per_step']:.0f} ns/step, material_point "
        f"{per['material_point']['ns_per_step']:.0f} ns/step)", ratio, "x", 3.0, "<=", per,
    )


def speed_vs_mdr(quick: bool = False, repeats: int = 5, strips: int = 1024) -> Target:
    """Cost per step of mdr (``strips`` strips) over mmd's on a prescribed random history.

    Accuracy is measured on the same history against the pure-Python memory-diagram reference:
    the target also requires mmd's error to be at most mdr's.
    """
    cycles, samples = (10, 50) if quick else (50, 50)
    a, b = random_history(cycles, samples, seed=11)
    _n_ref, t_ref = _history("mmd", None, "python").drive(a, b)
    t_mmd, _, tf_mmd = drive_timed("mmd", a, b, repeats=5 * repeats)
    t_mdr, _, tf_mdr = drive_timed("mdr", a, b, params={"strips": strips}, repeats=repeats)
    err_mmd = float(np.max(np.abs(tf_mmd - t_ref)))
    err_mdr = float(np.max(np.abs(tf_mdr - t_ref)))
    ratio = t_mdr / t_mmd
    details: dict[str, Any] = {
        "samples": int(a.size), "mmd_ns_per_step": 1e9 * t_mmd / a.size,
        "mdr_ns_per_step": 1e9 * t_mdr / a.size, "mmd_max_error": err_mmd,
        "mdr_max_error": err_mdr, "mdr_rms_error": float(np.sqrt(np.mean((tf_mdr - t_ref) ** 2))),
        "strips": strips,
    }
    if not quick:
        # context: mdr with 8x more strips is still far from mmd's accuracy
        t_8, _, tf_8 = drive_timed("mdr", a, b, params={"strips": 8 * strips}, repeats=2)
        details[f"mdr_{8 * strips}_ns_per_step"] = 1e9 * t_8 / a.size
        details[f"mdr_{8 * strips}_max_error"] = float(np.max(np.abs(tf_8 - t_ref)))
    return _target(
        "vs_mdr", f"mdr ({strips} strips) cost per step / mmd's, prescribed random history, "
        f"{a.size} samples (mmd {details['mmd_ns_per_step']:.0f} ns/step, max |dT*| {err_mmd:.1e}; "
        f"mdr {details['mdr_ns_per_step']:.0f} ns/step, max |dT*| {err_mdr:.1e} vs exact mmd)",
        ratio, "x", 20.0, ">=", details, extra_ok=err_mmd <= err_mdr,
    )


def speed_history_length(quick: bool = False, progress: bool = True) -> Target:
    """mmd cost per step after a long history against short ones (1e6 vs 1e4 steps).

    Both sides drive the kernel through the same samples of one drifting history, in calls of
    1e4 samples: the long side keeps one history for all 1e6 (1e5 with ``quick``) steps, the short
    side starts a fresh history every 1e4 steps. Memory traffic and call pattern are therefore
    identical and only the history length differs, which is what the target is about. The
    plain 1e6-sample call (input and output arrays streaming from memory) is reported too.
    """
    chunk = 10_000
    n_long = 100_000 if quick else 1_000_000
    a, b = drifting_history(n_long, seed=3)
    model = get_model("mmd")()

    def drive(fresh_each_chunk: bool) -> tuple[float, bool]:
        best, finite = math.inf, True
        for _ in range(3):
            hist = model.new_history()
            t0 = time.perf_counter()
            for i in range(0, n_long, chunk):
                if fresh_each_chunk:
                    hist.reset()
                _, t_f = hist.drive(a[i : i + chunk], b[i : i + chunk])
            best = min(best, time.perf_counter() - t0)
            finite = finite and bool(np.all(np.isfinite(t_f)))
        return best, finite

    drive(True)  # warm-up (compilation)
    t_short, ok_short = drive(True)
    t_long, ok_long = drive(False)
    streamed, _, t_f = drive_timed("mmd", a, b, repeats=3 if quick else 5)
    short, long = 1e9 * t_short / n_long, 1e9 * t_long / n_long
    ratio = long / short
    out: dict[str, Any] = {
        "short_ns_per_step": short, "long_ns_per_step": long, "ratio": ratio,
        "final_b": float(b[-1]), "streamed_long_ns_per_step": 1e9 * streamed / n_long,
        "streamed_ratio": (1e9 * streamed / n_long) / short,
    }
    deviation = abs(ratio - 1.0)
    return _target(
        "history_length", f"mmd cost per step, one {n_long:.0e}-step drifting history vs fresh "
        f"1e4-step histories on the same samples ({long:.1f} vs {short:.1f} ns/step, ratio "
        f"{ratio:.3f}, final b* = {b[-1]:.0f}; one unchunked call: "
        f"{out['streamed_long_ns_per_step']:.1f} ns/step); |ratio - 1|", 100.0 * deviation, "%", 20.0,
        "<=", out, extra_ok=ok_short and ok_long and bool(np.all(np.isfinite(t_f))),
    )


def speed(quick: bool = False, *, progress: bool = True, out: str | Path | None = None,
          report: bool = True) -> dict[str, Any]:
    """Measure the speed targets of issue 7 and print a PASS/FAIL report.

    Parameters
    ----------
    quick
        Small variants (seconds, for CI): a 9 x 9 sweep, shorter runs, 1e5 instead of 1e6 steps.
        The limits are those of the full targets, so a quick PASS is only a smoke test.
    progress
        tqdm progress bars (the sweep, and the list of targets).
    out
        Also write the result as JSON to this path.
    report
        Print the report to stdout.

    Returns
    -------
    dict
        ``{"quick", "machine", "targets": {name: {...}}, "all_passed"}``; every target has
        ``measured``, ``unit``, ``limit``, ``comparison``, ``passed`` and ``details``.
    """
    from tqdm import tqdm

    from . import speed_more

    # the sweep goes first: its worker processes are forked from this one, so it must not
    # inherit loops compiled by the other targets (a user's sweep compiles them in each worker)
    steps: list[tuple[str, Callable[[], Target]]] = [
        ("sweep", lambda: speed_sweep(quick, progress)),
        ("engines", lambda: speed_engines(quick)),
        ("vs_material_point", lambda: speed_vs_material_point(quick)),
        ("vs_mdr", lambda: speed_vs_mdr(quick)),
        ("history_length", lambda: speed_history_length(quick, progress)),
        ("steady", lambda: speed_more.speed_steady(quick)),
        ("adaptive", lambda: speed_more.speed_adaptive(quick, progress)),
        ("cold_start", lambda: speed_more.speed_cold_start(quick)),
    ]
    targets: dict[str, Target] = {}
    bar = tqdm(steps, desc="speed targets", unit="target", disable=not progress, leave=False,
               dynamic_ncols=True)
    for name, fn in bar:
        bar.set_postfix_str(name)
        got = fn()
        for t in got if isinstance(got, list) else [got]:
            targets[t.name if isinstance(got, list) else name] = t
    bar.close()
    import numba

    result: dict[str, Any] = {
        "quick": quick,
        "machine": {"cores": os.cpu_count(), "processor": platform.processor() or platform.machine(),
                    "python": platform.python_version(), "numba": numba.__version__,
                    "numpy": np.__version__},
        "targets": {name: asdict(t) for name, t in targets.items()},
        "all_passed": all(t.passed for t in targets.values()),
    }
    text = speed_report(targets, result)
    if report:
        print(text)
    if out is not None:
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        Path(out).write_text(json.dumps(result, indent=2, default=float))
    return result


def speed_report(targets: dict[str, Target], result: dict[str, Any]) -> str:
    """The printed report: one PASS/FAIL line per target."""
    m = result["machine"]
    head = (f"sawdrift speed targets{' (quick: smoke test, full-size limits)' if result['quick'] else ''}"
            f" - {m['cores']} cores, Python {m['python']}, numba {m['numba']}")
    lines = [head]
    lines += ["  " + t.line() for t in targets.values()]
    n_pass = sum(t.passed for t in targets.values())
    lines.append(f"{n_pass}/{len(targets)} targets met")
    return "\n".join(lines)
