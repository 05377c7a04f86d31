"""Validation harness: run the cases of ``validation/`` and write an HTML and JSON report.

A *case* is one Python file in the cases folder (by default ``validation/`` at the repository
root). It asserts one physical or numerical fact against a closed-form oracle or an independent
reference, with a stated tolerance, and defines

* ``CASE``: a :class:`Case` (name, group, statement, tolerance, whether it is in the quick subset,
  the models it is run for, and which of them deviate by design);
* ``run()`` (or ``run(model)`` when ``CASE.models`` is not empty; optionally a ``quick`` keyword)
  returning a :class:`CaseResult`, normally built with :meth:`Case.result`.

:func:`validate` discovers the cases, runs them (once per model for model-parametrized cases),
and writes ``OUT/index.html`` (summary, PASS/FAIL table per group, figures inline as base64 PNG),
``OUT/results.json`` and ``OUT/figures/*.png``. A case that raises, or whose model is not
registered, is reported as an *error* and counts as a failure; it never stops the other cases.
A case whose model is marked as not exact by design reports its deviation as an *expected
deviation*: shown with its value, not counted as a failure.

The module also holds the closed-form oracles the cases share (docs/physics.md).
"""

from __future__ import annotations

import fnmatch
import importlib.util
import inspect
import math
import platform
import sys
import time
import traceback
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any, Literal

import numpy as np

#: Case groups, in report order: key -> heading.
GROUPS: dict[str, str] = {
    "material_point": "1. Material point against the analytic results",
    "mindlin": "2. Cattaneo-Mindlin, Masing, loop area and proportional loading, every compliant model",
    "convergence": "3. Numerical cross-checks: mdr to mmd, kernels against references, Rayleigh ratio",
    "diagrams": "4. Regime diagrams and the paper's statements",
    "point_mass": "5. The later paper's point-mass claim",
    "device": "6. Physical units: conversion, orbit mirror, dimensional consistency",
    "conformance": "7. Conformance of every installed model: passivity, Coulomb bound, kernels",
    "rotation": "8. Rotation: a finite sphere that can roll",
}

#: The compliant models the oracle cases run for by default.
COMPLIANT_MODELS: tuple[str, ...] = ("mmd", "mdr", "jaeger", "hertz_mindlin_dem")

#: The models drawn in the regime diagrams.
DIAGRAM_MODELS: tuple[str, ...] = ("material_point", *COMPLIANT_MODELS)

#: Friction coefficient and Poisson's ratio of the paper's figures (docs/physics.md).
MU = 0.1
NU = 0.3

Status = Literal["pass", "fail", "expected deviation", "error"]
Compare = Literal["<=", ">="]


def default_cases_dir() -> Path:
    """The ``validation/`` folder at the repository root (next to ``src/``)."""
    import sawdrift

    return Path(sawdrift.__file__).resolve().parents[2] / "validation"


# -- the case API ------------------------------------------------------------------------------


@dataclass
class CaseResult:
    """The outcome of one case (for one model).

    A case's ``run`` fills the measured part (normally through :meth:`Case.result`); the harness
    fills the identity and the status.

    Attributes
    ----------
    value
        The measured metric (an error, a count, a ratio), NaN if it could not be measured.
    tolerance
        The bound the value is compared with.
    passed
        True if the fact holds: ``value`` within ``tolerance`` and every side condition met.
    message
        One or two sentences: what was measured, the numbers behind the value.
    figure
        Optional matplotlib ``Figure`` or PNG bytes (the harness converts and closes it).
    compare
        ``"<="`` (pass if value <= tolerance) or ``">="``.
    details
        Extra JSON-ready numbers written to ``results.json``.
    case, group, title, model
        Identity of the case (filled by the harness).
    status
        ``"pass"``, ``"fail"``, ``"expected deviation"`` or ``"error"`` (filled by the harness).
    expected_deviation
        True if the model is marked as not exact by design for this case.
    seconds
        Wall time of the case.
    figure_file
        Path of the written PNG relative to the report folder, if any.
    """

    value: float
    tolerance: float
    passed: bool
    message: str = ""
    figure: Any = field(default=None, repr=False)
    compare: Compare = "<="
    details: dict[str, Any] = field(default_factory=dict)
    case: str = ""
    group: str = ""
    title: str = ""
    model: str | None = None
    status: Status | Literal[""] = ""
    expected_deviation: bool = False
    seconds: float = 0.0
    figure_file: str | None = None

    @property
    def name(self) -> str:
        """``case[model]`` for a model-parametrized case, else ``case``."""
        return f"{self.case}[{self.model}]" if self.model else self.case

    @property
    def failed(self) -> bool:
        """True if this result counts as a failure (``fail`` or ``error``)."""
        return self.status in ("fail", "error")

    def to_json(self) -> dict[str, Any]:
        """JSON-ready summary (non-finite numbers become None)."""
        return {
            "name": self.name,
            "case": self.case,
            "group": self.group,
            "title": self.title,
            "model": self.model,
            "status": self.status,
            "passed": self.passed,
            "expected_deviation": self.expected_deviation,
            "value": _finite(self.value),
            "compare": self.compare,
            "tolerance": _finite(self.tolerance),
            "message": self.message,
            "seconds": round(self.seconds, 4),
            "figure": self.figure_file,
            "details": _jsonable(self.details),
        }


@dataclass(frozen=True)
class Case:
    """Declaration of one validation case (the ``CASE`` of a case file).

    Parameters
    ----------
    name
        Short identifier, unique in the cases folder (e.g. ``"cm_monotonic"``).
    group
        One of :data:`GROUPS` (unknown groups are reported last).
    title
        The fact asserted, in one sentence, with its oracle.
    tolerance
        Bound on the case's value; see ``compare``.
    quick
        True if the case belongs to the ``--quick`` subset (CI).
    models
        Run once per model name, calling ``run(model=...)``; empty for a model-free case.
    model_tolerance
        Per-model tolerances overriding ``tolerance`` (e.g. a discretized model).
    expected_deviation
        True, or the model names, for which the fact does not hold by design: a miss is reported
        as an expected deviation with its value, not as a failure.
    compare
        ``"<="``: pass if value <= tolerance; ``">="``: pass if value >= tolerance.
    """

    name: str
    group: str
    title: str
    tolerance: float
    quick: bool = False
    models: tuple[str, ...] = ()
    model_tolerance: Mapping[str, float] = field(default_factory=dict)
    expected_deviation: bool | tuple[str, ...] = False
    compare: Compare = "<="

    def tolerance_for(self, model: str | None) -> float:
        """The tolerance that applies to ``model``."""
        if model is not None and model in self.model_tolerance:
            return float(self.model_tolerance[model])
        return float(self.tolerance)

    def deviation_expected(self, model: str | None) -> bool:
        """True if ``model`` is marked as not exact by design for this case."""
        if isinstance(self.expected_deviation, bool):
            return self.expected_deviation
        return model is not None and model in self.expected_deviation

    def within(self, value: float, model: str | None = None) -> bool:
        """True if ``value`` satisfies the tolerance for ``model`` (NaN never does)."""
        tol = self.tolerance_for(model)
        if math.isnan(value):
            return False
        return value <= tol if self.compare == "<=" else value >= tol

    def result(
        self,
        value: float,
        *,
        model: str | None = None,
        message: str = "",
        figure: Any = None,
        require: bool = True,
        details: Mapping[str, Any] | None = None,
    ) -> CaseResult:
        """Build the :class:`CaseResult`: passed = value within tolerance and ``require``.

        Parameters
        ----------
        value
            The measured metric.
        model
            The model this result is for (selects the tolerance).
        message
            What was measured.
        figure
            Optional matplotlib figure or PNG bytes.
        require
            Side conditions of the fact (all must hold), e.g. "contact is kept at Gz = 0.98".
        details
            Extra numbers for ``results.json``.
        """
        value = float(value)
        return CaseResult(
            value=value,
            tolerance=self.tolerance_for(model),
            passed=bool(require) and self.within(value, model),
            message=message,
            figure=figure,
            compare=self.compare,
            details=dict(details or {}),
        )


@dataclass
class LoadedCase:
    """A case file after import: its declaration and its run function (or the import error)."""

    path: Path
    case: Case
    run: Callable[..., CaseResult] | None
    error: str | None = None


@dataclass
class ValidationReport:
    """All results of one :func:`validate` call.

    Attributes
    ----------
    results
        One :class:`CaseResult` per (case, model), in report order.
    out
        The report folder.
    quick
        True for the ``--quick`` subset.
    seconds
        Total wall time.
    """

    results: list[CaseResult] = field(repr=False)
    out: Path
    quick: bool
    seconds: float

    @property
    def passed(self) -> bool:
        """True if at least one case ran and none failed or errored (expected deviations do not count)."""
        return bool(self.results) and not any(r.failed for r in self.results)

    def count(self, status: Status) -> int:
        """Number of results with ``status``."""
        return sum(r.status == status for r in self.results)

    def get(self, name: str) -> CaseResult:
        """The result called ``name`` (``case`` or ``case[model]``)."""
        for r in self.results:
            if r.name == name:
                return r
        raise KeyError(name)

    def summary(self) -> str:
        """One line: N passed, M failed, K expected deviations (and errors among the failures)."""
        n_err = self.count("error")
        failed = self.count("fail") + n_err
        text = (
            f"{'PASS' if self.passed else 'FAIL'}: {self.count('pass')} passed, {failed} failed, "
            f"{self.count('expected deviation')} expected deviations"
        )
        if n_err:
            text += f" ({n_err} errors counted as failed)"
        return text + f", {self.seconds:.1f} s" + (" (quick)" if self.quick else "")

    def summary_line(self) -> str:
        """Same as :meth:`summary` (the line the CLI prints)."""
        return self.summary()

    def __str__(self) -> str:
        return self.summary()


# -- discovery and running ----------------------------------------------------------------------


def load_cases(cases_dir: Path | None = None) -> list[LoadedCase]:
    """Import every ``*.py`` in ``cases_dir`` (files starting with ``_`` are skipped).

    A file that fails to import, or defines no valid ``CASE``/``run``, becomes a case with an
    ``error`` (named after the file) instead of stopping the discovery.
    """
    cases_dir = Path(cases_dir) if cases_dir is not None else default_cases_dir()
    if not cases_dir.is_dir():
        from ..errors import SawdriftError

        raise SawdriftError(f"validation cases folder {str(cases_dir)!r} does not exist")
    loaded: list[LoadedCase] = []
    for path in sorted(cases_dir.glob("*.py")):
        if path.name.startswith("_"):
            continue
        fallback = Case(name=path.stem, group="?", title=f"case file {path.name}", tolerance=math.nan)
        try:
            spec = importlib.util.spec_from_file_location(f"sawdrift_validation_cases.{path.stem}", path)
            assert spec is not None and spec.loader is not None
            module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
            case = getattr(module, "CASE", None)
            run = getattr(module, "run", None)
            if not isinstance(case, Case) or not callable(run):
                raise TypeError("a case file must define CASE = Case(...) and a run() function")
            loaded.append(LoadedCase(path, case, run))
        except Exception as exc:  # noqa: BLE001 - a broken case file is reported, not fatal
            loaded.append(LoadedCase(path, fallback, None, _one_line(exc)))
    names = [lc.case.name for lc in loaded]
    for lc in loaded:
        if names.count(lc.case.name) > 1 and lc.error is None:
            lc.error = f"case name {lc.case.name!r} is used by more than one file"
    group_order = {g: i for i, g in enumerate(GROUPS)}
    loaded.sort(key=lambda lc: (group_order.get(lc.case.group, len(GROUPS)), lc.path.name))
    return loaded


def run_case(loaded: LoadedCase, model: str | None = None, quick: bool = False) -> CaseResult:
    """Run one case (for one model) and return its result with identity and status filled in.

    Never raises: an exception inside the case, an import error, or a model that is not
    registered becomes ``status = "error"``.
    """
    from ..contact.registry import registry

    case = loaded.case
    t0 = time.perf_counter()
    result: CaseResult
    try:
        if loaded.error is not None or loaded.run is None:
            raise _CaseError(loaded.error or "case has no run function")
        if model is not None and model not in registry.models:
            why = registry.failed.get(model)
            raise _CaseError(
                f"model {model!r} is not available" + (f" (plugin failed to load: {why})" if why else "")
                + f"; registered: {', '.join(registry.names()) or 'none'}"
            )
        params = inspect.signature(loaded.run).parameters
        kwargs: dict[str, Any] = {}
        if model is not None:
            kwargs["model"] = model
        if "quick" in params:
            kwargs["quick"] = quick
        result = loaded.run(**kwargs)
        if not isinstance(result, CaseResult):
            raise _CaseError(f"run() returned {type(result).__name__}, not a CaseResult")
        status: Status
        if result.passed:
            status = "pass"
        elif case.deviation_expected(model):
            status = "expected deviation"
        else:
            status = "fail"
    except Exception as exc:  # noqa: BLE001 - reported as an error, the other cases go on
        detail = str(exc) if isinstance(exc, _CaseError) else _one_line(exc)
        tb = "" if isinstance(exc, _CaseError) else traceback.format_exc(limit=-3)
        result = CaseResult(value=math.nan, tolerance=case.tolerance_for(model), passed=False,
                            message=f"error: {detail}", compare=case.compare,
                            details={"traceback": tb} if tb else {})
        status = "error"
    result.case, result.group, result.title, result.model = case.name, case.group, case.title, model
    result.status = status
    result.expected_deviation = case.deviation_expected(model)
    if status == "pass" and result.expected_deviation:
        result.message += " (a deviation is expected by design but stayed within the tolerance)"
    result.seconds = time.perf_counter() - t0
    return result


class _CaseError(Exception):
    """A case could not run (import error, missing model); reported without a traceback."""


def validate(
    out: Path,
    quick: bool = False,
    cases_dir: Path | None = None,
    progress: bool = True,
    *,
    models: Sequence[str] | None = None,
    only: Sequence[str] | None = None,
) -> ValidationReport:
    """Run the validation cases and write ``out/index.html``, ``out/results.json`` and figures.

    Parameters
    ----------
    out
        Report folder (created if needed).
    quick
        Run only the cases marked ``quick`` (the CI subset).
    cases_dir
        Folder of case files; default :func:`default_cases_dir`.
    progress
        Print one line per finished case on stderr.
    models
        Run the model-parametrized cases for these models instead of each case's own list
        (e.g. a model registered at run time); model-free cases are unaffected.
    only
        Keep only cases whose name or group matches one of these ``fnmatch`` patterns.

    Returns
    -------
    ValidationReport
        ``.passed`` is False if any case failed or errored, or if no case was selected.

    Raises
    ------
    SawdriftError
        If ``cases_dir`` does not exist.
    """
    t0 = time.perf_counter()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    clear_shared()
    loaded = load_cases(cases_dir)
    selected = [
        lc for lc in loaded
        if (not quick or lc.case.quick or lc.error is not None)
        and (only is None or any(fnmatch.fnmatch(lc.case.name, p) or fnmatch.fnmatch(lc.case.group, p)
                                 for p in only))
    ]
    jobs: list[tuple[LoadedCase, str | None]] = []
    for lc in selected:
        names = (list(models) if models is not None else list(lc.case.models)) if lc.case.models else [None]
        jobs.extend((lc, m) for m in names)
    results: list[CaseResult] = []
    for i, (lc, model) in enumerate(jobs, 1):
        res = run_case(lc, model, quick)
        results.append(res)
        if progress:
            label = {"pass": "PASS", "fail": "FAIL", "expected deviation": "DEV ", "error": "ERR "}
            print(f"[{i:>3}/{len(jobs)}] {label[res.status]} {res.name:<42} "
                  f"{_fmt(res.value):>10} {res.compare} {_fmt(res.tolerance):<9} ({res.seconds:.1f} s)",
                  file=sys.stderr, flush=True)
    clear_shared()
    report = ValidationReport(results, out, quick, time.perf_counter() - t0)
    _write_figures(report)
    write_json(report, out / "results.json")
    write_html(report, out / "index.html")
    if progress:
        print(report.summary(), file=sys.stderr, flush=True)
    return report


# -- small helpers -----------------------------------------------------------------------------


def _fmt(value: float) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "n/a"
    if value == 0:
        return "0"
    if isinstance(value, int) or (float(value).is_integer() and abs(value) < 1e6):
        return f"{int(value)}"
    return f"{value:.3g}"


def _finite(value: float) -> float | None:
    return float(value) if value is not None and math.isfinite(value) else None


def _jsonable(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _jsonable(obj.tolist())
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, bool | int | str) or obj is None:
        return obj
    return str(obj)


def _one_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0] if text else ''}"


def _environment() -> dict[str, str]:
    import numba

    import sawdrift

    return {
        "sawdrift": sawdrift.__version__,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "numba": numba.__version__,
        "platform": platform.platform(),
        "date": datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
    }


# the case files' helpers and the report writers live in their own modules; re-exported here so
# that a case file needs one import
from .validation_cases import (  # noqa: E402, F401
    DIAGRAM_GRID,
    amplitude_for_force_ratio,
    cattaneo_mindlin,
    clear_shared,
    heavy_sliding_v,
    loop_area,
    masing_unloading,
    mindlin_loop,
    point_prediction,
    point_scene,
    prescribed,
    regime_class,
    regime_table,
    shared,
)
from .validation_html import _write_figures, figure_png, write_html, write_json  # noqa: E402, F401

__all__ = [
    "COMPLIANT_MODELS",
    "DIAGRAM_GRID",
    "DIAGRAM_MODELS",
    "GROUPS",
    "Case",
    "CaseResult",
    "LoadedCase",
    "ValidationReport",
    "amplitude_for_force_ratio",
    "cattaneo_mindlin",
    "clear_shared",
    "default_cases_dir",
    "figure_png",
    "heavy_sliding_v",
    "load_cases",
    "loop_area",
    "masing_unloading",
    "mindlin_loop",
    "point_prediction",
    "prescribed",
    "point_scene",
    "regime_class",
    "regime_table",
    "run_case",
    "shared",
    "validate",
    "write_html",
    "write_json",
]
