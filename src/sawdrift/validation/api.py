"""The validation case API: a case declares one fact (Case) and returns its result (CaseResult)."""

from __future__ import annotations

import math
import platform
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any, Literal

import numpy as np

from .._version import __version__
from ..errors import SawdriftError

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
    "steady": "9. Steady drift: the settle method and the settled flag against brute-force runs",
    "bifurcation": "10. Bifurcation diagrams: located thresholds of the bouncing ball, step convergence",
    "loads": "11. Loads, inclines and restitution",
    "fields": "12. Two-wave drift fields: traps, phase shifts, direct runs, moving traps",
    "lammps": "13. LAMMPS: the same law in a DEM engine",
    "adhesion": "14. Adhesion: DMT and JKR against their closed forms, removal thresholds",
}

#: The compliant models the oracle cases run for by default.
COMPLIANT_MODELS: tuple[str, ...] = ("mmd", "mdr", "jaeger", "hertz_mindlin_dem")

#: The models drawn in the regime diagrams.
DIAGRAM_MODELS: tuple[str, ...] = ("material_point", *COMPLIANT_MODELS)

#: Friction coefficient and Poisson's ratio of the paper's figures (docs/physics.md).
MU = 0.1
NU = 0.3

Status = Literal["pass", "fail", "expected deviation", "skipped", "error"]
Compare = Literal["<=", ">="]


def default_cases_dir() -> Path:
    """The folder of the cases shipped with sawdrift: the package ``sawdrift.validation.cases``.

    Found through ``importlib.resources``: in an installed wheel it is the package's folder in
    site-packages; in a checkout (``pip install -e .``) it is the top-level ``validation/``, which
    pyproject maps to that package.
    """
    from importlib.resources import files

    try:
        root = files("sawdrift.validation.cases")
    except ModuleNotFoundError:
        raise SawdriftError("the validation cases (package sawdrift.validation.cases) are not installed: "
                            "reinstall sawdrift, or give a folder of cases with --cases") from None
    if not isinstance(root, Path):  # e.g. imported from a zip archive
        raise SawdriftError(f"the validation cases are not a folder ({root}): give one with --cases")
    return root

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
        ``"pass"``, ``"fail"``, ``"expected deviation"``, ``"skipped"`` or ``"error"`` (filled by
        the harness).
    expected_deviation
        True if the model is marked as not exact by design for this case.
    deviation_reason
        Why the model is not exact by design (one line, from :attr:`Case.deviation_reason`);
        empty if no deviation is expected.
    seconds
        Wall time of the case.
    figure_file
        Path of the written PNG relative to the report folder, if any.
    skip_reason
        Why the case could not run here (set by :meth:`Case.skip`): the harness reports it as
        ``skipped``, neither a pass nor a failure.
    deviation_matches
        For a model that deviates by design: whether it follows the closed form of its own
        documented deviation (the DEM spring's straight line to its cap, say). False fails the
        case: an expected deviation is that deviation, not any value at all. None: not checked.
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
    deviation_reason: str = ""
    seconds: float = 0.0
    figure_file: str | None = None
    skip_reason: str | None = None
    deviation_matches: bool | None = None

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
            "deviation_reason": self.deviation_reason if self.expected_deviation else "",
            "value": _finite(self.value),
            "compare": self.compare,
            "tolerance": _finite(self.tolerance),
            "message": self.message,
            "seconds": round(self.seconds, 4),
            "figure": self.figure_file,
            "skip_reason": self.skip_reason,
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
    deviation_reason
        Why the fact does not hold by design, in one line: one text for every deviating model,
        or a mapping model name -> text. Shown with each expected deviation in the report.
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
    deviation_reason: str | Mapping[str, str] = ""
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

    def reason_for(self, model: str | None) -> str:
        """The one-line reason why ``model`` deviates by design ("" if none is expected or given)."""
        if not self.deviation_expected(model):
            return ""
        reason = self.deviation_reason
        if not isinstance(reason, str):
            reason = reason.get(model, "") if model is not None else ""
        return " ".join(reason.split())

    def within(self, value: float, model: str | None = None) -> bool:
        """True if ``value`` satisfies the tolerance for ``model`` (NaN never does)."""
        tol = self.tolerance_for(model)
        if math.isnan(value):
            return False
        return value <= tol if self.compare == "<=" else value >= tol

    def skip(self, reason: str, *, model: str | None = None) -> CaseResult:
        """A :class:`CaseResult` saying the case cannot run here, and why (e.g. a missing extra).

        The harness reports it as ``skipped``: counted and listed with ``reason``, neither a pass
        nor a failure. ``reason`` is one line.
        """
        reason = " ".join(str(reason).split())
        return CaseResult(value=math.nan, tolerance=self.tolerance_for(model), passed=False,
                          message=f"skipped: {reason}", compare=self.compare, skip_reason=reason)

    def result(
        self,
        value: float,
        *,
        model: str | None = None,
        message: str = "",
        figure: Any = None,
        require: bool = True,
        details: Mapping[str, Any] | None = None,
        deviation_matches: bool | None = None,
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
        deviation_matches
            For a model that deviates by design: whether it follows its documented deviation's
            closed form (:attr:`CaseResult.deviation_matches`).
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
            deviation_reason=self.reason_for(model),
            deviation_matches=deviation_matches,
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
        """True if at least one case was selected and none failed or errored.

        Expected deviations and skipped cases do not count either way.
        """
        return bool(self.results) and not any(r.failed for r in self.results)

    @property
    def skipped(self) -> list[CaseResult]:
        """The skipped results, in report order (each with its ``skip_reason``)."""
        return [r for r in self.results if r.status == "skipped"]

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
        """One line: N passed, M failed, K expected deviations, S skipped (named), the time.

        Errors are counted among the failures; the skipped cases are named (their reasons are in
        the report).
        """
        n_err = self.count("error")
        failed = self.count("fail") + n_err
        text = (
            f"{'PASS' if self.passed else 'FAIL'}: {self.count('pass')} passed, {failed} failed, "
            f"{self.count('expected deviation')} expected deviations"
        )
        if n_err:
            text += f" ({n_err} errors counted as failed)"
        skipped = self.skipped
        if skipped:
            text += f", {len(skipped)} skipped ({', '.join(r.name for r in skipped)})"
        return text + f", {self.seconds:.1f} s" + (" (quick)" if self.quick else "")

    def summary_line(self) -> str:
        """Same as :meth:`summary` (the line the CLI prints)."""
        return self.summary()

    def __str__(self) -> str:
        return self.summary()


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

    return {
        "sawdrift": __version__,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "numba": numba.__version__,
        "platform": platform.platform(),
        "date": datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
    }
