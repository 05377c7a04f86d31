"""The Lyapunov twin restarted in place continues bit for bit as a freshly built twin would."""

from __future__ import annotations

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.contact.binding import bind, model_for
from sawdrift.dynamics.assembly import assemble
from sawdrift.dynamics.stepper import Stepper

#: (model, engine, effects, m*, A*): hopping (the memory is wiped at each lift-off) and drifting
#: in permanent contact (the memory diagram carries over, so a twin that kept another one differs)
CASES = [
    ("mmd", "compiled", {}, 0.1, 1.0),
    ("mmd", "compiled", {}, 1.0, 0.3),
    ("mmd", "python", {}, 1.0, 0.3),
    ("mmd", "compiled", {"rotation": True, "rolling_resistance": 0.01}, 1.0, 0.3),  # psi integrated
    ("mdr", "compiled", {}, 1.0, 0.3),
    ("material_point", "compiled", {}, 0.1, 1.0),
    ("material_point", "compiled", {"rotation": True}, 1.0, 0.3),
]


@pytest.mark.parametrize("model, engine, effects, m_star, amplitude", CASES)
def test_restart_from_matches_a_new_twin(model, engine, effects, m_star, amplitude):
    scene = bind(sd.Scene(model=model, particle={"m_star": m_star}, drive={"amplitude": amplitude},
                          effects=effects, numerics={"settle": False}))
    contact = model_for(scene)
    base = Stepper(scene, contact, assemble(scene, engine, contact), record=False)
    base.advance(base.k_per * 3)
    dy = np.array([0.0, 1e-7, -2e-8, 3e-8])
    reused = base.twin(dy)
    reused.advance(reused.k_per * 2 + 17)  # somewhere else: every part of its state differs
    base.advance(base.k_per + 5)
    fresh = base.twin(dy)
    reused.restart_from(base, dy)
    for twin in (fresh, reused):
        twin.advance(twin.k_per)
    assert np.array_equal(reused.y, fresh.y)
    assert np.array_equal(reused.ctr, fresh.ctr)
    if not base.rigid:
        assert np.array_equal(reused.fh, fresh.fh)
        if base.history is not None:
            a, b = reused.history.state(), fresh.history.state()
            assert a.keys() == b.keys()
            assert all(np.array_equal(a[k], b[k]) for k in a)
    # the statistics go on from the same values; the restarted twin's log holds only its own events
    assert np.array_equal(reused.st[:10], fresh.st[:10])
