"""A contact history's copy is independent of the original, on both engines.

A twin trajectory (the Lyapunov estimate), a checkpoint and ``ContactHistory.trial`` copy a
history and drive the copy and the original apart. The python engine of a slot law once
composed its functions over the readable reference object, which a deep copy kept: the copy
drove the original's memory diagram (mmd at m* = 0.01, A* = 10 then failed with 'level outside
the diagram').
"""

from __future__ import annotations

import numpy as np
import pytest

import sawdrift as sd

# small tangential moves (|db*| well below a*): the memory diagram keeps its kinks (a full slip
# would erase the history and hide a shared one)
PATH = [(1.0, 0.0), (1.0, 0.05), (0.9, 0.02), (1.1, 0.06), (1.0, 0.01)]
OTHER = [(1.2, -0.1), (0.95, 0.08), (1.05, -0.03)]


@pytest.mark.parametrize("engine", ["python", "compiled"])
@pytest.mark.parametrize("name", ["mmd", "mdr", "jaeger", "hertz_mindlin_dem"])
def test_a_copy_is_not_moved_by_its_original(name, engine):
    model = sd.registry.get(name)()
    h = sd.ContactHistory(model, engine)
    for a, b in PATH:
        h.advance(a, b)
    first, second = h.copy(), h.copy()
    for a, b in OTHER:  # the original goes elsewhere
        h.advance(a, b)
    out1 = [first.advance(a, b) for a, b in PATH]
    for a, b in OTHER:  # so does the first copy, before the second is driven
        first.advance(a, b)
    out2 = [second.advance(a, b) for a, b in PATH]
    assert np.array_equal(np.array(out1), np.array(out2))
