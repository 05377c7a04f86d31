"""The Scene: one whole experiment, validated and frozen (TOML in and out)."""

from .overrides import DERIVED
from .profiles import Profile
from .rayleigh import rayleigh_ratio, rayleigh_speed_ratio, theta
from .schema import (
    Effects,
    Impact,
    Material,
    Numerics,
    Particle,
    Prescribed,
    Scene,
    Wave,
    apply_overrides,
    build_scene,
    format_validation_error,
    get_dotted,
    set_dotted,
)

__all__ = [
    "DERIVED", "Effects", "Impact", "Material", "Numerics", "Particle", "Prescribed", "Profile",
    "Scene", "Wave", "apply_overrides", "build_scene", "format_validation_error", "get_dotted",
    "rayleigh_ratio", "rayleigh_speed_ratio", "set_dotted", "theta",
]
