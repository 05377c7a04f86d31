"""Rotation: the small-amplitude tangential contact resonance at fixed a* grows by sqrt(1 + 1/kappa).

At the static compression a* = 1 (substrate at rest) a small tangential motion sees the initial
Mindlin stiffness dT*/db* = p a*^(p-1) = 3/2 of the sphere. With theta mu b* = x* (no rotation),
m* x*'' = -mu T* gives omega^2 = 3 / (2 theta m*) per unit t*. A sphere free to turn moves its
contact point s = (1 + 1/kappa) x (docs/physics.md, Rotation), so theta mu b* = s* and
omega^2 = 3 (1 + 1/kappa) / (2 theta m*): the contact point is lighter by 1 + 1/kappa.

mmd, m* = 0.1, kappa = 2/5 and 2/3, a tangential velocity kick of b* amplitude 1e-4 (far inside
partial slip, where the law is linear to 1e-4), 2048 steps per period, 20 periods; the frequency is
read from the up-crossings of x*.
"""

from __future__ import annotations

import math

import numpy as np

import sawdrift as sd
from sawdrift.dynamics.assembly import assemble
from sawdrift.dynamics.stepper import Stepper
from sawdrift.validation import Case, CaseResult

KAPPAS = (0.4, 2.0 / 3.0)
M_STAR = 0.1

CASE = Case(
    name="rolling_tangential_resonance",
    group="rotation",
    title="Small-amplitude tangential resonance at a* = 1, mmd, m* = 0.1: omega^2 = 3/(2 theta m*) "
    "without rotation, times (1 + 1/kappa) with it (kappa = 2/5, 2/3); value: largest relative "
    "error of the measured frequencies and of their ratio against sqrt(1 + 1/kappa)",
    tolerance=1e-3,
    quick=True,
)


def frequency(rotation: bool, kappa: float) -> tuple[float, float]:
    """(measured, predicted) angular frequency of the free tangential oscillation."""
    scene = sd.Scene(model="mmd", particle={"m_star": M_STAR, **({"gyration": kappa} if rotation else {})},
                     drive={"amplitude": 0.0, "ramp_periods": 0.0},
                     effects={"rotation": rotation}, numerics={"steps_per_period": 2048})
    model = sd.model_for(scene)
    stepper = Stepper(scene, model, assemble(scene, "compiled", model), record=True)
    stepper.rec_every = 1
    c = 1.0 + 1.0 / kappa if rotation else 1.0
    omega = math.sqrt(1.5 * c / (scene.theta * M_STAR))
    # x*' kick giving a b* amplitude of 1e-4: b* = c x* / (theta mu)
    stepper.y[1] = 1e-4 * scene.theta * scene.material.mu * omega / c
    stepper.advance(20 * 2048)
    tr = stepper.trajectory()
    x, t = tr["x"].to_numpy(), tr["t"].to_numpy()
    i = np.nonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))[0]
    crossings = t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])
    return 2.0 * math.pi / float(np.diff(crossings).mean()), omega


def run() -> CaseResult:
    """Measure both frequencies for each kappa."""
    errors, notes = [], []
    for kappa in KAPPAS:
        (w0, p0), (w1, p1) = frequency(False, kappa), frequency(True, kappa)
        want = math.sqrt(1.0 + 1.0 / kappa)
        errors += [abs(w0 / p0 - 1), abs(w1 / p1 - 1), abs(w1 / w0 / want - 1)]
        notes.append(f"kappa = {kappa:.4g}: omega {w0:.5f} (closed form {p0:.5f}) -> {w1:.5f} "
                     f"({p1:.5f}), ratio {w1 / w0:.5f} vs sqrt(1 + 1/kappa) = {want:.5f}")
    return CASE.result(max(errors), message="; ".join(notes))
