"""Drives: the substrate's motion, one module each (see :mod:`.base` for the protocol).

* :mod:`.travelling` - the travelling wave at one place: an elliptic local orbit of any phase;
* :mod:`.rest` - a substrate at rest (free impacts).

:func:`drive_of` picks the drive of a scene by its ``drive.kind``.
"""

from __future__ import annotations

from typing import Any

from .base import Drive
from .rest import SubstrateAtRest
from .travelling import TravellingWave

#: the drive of each scene ``drive.kind`` that the integrators run
DRIVES: dict[str, Drive] = {d.kind: d for d in (TravellingWave(), SubstrateAtRest())}

__all__ = ["DRIVES", "Drive", "drive_of"]


def drive_of(scene: Any) -> Drive:
    """The drive that runs ``scene`` (a KeyError names a kind without one, e.g. prescribed)."""
    return DRIVES[scene.drive.kind]
