"""Validation harness: run the cases of ``validation/`` and write an HTML and JSON report.

A *case* is one Python file in the cases folder: by default the cases shipped with sawdrift,
the package ``sawdrift.validation.cases`` (the repository's top-level ``validation/``, mapped by
pyproject; :func:`default_cases_dir`). It asserts one physical or numerical fact against a
closed-form oracle or an independent reference, with a stated tolerance, and defines

* ``CASE``: a :class:`Case` (name, group, statement, tolerance, whether it is in the quick subset,
  the models it is run for, and which of them deviate by design);
* ``run()`` (or ``run(model)`` when ``CASE.models`` is not empty; optionally a ``quick`` keyword)
  returning a :class:`CaseResult`, normally built with :meth:`Case.result`.

:func:`validate` discovers the cases, runs them (once per model for model-parametrized cases),
and writes ``OUT/index.html`` (summary, PASS/FAIL table per group, figures inline as base64 PNG),
``OUT/results.json`` and ``OUT/figures/*.png``. A case that raises, or whose model is not
registered, is reported as an *error* and counts as a failure; it never stops the other cases.
A case whose model is marked as not exact by design reports its deviation as an *expected
deviation*: shown with its value, not counted as a failure. A case that cannot run here (an
optional extra such as LAMMPS is missing) returns :meth:`Case.skip` with the reason: *skipped*,
counted and listed with its reason, neither a pass nor a failure.

The module also holds the closed-form oracles the cases share (docs/physics.md).
"""

from __future__ import annotations

import fnmatch
import importlib.util
import inspect
import math
import sys
import time
import traceback
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..errors import SawdriftError
from .api import (  # noqa: F401 - the case API, re-exported for case files
    COMPLIANT_MODELS,
    DIAGRAM_MODELS,
    GROUPS,
    MU,
    NU,
    Case,
    CaseResult,
    LoadedCase,
    Status,
    ValidationReport,
    _environment,
    _finite,
    _fmt,
    _jsonable,
    _one_line,
    default_cases_dir,
)

# -- discovery and running ----------------------------------------------------------------------


def load_cases(cases_dir: Path | None = None) -> list[LoadedCase]:
    """Import every ``*.py`` in ``cases_dir`` (files starting with ``_`` are skipped).

    A file that fails to import, or defines no valid ``CASE``/``run``, becomes a case with an
    ``error`` (named after the file) instead of stopping the discovery.
    """
    cases_dir = Path(cases_dir) if cases_dir is not None else default_cases_dir()
    if not cases_dir.is_dir():
        # a file was said not to exist
        what = "is a file, not a folder" if cases_dir.exists() else "does not exist"
        raise SawdriftError(f"validation cases folder {str(cases_dir)!r} {what}")
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
    if not loaded:
        raise SawdriftError(f"validation cases folder {str(cases_dir)!r} holds no case files "
                            "(*.py, each with CASE = Case(...) and run())")
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
        if result.skip_reason is not None:
            status = "skipped"
        elif result.passed:
            status = "pass"
        elif case.deviation_expected(model) and result.deviation_matches is not False:
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
    if status == "skipped":
        result.expected_deviation = False
    if status == "fail" and result.deviation_matches is False:
        result.message += " (not even the deviation expected by design: see its closed form)"
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
            label = {"pass": "PASS", "fail": "FAIL", "expected deviation": "DEV ", "skipped": "SKIP",
                     "error": "ERR "}
            print(f"[{i:>3}/{len(jobs)}] {label[res.status]} {res.name:<42} "
                  f"{_fmt(res.value):>10} {res.compare} {_fmt(res.tolerance):<9} ({res.seconds:.1f} s)",
                  file=sys.stderr, flush=True)
    clear_shared()
    report = ValidationReport(results, out, quick, time.perf_counter() - t0)
    _write_figures(report)
    write_json(report, out / "results.json")
    write_html(report, out / "index.html")
    # the summary is the caller's to print (sawdrift validate prints it on stdout: on a terminal
    # it came twice, once here on stderr)
    return report


# the case files' helpers and the report writers live in their own modules; re-exported here so
# that a case file needs one import
from .oracles import (  # noqa: E402, F401
    DEVIATION_TOL,
    DIAGRAM_GRID,
    amplitude_for_force_ratio,
    cattaneo_mindlin,
    clear_shared,
    dem_spring,
    heavy_sliding_v,
    lammps_case,
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
from .page import _write_figures, figure_png, write_html, write_json  # noqa: E402, F401

__all__ = [
    "COMPLIANT_MODELS",
    "DEVIATION_TOL",
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
    "dem_spring",
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
