"""Words the Result writes into its warnings and the readers of a table look for.

A light module (no imports): the command line's notes read it before the heavy modules load.
"""

from __future__ import annotations

#: the words of a long-time mean's warning whose bounces gain energy over the mean
#: (:func:`sawdrift.dynamics.batch_means.heats_up`): the Result writes them, and the command
#: line's note and the explorer's tooltip find such a cell by them
HEATING = "the bounces heat up"

#: the words of the warning of a long-time mean whose halves still differ after its extensions
#: (:func:`sawdrift.dynamics.batch_means.still_moving`): the Result writes them, and the
#: benchmarks find such a run by them
STILL_MOVING = "the mean drift was still moving"


def says_heating(warnings: object) -> bool:
    """Whether ``warnings`` (a Result's tuple, or a table's "; "-joined string) hold the
    heating warning."""
    return _says(HEATING, warnings)


def says_still_moving(warnings: object) -> bool:
    """Whether ``warnings`` (as for :func:`says_heating`) hold the still-moving warning."""
    return _says(STILL_MOVING, warnings)


def _says(words: str, warnings: object) -> bool:
    if isinstance(warnings, str):
        return words in warnings
    return any(words in str(w) for w in warnings or ())
