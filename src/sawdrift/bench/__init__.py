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
  default steps, all fixed-length runs (settling off: a settled heavy cell is a chaotic
  long-time mean, whose change with the step says nothing about the integrator).

* :func:`speed` measures the speed targets of issue 7 and prints a PASS/FAIL report.

Timing rules: every timed call is preceded by an identical warm-up call that is discarded (it
absorbs numba compilation and cache loading), and the best of a few repeats is kept.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

import pandas as pd

from .core import (  # noqa: F401 - re-exported: the study's shared pieces
    COLUMNS,
    DEFAULT_MODELS,
    FULL,
    QUICK,
    WAVE_AMPLITUDE,
    WAVE_M_STAR,
    StudyConfig,
    _history,
    _is_rigid,
    _models_list,
    _progress,
    _row,
    _wave_scene,
    best_time,
    drifting_history,
    drive_timed,
    fit_order,
    random_history,
)


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
        progress on stderr: tqdm bars on a terminal, plain lines in a log.
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
        plot_prescribed(frame, out / "work_precision_prescribed.png", strip_orders(frame))
    if (frame["setting"] == "wave").any():
        plot_wave(frame, out / "work_precision_wave.png", WAVE_M_STAR, WAVE_AMPLITUDE)
    (out / "summary.md").write_text(summary_markdown(frame, orders, cfg, quick))
    return frame


def strip_orders(frame: pd.DataFrame) -> tuple[float, float]:
    """mdr's observed order against the strip count in the prescribed setting (max and rms error).

    NaN when the frame has fewer than two strip counts.
    """
    strips = frame[(frame["setting"] == "prescribed") & (frame["ladder"] == "strips")].sort_values("strips")
    if strips.empty:
        return math.nan, math.nan
    s = strips["strips"].astype(float)
    return (fit_order(s, strips["error"], finest=len(s)), fit_order(s, strips["error_rms"], finest=len(s)))


# the study's parts live in their own modules; their public names are re-exported here
from ..report.work_precision_plot import plot_prescribed, plot_wave  # noqa: E402
from .speed_targets import (  # noqa: E402, F401
    Target,
    _target,
    speed,
    speed_engines,
    speed_history_length,
    speed_report,
    speed_sweep,
    speed_vs_material_point,
    speed_vs_mdr,
)
from .study_rows import (  # noqa: E402, F401
    _default_strips,
    _defaults_rows,
    _long_rows,
    _prescribed_rows,
    _wave_rows,
    converged_cells,
)
from .summary import observed_orders, recommendations, summary_markdown  # noqa: E402, F401
