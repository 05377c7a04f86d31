"""A contact history's snapshot (``ContactHistory.state`` / ``set_state``) continues bit for bit.

The bifurcation journals keep an integration between values as text (``Stepper.save``, through
``numpy.savez``) and a run that was stopped goes on from it (``Stepper.restore``). Saved and put
back, on a fresh history or on the one that went elsewhere meanwhile, a history (the memory
diagram mmd, and the other compliant built-ins) must go on exactly as the uninterrupted one, on
both engines.
"""

from __future__ import annotations

import io

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.contact.binding import model_for
from sawdrift.dynamics.assembly import assemble
from sawdrift.dynamics.stepper import Stepper, StepperState

# small tangential moves (|db*| below a*): the memory diagram gathers kinks, then goes elsewhere
RNG = np.random.default_rng(7)
BEFORE = [(1.0 + 0.1 * np.sin(0.3 * k), 0.04 * np.sin(0.7 * k) + 0.01 * RNG.standard_normal())
          for k in range(60)]
AFTER = [(1.0 + 0.15 * np.cos(0.2 * k), 0.05 * np.cos(0.5 * k) + 0.01 * RNG.standard_normal())
         for k in range(60)]
ELSEWHERE = [(1.3, -0.2), (0.4, 0.1), (0.0, 0.0), (1.1, 0.3)]


def _through_npz(state: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    buf = io.BytesIO()
    np.savez(buf, **state)
    buf.seek(0)
    with np.load(buf) as data:
        return {key: data[key] for key in data.files}


def _bits(values) -> np.ndarray:
    return np.asarray(values, dtype=np.float64).view(np.int64)


@pytest.mark.parametrize("engine", ["python", "compiled"])
@pytest.mark.parametrize("name", ["mmd", "mdr", "jaeger", "hertz_mindlin_dem", "hertz_tsuji"])
def test_a_restored_history_continues_bit_for_bit(name, engine):
    model = sd.registry.get(name)()
    whole = sd.ContactHistory(model, engine)
    for a, b in BEFORE:
        whole.advance(a, b)
    saved = _through_npz(whole.state())
    assert set(saved) == ({"ref"} if engine == "python" else {"fs", "is"})
    expected = [whole.advance(a, b) for a, b in AFTER]

    fresh = sd.ContactHistory(model, engine)
    fresh.set_state(saved)
    assert np.array_equal(_bits([fresh.advance(a, b) for a, b in AFTER]), _bits(expected))

    # put back on a history that went elsewhere, through a kernel call taken before: it drives
    # the restored history (the integration loops stay bound to it)
    moved = sd.ContactHistory(model, engine)
    force, fs, is_, pp = moved.kernel_call()
    for a, b in BEFORE + ELSEWHERE:
        force(fs, is_, pp, a, b, 0.0, 0.0)
    moved.set_state(saved)
    out = [force(fs, is_, pp, a, b, 0.0, 0.0) for a, b in AFTER]
    assert np.array_equal(_bits(out), _bits(expected))


@pytest.mark.parametrize("engine", ["python", "compiled"])
def test_the_snapshot_is_a_copy(engine):
    model = sd.registry.get("mmd")()
    h = sd.ContactHistory(model, engine)
    for a, b in BEFORE:
        h.advance(a, b)
    state = h.state()
    kept = {key: value.copy() for key, value in state.items()}
    for a, b in ELSEWHERE:
        h.advance(a, b)
    for key, value in state.items():
        assert np.array_equal(value, kept[key])


def test_a_snapshot_of_the_other_engine_is_refused():
    model = sd.registry.get("mmd")()
    compiled, python = sd.ContactHistory(model, "compiled"), sd.ContactHistory(model, "python")
    with pytest.raises(ValueError, match="'fs' and 'is'"):
        compiled.set_state(python.state())
    with pytest.raises(ValueError, match="'ref'"):
        python.set_state(compiled.state())


def _stepper(scene: sd.Scene, engine: str) -> Stepper:
    model = model_for(scene)
    return Stepper(scene, model, assemble(scene, engine, model), record=False)


@pytest.mark.parametrize("engine", ["python", "compiled"])
def test_a_restored_mmd_stepper_continues_bit_for_bit(engine):
    # the journal's way: Stepper.save, as text, restored on a new stepper and on the old one
    scene = sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.5},
                     numerics={"steps_per_period": 64})
    first, then = (3, 2) if engine == "python" else (40, 20)
    whole = _stepper(scene, engine)
    whole.advance(first * whole.k_per)
    text = whole.save().to_text()
    whole.advance(then * whole.k_per)
    expected = whole.save().arrays

    for stepper in (_stepper(scene, engine), None):
        if stepper is None:  # the stepper that went on: put back where it was saved
            stepper = whole
        stepper.restore(StepperState.from_text(text))
        stepper.advance(then * stepper.k_per)
        got = stepper.save().arrays
        assert set(got) == set(expected)
        for key in expected:
            assert np.array_equal(got[key], expected[key]), key
