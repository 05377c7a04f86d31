"""Shared pieces of the performance study: the study configuration, the wave scene, timing,
histories and order fits (used by :mod:`.bench` and its parts, which import from here).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np

from ..contact.binding import model_for
from ..contact.history import ContactHistory
from ..contact.registry import get_model
from ..dynamics.prescribed import prescribed_history
from ..errors import SceneError
from ..scene.schema import Prescribed, Scene
from ..study.progress import counter

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
    """A progress counter: a tqdm bar on a terminal, plain lines in a log (``study.progress``)."""
    return counter(total, desc, "run", enabled=enabled, leave=False)


def _wave_scene(model: str, *, order: int | None = None, steps_per_period: int | None = None,
                periods: float = 60.0, m_star: float = WAVE_M_STAR,
                amplitude: float = WAVE_AMPLITUDE,
                model_params: dict[str, Any] | None = None, settle: bool | None = None) -> Scene:
    numerics: dict[str, Any] = {"periods": periods, "settle": settle}
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
    inst = model_for(scene)
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
