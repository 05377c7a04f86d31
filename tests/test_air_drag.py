"""Air drag (sawdrift.dynamics.air_drag): the closed-form terminal velocity, and off is never computed."""

from __future__ import annotations

import math

import pytest

from sawdrift.contact.binding import model_for
from sawdrift.dynamics.assembly import assemble, explain
from sawdrift.dynamics.stepper import Stepper
from sawdrift.errors import SceneError
from sawdrift.result.runner import run
from sawdrift.scene.schema import Scene

MU = 0.1


def _sliding(model: str, load: float, drag: float) -> Scene:
    """A particle on a still substrate (no wave) under a constant load |L| > mu: it slides."""
    return Scene(model=model, particle={"m_star": 0.1, "load": load}, drive={"amplitude": 0.0},
                 material={"mu": MU}, effects={"air_drag": drag}, numerics={"periods": 30})


@pytest.mark.parametrize(("model", "load", "drag"), [("mmd", 0.2, 0.5), ("jaeger", -0.35, 2.0)])
def test_sliding_reaches_the_terminal_velocity(model, load, drag):
    """m* x*'' = -mu sgn(x*') + L - c x*' (N* = 1 at rest on the substrate): x*' -> (L - mu sgn L)/c.

    The approach exp(-c t*/m*) is over within the ramp-free 30 periods (m*/c <= 0.2 periods), so
    the measured drift velocity is the terminal one to rounding: 1e-12 asked, 4e-14 measured.
    """
    terminal = (load - MU * (1.0 if load > 0.0 else -1.0)) / drag
    result = run(_sliding(model, load, drag))
    assert result.drift_velocity == pytest.approx(terminal, rel=1e-12, abs=1e-12)


def test_drag_off_is_never_computed():
    """effects.air_drag = 0 (the default) runs the loop without the term: bit for bit the same."""
    base = dict(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.316},
                numerics={"periods": 20})
    plain = run(Scene(**base))
    off = run(Scene(**base, effects={"air_drag": 0.0}))
    assert off.drift_velocity.hex() == plain.drift_velocity.hex()
    assert assemble(Scene(**base)).param("air_drag") == 0.0
    assert "air drag" not in explain(Scene(**base))
    assert "air drag c = 0.5" in explain(_sliding("mmd", 0.2, 0.5))


def test_rigid_model_refuses_air_drag():
    """The rigid scheme's closed forms have no drag term: asking for it is an error, not ignored."""
    with pytest.raises(SceneError, match="air_drag"):
        assemble(Scene(model="material_point", effects={"air_drag": 0.1}))


def test_free_fall_reaches_the_terminal_velocity():
    """m* y*'' = 1 - c y*' in flight: y*' = (1 - exp(-c t*/m*))/c from rest, terminal 1/c.

    Started far above the surface (y* = -1e3, no contact for the whole fall); after half a period
    the transient agrees to 2e-7 (the Adams-Bashforth start-up), after 10.5 periods the terminal
    velocity to rounding.
    """
    c, m = 2.0, 0.1
    scene = Scene(model="mmd", particle={"m_star": m}, drive={"amplitude": 0.0},
                  effects={"air_drag": c})
    model = model_for(scene)
    stepper = Stepper(scene, model, assemble(scene, "compiled", model), record=False)
    stepper.y[2] = -1e3
    half = stepper.k_per // 2
    stepper.advance(half)
    assert stepper.y[3] == pytest.approx((1.0 - math.exp(-c * half * stepper.h / m)) / c, abs=1e-6)
    stepper.advance(10 * stepper.k_per)
    assert stepper.y[2] < 0.0  # still in flight
    assert stepper.y[3] == pytest.approx(1.0 / c, rel=1e-14)
