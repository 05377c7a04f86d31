"""Words the Result writes into its warnings and the readers of a table look for.

A light module (no imports): the command line's notes read it before the heavy modules load.
"""

from __future__ import annotations

#: the words of a long-time mean's warning whose bounces gain energy over the mean
#: (:func:`sawdrift.dynamics.batch_means.heats_up`): the Result writes them, and the command
#: line's note and the explorer's tooltip find such a cell by them
HEATING = "the bounces heat up"


def says_heating(warnings: object) -> bool:
    """Whether ``warnings`` (a Result's tuple, or a table's "; "-joined string) hold the
    heating warning."""
    if isinstance(warnings, str):
        return HEATING in warnings
    return any(HEATING in str(w) for w in warnings or ())
