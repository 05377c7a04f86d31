"""A free normal impact: the contact from first touch until it is lost again, measured for the
coefficient of restitution and the contact duration (the ``impact`` drive)."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..contact.base import ContactModel
from ..scene.schema import Impact, Scene
from .assembly import Assembly
from .stepper import Stepper

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["ImpactRun", "integrate_impact"]


@dataclass
class ImpactRun:
    """A free normal impact, from first touch until contact is lost (see :func:`integrate_impact`).

    Attributes
    ----------
    stepper
        The integration, one step after the separation (or at the step limit).
    separated
        Whether contact was lost within ``numerics.periods``.
    rebound_ratio
        |v_out / v_in| of the normal velocity (NaN if not separated).
    contact_duration
        Time in contact, in the scene's time unit (NaN if not separated).
    trajectory
        Every step, from first touch.
    wall_time_s
        The integration.
    """

    stepper: Stepper
    separated: bool
    rebound_ratio: float
    contact_duration: float
    trajectory: pd.DataFrame = field(repr=False)
    wall_time_s: float


def integrate_impact(scene: Scene, model: ContactModel, plan: Assembly) -> ImpactRun:
    """A free normal impact: integrate from first touch until contact is lost again."""
    drive = scene.drive
    assert isinstance(drive, Impact)
    t0 = time.perf_counter()
    stepper = Stepper(scene, model, plan, record=True, preload=False)
    stepper.rec_every = 1
    stepper.y[:4] = (0.0, drive.tangential_velocity, 0.0, drive.velocity)
    chunk = max(8, stepper.k_per // 8)
    n_max = int(round(scene.numerics.periods * stepper.k_per))
    separated = False
    while stepper.step < n_max and not separated:
        stepper.advance(chunk)
        separated = bool(stepper.y[2] < 0.0 and stepper.step > 1)
    if separated:
        stepper.advance(1)  # records the first state out of contact (rows are taken before a step)
    tr = stepper.trajectory()
    rebound = float("nan")
    duration = float("nan")
    if separated:
        a = tr["a"].to_numpy()
        k = int(np.nonzero((a[:-1] > 0.0) & (a[1:] <= 0.0))[0][-1])
        w = a[k] / (a[k] - a[k + 1])
        v_out = (1 - w) * tr["vy"].iloc[k] + w * tr["vy"].iloc[k + 1]
        rebound = float(abs(v_out) / drive.velocity)
        duration = float((k + w) * stepper.h)
    return ImpactRun(stepper=stepper, separated=separated, rebound_ratio=rebound,
                     contact_duration=duration, trajectory=tr,
                     wall_time_s=time.perf_counter() - t0)
