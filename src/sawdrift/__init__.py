"""sawdrift: frictional contact models compared on a particle driven by a Rayleigh wave.

The public API; the CLI uses nothing else. Names are imported on first use, so that
``import sawdrift`` (and ``sawdrift --help``) does not pay for numba, pandas or matplotlib, nor
for the package metadata (``__version__``) or pluggy (``hookimpl``) before they are asked for.

The package follows the pipeline::

    scene/     Scene (normalized), profiles, the Rayleigh ratio
    contact/   the contact-model interface, committed histories, the plugin registry,
               a Scene bound to its model (bind, model_for)
    dynamics/  wave kinematics, one integration scheme per module, the runner
    result/    Result, evidence, regimes
    study/     sweeps and their resumable tables
    report/    drawing only: phase diagrams, comparisons, the explorer page, figures
    bench/     work-precision study and speed targets (sawdrift bench)
    validation/  the validation harness (sawdrift validate); its cases ship as validation.cases
"""

from __future__ import annotations

import importlib
from typing import Any

from .errors import ModelNotFoundError, NonFiniteStateError, PluginError, SawdriftError, SceneError

#: public name -> module (relative to the package) that defines it
_LAZY: dict[str, str] = {
    "__version__": "_version",
    "hookimpl": "hookspecs",
    "Capabilities": "contact.base",
    "ContactHistory": "contact.history",
    "ContactModel": "contact.base",
    "KernelPair": "contact.base",
    "NoParams": "contact.base",
    "Profile": "scene.profiles",
    "rayleigh_ratio": "scene.rayleigh",
    "rayleigh_speed_ratio": "scene.rayleigh",
    "theta": "scene.rayleigh",
    "REGIMES": "result.regimes",
    "classify": "result.regimes",
    "get_model": "contact.registry",
    "registry": "contact.registry",
    "bind": "contact.binding",
    "model_for": "contact.binding",
    "SUMMARY_FIELDS": "result.result",
    "Result": "result.result",
    "Assembly": "dynamics.assembly",
    "assemble": "dynamics.assembly",
    "explain": "dynamics.assembly",
    "prescribed_history": "dynamics.prescribed",
    "run": "result.runner",
    "Effects": "scene.schema",
    "Impact": "scene.schema",
    "Material": "scene.schema",
    "Numerics": "scene.schema",
    "Particle": "scene.schema",
    "Prescribed": "scene.schema",
    "Scene": "scene.schema",
    "Wave": "scene.schema",
    "parse_axis": "study.sweep",
    "sweep": "study.sweep",
    "code_hash": "study.provenance",
    "plot_trajectory": "report.plots",
    "check_model": "contact.conformance",
    "load_grid": "study.export",
    "to_dataset": "study.export",
    "write_grid": "study.export",
    "adaptive_sweep": "study.adaptive",
    "plot_phase_diagram": "report.diagrams",
    "plot_drift_map": "report.diagrams",
    "plot_compare": "report.compare_plot",
    "demo": "report.demo",
    "write_explorer": "report.explore",
    "bifurcation": "study.bifurcation",
    "plot_bifurcation": "report.bifurcation_plot",
    "drift_field": "study.field",
    "direct_run": "study.field_direct",
    "rayleigh_wavelength": "scene.device",
    "plot_field": "report.field_plot",
    "load_curve": "study.load_curve",
    "LoadCurve": "study.load_curve",
    "plot_load_curve": "report.load_curve_plot",
    "validate": "validation",
    "work_precision": "bench",
    "bench_speed": "bench:speed",
}
_SUBPACKAGES = ("scene", "contact", "dynamics", "result", "study", "report", "bench", "validation",
                "analytic", "testing")


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        module, _, attr = _LAZY[name].partition(":")
        value = getattr(importlib.import_module(f".{module}", __name__), attr or name)
        globals()[name] = value
        return value
    if name == "regimes":
        return importlib.import_module(".result.regimes", __name__)
    if name in _SUBPACKAGES:
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'sawdrift' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY) | set(_SUBPACKAGES))


__all__ = [
    "ModelNotFoundError",
    "NonFiniteStateError",
    "PluginError",
    "SawdriftError",
    "SceneError",
    "regimes",
    *_LAZY,
]
