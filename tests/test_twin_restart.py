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


#: (model, effects, m*, A*, compiled live size): bouncing (memory wiped at each lift-off), and
#: drifting in permanent contact, where a twin whose memory was not put back on the copy's
#: (a live part copied short) moves apart from the first periods on
STRETCH_CASES = [
    ("mmd", {}, 0.0316, 7.08, True),
    ("mmd", {}, 1.0, 0.3, True),
    ("mmd", {"rotation": True, "rolling_resistance": 0.01}, 1.0, 0.3, True),
    ("jaeger", {}, 0.1, 1.0, False),
    ("mdr", {}, 1.0, 0.3, False),
    ("material_point", {}, 0.1, 1.0, None),  # the rigid scheme: no memory, no live size
    ("material_point", {"rotation": True}, 1.0, 0.3, None),
    ("material_point", {"restitution": 0.9}, 0.1, 1.0, None),  # chaotic rebounds
]


@pytest.mark.parametrize("model, effects, m_star, amplitude, live", STRETCH_CASES)
def test_compiled_stretchings_are_the_python_loops_bit_for_bit(model, effects, m_star, amplitude,
                                                               live):
    """The Lyapunov stretchings by one compiled call per stretch (dynamics.stretching) are the
    per-period Python loop's numbers exactly, with and without the early checks."""
    from sawdrift.dynamics import window
    from sawdrift.dynamics.stretching import stretch_loop

    effects = dict(effects)
    material = {"restitution": effects.pop("restitution")} if "restitution" in effects else {}
    scene = bind(sd.Scene(model=model, particle={"m_star": m_star}, drive={"amplitude": amplitude},
                          effects=effects, material=material, numerics={"settle": False}))
    contact = model_for(scene)
    stepper = Stepper(scene, contact, assemble(scene, "compiled", contact), record=False)
    stepper.advance(stepper.k_per * 20)
    assert stretch_loop(stepper) is not None
    if live is not None:
        assert (stepper.history.model.compiled_live_floats() is not None) == live
    scale = stepper.drive.state_scale(scene)
    got = {}
    for compiled in (True, False):
        window.COMPILED_STRETCHINGS = compiled
        try:
            got[compiled] = [window.stretching_logs(stepper, scale, 96, early=early)
                             for early in ((), window.EARLY_CHECKS)]
        finally:
            window.COMPILED_STRETCHINGS = True
    for fast, slow in zip(got[True], got[False], strict=True):
        assert fast.size == slow.size
        assert np.array_equal(fast, slow)
    first = got[True][0]
    assert first.size == 96 and np.isfinite(first).all() or first[-1] == -np.inf


def test_the_python_engine_keeps_the_python_stretchings():
    from sawdrift.dynamics.stretching import stretch_loop

    for model, engine in (("material_point", "python"), ("mmd", "python")):
        scene = bind(sd.Scene(model=model, particle={"m_star": 0.1}, drive={"amplitude": 1.0},
                              numerics={"settle": False}))
        contact = model_for(scene)
        stepper = Stepper(scene, contact, assemble(scene, engine, contact), record=False)
        assert stretch_loop(stepper) is None


def test_a_period_that_fills_the_event_log_falls_back_to_the_python_loop():
    """A run whose event log is short of the loop's margin returns from its loop before the
    period ends: the compiled stretch reports it (None) and the per-period Python loop, which
    grows the log, gives the numbers, the same as with the compiled path switched off."""
    from sawdrift.dynamics import evidence as ev
    from sawdrift.dynamics import window
    from sawdrift.dynamics.stretching import compiled_stretchings

    scene = bind(sd.Scene(model="mmd", particle={"m_star": 0.0316}, drive={"amplitude": 7.08},
                          numerics={"settle": False}))
    contact = model_for(scene)
    stepper = Stepper(scene, contact, assemble(scene, "compiled", contact), record=False)
    stepper.advance(stepper.k_per * 20)
    stepper.st = ev.new_stats(ev.EV_MARGIN - 1)  # short of the margin: each loop call returns early
    stepper.keep_events = True
    scale = stepper.drive.state_scale(scene)
    assert compiled_stretchings(stepper, scale, 64, window.ALIGN_PERIODS,
                                window.LYAPUNOV_D0, ()) is None
    fell_back = window.stretching_logs(stepper, scale, 64)
    window.COMPILED_STRETCHINGS = False
    try:
        python = window.stretching_logs(stepper, scale, 64)
    finally:
        window.COMPILED_STRETCHINGS = True
    assert fell_back.size == 64 and np.array_equal(fell_back, python)
