"""Stepper.continued: a warm start carries the state, the memory and the time over exactly."""

from __future__ import annotations

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.dynamics.assembly import assemble
from sawdrift.dynamics.stepper import Stepper


def _stepper(scene: sd.Scene) -> Stepper:
    model = sd.model_for(scene)
    return Stepper(scene, model, assemble(scene, "compiled", model), record=False)


@pytest.mark.parametrize("model", ["mmd", "mdr", "jaeger", "material_point"])
def test_continuing_with_the_same_scene_is_the_same_run(model):
    scene = sd.Scene(model=model, particle={"m_star": 0.1}, drive={"amplitude": 0.5},
                     numerics={"steps_per_period": 256})
    a = _stepper(scene)
    a.advance(40 * a.k_per)
    b = a.continued(scene)
    a.advance(20 * a.k_per)
    b.advance(20 * b.k_per)
    assert b.step == a.step
    np.testing.assert_array_equal(a.y, b.y)


def test_continuation_in_amplitude_keeps_the_memory_and_reaches_the_new_attractor():
    # warm start at A* = 0.4 from the A* = 0.3 attractor: after a transient the drift is the one
    # of a cold run at A* = 0.4, to 1e-6. Normal damping makes that attractor unique: without it
    # the free vertical oscillation never decays and its amplitude depends on the history
    base = sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 0.3},
                    effects={"normal_damping": 0.3}, numerics={"steps_per_period": 256})
    a = _stepper(base)
    a.advance(60 * a.k_per)
    target = base.with_updates(**{"drive.amplitude": 0.4, "numerics.periods": 400,
                                  "numerics.measure_periods": 100})
    warm = a.continued(target)
    x0 = warm.y[0]
    warm.advance(300 * warm.k_per)
    x1 = warm.y[0]
    warm.advance(100 * warm.k_per)
    drift = (warm.y[0] - x1) / 100
    cold = sd.run(target)
    assert drift == pytest.approx(cold.drift_velocity, rel=1e-6)
    assert x1 != x0


@pytest.mark.parametrize("model", ["mmd", "material_point"])
def test_continuing_a_rolling_sphere_moves_its_contact_point_with_the_surface(model):
    # continue_to shifts the particle with the surface so that a*, b* and the slip velocity
    # s' - u_x' carry over; on a sphere rolling from rest the contact point is s = c x
    # (c = 1 + 1/kappa), so the centre moves by 1/c of the surface's shift
    from sawdrift.study.branch import continue_to

    base = sd.Scene(model=model, particle={"m_star": 0.1}, drive={"amplitude": 0.3},
                    effects={"rotation": True}, numerics={"steps_per_period": 256})
    a = _stepper(base)
    a.advance(20 * a.k_per)
    c = a.roll

    def slip(st: Stepper) -> float:
        return c * st.y[1] - st.surface()[1]

    before = (slip(a), *a.displacements())
    new = continue_to(a, base.with_updates(**{"drive.amplitude": 0.5}))
    after = (slip(new), *new.displacements())
    assert new.surface()[1] != a.surface()[1]  # the surface velocity really changed
    np.testing.assert_allclose(after, before, rtol=0, atol=1e-12)


def test_continuation_in_restitution_applies_the_new_damping_to_the_dem_spring():
    # hertz_mindlin_dem carries the restitution damping in its contact: a warm start from e = 0.5
    # at e = 0.8 must damp with the new e. Its attractor is the cold run's at e = 0.8 (drift
    # velocity +0.42 a0 per period there against -0.42 at e = 0.5); to 1e-6
    base = sd.Scene(model="hertz_mindlin_dem", particle={"m_star": 0.067},
                    drive={"amplitude": 0.31}, material={"restitution": 0.5},
                    numerics={"steps_per_period": 256})
    a = _stepper(base)
    a.advance(30 * a.k_per)
    target = base.with_updates(**{"material.restitution": 0.8, "numerics.periods": 100,
                                  "numerics.measure_periods": 40, "numerics.settle": False})
    warm = a.continued(target)
    warm.advance(60 * warm.k_per)
    x1 = warm.y[0]
    warm.advance(40 * warm.k_per)
    cold = sd.run(target)
    assert (warm.y[0] - x1) / 40 == pytest.approx(cold.drift_velocity, rel=1e-6)
    assert sd.run(base).drift_velocity < 0.0 < cold.drift_velocity
