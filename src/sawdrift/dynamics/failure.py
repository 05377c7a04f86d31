"""Why an integration failed, in one line: a non-finite state (the step too coarse, the scene
beyond what the scheme resolves, or a contact model's non-finite force) or the rigid scheme
falling behind in time."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from ..errors import NonFiniteStateError
from ..scene.parts import FINEST_STEPS
from . import evidence as ev
from . import rigid as rg
from .adams_bashforth import P_MX, P_ORDER

if TYPE_CHECKING:
    from .stepper import Stepper

__all__ = ["failure"]

#: the end of the real stability interval of the Adams-Bashforth step of each order: a decay
#: rate lambda is stable for h lambda up to this (Hairer, Norsett and Wanner, Solving ODE I,
#: section III.3)
STABLE_DAMPING = {1: 2.0, 2: 1.0, 3: 6.0 / 11.0, 4: 0.3}


def failure(stepper: Stepper) -> NonFiniteStateError:
    """One line on why the state of ``stepper`` became non-finite (or the rigid scheme fell
    behind): the state, the time, and what to change (the step, the scene, or the model:
    a force that was not finite at the first step from rest)."""
    k = int(stepper.st[ev.S_BADSTEP])
    m = stepper.scene.particle.m_star
    state = (f"x* = {stepper.y[0]:.6g}, x*' = {stepper.y[1]:.6g}, y* = {stepper.y[2]:.6g}, "
             f"y*' = {stepper.y[3]:.6g}")
    if stepper.st[ev.S_BAD] == ev.BAD_EVENTS:
        return NonFiniteStateError(
            f"the rigid scheme met more than {rg._MAX_EVENTS} events (impacts, lift-offs, "
            f"stick-slip changes) in the step at t* = {k * stepper.h:.6g} ({state}) and would "
            "fall behind in time (an inelastic collapse of bounces); try a larger "
            "--steps-per-period" + ("" if float(stepper.prm[rg.P_RESTITUTION]) < 1.0
                                    else " or a restitution below 1")
        )
    amp = float(getattr(stepper.scene.drive, "amplitude", math.nan))
    model = stepper.scene.model
    check = f"the contact model returned a non-finite force: sawdrift check-model {model}"
    # at the finest step allowed, the scene itself is beyond what the scheme resolves
    hint = (f"at the finest step allowed, 1/{stepper.k_per}: particle.m_star = {m:g} with "
            f"drive.amplitude = {amp:g} is beyond what the scheme resolves; give values "
            "nearer m* 1e-6..1e8, A* below 1e6" if stepper.k_per >= FINEST_STEPS else
            f"the step 1/{stepper.k_per} is likely too coarse for m* = {m:g}; try a larger "
            f"--steps-per-period or a lower Adams-Bashforth order, or {check}")
    drag = float(stepper.scene.effects.air_drag)
    m_drag = min(m, float(stepper.prm[P_MX])) if not stepper.rigid else m
    order = int(stepper.prm[P_ORDER])
    limit = STABLE_DAMPING.get(order, STABLE_DAMPING[4])
    if drag * stepper.h / m_drag > limit:
        # the Adams-Bashforth step of a decay rate c / m* is stable only for h c / m* within
        # its real stability interval (Euler 2, AB2 1, AB3 6/11, AB4 0.3): past it the velocity
        # grows without bound whatever the contact (--air-drag 1e308 blamed the step size)
        hint = (f"effects.air_drag = {drag:g} damps m* = {m_drag:g} by c h / m* = "
                f"{drag * stepper.h / m_drag:.3g} a step of 1/{stepper.k_per}, beyond the "
                f"{limit:.3g} an order-{order} Adams-Bashforth step is stable to: give a smaller "
                "air drag (c a0 f / (M g) of a real particle is far below 1) or more steps per "
                "period")
    elif k == 0:
        # the first step from rest on its static compression: its state is finite, so the
        # force was not (a plugin's NaN force was blamed on the step size)
        hint = f"at the first step from rest, {check}"
    return NonFiniteStateError(f"non-finite state at t* = {k * stepper.h:.6g} (step {k}; "
                               f"{state}): {hint}")
