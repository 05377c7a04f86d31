"""The contact law a heavy particle's solved orbit drives (:mod:`.separated`), damping included.

The fast parts of the orbit run the contact law alone, with no integration loop around it. Where
the loop adds the scene's normal damping after the contact force (``effects.normal_damping``,
``material.restitution``: :func:`~sawdrift.contact.slot_kernels.damped_contact`), the law they
drive carries that damping in its normal-damping slot, so that they see the loop's (N*, T*).
"""

from __future__ import annotations

from ..contact.history import ContactHistory
from ..contact.scene_damping import damped_law
from . import adams_bashforth as ig
from .stepper import Stepper


def damped_normal(stepper: Stepper) -> bool:
    """Whether the built run damps its normal force: its contact model itself (a normal-damping
    slot, as hertz_tsuji's) or the loop (``effects.normal_damping``, ``material.restitution``).
    The free vertical oscillation then decays, and the steady state is the period-one orbit
    (:mod:`.direct`), not an average over a slow cycle (:mod:`.torus`)."""
    model = getattr(stepper.history, "model", None)
    return getattr(model, "damping", None) is not None or _loop_damping(stepper) is not None


def _loop_damping(stepper: Stepper) -> tuple[float, float, float] | None:
    """(c, C, q) of the normal damping the run's loop adds after the contact force
    (:func:`~sawdrift.contact.slot_kernels.damped_contact`), or None without one."""
    prm = stepper.prm
    viscous, restitution = float(prm[ig.P_DAMP]), float(prm[ig.P_REST])
    if not (viscous > 0.0 or restitution > 0.0):
        return None
    return viscous, restitution, 0.5 * (float(prm[ig.P_P]) - 1.0)


def solver_history(stepper: Stepper) -> ContactHistory:
    """The contact history the fast parts drive: the run's, and where its loop adds the scene's
    normal damping after the contact force, the same law with that damping in its slot
    (:func:`~sawdrift.contact.scene_damping.damped_law`): (N*, T*) as the loop has them, the
    damped N* and T* capped by it. Left out, a damped heavy hop was solved 1e-3 to 8e-3 off in
    drift ratio (mmd m* = 100, A* = 1, mu = 0.2, c = 0.1: 0.49525 against 0.49594)."""
    assert stepper.history is not None
    damping = _loop_damping(stepper)
    law = None if damping is None else damped_law(stepper.history.model, *damping, always=True)
    if law is None:
        return stepper.history.copy()
    return ContactHistory(law, stepper.history.engine)
