"""What a drive is: the substrate's motion at time t* and position x*, as one part of a run.

A drive is one module: a :class:`Drive` subclass (its scene kind, its named parameters, how the
drift ratio is scaled, its lines of ``--explain``) and two compiled functions the integrators
call, bound in per drive when the loops are generated (:mod:`sawdrift.codegen`)::

    surface(t, x, dp)     -> (u_x, u_x', u_y, u_y')
    kinematics(t, x, dp)  -> (u_x, u_x', u_x'', u_y, u_y', u_y'')

``t`` is t*, ``x`` the particle's position x* (for drives that vary along the surface; a drive
of one local orbit ignores it) and ``dp`` the float64 vector of the drive's parameters, in the
order of :attr:`Drive.names`. y* points into the substrate (docs/physics.md). The scene's
``effects.horizontal_wave`` and ``effects.vertical_wave`` switch the components off in every
drive (they arrive as parameters ``horizontal`` and ``vertical``, 1 or 0).
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np


class Drive:
    """Base class of a drive (see the module docstring)."""

    #: the scene's ``drive.kind`` this drive runs
    kind: ClassVar[str]
    #: importable module holding the compiled ``surface`` and ``kinematics``
    module: ClassVar[str]
    #: names of the entries of the parameter vector ``dp``, in order
    names: ClassVar[tuple[str, ...]]

    def parameters(self, scene: Any) -> dict[str, float]:
        """The drive's parameters for ``scene``, by name (all of :attr:`names`)."""
        raise NotImplementedError

    def pack(self, scene: Any) -> np.ndarray:
        """The parameter vector ``dp`` for ``scene``."""
        values = self.parameters(scene)
        return np.array([float(values[n]) for n in self.names], dtype=np.float64)

    def for_steps(self, dp: np.ndarray, k_per: int) -> np.ndarray:
        """The parameter vector the loops get at ``k_per`` steps per period: ``dp`` itself, or
        ``dp`` followed by what the drive's functions can look up at the steps instead of
        computing (the travelling wave's phase table)."""
        return dp

    def functions(self) -> tuple[Any, Any]:
        """The compiled ``(surface, kinematics)`` of this drive."""
        import importlib

        mod = importlib.import_module(self.module)
        return mod.surface, mod.kinematics

    def ramp_periods(self, scene: Any) -> float:
        """Length of the start-up ramp in periods (0: none)."""
        return 0.0

    def horizontal_speed(self, scene: Any) -> float:
        """Amplitude of the horizontal surface velocity u_x' (the drift ratio's scale; 0: none)."""
        return 0.0

    def vertical_amplitude(self, scene: Any) -> float:
        """Amplitude of u_y (sets the natural size of the vertical state)."""
        return 0.0

    def surface_bound(self, scene: Any) -> float:
        """A bound U of |u_y| over every t* and x*, ramp included, or -1 where the drive gives
        none: a free flight whose height stays below -U cannot land, and goes over those steps
        at once (:func:`~sawdrift.dynamics.flight.flight_skip`). A drive of a plugin that does
        not give one keeps every flight step."""
        return -1.0

    def state_scale(self, scene: Any) -> np.ndarray:
        """Natural sizes of the stroboscopic state (x*', y*, y*')."""
        amp = self.vertical_amplitude(scene)
        return np.array([max(self.horizontal_speed(scene), 2 * math.pi * 1e-12), 1.0 + amp,
                         2 * math.pi * (1.0 + amp)])

    def describe(self, scene: Any) -> list[str]:
        """The drive's lines of ``--explain``."""
        return []

    def orbit_name(self, scene: Any) -> str:
        """A short name of the local orbit for results ("prograde", "retrograde", ...)."""
        return ""
