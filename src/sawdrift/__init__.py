"""sawdrift: frictional contact models compared on a particle driven by a Rayleigh wave.

The public API; the CLI uses nothing else.
"""

from . import regimes, scene
from .contact import Capabilities, ContactHistory, ContactModel, KernelPair, NoParams
from .errors import ModelNotFoundError, NonFiniteStateError, PluginError, SawdriftError, SceneError
from .hookspecs import hookimpl
from .profiles import Profile
from .rayleigh import rayleigh_ratio, rayleigh_speed_ratio, theta
from .regimes import REGIMES, classify
from .registry import get_model, registry
from .result import SUMMARY_FIELDS, Result
from .runner import Assembly, assemble, explain, prescribed_history, run
from .scene import Effects, Impact, Material, Numerics, Particle, Prescribed, Scene, Wave
from .sweep import parse_axis, sweep

__version__ = "0.1.0"

_LAZY = {"plot_trajectory": "plots"}


def __getattr__(name: str):
    # matplotlib is imported only when a figure is asked for
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module 'sawdrift' has no attribute {name!r}")


__all__ = [
    "Assembly",
    "Impact",
    "assemble",
    "explain",
    "REGIMES",
    "SUMMARY_FIELDS",
    "Capabilities",
    "ContactHistory",
    "ContactModel",
    "Effects",
    "KernelPair",
    "Material",
    "ModelNotFoundError",
    "NoParams",
    "NonFiniteStateError",
    "Numerics",
    "Particle",
    "PluginError",
    "Prescribed",
    "Profile",
    "Result",
    "SawdriftError",
    "Scene",
    "SceneError",
    "Wave",
    "classify",
    "get_model",
    "hookimpl",
    "plot_trajectory",
    "prescribed_history",
    "rayleigh_ratio",
    "rayleigh_speed_ratio",
    "regimes",
    "registry",
    "run",
    "scene",
    "sweep",
    "parse_axis",
    "theta",
]
