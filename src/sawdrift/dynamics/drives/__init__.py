"""Drives: the substrate's motion, one module each (see :mod:`.base` for the protocol).

* :mod:`.travelling` - the travelling wave at one place: an elliptic local orbit of any phase;
* :mod:`.two_wave` - the wave and its counter-propagating mirror image: the local orbit at
  ``drive.position``, or a direct run at the particle's own position (``drive.wavelength``);
* :mod:`.rest` - a substrate at rest (free impacts);
* :mod:`.biharmonic` - a plate vibrating with two harmonics per axis (Blekhman's transport).

:func:`drive_of` picks the drive of a scene by its ``drive.kind``; a wave with a second wave, a
position, a wavelength or a phase ramp (:func:`.two_wave.needs_two_waves`) runs
:class:`.two_wave.TwoWaves`, every other wave the travelling one (bit for bit as before).
"""

from __future__ import annotations

from typing import Any

from .base import Drive
from .biharmonic import Biharmonic
from .rest import SubstrateAtRest
from .travelling import TravellingWave
from .two_wave import TwoWaves, needs_two_waves

#: the drive of each scene ``drive.kind`` that the integrators run
DRIVES: dict[str, Drive] = {d.kind: d for d in (TravellingWave(), SubstrateAtRest(), Biharmonic())}

#: the drive of a wave scene with two waves, a position or a wavelength
TWO_WAVES = TwoWaves()

__all__ = ["DRIVES", "TWO_WAVES", "Drive", "drive_of"]


def drive_of(scene: Any) -> Drive:
    """The drive that runs ``scene`` (a KeyError names a kind without one, e.g. prescribed)."""
    if needs_two_waves(scene.drive):
        return TWO_WAVES
    return DRIVES[scene.drive.kind]
