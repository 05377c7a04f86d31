"""The scales of a free impact (``drive.kind = "impact"``): its deepest compression and contact
time, which set the step and the length of an impact run."""

from __future__ import annotations

import math

from ..scene.schema import Impact, Scene

#: steps a free impact's contact is resolved with (:func:`~.assembly.steps_per_period`): the rebound ratio
#: of a damped Hertz contact (mmd, e = 0.5, m* = 1, v = 1000) is off by 3.4e-3 at 129 steps in
#: contact, 2.4e-4 at 1024 per period (about 250 in contact), 4e-5 at about 1000
STEPS_PER_IMPACT = 2000


def impact_compression(scene: Scene) -> float:
    """The deepest compression a* of a free impact, from the energy balance with gravity,
    a^(p+1) / (p+1) - a = m* v^2 / 2 (undamped), by fixed-point iteration."""
    drive = scene.drive
    assert isinstance(drive, Impact)
    p = scene.particle.profile.p
    energy = 0.5 * scene.particle.m_star * drive.velocity**2
    a_ref = 1.0
    for _ in range(60):
        a_ref = ((p + 1.0) * (energy + a_ref)) ** (1.0 / (p + 1.0))
    return a_ref


def impact_duration(scene: Scene, a_max: float | None = None) -> float:
    """An estimate of a free impact's contact time in t*: 3 a*_max / v (a Hertz contact, p = 3/2,
    lasts 2.94 a_max / v; a linear spring pi a_max / v), at most one period 2 pi sqrt(m* / p) of
    the contact's oscillation about the static compression a* = 1 (a slow impact, where gravity
    sets the depth: the particle falls into the contact and comes back out). ``a_max``: the
    :func:`impact_compression` where the caller has it."""
    drive = scene.drive
    assert isinstance(drive, Impact)
    p = scene.particle.profile.p
    slow = 2.0 * math.pi * math.sqrt(scene.particle.m_star / p)
    a_max = impact_compression(scene) if a_max is None else a_max
    return min(3.0 * a_max / drive.velocity, slow)
