"""The Scene: one whole experiment, validated and frozen (TOML in and out)."""

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
    build_scene,
    format_validation_error,
    set_dotted,
)

__all__ = [
    "Effects", "Impact", "Material", "Numerics", "Particle", "Prescribed", "Profile", "Scene",
    "Wave", "build_scene", "format_validation_error", "rayleigh_ratio", "rayleigh_speed_ratio",
    "set_dotted", "theta",
]
