"""Air drag: a linear drag force on the particle's centre, relative to still air.

The worked example of docs/architecture.md, "Adding a force": the force's physics is this module
(its value from the scene, its ``--explain`` line, the scenes it refuses, its compiled term), and
the rest is registration (the scene field ``effects.air_drag``, the scheme parameter
``air_drag`` of :data:`~sawdrift.dynamics.adams_bashforth.PRM_NAMES`, one call in the loop).

A drag F = -c_d v on the centre's velocity v (Stokes drag of a sphere in a viscous gas:
c_d = 6 pi eta R), normalized as docs/physics.md normalizes every force (by M g, velocities by
a0 f), adds to the equations of motion

    m*_x x*'' = ... - c x*'          m* y*'' = ... - c y*'          c = c_d a0 f / (M g)

with c = ``effects.air_drag`` (0: off, never computed). Its closed forms, the checks of
``tests/test_air_drag.py``: on a still substrate under a load L > mu the particle slides
(N* = 1, mu T* = mu) towards the terminal velocity x*' = (L - mu)/c, approached as
exp(-c t*/m*); in free flight it falls towards y*' = 1/c. The drag acts on the centre only (no
torque) and on the horizontal inertia m*_x that ``numerics.settle`` may reduce (a force, like the
load: the terminal velocity does not involve the inertia).

Only the compliant scheme carries it: the rigid scheme's closed forms within a step (slip with
N*(t), flight) have no drag term, so a rigid model with air drag is refused.
"""

from __future__ import annotations

from numba import njit

from ..errors import SceneError
from .rolling import JIT

#: the scheme parameter that carries c (adams_bashforth.PRM_NAMES)
PARAM = "air_drag"


def parameter(scene, rigid: bool) -> float:
    """c of the scene (``effects.air_drag``); a rigid model with air drag is an error."""
    c = float(scene.effects.air_drag)
    if c > 0.0 and rigid:
        raise SceneError(f"effects.air_drag = {c:g}: the rigid scheme's closed forms have no drag "
                         f"term; use a compliant model (model {scene.model!r} is rigid)")
    return c


def describe(scene) -> list[str]:
    """The ``--explain`` line of the drag (none when it is off)."""
    c = scene.effects.air_drag
    if c <= 0.0:
        return []
    return [f"air drag c = {c:g} on the centre, relative to still air: m*_x x*'' += -c x*', "
            f"m* y*'' += -c y*' (terminal velocities (L - mu)/c sliding, 1/c falling)"]


@njit(**JIT)
def drag_acceleration(y, c, m_x, m):
    """(x*'', y*'') of the linear drag -c v on the centre: (-c x*'/m*_x, -c y*'/m*)."""
    return -c * y[1] / m_x, -c * y[3] / m
