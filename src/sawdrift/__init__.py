"""sawdrift: frictional contact models compared on a particle driven by a Rayleigh wave."""

from .contact import Capabilities, ContactHistory, ContactModel, KernelPair, NoParams
from .errors import SawdriftError, SceneError
from .hookspecs import hookimpl
from .profiles import Profile
from .rayleigh import rayleigh_ratio, rayleigh_speed_ratio, theta
from .registry import get_model, registry

__version__ = "0.1.0"

__all__ = [
    "Capabilities",
    "ContactHistory",
    "ContactModel",
    "KernelPair",
    "NoParams",
    "Profile",
    "SawdriftError",
    "SceneError",
    "get_model",
    "hookimpl",
    "rayleigh_ratio",
    "rayleigh_speed_ratio",
    "registry",
    "theta",
]
