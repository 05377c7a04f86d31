"""A free normal impact: the contact from first touch until it is lost again, measured for the
coefficient of restitution and the contact duration (the ``impact`` drive)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..contact.base import ContactModel
from ..scene.schema import Impact, Scene
from .assembly import Assembly
from .impact_scale import impact_duration
from .records import MAX_TRAJECTORY_ROWS
from .stepper import Stepper

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["IMPACT_DURATIONS", "MAX_IMPACT_STEPS", "ImpactRun", "impact_steps",
           "integrate_impact"]


@dataclass
class ImpactRun:
    """A free normal impact, from first touch until contact is lost (see :func:`integrate_impact`).

    Attributes
    ----------
    stepper
        The integration, one step after the separation (or at the step limit).
    separated
        Whether contact was lost within :func:`impact_steps`.
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


#: contact times (:func:`~.impact_scale.impact_duration`) a default impact run lasts at most: a
#: contact that outlasts them holds the particle (damped, it came to rest under gravity)
IMPACT_DURATIONS = 4.0

#: most steps of an impact run, whose trajectory keeps every step: with the row after the
#: separation, the most rows a trajectory keeps before it is thinned (2e6 let 1.6e6-step
#: impacts be thinned, halving their contact time as rows counted in steps; 92 MB)
MAX_IMPACT_STEPS = MAX_TRAJECTORY_ROWS - 1


def impact_steps(scene: Scene, k_per: int) -> int:
    """Steps an impact run may take before contact is lost: ``numerics.periods``, or
    :data:`IMPACT_DURATIONS` estimated contact times where that is longer (the default 60
    periods cut off a heavy particle's contact of 83: m* = 1e4, v = 10 ended with no rebound
    ratio and no word why; a length told apart from the default by its value ignored a 60 given
    on purpose), within :data:`MAX_IMPACT_STEPS`."""
    periods = max(scene.numerics.periods, IMPACT_DURATIONS * impact_duration(scene))
    return max(1, min(MAX_IMPACT_STEPS, int(math.ceil(periods * k_per))))


def integrate_impact(scene: Scene, model: ContactModel, plan: Assembly) -> ImpactRun:
    """A free normal impact: integrate from first touch until contact is lost again, within
    :func:`impact_steps`."""
    drive = scene.drive
    assert isinstance(drive, Impact)
    t0 = time.perf_counter()
    stepper = Stepper(scene, model, plan, record=True, preload=False)
    stepper.rec_every = 1
    stepper.y[:4] = (0.0, drive.tangential_velocity, 0.0, drive.velocity)
    chunk = max(8, stepper.k_per // 8)
    n_max = impact_steps(scene, stepper.k_per)
    separated = False
    while stepper.step < n_max and not separated:
        stepper.advance(min(chunk, n_max - stepper.step))
        separated = bool(stepper.y[2] < 0.0 and stepper.step > 1)
    if separated:
        stepper.advance(1)  # records the first state out of contact (rows are taken before a step)
    tr = stepper.trajectory()
    rebound = math.nan
    duration = math.nan
    if separated:
        a = tr["a"].to_numpy()
        k = int(np.nonzero((a[:-1] > 0.0) & (a[1:] <= 0.0))[0][-1])
        w = a[k] / (a[k] - a[k + 1])
        v_out = (1 - w) * tr["vy"].iloc[k] + w * tr["vy"].iloc[k + 1]
        rebound = float(abs(v_out) / drive.velocity)
        t = tr["t"].to_numpy()  # the rows' own times, whatever the recording interval
        duration = float(t[k] + w * (t[k + 1] - t[k]))
    return ImpactRun(stepper=stepper, separated=separated, rebound_ratio=rebound,
                     contact_duration=duration, trajectory=tr,
                     wall_time_s=time.perf_counter() - t0)
